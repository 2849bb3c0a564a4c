#!/usr/bin/python3
"""sable against YADE on petit2017's Mohr protocol (issue 44 item 7), on the same packings.

    /usr/bin/python3 -m sable_tools.mohr.compare_mohr [--seeds S ...] [--N 500] [--cycles 3]
        [--var NAME VALUE ...] [--ref yade|yade-stored] [--store] [--out DIR] [--sable PATH] [--yade PATH]

For each seed, sable runs input_scripts/mohr/mohr.in (-var N, cycles, seed, out m and the
--var pairs) in DIR/sable/seed_S/; it writes the packing m_pack.dump and m_states.txt. YADE then
runs input_scripts/mohr/mohr_yade.py (the hand translation; sable --export-yade refuses this
protocol) in DIR/yade/seed_S/ from a copy of that packing, with the same parameters and the
dt, H, dy, nramp of sable's states header, and writes m_yade_states.txt (same columns).

Per run: mu_M of the first and of the last cycle (sable-analyze mohr-cycles), K (Eq. 6,
sable-analyze bulk-modulus) of the last loading increment of the last cycle, Z, porosity,
sigma_yy and sigma_xx at the first and the last cycle's peak (eps 0.15), states and capped
relaxations. Per code the mean and the seed-to-seed standard error SE = sd / sqrt(n); a
quantity passes when |mean_sable - mean_yade| <= 2 sqrt(SE_s^2 + SE_y^2) (as
sable_tools/compare_seeds.py). The paired difference (same packing in both codes) is shown
too, not judged. Writes DIR/compare.md, DIR/compare.csv, DIR/compare.json and
DIR/mohr_circles.png (both codes' loading Mohr circles of the first and last cycle and their
envelopes, one row per seed, the first --figure-seeds; --replot redraws it and runs nothing). Exit status 0 when every judged quantity passes.

--store (with --ref yade): YADE's per-seed reductions and states files go to
reference_runs/reference/mohr/yade/ with the sha256 of mohr.in and mohr_yade.py, the
parameters, the seeds and each seed's packing. --ref yade-stored compares sable (run now) with
them without running YADE; refused before anything runs when mohr.in or mohr_yade.py changed
since, or the parameters or seeds differ, and after sable's runs when a packing differs from
the one YADE started from.
"""
import argparse, csv, datetime, hashlib, json, os, shutil, subprocess, sys

from sable_tools.mohr import mohr_report  # the states files' one reader; mean_se: seedstats.summary
from sable_tools import runner, seedstats  # the runs into their logs; the agreement test
from sable_tools.paths import REPO
from sable_tools.readers import analyze as analyze_csv, yade  # sable-analyze's CSV; the states files

HERE = os.path.join(REPO, 'input_scripts', 'mohr')  # mohr.in and mohr_yade.py
DECK = os.path.join(HERE, 'mohr.in')
YSCRIPT = os.path.join(HERE, 'mohr_yade.py')
STORED = os.path.join(REPO, 'reference_runs', 'reference', 'mohr', 'yade')
SEEDS = ['32452843', '15485867', '49979687', '67867967', '86028121']
DEFAULTS = {'N': '500', 'cycles': '3'}
# judged quantities (name, text); the others are listed, not judged
JUDGED = ['muM_c1', 'muM_last', 'K_last', 'Z_peak_c1', 'Z_peak_last', 'porosity_peak_last',
          'syy_peak_c1', 'sxx_peak_c1', 'syy_peak_last', 'sxx_peak_last']
INFO = ['states', 'capped', 'steps']


def sha256(path):
    return hashlib.sha256(open(path, 'rb').read()).hexdigest()


def show(p):
    return os.path.relpath(p, REPO)


def read_states(path):
    return yade.read_states(path)[1]


def analyze(args, *cmd):
    r = runner.analyze(cmd)
    if r.returncode:
        sys.exit(f'sable-analyze {" ".join(cmd)} failed:\n{r.stdout}{r.stderr}')


def reduce(states_path, workdir):
    """The per-run quantities of one states file (sable's or YADE's)."""
    rows = read_states(states_path)
    mc, bk = os.path.join(workdir, 'mohr_cycles.csv'), os.path.join(workdir, 'bulk_modulus.csv')
    analyze(None, 'mohr-cycles', states_path, '--sxx', 'sxx', '--syy', 'syy', '--cycle', 'cycle',
            '--loading', 'loading', '--out', mc)
    analyze(None, 'bulk-modulus', states_path, '--syy', 'syy', '--sxx', 'sxx', '--eyy', 'eps', '--cycle', 'cycle',
            '--loading', 'loading', '--out', bk)
    env = analyze_csv.rows(mc)
    kr = analyze_csv.rows(bk)  # row,cycle,syy,syy_mid,eyy,K: one row per Eq. 6 increment
    last = int(max(r['cycle'] for r in rows))
    peaks = {}
    for c in (1, last):
        ld = [r for r in rows if int(r['cycle']) == c and r['loading'] == 1]
        peaks[c] = ld[-1]
    if int(kr[-1]['cycle']) != last:
        sys.exit(f'{states_path}: the last Eq. 6 increment is of cycle {kr[-1]["cycle"]}, not {last}')
    out = {'muM_c1': float(env[0]['mu_M']), 'muM_last': float(env[-1]['mu_M']),
           'C_c1': float(env[0]['C']), 'C_last': float(env[-1]['C']), 'K_last': float(kr[-1]['K'])}
    for tag, c in (('c1', 1), ('last', last)):
        out[f'Z_peak_{tag}'] = peaks[c]['Z']
        out[f'porosity_peak_{tag}'] = peaks[c]['porosity']
        out[f'syy_peak_{tag}'] = peaks[c]['syy']
        out[f'sxx_peak_{tag}'] = peaks[c]['sxx']
    out['states'] = float(len(rows))
    out['capped'] = sum(r['capped'] for r in rows)
    out['steps'] = sum(r['steps'] for r in rows)
    return out, env


def trim_log(src, dst):
    """STATE/PEAK/RESULT lines, errors and warnings, and the last 15 lines."""
    lines = open(src, errors='replace').read().splitlines()
    keep = [l for l in lines if l.startswith(('STATE', 'PEAK', 'RESULT', 'ERROR', 'WARNING', 'Traceback'))]
    tail = [l for l in lines[-15:] if l not in keep]
    open(dst, 'w').write('\n'.join(keep + ['# ---- last lines (others)'] + tail) + '\n')


def run(cmd, cwd, log, timeout):
    rc = runner.run_logged(cmd, cwd, log, timeout=timeout)
    if rc is None:
        return f'timed out after {timeout} s'
    return None if rc == 0 else f'exit status {rc}'


def figure(path, seeds, states, envs):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    import numpy as np
    nrow = len(seeds)
    fig, axes = plt.subplots(nrow, 2, figsize=(8, 2.3 * nrow + 0.4), squeeze=False)
    th = np.linspace(0, np.pi, 60)
    style = {'sable': dict(color='tab:blue', ls='-'), 'yade': dict(color='tab:red', ls='--')}
    for i, s in enumerate(seeds):
        for j, which in enumerate(('first', 'last')):
            ax = axes[i][j]
            smax = 0
            for code in ('sable', 'yade'):
                rows = states[code][s]
                last = int(max(r['cycle'] for r in rows))
                c = 1 if which == 'first' else last
                env = envs[code][s][0 if which == 'first' else -1]
                for r in rows:
                    if int(r['cycle']) != c or r['loading'] != 1:
                        continue
                    cen, rad = 0.5 * (r['syy'] + r['sxx']) / 1e6, 0.5 * abs(r['syy'] - r['sxx']) / 1e6
                    ax.plot(cen + rad * np.cos(th), rad * np.sin(th), lw=0.6, alpha=0.8, **style[code])
                    smax = max(smax, cen + rad)
                mu, C = float(env['mu_M']), float(env['C']) / 1e6
                x = np.array([0, smax])
                ax.plot(x, C + mu * x, lw=1.6, color=style[code]['color'], ls=style[code]['ls'],
                        label=f'{code}: $\\mu_M$ {mu:.3f}')
            ax.set_xlim(0, smax * 1.02)
            ax.set_ylim(0, None)
            ax.set_aspect('equal', adjustable='box')
            ax.set_title(f'seed {s}, {which} cycle (c{c})', fontsize=8)
            ax.legend(fontsize=7, loc='upper left')
            ax.tick_params(labelsize=7)
            if i == nrow - 1:
                ax.set_xlabel(r'$\sigma$ (MPa)', fontsize=8)
            if j == 0:
                ax.set_ylabel(r'$\tau$ (MPa)', fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=72)
    plt.close(fig)


def judge(values, seeds):
    """The table's rows (per quantity: each code's mean and seed-to-seed SE, the difference and its
    tolerance 2 sqrt(SE_s^2 + SE_y^2), the paired difference) and whether every JUDGED quantity
    agrees within its tolerance. values: {code: {seed: {quantity: value}}}."""
    ok = True
    rows = []
    for q in JUDGED + INFO:
        vs = [values['sable'][s][q] for s in seeds if s in values['sable']]
        vy = [values['yade'][s][q] for s in seeds if s in values['yade']]
        ms, ses, ns = mohr_report.mean_se(vs)
        my, sey, ny = mohr_report.mean_se(vy)
        se = seedstats.combined_se(ses, sey)
        diff = ms - my
        pd = [values['sable'][s][q] - values['yade'][s][q] for s in seeds
              if s in values['sable'] and s in values['yade']]
        pm, pse, _ = mohr_report.mean_se(pd)
        if q in JUDGED:
            passed = bool(seedstats.agrees(diff, se, 2.0))  # |diff| <= 2 combined SE; False without an SE
            res = 'PASS' if passed else 'FAIL'
            ok = ok and passed
        else:
            res = 'not judged'
        rows.append({'quantity': q, 'sable_mean': ms, 'sable_se': ses, 'yade_mean': my, 'yade_se': sey,
                     'n': min(ns, ny), 'diff': diff, 'tolerance': 2 * se, 'paired_diff': pm, 'paired_se': pse,
                     'result': res})
    return rows, ok


def run_seeds(a, variables, extra, codes):
    """Each seed: sable's deposit and protocol in OUT/sable/seed_S, YADE's from that packing in
    OUT/yade/seed_S when 'yade' is in codes; their reductions. Returns (values, states, envs:
    {code: {seed: ...}}, packs: the packing's sha256 per seed, errors)."""
    values = {c: {} for c in ('sable', 'yade')}
    states = {c: {} for c in ('sable', 'yade')}
    envs = {c: {} for c in ('sable', 'yade')}
    packs, errors = {}, []
    for s in a.seeds:
        sd = os.path.join(a.out, 'sable', f'seed_{s}')
        os.makedirs(sd, exist_ok=True)
        cmd = [a.sable, '-in', DECK, '-var', 'seed', s, '-var', 'out', 'm']
        for k, v in variables.items():
            cmd += ['-var', k, v]
        print(f'sable seed {s} ...', flush=True)
        err = run(cmd, sd, os.path.join(sd, 'screen.txt'), a.timeout)
        if err:
            errors.append(f'sable seed {s}: {err}')
            continue
        packs[s] = sha256(os.path.join(sd, 'm_pack.dump'))
        for c in codes[1:]:
            yd = os.path.join(a.out, 'yade', f'seed_{s}')
            os.makedirs(yd, exist_ok=True)
            shutil.copy(os.path.join(sd, 'm_pack.dump'), yd)
            ycmd = [a.yade, '-n', '-x', YSCRIPT, '--out', 'm', '--states', os.path.join(sd, 'm_states.txt'),
                    '--cycles', variables['cycles']] + [x for k, v in extra.items() for x in (f'--{k}', v)]
            print(f'yade seed {s} ...', flush=True)
            err = run(ycmd, yd, os.path.join(yd, 'screen.txt'), a.timeout)
            if err:
                errors.append(f'yade seed {s}: {err}')
            else:
                values['yade'][s], envs['yade'][s] = reduce(os.path.join(yd, 'm_yade_states.txt'), yd)
                states['yade'][s] = read_states(os.path.join(yd, 'm_yade_states.txt'))
            trim_log(os.path.join(yd, 'screen.txt'), os.path.join(yd, 'log.txt'))
            for f in ('screen.txt', 'm_pack.dump'):
                os.remove(os.path.join(yd, f))
        values['sable'][s], envs['sable'][s] = reduce(os.path.join(sd, 'm_states.txt'), sd)
        states['sable'][s] = read_states(os.path.join(sd, 'm_states.txt'))
        trim_log(os.path.join(sd, 'screen.txt'), os.path.join(sd, 'log.txt'))
        for f in ('screen.txt', 'log.sable', 'm_pack.dump', 'm_peak_c1.txt', 'm_peak_last.txt'):
            if os.path.exists(os.path.join(sd, f)):
                os.remove(os.path.join(sd, f))
    return values, states, envs, packs, errors


def report_lines(rows, values, seeds, variables, refnote, sable, errors, ok):
    """compare.md's lines: the setting, the judged table, each seed's values, errors, the verdict."""
    g = lambda v: f'{v:.5g}'  # noqa: E731
    lines = [f'# Mohr protocol (petit2017): sable vs YADE on the same packings ({datetime.date.today().isoformat()})', '',
             '`input_scripts/mohr/mohr.in`' + ''.join(f' -var {k} {v}' for k, v in variables.items()) +
             f', seeds {" ".join(seeds)}; YADE: `input_scripts/mohr/mohr_yade.py` from each sable packing. '
             'Mean ± seed-to-seed SE per code; tolerance 2 sqrt(SE_s^2 + SE_y^2); paired: mean ± SE of the '
             'per-seed difference sable - YADE (same packing; not judged). Stresses in Pa, K in Pa.', '',
             f'- {refnote}', f'- sable: `{sable}` ran now', '',
             '| quantity | sable | YADE | n | diff | tolerance | paired diff | result |', '|---|---|---|---|---|---|---|---|']
    for r in rows:
        lines.append(f'| {r["quantity"]} | {g(r["sable_mean"])} ± {r["sable_se"]:.2g} | {g(r["yade_mean"])} ± '
                     f'{r["yade_se"]:.2g} | {r["n"]} | {r["diff"]:.3g} | {r["tolerance"]:.3g} | '
                     f'{r["paired_diff"]:.3g} ± {r["paired_se"]:.2g} | {r["result"]} |')
    lines += ['', '| seed | code | ' + ' | '.join(JUDGED[:5]) + ' |', '|---|---|' + '---|' * 5]
    for s in seeds:
        for c in ('sable', 'yade'):
            if s in values[c]:
                lines.append(f'| {s} | {c} | ' + ' | '.join(g(values[c][s][q]) for q in JUDGED[:5]) + ' |')
    lines += [''] + [f'- error: {e}' for e in errors] + ['', f'**{"PASS" if ok else "FAIL"}**']
    return lines


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--seeds', nargs='+', default=SEEDS)
    p.add_argument('--N', default=DEFAULTS['N'])
    p.add_argument('--cycles', default=DEFAULTS['cycles'])
    p.add_argument('--var', nargs=2, action='append', default=[], metavar=('NAME', 'VALUE'),
                   help="more of mohr.in's variables (mu, rotation, delta, E, deps, thr, cap, damp, e, dtfrac, "
                        "ramp, piston, thick), given to both codes")
    p.add_argument('--ref', choices=['yade', 'yade-stored'], default='yade')
    p.add_argument('--store', action='store_true', help='store the YADE reductions (with --ref yade)')
    p.add_argument('--out', default=os.path.join(REPO, 'reference_runs', 'mohr', 'compare'))
    p.add_argument('--sable', default=runner.built('sable'))
    p.add_argument('--yade', default='yade')
    p.add_argument('--timeout', type=float, default=1800)
    p.add_argument('--figure-seeds', type=int, default=3, help='seeds drawn in mohr_circles.png (the first K)')
    p.add_argument('--replot', action='store_true',
                   help="redraw DIR/mohr_circles.png from DIR's states and mohr_cycles.csv files; runs nothing")
    a = p.parse_args()
    a.sable, a.out = os.path.abspath(a.sable), os.path.abspath(a.out)
    if a.replot:
        states, envs = {'sable': {}, 'yade': {}}, {'sable': {}, 'yade': {}}
        for s in a.seeds:
            for c, f in (('sable', 'm_states.txt'), ('yade', 'm_yade_states.txt')):
                d = os.path.join(a.out, c, f'seed_{s}')
                yp = os.path.join(STORED, f'seed_{s}_yade_states.txt')
                states[c][s] = read_states(os.path.join(d, f) if os.path.exists(os.path.join(d, f)) else yp)
                if os.path.exists(os.path.join(d, 'mohr_cycles.csv')):
                    envs[c][s] = analyze_csv.rows(os.path.join(d, 'mohr_cycles.csv'))
                else:
                    envs[c][s] = json.load(open(os.path.join(STORED, 'results.json')))['envelopes'][s]
        figure(os.path.join(a.out, 'mohr_circles.png'), a.seeds[:a.figure_seeds], states, envs)
        print(f'written: {show(os.path.join(a.out, "mohr_circles.png"))}')
        return
    stored = a.ref == 'yade-stored'
    extra = dict(a.var)
    for k in ('N', 'cycles', 'seed', 'out'):
        if k in extra:
            sys.exit(f'--var {k}: use --N, --cycles, --seeds (out is fixed)')
    variables = {'N': a.N, 'cycles': a.cycles, **extra}
    made_from = {'mohr.in': sha256(DECK), 'mohr_yade.py': sha256(YSCRIPT)}
    if a.store and stored:
        sys.exit('--store writes the reference from a YADE run: use --ref yade')
    if not stored and not shutil.which(a.yade):
        sys.exit(f'{a.yade} is not on PATH (apt-get install yade), or use --ref yade-stored')
    if stored:  # before anything runs
        path = os.path.join(STORED, 'results.json')
        if not os.path.exists(path):
            sys.exit(f'no stored YADE reference ({show(path)}): run with --ref yade --store')
        rec = json.load(open(path))
        changed = [f for f in made_from if rec['made_from'].get(f) != made_from[f]]
        if changed:
            sys.exit(f'the stored YADE reference {show(path)} was made from another {" and ".join(changed)} '
                     f'(sha256 differs): rerun with --ref yade --store')
        if rec['vars'] != variables:
            sys.exit(f'the stored YADE reference was made with {rec["vars"]}, not {variables}')
        missing = [s for s in a.seeds if s not in rec['seeds']]
        if missing:
            sys.exit(f'the stored YADE reference has no seed {" ".join(missing)} (it has {" ".join(rec["seeds"])})')
    codes = ['sable'] + ([] if stored else ['yade'])
    values, states, envs, packs, errors = run_seeds(a, variables, extra, codes)
    if stored:
        bad = [s for s in a.seeds if s in packs and packs[s] != rec['pack_sha256'][s]]
        if bad:
            sys.exit(f'sable deposited other packings than YADE started from (seeds {" ".join(bad)}): '
                     'the stored YADE reference is not for them; rerun with --ref yade --store')
        for s in a.seeds:
            values['yade'][s] = rec['values'][s]
            sp = os.path.join(STORED, f'seed_{s}_yade_states.txt')
            states['yade'][s] = read_states(sp)
            envs['yade'][s] = rec['envelopes'][s]
        refnote = f'YADE: stored in {show(STORED)} (run of {rec["date"]}, {rec.get("yade", "?")}), not run now'
    else:
        ver = subprocess.run([a.yade, '--version'], capture_output=True, text=True).stdout.split('\n')[0].strip()
        refnote = f'YADE: `{shutil.which(a.yade)}` ({ver}) ran now'
        if a.store:
            if errors:
                sys.exit('a run failed, reference not stored: ' + '; '.join(errors))
            if {'mohr.in': sha256(DECK), 'mohr_yade.py': sha256(YSCRIPT)} != made_from:
                sys.exit('mohr.in or mohr_yade.py changed while YADE ran: reference not stored')
            os.makedirs(STORED, exist_ok=True)
            for s in a.seeds:
                shutil.copy(os.path.join(a.out, 'yade', f'seed_{s}', 'm_yade_states.txt'),
                            os.path.join(STORED, f'seed_{s}_yade_states.txt'))
            json.dump({'code': 'yade', 'yade': ver, 'date': datetime.date.today().isoformat(), 'vars': variables,
                       'seeds': a.seeds, 'made_from': made_from, 'pack_sha256': packs, 'values': values['yade'],
                       'envelopes': envs['yade']}, open(os.path.join(STORED, 'results.json'), 'w'), indent=1)
            print(f'stored the YADE reference in {show(STORED)}')
    # ---- the table
    rows, passed = judge(values, a.seeds)
    ok = not errors and passed
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, 'compare.csv'), 'w', newline='') as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f'{v:.10g}' if isinstance(v, float) else v) for k, v in r.items()})
    lines = report_lines(rows, values, a.seeds, variables, refnote, a.sable, errors, ok)
    open(os.path.join(a.out, 'compare.md'), 'w').write('\n'.join(lines) + '\n')
    json.dump({'vars': variables, 'seeds': a.seeds, 'ref': a.ref, 'values': values, 'rows': rows, 'errors': errors},
              open(os.path.join(a.out, 'compare.json'), 'w'), indent=1)
    seeds_ok = [s for s in a.seeds if s in states['sable'] and s in states['yade']]
    if seeds_ok:
        figure(os.path.join(a.out, 'mohr_circles.png'), seeds_ok[:a.figure_seeds], states, envs)
    print('\n'.join(lines))
    print(f'written: {show(os.path.join(a.out, "compare.md"))}, compare.csv, compare.json, mohr_circles.png')
    sys.exit(0 if ok else 1)


if __name__ == '__main__':
    main()
