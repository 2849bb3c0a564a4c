#!/usr/bin/python3
"""Where does the time step become unsafe? Sweeps dt on two small decks and writes a table
(sweep.md) and a figure (sweep.png) next to this file (issue 47 item 6; REPORT.md reads them).

collision: two grains (r = 1 mm, rho = 2500, nu = 0.3) meet head on at v_rel, Hertz law
  (pair_style gran model hertz), restitution e = 1 (no damping: the kinetic energy after must
  equal the one before) or e = 0.5. Measured: e_meas = (v2 - v1)_after / v_rel against the
  converged value (dt = 0.005 t_c) and, for e = 1, against 1. t_c is the Hertz contact time
  2.87 (m*^2 / (R* E*^2 v_rel))^(1/5), m* = m/2, R* = r/2, E* = E / (2 (1 - nu^2)); each point is
  the worst of three contact phases (where the first touch falls within a step).
bed: 30 grains poured by fix insert/pack onto a floor in a periodic box, gravity g (g = 981
  is a bed under load: overlaps of a bed 100 times deeper), settled for T, then run T/2 more.
  Measured: kinetic energy at the end over the bed's N m g d (blow-up: grains lost, non-finite
  state, or that ratio above 1), against dt / t_R and dt over the contact time that sable's setup
  check weighs (Hertz time at twice the free-fall speed across the 12 mm box).

  /usr/bin/python3 input_scripts/stability/sweep.py --fine     (what REPORT.md shows, ~3 min)
  options: --sable BIN (default build/sable), --quick, --only collision|bed, --replot
"""
import argparse
import json
import math
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, REPO)
from sable_tools.runner import execute, find_sable  # noqa: E402  (the one runner of the studies)
R, RHO, NU = 0.001, 2500.0, 0.3


def rayleigh(E):
    G = E / (2 * (1 + NU))
    return math.pi * R * math.sqrt(RHO / G) / (0.1631 * NU + 0.8766)


def hertz_time(E, v):
    m = 4 / 3 * math.pi * R ** 3 * RHO
    ms, rs, es = m / 2, R / 2, E / (2 * (1 - NU ** 2))
    return 2.87 * (ms * ms / (rs * es * es * v)) ** 0.2


MATERIALS = """fix m1 all property/global youngsModulus peratomtype {E}
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 {e}
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
"""


def collision_deck(E, e, v, dt, phase):
    # Gap so that the first touch falls `phase` of a step into the run; enough steps for 3 t_c.
    gap = (1.0 + phase) * v * dt
    steps = int(3 * hertz_time(E, v) / dt) + 4
    x = R + gap / 2
    return f"""units si
atom_style granular
atom_modify map array
boundary f f f
region box block -0.05 0.05 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor {max(0.0005, 2 * v * dt):g} bin
neigh_modify delay 0
soft_particles yes
{MATERIALS.format(E=E, e=e)}pair_style gran model hertz tangential history
pair_coeff * *
create_atoms 1 single {-x:.17g} 0 0 units box
create_atoms 1 single {x:.17g} 0 0 units box
set group all diameter {2 * R} density {RHO}
set atom 1 vx {v / 2:.17g}
set atom 2 vx {-v / 2:.17g}
timestep {dt:.17g}
timestep_check accept
fix i all nve/sphere
run {steps}
print "RESULT vx1=$(vx[1]:%.17g) vx2=$(vx[2]:%.17g) x1=$(x[1]:%.17g) x2=$(x[2]:%.17g)"
"""


N_BED, LZ = 30, 0.012


def bed_deck(E, g, dt, T, N=N_BED):
    steps = int(T / dt) + 1
    return f"""units si
atom_style granular
atom_modify map array
boundary p p f
region box block 0 0.008 0 0.008 0 0.012 units box
create_box 1 box
neighbor 0.0004 bin
neigh_modify delay 0
soft_particles yes
{MATERIALS.format(E=E, e=0.5)}pair_style gran model hertz tangential history
pair_coeff * *
timestep {dt:.17g}
timestep_check accept
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant {RHO} radius constant {R}
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
region ins block 0 0.008 0 0.008 0.001 0.0115 units box
fix ins all insert/pack seed 49979687 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region {N} region ins
fix g all gravity {g} vector 0 0 -1
fix i all nve/sphere
thermo_modify lost ignore
run {steps}
print "RESULT ke1=$(ke:%.17g) n1=$(atoms)"
run {steps // 2}
print "RESULT ke2=$(ke:%.17g) n2=$(atoms)"
"""


def run(sable, deck, timeout=120):
    with tempfile.TemporaryDirectory() as d:
        p = os.path.join(d, 'in.deck')
        with open(p, 'w') as f:
            f.write(deck)
        out, rc = execute([sable, '-in', p, '-log', 'none'], d, timeout)
        if rc == -1:
            return {'error': 'timeout'}, out
    res = {}
    for line in out.splitlines():
        if line.startswith('RESULT'):
            for kv in line.split()[1:]:
                k, v = kv.split('=')
                res[k] = float(v)
    if 'ERROR' in out and not res:
        res['error'] = next(l for l in out.splitlines() if 'ERROR' in l)[:200]
    return res, out


def collisions(sable, quick):
    cases = [(1e7, 0.2), (1e7, 2.0), (1e7, 20.0), (7e10, 2.0), (7e10, 200.0)]
    fracs = [0.02, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.5, 0.6, 0.8, 1.0]
    if quick:
        cases, fracs = cases[1:2] + cases[3:4], [0.05, 0.2, 0.5]
    rows = []
    for E, v in cases:
        tc, tr = hertz_time(E, v), rayleigh(E)
        for e in (1.0, 0.5):
            ref, _ = run(sable, collision_deck(E, e, v, 0.005 * tc, 0.5))
            eref = (ref['vx2'] - ref['vx1']) / v
            for f in fracs:
                dt = f * tc
                worst, err = None, ''
                for ph in (0.1, 0.4, 0.7):
                    r, _ = run(sable, collision_deck(E, e, v, dt, ph))
                    if 'vx1' not in r or not all(math.isfinite(r[k]) for k in ('vx1', 'vx2')):
                        err = r.get('error', 'no result')
                        continue
                    em = (r['vx2'] - r['vx1']) / v
                    if r['x2'] < r['x1']:
                        err = 'passed through'
                    if worst is None or abs(em - eref) > abs(worst - eref):
                        worst = em
                rows.append(dict(E=E, v=v, e=e, tc=tc, tr=tr, dt=dt, f_tc=f, f_tr=dt / tr, eref=eref,
                                 emeas=worst, err=err))
                print(f"collision E={E:g} v={v:g} e={e} dt/tc={f:.3g} dt/tR={dt / tr:.3g} "
                      f"e_ref={eref:.5f} e={worst if worst is None else round(worst, 5)} {err}", flush=True)
    return rows


def beds(sable, quick, fine=False):
    # (E, g, T): settle time T covers the fall from 12 mm and the ring-down.
    cases = [(1e7, 9.81, 0.15), (1e7, 981.0, 0.015), (7e10, 981.0, 0.012), (7e10, 9.81, 0.06)]
    fracs_tr = [0.2, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 6.0]
    if quick:
        cases, fracs_tr = cases[1:2], [0.2, 2.0]
    rows = []
    for E, g, T in cases:
        tr = rayleigh(E)
        tcg = hertz_time(E, 2 * max(math.sqrt(2 * g * LZ), 1e-3))
        if fine:  # around the onset: dt = 0.25 .. 0.5 of the guard's contact time
            fracs_tr = [c * tcg / tr for c in (0.25, 0.3, 0.35, 0.4, 0.45, 0.5)]
        for f in fracs_tr:
            if E > 1e9 and g < 100 and f < 0.5 and not fine:
                continue  # 1e5+ steps: skipped to keep the sweep in seconds
            dt = f * tr
            r, out = run(sable, bed_deck(E, g, dt, T))
            m = 4 / 3 * math.pi * R ** 3 * RHO
            scale = N_BED * m * g * 2 * R
            ke1, ke2 = r.get('ke1', float('nan')), r.get('ke2', float('nan'))
            n2 = r.get('n2', 0)
            blow = (not math.isfinite(ke2)) or n2 < N_BED or ke2 / scale > 1 or 'error' in r
            rows.append(dict(E=E, g=g, dt=dt, f_tr=round(f, 3), f_tcg=dt / tcg,
                             ke1=ke1 / scale, ke2=ke2 / scale, n=n2, blow=blow, err=r.get('error', '')))
            print(f"bed E={E:g} g={g:g} dt/tR={f:g} dt/tc(guard)={dt / tcg:.3g} "
                  f"ke1/mgd={ke1 / scale:.3g} ke2/mgd={ke2 / scale:.3g} n={n2:g} {'BLOW-UP' if blow else ''} "
                  f"{r.get('error', '')}", flush=True)
    return rows


def write(crows, brows, path):
    with open(path, 'w') as f:
        f.write('## Two-grain head-on collisions (Hertz)\n\n')
        f.write('| E (Pa) | v_rel (m/s) | e set | t_c (s) | t_R (s) | dt/t_c | dt/t_R | e converged | e measured (worst phase) | rel. error | note |\n')
        f.write('|---|---|---|---|---|---|---|---|---|---|---|\n')
        for r in crows:
            em = r['emeas']
            rel = abs(em - r['eref']) / r['eref'] if em is not None else float('nan')
            f.write(f"| {r['E']:g} | {r['v']:g} | {r['e']:g} | {r['tc']:.3g} | {r['tr']:.3g} | {r['f_tc']:.3g} | "
                    f"{r['f_tr']:.3g} | {r['eref']:.5f} | {em if em is None else f'{em:.5f}'} | {rel:.2%} | {r['err']} |\n")
        f.write('\n## Settled bed (30 grains, Hertz, e = 0.5, periodic sides, floor)\n\n')
        f.write('| E (Pa) | g (m/s^2) | dt/t_R | dt/t_c at the guard speed | KE/(N m g d) after T | after 1.5 T | grains | blow-up |\n')
        f.write('|---|---|---|---|---|---|---|---|\n')
        for r in brows:
            f.write(f"| {r['E']:g} | {r['g']:g} | {r['f_tr']:g} | {r['f_tcg']:.3g} | {r['ke1']:.3g} | "
                    f"{r['ke2']:.3g} | {r['n']:g} | {'yes' if r['blow'] else 'no'} {r['err']} |\n")


def figure(crows, brows, path):
    try:
        import matplotlib
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
    except ImportError:
        print('matplotlib missing: no figure')
        return
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    keys = sorted({(r['E'], r['v'], r['e']) for r in crows})
    for k in keys:
        rs = [r for r in crows if (r['E'], r['v'], r['e']) == k]
        xs = [r['f_tc'] for r in rs]
        ys = [abs(r['emeas'] - r['eref']) / r['eref'] if r['emeas'] is not None else 10 for r in rs]
        ax[0].loglog(xs, [max(y, 1e-7) for y in ys], 'o-' if k[2] == 1 else 's--', ms=3,
                     label=f"E={k[0]:g} v={k[1]:g} e={k[2]:g}")
    ax[0].set_xlabel('dt / t_c (Hertz contact time at v_rel)')
    ax[0].set_ylabel('|e - e(dt->0)| / e (worst of 3 phases)')
    ax[0].axhline(0.01, color='k', lw=0.5)
    ax[0].legend(fontsize=6)
    ax[0].axvline(0.3, color='r', lw=0.8, ls=':')
    for k in sorted({(r['E'], r['g']) for r in brows}):
        rs = [r for r in brows if (r['E'], r['g']) == k and not r['blow']]
        line, = ax[1].loglog([r['f_tcg'] for r in rs], [max(r['ke2'], 1e-12) for r in rs], 'o-', ms=3,
                             label=f"E={k[0]:g} g={k[1]:g}")
        bs = [r['f_tcg'] for r in brows if (r['E'], r['g']) == k and r['blow']]
        ax[1].plot(bs, [1.0] * len(bs), 'x', color=line.get_color(), ms=7)
    ax[1].axvline(0.3, color='r', lw=0.8, ls=':')
    ax[1].set_xlabel('dt / t_c (guard: Hertz time at twice the free-fall speed across the box)')
    ax[1].set_ylabel('KE / (N m g d) after 1.5 T (x at 1: blow-up)')
    ax[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--sable', default=None, help='the sable binary (default: the build of this checkout)')
    ap.add_argument('--quick', action='store_true')
    ap.add_argument('--only', choices=('collision', 'bed'))
    ap.add_argument('--fine', action='store_true', help='beds only, dt around the onset of instability')
    ap.add_argument('--out', default=HERE)
    ap.add_argument('--replot', action='store_true', help='table and figure from the stored sweep.json')
    a = ap.parse_args()
    a.sable = find_sable(a.sable)
    if not a.replot and not a.sable:
        sys.exit('no sable binary: build it (README) or give --sable')
    data = os.path.join(a.out, 'sweep.json')
    if a.replot:  # the figure and table again from the stored rows, without running
        with open(data) as f:
            crows, brows = json.load(f)
    else:
        crows = [] if a.only == 'bed' else collisions(a.sable, a.quick)
        brows = [] if a.only == 'collision' else beds(a.sable, a.quick) + (beds(a.sable, a.quick, True) if a.fine else [])
        brows.sort(key=lambda r: (r['E'], r['g'], r['dt']))
        with open(data, 'w') as f:
            json.dump([crows, brows], f, indent=0)
    write(crows, brows, os.path.join(a.out, 'sweep.md'))
    figure(crows, brows, os.path.join(a.out, 'sweep.png'))


if __name__ == '__main__':
    sys.exit(main())
