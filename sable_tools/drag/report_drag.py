#!/usr/bin/python3
"""Tables and figures of a drag campaign run by run_drag.py.

    /usr/bin/python3 -m sable_tools.drag.report_drag [--out RUNS_DIR] [--report DIR] [--margin 0.1]
        [--time wall|cpu]

Reads RUNS_DIR/cases.json and every RUNS_DIR/<case>/<code>_s<seed>/run.json whose
status is ok, and writes DIR/results.md (default DIR = RUNS_DIR) and the figures
DIR/drag_turns.png, drag_depth.png, drag_stiffness.png and, when some cases form
a speed-against-error series, speed_error.png. Statistics over seeds are
sable_tools/seedstats.py's: per case and code, F_first and F_stat are
the mean over the n seeds +- the seed-to-seed SE, sd / sqrt(n) (none for one seed).
A run's block error (F_stat_err; for F_first, a one-half-turn mean, F_stat_err
sqrt(turns), the sd of one stationary half-turn block) is never added to it; it is
shown as a check, seedstats.block_check: the rms block error over the seed sd
(below 1 when the seed scatter holds the block noise). sable against LIGGGHTS:
Welch's difference of the means with its 90 % interval, and the equivalence test
(TOST, alpha 0.05) against +- margin x |LIGGGHTS mean| (--margin, default 0.10):
'equivalent' when the 90 % interval lies inside; 'n/a (n<2)' when either code has
fewer than two seeds (not judged). Exit status 1 only if a judged row is not shown
equivalent. Times: CPU seconds per run (user + system) and their ratio
LIGGGHTS / sable; wall seconds beside them, not compared.
"""
import argparse, datetime, glob, json, math, os, re, sys

import numpy as np
import matplotlib
import matplotlib.ticker
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402

from sable_tools import seedstats  # noqa: E402  (statistics over seeds)
from sable_tools.drag import run_drag  # noqa: E402  (the deck's numbers)
from sable_tools.readers import ave_time  # noqa: E402  (the torque files)

NAMES = {'sable': 'sable', 'liggghts': 'LIGGGHTS'}
COLORS = {'sable': 'tab:blue', 'liggghts': 'tab:red'}
MARGIN = 0.10  # equivalence margin, fraction of the LIGGGHTS mean (--margin)
SPEED_TOL = 0.05  # the speed-against-error target (issue 21: which settings reach 5 % fastest)
SMOOTH = 5  # 1/100-turn rows per point of the F*(turns) curves


# ---------------------------------------------------------------- reading runs
def torque_curve(folder, rec):
    """(turns, F*) from drag_torque.txt (and a run in pieces' drag_torque_K.txt, in order):
    each row is M_z averaged over the 1/100 turn ending at its step; plotted at the
    window's centre."""
    path = os.path.join(folder, 'drag_torque.txt')
    if not os.path.exists(path):
        return None
    pieces = sorted(glob.glob(os.path.join(folder, 'drag_torque_*.txt')),
                    key=lambda p: int(re.search(r'_(\d+)\.txt$', p).group(1)))
    a = np.concatenate([ave_time.read_rows(p)[1] for p in [path] + pieces])
    s = run_drag.scene(rec['vars'])
    turns = (a[:, 0] - rec['settled']['step0']) / (100 * s['Nrec']) - 0.005
    return turns, 4 * np.abs(a[:, 1]) / s['L'] / s['Fscale']


def load(out):
    """The cases of RUNS_DIR/cases.json, each with its ok runs per code."""
    cases = json.load(open(os.path.join(out, 'cases.json')))['cases']
    for c in cases:
        c['scene'] = run_drag.scene(c['vars'])
        c['runs'] = {}
        for path in sorted(glob.glob(os.path.join(out, c['name'], '*_s*', 'run.json'))):
            rec = json.load(open(path))
            if rec.get('status') == 'ok':
                rec['folder'] = os.path.dirname(path)
                rec['curve'] = torque_curve(rec['folder'], rec)
                c['runs'].setdefault(rec['code'], []).append(rec)
    return [c for c in cases if c['runs']]


# ---------------------------------------------------------------- statistics
def mean_se(values):
    """(mean, seed-to-seed SE, n) over seeds (seedstats.summary; SE nan for one seed)."""
    m = seedstats.summary(values)
    return m.mean, m.se, m.n


def summary(c, code):
    """Per code: F_first, F_stat as (mean, SE, n) (SE: seed-to-seed only), their values over
    the seeds and block checks, wall and CPU time, measured depth."""
    runs = c['runs'].get(code, [])
    res = [r['result'] for r in runs]
    values = {'F_first': [r['F_first'] for r in res], 'F_stat': [r['F_stat'] for r in res]}
    # each run's block noise: F_stat_err for F_stat; F_first is one half-turn mean, whose noise
    # is taken as the sd of one stationary half-turn block, F_stat_err sqrt(turns)
    block = {'F_first': [r['F_stat_err'] * math.sqrt(r['turns']) for r in res],
             'F_stat': [r['F_stat_err'] for r in res]}
    return {**{q: mean_se(v) for q, v in values.items()},
            'values': values,
            'block': {q: seedstats.block_check(block[q], values[q]) for q in values},
            'wall': np.mean([r['wall_s'] for r in runs]) if runs else math.nan,
            'cpu': np.mean([r['cpu_s'] for r in runs]) if runs else math.nan,
            'threads': sorted({r.get('threads', 1) for r in runs}),
            'hL': np.mean([r['result']['h_meas'] for r in runs]) / c['scene']['L'] if runs else math.nan,
            'stored': any(r.get('stored') for r in runs)}


def judge(a, b, margin):
    """sable's values over seeds against LIGGGHTS': (Welch difference, TOST, verdict); the
    margin is a fraction of |LIGGGHTS mean|. Not judged ('n/a (n<2)', None, None) when
    either has fewer than two seeds, or '—' when either has none."""
    if not (a and b):
        return None, None, '—'
    if len(a) < 2 or len(b) < 2:
        return None, None, 'n/a (n<2)'
    d = seedstats.welch_diff(a, b)
    e = seedstats.tost(d, margin * abs(seedstats.summary(b).mean))
    return d, e, 'equivalent' if e.equivalent else 'not shown equivalent'


# ---------------------------------------------------------------- the table
def fmt(m):
    mean, se, n = m
    if not n:
        return '—'
    return f'{mean:.3f} ± {se:.3f} ({n})' if not math.isnan(se) else f'{mean:.3f} ({n})'


def check(x):
    return 'n/a' if math.isnan(x) else f'{x:.2f}'


def times(sm):
    return '—' if math.isnan(sm['wall']) else f"{sm['wall']:.0f} ({sm['cpu']:.0f})"


def series_table(cases, name, clock='wall'):
    """Markdown lines: each case of a speed-against-error series against its reference,
    and per code the fastest setting within SPEED_TOL of it."""
    series = [c for c in cases if name in series_of(c)]
    lines = [f'### series {name}: F_stat against the costliest case (ref)', '',
             '| case | code | particle-steps | F_stat mean ± SE (n) | error vs ref ± combined SE | wall (CPU) s |',
             '|---|---|---|---|---|---|']
    verdicts = []
    for code in ('sable', 'liggghts'):
        ref = reference_case(series, code)
        within = []
        for c in series:
            if code in c['runs']:
                sm = summary(c, code)
                err, comb = rel_error(sm['F_stat'], summary(ref, code)['F_stat'])
                if c is ref:
                    shown = 'ref'
                else:
                    shown = f'{100 * err:.1f} %' + ('' if math.isnan(comb) else f' ± {100 * comb:.1f} %')
                    if err <= SPEED_TOL:
                        within.append((sm[clock], c['name'], None if math.isnan(comb) else err + comb <= SPEED_TOL))
                lines.append(f"| {c['name']} | {NAMES[code]} | {c['scene']['particle_steps']:.3g} | {fmt(sm['F_stat'])} "
                             f"| {shown} | {times(sm)} |")
        if within:
            t, best, sure = min(within)
            verdicts.append(f"- {NAMES[code]}: fastest within {100 * SPEED_TOL:g} % of its reference: {best} "
                            f"({t:.0f} s {clock})" + ('' if sure else ', within the statistical error only '
                                                      '(error + combined SE above 5 %)' if sure is False else
                                                      ' (no seed-to-seed SE: fewer than 2 seeds)'))
    return lines + [''] + verdicts + ['']


def rel_error(a, ref):
    """|a / ref - 1| and its SE from both (mean, SE, n); nan when either has one seed."""
    err = abs(a[0] - ref[0]) / ref[0]
    return err, math.sqrt(a[1] ** 2 + ref[1] ** 2) / ref[0]


def case_table(c, margin):
    """Markdown lines for one case; and whether every judged row was shown equivalent."""
    s = c['scene']
    sm = {code: summary(c, code) for code in ('sable', 'liggghts')}
    hl = sm['sable']['hL'] if not math.isnan(sm['sable']['hL']) else sm['liggghts']['hL']
    lig = 'LIGGGHTS' + (' (stored)' if sm['liggghts']['stored'] else '')
    lines = [f"### {c['name']}: h/L = {s['hL']:g} (measured {hl:.2f}), E* = {s['Estar']:.3g}, "
             f"{s['grains']} grains, {s['turns']:g} turns, dt = {s['dt']:.3g} s", '',
             f'| quantity | sable mean ± SE (n) | block/sd | {lig} mean ± SE (n) | block/sd | sable − LIGGGHTS '
             f'| 90 % interval (margin ± {100 * margin:g} %) | TOST p | result |',
             '|---|---|---|---|---|---|---|---|---|']
    ok = True
    for q in ('F_first', 'F_stat'):
        a, b = sm['sable'][q], sm['liggghts'][q]
        d, e, verdict = judge(sm['sable']['values'][q], sm['liggghts']['values'][q], margin)
        ok = ok and verdict != 'not shown equivalent'
        diff = a[0] - b[0] if a[2] and b[2] else math.nan
        shown = '—' if math.isnan(diff) else f'{diff:+.3f} ({100 * diff / b[0]:+.1f} %)'
        ci = '—' if d is None or math.isnan(d.lo) else f'[{d.lo:+.3f}, {d.hi:+.3f}] (± {e.margin_hi:.3f})'
        p = '—' if e is None or math.isnan(e.p) else f'{e.p:.3f}'
        blk = {code: check(sm[code]['block'][q]) if sm[code][q][2] else '—' for code in sm}
        lines.append(f"| {q} | {fmt(a)} | {blk['sable']} | {fmt(b)} | {blk['liggghts']} | {shown} | {ci} | {p} "
                     f"| {verdict} |")
    cs, cl = sm['sable']['cpu'], sm['liggghts']['cpu']
    ratio = f'LIGGGHTS / sable {cl / cs:.2f}' if cs > 0 and cl > 0 else ''
    cpu = {code: '—' if math.isnan(sm[code]['cpu']) else f"{sm[code]['cpu']:.0f}" for code in sm}
    wall = {code: '—' if math.isnan(sm[code]['wall']) else f"{sm[code]['wall']:.0f}" for code in sm}
    th = '/'.join(str(t) for t in sm['sable']['threads']) or '—'
    lines.append(f"| CPU s per run | {cpu['sable']} | | {cpu['liggghts']} | | {ratio} | | | |")
    lines.append(f"| wall s per run (not compared; sable threads: {th}) | {wall['sable']} | | {wall['liggghts']} "
                 "| | | | | |")
    return lines + [''], ok


def short(v):
    """One code version record, old (sha256 16 hex, checkout_head) or new (commit, commit_source)."""
    if 'commit' in v:
        return f"commit {v['commit'][:12]} ({v.get('commit_source', '?')}), sha256 {v['sha256'][:16]}"
    return ', '.join(f'{k} {x}' for k, x in v.items() if k != 'binary')


def versions(cases):
    """Per code its binaries' versions, and the harness commits (run_drag.py and the deck) of
    the runs; runs made before run.json recorded them say so."""
    v, hv = {}, {}
    for c in cases:
        for code, runs in c['runs'].items():
            for r in runs:
                v.setdefault(code, set()).add(short(r['version']))
                h = r.get('harness')
                key = (f"{h['commit'][:12]}" + (' with uncommitted changes' if h['dirty'] else '') +
                       f", deck sha256 {h['deck_sha256'][:12]}") if h else 'not recorded (runs made before it was)'
                hv[key] = hv.get(key, 0) + 1
    return ([f'- {NAMES.get(k, k)}: ' + '; '.join(sorted(x)) for k, x in v.items()] +
            ['- harness (run_drag.py and the deck): ' + '; '.join(f'{k}: {n} runs' for k, n in sorted(hv.items()))])


def write_markdown(cases, path, margin, figures, clock='wall'):
    lines = [f'# Drag: sable against LIGGGHTS ({datetime.date.today().isoformat()})', '',
             'F* = F / (ρ g D L²), F = 4|M_z|/L. F_first: over turns 0-0.5; F_stat: over the last half of '
             'the turns in half-turn blocks. Mean over seeds ± the seed-to-seed SE, sd/√n (none for one seed; '
             'sable_tools/seedstats.py). block/sd: the runs\' rms block error (F_stat_err; for '
             'F_first, one half-turn, F_stat_err √turns) over the seed sd, a check that should be below 1 '
             '(n/a for one seed); it is not added to the SE. sable − LIGGGHTS: Welch\'s difference with its '
             f'90 % interval; equivalent (TOST, α 0.05) when that interval lies within ± {100 * margin:g} % of the '
             'LIGGGHTS mean; n/a (n<2) when either code has fewer than two seeds (not judged). '
             'CPU: the process\' user + system time per run, and the ratio LIGGGHTS / sable; wall: the process '
             'alone, not compared (sable may run on several threads).', '']
    status = True
    for c in cases:
        t, ok = case_table(c, margin)
        lines += t
        status = status and ok
    for name in series_names(cases):
        lines += series_table(cases, name, clock)
    lines += ['Code versions:'] + versions(cases) + [''] + [f'![{f}]({f})' for f in figures]
    open(path, 'w').write('\n'.join(lines) + '\n')
    return status, lines


# ---------------------------------------------------------------- figures
def seed_mean_curve(runs):
    """Mean over seeds of F*(turns) on the shortest common grid, and the seed sd."""
    curves = [r['curve'] for r in runs if r['curve'] is not None]
    if not curves:
        return None
    n = min(len(t) for t, _ in curves)
    k = np.ones(SMOOTH) / SMOOTH  # running mean over SMOOTH/100 turn
    f = np.array([np.convolve(y[:n], k, 'valid') for _, y in curves])
    t = np.convolve(curves[0][0][:n], k, 'valid')
    mean, sd = seedstats.pointwise(f)
    return t, mean, np.nan_to_num(sd)  # no band (0) for one seed


def study_cases(cases):
    """The cases outside a speed-against-error series (all of them if none is)."""
    plain = [c for c in cases if not series_of(c)]
    return plain or cases


def fig_turns(cases, path):
    cs = study_cases(cases)[:6]
    fig, axes = plt.subplots(1, len(cs), figsize=(3.6 * len(cs), 3), squeeze=False, sharey=True)
    for ax, c in zip(axes[0], cs):
        for code, runs in c['runs'].items():
            m = seed_mean_curve(runs)
            if m is None:
                continue
            t, f, sd = m
            ax.plot(t, f, color=COLORS.get(code), lw=0.8, label=f'{NAMES.get(code, code)} ({len(runs)} seeds)')
            ax.fill_between(t, f - sd, f + sd, color=COLORS.get(code), alpha=0.25, lw=0)
        ax.set_title(f"{c['name']}: h/L {c['scene']['hL']:g}", fontsize=9)
        ax.set_xlabel('turns')
        ax.legend(fontsize=7)
    axes[0][0].set_ylabel(f'F* ({SMOOTH}/100-turn means; band: ± sd over seeds)', fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


def points(cases, x, quantity):
    """Per code: x values, means and SEs of a quantity over the cases."""
    out = {}
    for c in cases:
        for code in c['runs']:
            sm = summary(c, code)
            m, se, _ = sm[quantity]
            xs, ms, ses = out.setdefault(code, ([], [], []))
            xs.append(x(c, sm))
            ms.append(m)
            ses.append(0 if math.isnan(se) else se)
    return out


def fig_scatter(cases, path, x, xlabel, quantities, logx=False, panels=None):
    """F* against x, both codes; with `panels` (case -> label), one panel per label."""
    groups = {}
    for c in cases:
        groups.setdefault(panels(c) if panels else '', []).append(c)
    fig, axes = plt.subplots(1, len(groups), figsize=(4.5 * len(groups), 3.2), squeeze=False, sharey=True)
    for ax, (label, group) in zip(axes[0], sorted(groups.items())):
        for q, marker, fill in zip(quantities, 'os', (True, False)):
            for code, (xs, ms, ses) in points(group, x, q).items():
                ax.errorbar(xs, ms, ses, ls='none', marker=marker, color=COLORS.get(code), capsize=2,
                            mfc=COLORS.get(code) if fill else 'none', label=f'{q} {NAMES.get(code, code)}')
        if logx:
            ax.set_xscale('log')
        ax.set_title(label, fontsize=9)
        ax.set_xlabel(xlabel)
        ax.legend(fontsize=7)
    axes[0][0].set_ylabel('F*')
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


def series_of(c):
    """The speed-against-error series a case belongs to: `series` is a name or a list
    (a base case shared by several series)."""
    v = c.get('series') or []
    return [v] if isinstance(v, str) else list(v)


def series_names(cases):
    return sorted({n for c in cases for n in series_of(c)})


def reference_case(series, code):
    """The series' costliest setting that this code ran: finest step, stiffest, largest."""
    ran = [c for c in series if code in c['runs']]
    return max(ran, key=lambda c: c['scene']['particle_steps']) if ran else None


def fig_speed(cases, path, clock):
    names = series_names(cases)
    fig, axes = plt.subplots(1, len(names), figsize=(4.5 * len(names), 3.4), squeeze=False)
    for ax, name in zip(axes[0], names):
        series = [c for c in cases if name in series_of(c)]
        for code in ('sable', 'liggghts'):
            ref = reference_case(series, code)
            if ref is None:
                continue
            f_ref = summary(ref, code)['F_stat'][0]
            for c in series:
                if code not in c['runs']:
                    continue
                sm = summary(c, code)
                m, se, _ = sm['F_stat']
                y = 100 * abs(m - f_ref) / f_ref
                star = c is ref
                ax.errorbar(sm[clock], y, 0 if math.isnan(se) else 100 * se / f_ref, marker='*' if star else 'o', ms=10 if star else 5,
                            color=COLORS[code], capsize=2, ls='none')
                ax.annotate(c['name'] + (' (ref)' if star else ''), (sm[clock], y), fontsize=6,
                            xytext=(3, 3), textcoords='offset points')
            ax.plot([], [], 'o', color=COLORS[code], label=NAMES[code])
        ax.set_xscale('log')
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_xlabel(f'{clock} time per run (s)')
        ax.set_ylabel('|F_stat / F_stat(ref) − 1| (%)')
        ax.set_title(f'series {name} (ref: star, each code its own)', fontsize=9)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


def depth_panel(c):
    """The depth figure's panels: one per stiffness and bed preparation (friction while poured)."""
    mu = c['vars'].get('muprep')
    return f"E* = {c['scene']['Estar']:.2g}" + (f", poured with μ {float(mu):g}" if mu is not None else '')


def figures(cases, folder, clock):
    out = ['drag_turns.png', 'drag_depth.png', 'drag_stiffness.png']
    fig_turns(cases, os.path.join(folder, out[0]))
    fig_scatter(study_cases(cases), os.path.join(folder, out[1]), lambda c, sm: sm['hL'], 'h/L (measured)',
                ('F_stat', 'F_first'), panels=depth_panel)
    fig_scatter(cases, os.path.join(folder, out[2]), lambda c, sm: c['scene']['Estar'], 'E* = E / (ρ g d)',
                ('F_stat',), logx=True)
    if series_names(cases):
        out.append('speed_error.png')
        fig_speed(cases, os.path.join(folder, out[-1]), clock)
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--out', default=os.path.join(run_drag.REPO, 'build', 'drag_runs'), help='the runs folder')
    p.add_argument('--report', default=None, help='where results.md and the figures go (default: --out)')
    p.add_argument('--margin', type=float, default=MARGIN,
                   help='equivalence margin, fraction of the LIGGGHTS mean (default 0.10)')
    p.add_argument('--time', choices=('wall', 'cpu'), default='wall',
                   help='the speed plot\'s clock (cpu: for runs made on a busy machine)')
    args = p.parse_args()
    folder = args.report or args.out
    os.makedirs(folder, exist_ok=True)
    cases = load(args.out)
    if not cases:
        sys.exit(f'no finished runs in {args.out}')
    figs = figures(cases, folder, args.time)
    ok, lines = write_markdown(cases, os.path.join(folder, "results.md"), args.margin, figs, args.time)
    print('\n'.join(l for l in lines if l.startswith(('|', '###'))))
    print(f"written: {os.path.join(folder, 'results.md')} and {', '.join(figs)}")
    sys.exit(0 if ok else 1)


if __name__ == '__main__':
    main()
