#!/usr/bin/python3
"""How much of the bed's weight the container's side wall carries, and what that does to
the pressure at the cylinder (Janssen screening), from sable runs of drag.in with
`-var load 1` (drag_load*.txt: the vertical force on floor, side wall and cylinder per
half-turn).

    /usr/bin/python3 -m sable_tools.drag.wall_load RUNS_DIR [--md OUT.md] [--png OUT.png]

Per run: the side wall's share s of the weight W (grains x m g) in the first half-turn and
over the stationary half-turns (the last `turns`), and the Janssen length lambda that gives
that share in a bed of height H (top grain + r): with the mean vertical stress
sigma(z) = rho_b g lambda (1 - exp(-z / lambda)) at depth z, the wall carries
    s = 1 - (lambda / H) (1 - exp(-H / lambda)).
A negative share (the wall pushing the bed down: a bed dilating upward against the wall's
friction, as in the first half-turn) gives a negative lambda: the stress grows faster than
hydrostatic.
J = (lambda / h) (1 - exp(-h / lambda)) is then the mean vertical stress at the axis' depth h
over the hydrostatic one: a drag proportional to the local pressure grows as h J(h).
F / (h/L J) is the drag with that screening taken out; the paper's effect (a stationary drag
that stops growing with depth) is the part of the flattening that this does not explain.
Per case the drags are those of every ok sable run, with or without load files (mean +- SE as in
report_drag.py); the shares and J are the means over the runs with load files.
"""
import argparse, glob, math, os, re, sys

import numpy as np

from sable_tools import seedstats  # the means over the seeds with load files
from sable_tools.drag import report_drag  # the runs and their statistics
from sable_tools.drag import run_drag  # the deck's numbers
from sable_tools.readers import ave_time  # the load files (fix ave/time)

G = 9.81


def load_rows(folder):
    """(floor, side, cylinder) vertical forces per half-turn, pieces in order."""
    paths = glob.glob(os.path.join(folder, 'drag_load*.txt'))
    key = lambda p: int(m.group(1)) if (m := re.search(r'_load_(\d+)\.txt$', p)) else 0
    rows = [ave_time.read_rows(p)[1] for p in sorted(paths, key=key)]  # step, f_floor[3], f_side[3], f_cyl[3]
    return np.concatenate(rows)[:, 1:4] if rows else None


def share_of(x):
    """Side-wall share of a bed of height H with x = H / lambda (x < 0: the wall pushes the bed down)."""
    return 0.0 if x == 0 else 1 + math.expm1(-x) / x


def janssen_length(share, H):
    """lambda with share_of(H / lambda) = share (bisection; share_of rises from -inf to 1)."""
    if share >= 1:
        return 0.0
    lo, hi = -30.0, 1e3
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if share_of(mid) < share else (lo, mid)
    x = 0.5 * (lo + hi)
    return math.inf if x == 0 else H / x


def screening(lam, h):
    """Mean vertical stress at depth h over rho_b g h (> 1 when the wall pushes down, lambda < 0)."""
    return 1.0 if math.isinf(lam) else 1 - share_of(h / lam)


def run_load(rec, folder):
    rows = load_rows(folder)
    if rows is None:
        return None
    s = run_drag.scene(rec['vars'])
    r = rec['result']
    W = r['grains'] * s['rho'] * math.pi * s['d'] ** 3 / 6 * G
    H = rec['settled']['level'] + 0.5 * s['d']
    turns = int(r['turns'])
    side = -rows[:, 1] / W
    out = {'first': side[0], 'stat': float(np.mean(side[-turns:])), 'cyl': float(np.mean(rows[-turns:, 2])) / W,
           'H': H, 'h': r['h_meas'], 'L': s['L']}
    for k in ('first', 'stat'):
        lam = janssen_length(out[k], H)
        out['lam_' + k] = lam / s['L']
        out['J_' + k] = screening(lam, r['h_meas'])
    return out


def cases(out):
    """Per case with load files: the shares and J (mean over those runs) and the drags of
    every sable run (report_drag's mean and SE)."""
    rows = []
    for c in report_drag.load(out):
        runs = c['runs'].get('sable', [])
        loads = [ld for r in runs if (ld := run_load(r, r['folder']))]
        if not loads:
            continue
        sm = report_drag.summary(c, 'sable')
        row = {'case': c['name'], 'hL': sm['hL'], 'seeds': len(runs), 'load_seeds': len(loads),
               'grains': int(runs[0]['result']['grains']), 'cyl': seedstats.summary([ld['cyl'] for ld in loads]).mean}
        for k in ('first', 'stat'):
            row['F_' + k] = sm['F_' + k][:2]
            row['share_' + k] = seedstats.summary([ld[k] for ld in loads]).mean
            for q in ('lam_', 'J_'):
                row[q + k] = seedstats.summary([ld[q + k] for ld in loads]).mean
            row['Fn_' + k] = row['F_' + k][0] / (row['hL'] * row['J_' + k])
        rows.append(row)
    return sorted(rows, key=lambda r: r['hL'])


def pm(v):
    m, e = v
    return f'{m:.2f}' + (f' ± {e:.2f}' if e == e else '')


def table(rows):
    out = ['Drags: mean over the seeds ± the seed-to-seed SE (report_drag.summary; none for one seed). '
           'Shares, lambda, J and the lift: the runs with load files (drag.in -var load 1). '
           'A negative share: the side wall pushes the bed down.', '',
           '| h/L | grains | seeds (with loads) | side-wall share: first half-turn / stationary | '
           'lambda/L first / stationary | J(h) first / stationary | cylinder lift share | '
           'F_first | F_stat | F_first / (h/L J) | F_stat / (h/L J) |',
           '|' + '---|' * 11]
    for r in rows:
        out.append(f"| {r['hL']:.2f} | {r['grains']} | {r['seeds']} ({r['load_seeds']}) | "
                   f"{r['share_first']:.3f} / {r['share_stat']:.3f} | {r['lam_first']:.1f} / {r['lam_stat']:.1f} | "
                   f"{r['J_first']:.3f} / {r['J_stat']:.3f} | {r['cyl']:.3f} | {pm(r['F_first'])} | {pm(r['F_stat'])} | "
                   f"{r['Fn_first']:.2f} | {r['Fn_stat']:.2f} |")
    return '\n'.join(out)


def figure(rows, path):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    h = np.array([r['hL'] for r in rows])
    for k, c in (('first', 'tab:orange'), ('stat', 'tab:blue')):
        F = np.array([r['F_' + k][0] for r in rows])
        e = np.array([r['F_' + k][1] or 0 for r in rows])
        ax[0].errorbar(h, F, e, fmt='o', color=c, capsize=3, label=f'F_{k}')
        # the drag a pressure-proportional law gives through the shallowest point, with the
        # measured screening
        ax[0].plot(h, F[0] / (h[0] * rows[0]['J_' + k]) * h * np.array([r['J_' + k] for r in rows]), '--', color=c,
                   label=f'F_{k} ∝ h J(h) (Janssen, through the first point)')
        ax[1].plot(h, [r['share_' + k] for r in rows], 'o-', color=c, label=f'side-wall share, {k}')
    ax[0].set(xlabel='h / L', ylabel='F*', title='drag and the Janssen-screened pressure')
    ax[1].axhline(0, color='k', lw=0.6)
    ax[1].set(xlabel='h / L', ylabel='share of the weight (< 0: the wall pushes the bed down)',
              title='weight carried by the side wall')
    for a in ax:
        a.legend(fontsize=7)
        a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('runs')
    p.add_argument('--md')
    p.add_argument('--png')
    a = p.parse_args()
    rows = cases(a.runs)
    if not rows:
        sys.exit(f'{a.runs}: no sable run with drag_load*.txt (run drag.in with -var load 1)')
    text = table(rows)
    print(text)
    if a.md:
        open(a.md, 'w').write(text + '\n')
    if a.png:
        figure(rows, a.png)


if __name__ == '__main__':
    main()
