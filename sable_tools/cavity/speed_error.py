#!/usr/bin/python3
"""Speed against error for the cavity (issue 43, item 6): run, then report.

    /usr/bin/python3 -m sable_tools.cavity.speed_error run [--work DIR] [--seeds 11 12 13 14] [--no-yade]
    /usr/bin/python3 -m sable_tools.cavity.speed_error report [--work DIR] [--ps sable=X yade=Y]

One scene, H/d 8, N_U 1, N_P 1 (I_M 0.044), 1.5 s recorded after 0.5 s, four seeds. Each
setting changes one knob from the deck's defaults (dtfrac 0.1, N0 1.5e4, 10 kHz, H/d 8):
dtfrac 0.025-0.2, N0 5e3-5e4, recording 5-20 kHz, and H/d 12 at the same I_M (N_U 1.837).
The error of a setting is measured against the finest setting of its knob (dtfrac 0.025,
N0 5e4, 20 kHz, H/d 12): |mean F/(PLd) - finest| / finest over the seeds' means, with the
differences taken seed by seed (each seed's runs share its deposit), and the KS distance
between the seeds' pooled F/F̄ samples. Cost is counted in particle-steps (atoms x steps)
and turned into one-core time by each code's particle-steps per second from the benchmark
input_scripts/bench/cavity_yade.sh (`--ps`): wall times on the shared host vary with its load.
YADE runs the default setting and dtfrac 0.2 from the same sable deposits (the shear
exported by `sable --export-yade`); its error is against sable's finest dtfrac. Raw outputs
in DIR (default /tmp/cavity_speed); per-run RESULT values, the report and the figure in
reference_runs/cavity/speed_error/.
"""
import argparse, json, os, sys, time

import numpy as np

from sable_tools import runner, seedstats  # YADE runs into their logs; statistics over seeds
from sable_tools.cavity import sweep  # the deck, the binaries, key_values
from sable_tools.readers import analyze as analyze_csv, h5  # sable-analyze's CSV; the series files
from sable_tools.readers import screen as screen_reader  # the ERROR lines of a failed run

OUT = os.path.join(sweep.ROOT, 'reference_runs', 'cavity', 'speed_error')
BASE = {'Hd': 8, 'NU': 1, 'NP': 1, 'tshear': 2, 'trec': 0.5, 'dtfrac': 0.1, 'N0': 1.5e4, 'rate': 10}
# (knob, value, extra variables); the first of each knob is its finest
SETTINGS = [('dtfrac', 0.025, {}), ('dtfrac', 0.05, {}), ('dtfrac', 0.1, {}), ('dtfrac', 0.2, {}),
            ('N0', 5e4, {}), ('N0', 1.5e4, {}), ('N0', 5e3, {}),
            ('rate', 20, {}), ('rate', 10, {}), ('rate', 5, {}),
            ('Hd', 12, {'NU': 1.8371173070873836}), ('Hd', 8, {})]
YADE = [('dtfrac', 0.1), ('dtfrac', 0.2)]
SEEDS = [11, 12, 13, 14]


def variables(knob, value, extra):
    v = dict(BASE, **extra)
    v[knob] = value
    return v


def name(knob, value, seed, code='sable'):
    return f'{code}_{knob}{value:g}_s{seed}'


def args_of(v):
    out = []
    for k, x in v.items():
        out += ['-var', k, f'{x:.17g}' if isinstance(x, float) else str(x)]
    return out


def run_sable(work, knob, value, extra, seed):
    """The default setting deposits and shears; dtfrac and rate shear from its deposit (the
    deposit does not settle at dtfrac 0.2: README), N0 and H/d deposit their own beds."""
    d = os.path.join(work, name(knob, value, seed))
    os.makedirs(d, exist_ok=True)
    v = dict(variables(knob, value, extra), seed=seed, fields=0, contacts=0, out='cav',
             restart=os.path.join(d, 'dep.restart'))
    if knob in ('dtfrac', 'rate') and (knob, value) != ('dtfrac', 0.1):
        v.update(phase='shear', restart=os.path.join(work, name('dtfrac', 0.1, seed), 'dep.restart'))
    sweep.sable(args_of(v), os.path.join(d, 'log.sable'), d)
    return d


def run_yade(work, knob, value, seed):
    """The shear in YADE from the sable deposit of the default setting's run of this seed."""
    d = os.path.join(work, name(knob, value, seed, 'yade'))
    os.makedirs(d, exist_ok=True)
    dep = os.path.join(work, name('dtfrac', 0.1, seed), 'dep.restart')
    v = dict(variables(knob, value, {}), seed=seed, fields=0, contacts=0, out='cav', phase='shear', restart=dep)
    script = os.path.join(d, 'shear.py')
    if runner.run_logged(runner.export_yade(sweep.SABLE, sweep.DECK, args_of(v), script), d,
                         os.path.join(d, 'export.screen')):
        sys.exit(f'speed_error: export failed, see {d}/export.screen')
    if runner.run_logged(runner.yade(script), d, os.path.join(d, 'log.yade'), runner.one_thread()):
        sys.exit(f'speed_error: YADE failed, see {d}/log.yade')
    return d


def record(d, code):
    """RESULT values of a finished run, and its F/F̄ samples saved beside it."""
    res = sweep.key_values(os.path.join(d, 'log.' + code), 'RESULT')
    cols, values, _ = h5.read_series(os.path.join(d, 'cav_series.h5'))
    F = values[:, cols.index('v_F')]
    np.save(os.path.join(d, 'F_norm.npy'), F / F.mean())
    return res


def run_all(a):
    os.makedirs(OUT, exist_ok=True)
    path = os.path.join(OUT, 'runs.json')
    runs = json.load(open(path)) if os.path.exists(path) else {}
    jobs = [('dtfrac', 0.1, {}, 'sable')] + [  # the default setting runs once, first, as dtfrac 0.1
        (k, v, e, 'sable') for k, v, e in SETTINGS if (k, v) not in (('dtfrac', 0.1), ('N0', 1.5e4), ('rate', 10), ('Hd', 8))]
    if not a.no_yade:
        jobs += [(k, v, {}, 'yade') for k, v in YADE]
    for seed in a.seeds:
        for knob, value, extra, code in jobs:
            key = name(knob, value, seed, code)
            if key in runs:
                continue
            t0 = time.time()
            try:
                d = run_sable(a.work, knob, value, extra, seed) if code == 'sable' else run_yade(a.work, knob, value, seed)
            except SystemExit as e:  # a run that stops (e.g. blows up at dtfrac 0.2) is a result: keep its error
                runs[key] = dict(code=code, knob=knob, value=value, seed=seed, failed=last_error(str(e)))
                json.dump(runs, open(path, 'w'), indent=1)
                print(f'{time.strftime("%H:%M:%S")} {key}: FAILED {runs[key]["failed"]}', flush=True)
                continue
            runs[key] = dict(record(d, code), code=code, knob=knob, value=value, seed=seed, wall_total=time.time() - t0)
            json.dump(runs, open(path, 'w'), indent=1)
            r = runs[key]
            print(f'{time.strftime("%H:%M:%S")} {key}: F/(PLd) {r["F_PLd"]:.4f} wall_s {r["wall_s"]:.1f} '
                  f'PS/s {r["PS_per_s"]:.3g}', flush=True)


def last_error(msg):
    """The ERROR line of the screen file a failed run's message names, else the message."""
    screen = msg.rsplit('see ', 1)[-1].strip()
    if os.path.exists(screen):
        with open(screen, errors='replace') as f:
            errs = screen_reader.error_lines(f.read())
        if errs:
            return errs[-1][:400]
    return msg[:400]


def group(runs, code, knob, value):
    """The runs of one setting (the default is stored under dtfrac 0.1)."""
    if code == 'sable' and (knob, value) in (('N0', 1.5e4), ('rate', 10), ('Hd', 8)):
        knob, value = 'dtfrac', 0.1
    return [r for k, r in runs.items() if r['code'] == code and r['knob'] == knob and r['value'] == value
            and 'failed' not in r]


def failures(runs):
    return [(k, r['failed']) for k, r in runs.items() if 'failed' in r]


def ks(work, a, b, tag):
    """sable-analyze ks of two sets of runs' pooled F/F̄ samples: D and its 5 % critical value."""
    files = []
    for rs, side in ((a, 'a'), (b, 'b')):
        x = np.concatenate([np.load(os.path.join(work, name(r['knob'], r['value'], r['seed'], r['code']), 'F_norm.npy'))
                            for r in rs])
        f = os.path.join(work, f'ks_{tag}_{side}.csv')
        np.savetxt(f, x, header='x', comments='')
        files.append(f)
    out = os.path.join(work, f'ks_{tag}.csv')
    sweep.analyze(['ks', files[0], files[1], '--column', 'x', '--out', out])
    t = analyze_csv.columns(out)
    return float(t['d'][0]), float(t['critical'][0])


def mean_se(rs, key):
    """Seed mean and seed-to-seed SE of one key (seedstats.summary; SE nan for one seed)."""
    s = seedstats.summary([r[key] for r in rs])
    return s.mean, s.se


def paired(rs, ref):
    """Seed by seed differences of F/(PLd) (setting - finest) over the seeds both ran: the
    error's mean and its standard error (both share each seed's deposit where they can)."""
    by = {r['seed']: r['F_PLd'] for r in ref}
    s = seedstats.summary([r['F_PLd'] - by[r['seed']] for r in rs if r['seed'] in by])
    return s.mean, s.se, s.n


def report(a):
    """Per setting: F/(PLd) over seeds, its paired error against the knob's finest setting, the
    KS distance of the pooled F/F̄, the cost in particle-steps (deterministic) and the one-core
    time it takes at each code's measured particle-steps per second (--ps, the benchmark's)."""
    runs = json.load(open(os.path.join(OUT, 'runs.json')))
    ps = dict(x.split('=') for x in a.ps) if a.ps else {}
    rows = []
    finest = {}
    for knob, value, _ in SETTINGS:
        finest.setdefault(knob, value)
    for code, knob, value in [('sable', k, v) for k, v, _ in SETTINGS] + [('yade', k, v) for k, v in YADE]:
        rs = group(runs, code, knob, value)
        ref = group(runs, 'sable', knob, finest[knob])
        if not rs or not ref:
            continue
        m, se = mean_se(rs, 'F_PLd')
        mr = seedstats.summary([r['F_PLd'] for r in ref]).mean  # the finest setting's seed mean
        same = code == 'sable' and value == finest[knob]
        dm, dse, npair = (0.0, 0.0, len(rs)) if same else paired(rs, ref)
        D, Dc = (0.0, float('nan')) if same else ks(a.work, rs, ref, f'{code}_{knob}{value:g}')
        cost = np.mean([r['atoms'] * r['steps'] for r in rs])
        rows.append(dict(code=code, knob=knob, value=value, n=len(rs), F=m, F_se=se, pairs=npair,
                         err=dm / mr, err_se=dse / mr, ks=D, ks_crit=Dc, cost=cost,
                         t_est=cost / float(ps[code]) if code in ps else float('nan'),
                         wall=np.mean([r['wall_s'] for r in rs]), ps=np.mean([r['PS_per_s'] for r in rs])))
    json.dump(rows, open(os.path.join(OUT, 'summary.json'), 'w'), indent=1)
    lines = ['| code | knob | value | seeds | F/(PLd) ± SE | error vs finest (paired seeds) | KS D of F/F̄ (crit 5 %, '
             'uncorrelated) | particle-steps | one-core s at --ps | measured wall s (loaded host) |',
             '|---|---|---|---|---|---|---|---|---|---|']
    for r in rows:
        lines.append(f'| {r["code"]} | {r["knob"]} | {r["value"]:g} | {r["n"]} | {r["F"]:.4f} ± {r["F_se"]:.4f} | '
                     f'{100 * r["err"]:+.1f} % ± {100 * r["err_se"]:.1f} % ({r["pairs"]}) | {r["ks"]:.3f} '
                     f'({r["ks_crit"]:.3f}) | {r["cost"]:.3g} | {r["t_est"]:.3g} | {r["wall"]:.1f} |')
    lines.append(f'\n--ps (particle-steps per second, one core): {", ".join(a.ps) if a.ps else "not given"}')
    for k, msg in failures(runs):
        lines.append(f'\nFailed: {k}: {msg}')
    open(os.path.join(OUT, 'table.md'), 'w').write('\n'.join(lines) + '\n')
    print('\n'.join(lines))
    figure(rows)


def figure(rows):
    from sable_tools import figstyle
    figstyle.use()
    import matplotlib.pyplot as plt
    fig, axs = plt.subplots(1, 2, figsize=(7.0, 3.0))
    marks = {'dtfrac': 'o', 'N0': 's', 'rate': '^', 'Hd': 'D'}
    xkey = 't_est' if all(np.isfinite(r['t_est']) for r in rows) else 'cost'
    for r in rows:
        c = 'C0' if r['code'] == 'sable' else 'C1'
        lab = f'{r["code"]} {r["knob"]} {r["value"]:g}'
        axs[0].errorbar(r[xkey], 100 * abs(r['err']), yerr=100 * np.nan_to_num(r['err_se']), fmt=marks[r['knob']],
                        color=c, ms=4)
        axs[0].annotate(lab, (r[xkey], 100 * abs(r['err'])), fontsize=5)
        axs[1].plot(r[xkey], r['ks'], marks[r['knob']], color=c, ms=4)
    axs[0].axhline(5, ls='--', color='grey', lw=0.8)
    xl = 'one-core time of the shear (s)' if xkey == 't_est' else 'particle-steps of the shear'
    for ax in axs:
        ax.set_xscale('log')
        ax.set_xlabel(xl)
    axs[0].set_ylabel('|F/(PLd) error| vs finest (%)')
    axs[1].set_ylabel('KS distance of F/F̄ to the finest')
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, 'speed_error.png'), dpi=150)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('what', choices=['run', 'report'])
    p.add_argument('--work', default='/tmp/cavity_speed')
    p.add_argument('--seeds', type=int, nargs='+', default=SEEDS)
    p.add_argument('--no-yade', action='store_true')
    p.add_argument('--ps', nargs='+', help='CODE=particle-steps/s of one core (report), e.g. sable=1.6e7 yade=1e6')
    a = p.parse_args()
    os.makedirs(a.work, exist_ok=True)
    run_all(a) if a.what == 'run' else report(a)


if __name__ == '__main__':
    main()
