#!/usr/bin/python3
"""The cavity sweep of reference_runs/cavity/sweep/PLAN.md: run, then reduce each run.

    /usr/bin/python3 -m sable_tools.cavity.sweep run [--work DIR] [--only NU,NP] [--seeds 1 2 3] [--reverse]
    /usr/bin/python3 -m sable_tools.cavity.sweep reduce [--work DIR]
    /usr/bin/python3 -m sable_tools.cavity.sweep yade [--work DIR] [--only NU,NP] [--seeds 1 2 3]

`run` runs the plan's points (seed 1 first, the table's order, each deposit once per
(N_P, seed)) that have no reduced result yet, and reduces each as it ends; a killed
sweep resumes where it stopped. Raw outputs (HDF5 series, slices and fields, contact
rows) go to DIR (default /tmp/cavity_sweep); what is committed goes to
reference_runs/cavity/sweep/runs/NU<nu>_NP<np>_s<seed>/: the run's log, block means and
reduced.json (the RESULT and CAVITY values, l/L, the ACF times, the paper-region nodes'
I and mu_loc). `reduce` redoes the reductions from DIR. The seeds' normalised force
samples are kept in DIR for sweep_figures.py (pooled PDFs and Eq. 7 fits).
"""
import argparse, fcntl, json, os, shutil, sys, time

import numpy as np

from sable_tools import runner  # sable and YADE runs into their logs
from sable_tools.paths import REPO as ROOT
from sable_tools.readers import analyze as analyze_csv, dump, h5, screen  # sable-analyze's CSV; contacts; series; KEY k=v lines

DECK = os.path.join(ROOT, 'input_scripts', 'cavity', 'cavity.in')
SABLE = runner.built('sable')
OUT = os.path.join(ROOT, 'reference_runs', 'cavity', 'sweep', 'runs')

HD, TSHEAR, TREC = 12, 6, 1
if os.environ.get('CAVITY_SWEEP_SMOKE'):  # a seconds-long check of this script itself, not the plan
    HD, TSHEAR, TREC = 8, 0.3, 0.1
    OUT = os.path.join(os.environ['CAVITY_SWEEP_SMOKE'], 'runs')
POINTS = [(1, 100), (1, 10), (1, 1), (2, 4), (2, 1), (5, 1), (10, 1), (1, 0.01), (20, 1)]
SEEDS = [1, 2, 3]
YADE_HD = 8  # the code comparison: H/d 8, where YADE's 6 s shear takes ~7 min, not ~30 at H/d 12
YADE_POINTS = [(0.45, 1), (4.5, 1)]  # I_M 0.020 and 0.199 at H/d 8
D, RHO_P = 1e-3, 2500.0


def tag(nu, np_, seed):
    return f'NU{nu:g}_NP{np_:g}_s{seed}'


def key_values(path, prefix):
    """key=value pairs of the lines starting with prefix (numbers only; the last wins)."""
    with open(path, errors='replace') as f:
        return screen.numeric_keys(f.read(), prefix)


def sable(args, log, cwd):
    cmd = [SABLE, '-in', DECK, '-log', log, '-echo', 'none'] + args
    rc = runner.run_logged(cmd, cwd, log + '.screen', runner.one_thread())
    if rc != 0:
        sys.exit(f'sweep: {" ".join(cmd)} failed (exit {rc}); see {log}.screen')


def analyze(args):
    r = runner.analyze(args)
    if r.returncode != 0:
        sys.exit(f'sweep: sable-analyze {" ".join(args)} failed: {r.stderr.strip()}')
    return r.stdout


def deposit(work, np_, seed, hd=None):
    """The (H/d, N_P, seed) deposit's restart, written once (a lock: sweeps in parallel share it)."""
    hd = hd or HD
    rs = os.path.join(work, f'dep_NP{np_:g}_s{seed}.restart' if hd == HD else f'dep_Hd{hd}_NP{np_:g}_s{seed}.restart')
    with open(rs + '.lock', 'w') as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not os.path.exists(rs):
            vs = ['-var', 'Hd', str(hd), '-var', 'NP', f'{np_:g}', '-var', 'seed', str(seed),
                  '-var', 'phase', 'deposit', '-var', 'restart', rs + '.part']
            sable(vs, rs + '.log', work)
            os.rename(rs + '.part', rs)
    return rs


def raw_dir(work, nu, np_, seed, code='sable', cmp=False):
    """Raw outputs: the sweep's sable runs in work/TAG, the code comparison's in work/compare/CODE/TAG."""
    return os.path.join(work, 'compare', code, tag(nu, np_, seed)) if cmp else os.path.join(work, tag(nu, np_, seed))


def out_dir(nu, np_, seed, code='sable', cmp=False):
    return os.path.join(OUT, 'compare', code, tag(nu, np_, seed)) if cmp else os.path.join(OUT, tag(nu, np_, seed))


def shear(work, nu, np_, seed, code='sable', cmp=False):
    """The shear phase from the seed's sable deposit, in sable (fields on) or in YADE through
    `sable --export-yade` (fields off: the exporter has no translation of stress/cg)."""
    hd = YADE_HD if cmp else HD
    raw = raw_dir(work, nu, np_, seed, code, cmp)
    os.makedirs(raw, exist_ok=True)
    rs = deposit(work, np_, seed, hd)
    vs = ['-var', 'Hd', str(hd), '-var', 'NU', f'{nu:g}', '-var', 'NP', f'{np_:g}', '-var', 'seed', str(seed),
          '-var', 'tshear', str(TSHEAR), '-var', 'trec', str(TREC), '-var', 'phase', 'shear', '-var', 'restart', rs,
          '-var', 'fields', '1' if code == 'sable' else '0', '-var', 'contacts', '1', '-var', 'out', 'cav']
    t0 = time.time()
    if code == 'sable':
        sable(vs, os.path.join(raw, 'log.sable'), raw)
        return raw, time.time() - t0
    script = os.path.join(raw, 'shear.py')
    rc = runner.run_logged(runner.export_yade(SABLE, DECK, vs, script), raw, os.path.join(raw, 'export.screen'))
    if rc != 0:
        sys.exit(f'sweep: the export of {raw} failed (exit {rc}); see {raw}/export.screen')
    t0 = time.time()
    rc = runner.run_logged(runner.yade(script), raw, os.path.join(raw, 'log.yade'), runner.one_thread())
    if rc != 0:
        sys.exit(f'sweep: YADE on {script} failed (exit {rc}); see {raw}/log.yade')
    return raw, time.time() - t0


ACF_LAGS = 400  # samples of C kept per series (40 ms at 10 kHz) for the figures


def acf_time(path, column, dt, skip=0):
    """sable-analyze acf's metadata (first_lag_below in rows, g) and C's first ACF_LAGS values
    of one column, threshold C < 0.15 (kneib2017 Sec. IV B)."""
    out = os.path.join(os.path.dirname(path), 'acf_tmp.csv')
    analyze(['acf', path, '--column', column, '--threshold', '0.15', '--dt', repr(dt), '--out', out])
    t = analyze_csv.table(out)
    meta = dict(t.meta)
    meta['c'] = [round(float(x), 4) for x in t['c'][:ACF_LAGS]]
    os.remove(out)
    return meta


def reduce_run(work, nu, np_, seed, wall=None, code='sable', cmp=False):
    raw = raw_dir(work, nu, np_, seed, code, cmp)
    log = os.path.join(raw, 'log.' + code)
    res = key_values(log, 'RESULT')
    cav = key_values(log, 'CAVITY')
    first = int(cav['record_from'])
    dt, U, L = res['dt'], res['U'], res['L']
    red = {'code': code, 'NU': nu, 'NP': np_, 'seed': seed, 'Hd': YADE_HD if cmp else HD, 'tshear': TSHEAR, 'trec': TREC,
           'result': res, 'cavity': cav}
    if wall is not None:
        red['wall_s_run'] = wall
    # time series at 10 kHz: F and its slices, each normalised by its own mean
    cols, ser, steps = h5.read_series(os.path.join(raw, 'cav_series.h5'))
    F = ser[:, cols.index('v_F')]
    sl = h5.read_series(os.path.join(raw, 'cav_slices.h5'))[1][:, :, 0]  # [sample, slice, the one value]
    dts = float(steps[1] - steps[0]) * dt
    red['samples'] = int(len(F))
    red['sample_dt'] = dts
    red['first_step'] = int(steps[0])
    red['slice_means_over_F'] = (sl.mean(axis=0) / F.mean()).tolist()
    red['slices_sum_max_dev'] = float(np.max(np.abs(sl.sum(axis=1) - F)))
    # contact rows after the recording's start: f = fx on the wall
    fc = contact_forces(os.path.join(raw, 'cav_contacts.txt'), first)
    red['contact_rows'] = int(len(fc))
    np.save(os.path.join(raw, 'F_norm.npy'), F / F.mean())
    np.save(os.path.join(raw, 'Fi_norm.npy'), (sl[:, 2:9] / sl[:, 2:9].mean(axis=0)).ravel())
    np.save(os.path.join(raw, 'f_norm.npy'), fc / fc.mean())
    # autocorrelation times (threshold 0.15, Sec. IV B): the whole wall and each slice
    tmp = os.path.join(raw, 'slices.csv')
    np.savetxt(tmp, np.column_stack([F, sl]), delimiter=',',
               header=','.join(['F'] + [f'F{i}' for i in range(1, 11)]), comments='')
    acf = {}
    for k, c in enumerate(['F'] + [f'F{i}' for i in range(1, 11)]):
        x = F if k == 0 else sl[:, k - 1]
        if np.ptp(x) == 0:  # e.g. a slice no grain touched: no correlation to measure
            acf[c] = {'dt_c': float('nan'), 'g': float('nan'), 'c': [], 'constant': float(x[0])}
            continue
        m = acf_time(tmp, c, dts)
        lag = float(m['first_lag_below'])  # rows; < 0 when C never falls under 0.15
        acf[c] = {'dt_c': lag * dts if lag >= 0 else float('nan'), 'g': float(m['g']), 'c': m['c']}
    red['acf'] = acf
    dst = out_dir(nu, np_, seed, code, cmp)
    os.makedirs(dst, exist_ok=True)
    for f in ('log.' + code, 'cav_blocks.txt'):
        shutil.copy(os.path.join(raw, f), dst)
    if code == 'sable':
        red.update(fields(raw, cav, L))
    json.dump(red, open(os.path.join(dst, 'reduced.json'), 'w'), indent=1)
    return red


def fields(raw, cav, L):
    """The vortex centre and the paper region's mu_loc(I) from the recording's mean fields."""
    red = {}
    skip = int(cav['fields_skip'])
    fld = os.path.join(raw, 'cav_fields.h5')
    vc = os.path.join(raw, 'vortex.csv')
    analyze(['vortex-centre', fld, '--skip', str(skip), '--xlo', '0', '--xhi', repr(L), '--out', vc])
    red['vortex'] = {k: float(v[0]) for k, v in analyze_csv.columns(vc).items()}
    pts = os.path.join(raw, 'rheology_points.csv')
    # 2D stresses are N/m: rho_p d (kg/m^2) in Eq. 18 gives I with the 3D stress sigma_2D / d
    analyze(['local-rheology', fld, '--skip', str(skip), '--d', repr(D), '--rho-p', repr(RHO_P * D),
             '--region', 'paper', '--xlo', '0', '--xhi', repr(L), '--out', pts])
    a = analyze_csv.columns(pts)
    red['rheology'] = {'I': a['I'].tolist(), 'mu_loc': a['mu_loc'].tolist(), 'align': a['align'].tolist()}
    return red


def contact_forces(path, first):
    """fx of every dump local row whose step is >= first (the recording)."""
    return dump.local_column(path, 2, first)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('what', choices=['run', 'reduce', 'yade'])
    p.add_argument('--work', default='/tmp/cavity_sweep')
    p.add_argument('--only', help='NU,NP of one point')
    p.add_argument('--seeds', type=int, nargs='+', default=SEEDS)
    p.add_argument('--reverse', action='store_true', help='the points in reverse order (a second sweep beside one)')
    a = p.parse_args()
    os.makedirs(a.work, exist_ok=True)
    pts = YADE_POINTS if a.what == 'yade' else POINTS
    if a.only:
        nu, np_ = (float(x) for x in a.only.split(','))
        pts = [q for q in pts if q == (nu, np_)]
    if a.reverse:
        pts = pts[::-1]
    for seed in a.seeds:
        for nu, np_ in pts:
            if a.what == 'yade':
                for code in ('sable', 'yade'):
                    one(a.work, nu, np_, seed, code, cmp=True)
            elif a.what == 'run':
                one(a.work, nu, np_, seed)
            elif os.path.exists(os.path.join(raw_dir(a.work, nu, np_, seed), 'log.sable')):
                reduce_run(a.work, nu, np_, seed)


def one(work, nu, np_, seed, code='sable', cmp=False):
    """Run and reduce one shear unless its reduced result exists; drop the bulky raw files."""
    t = ('compare ' + code + ' ' if cmp else '') + tag(nu, np_, seed)
    if os.path.exists(os.path.join(out_dir(nu, np_, seed, code, cmp), 'reduced.json')):
        return
    os.makedirs(raw_dir(work, nu, np_, seed, code, cmp), exist_ok=True)
    try:  # a claim, so that sweeps running side by side (--reverse) take each run once
        os.close(os.open(os.path.join(raw_dir(work, nu, np_, seed, code, cmp), 'claim'), os.O_CREAT | os.O_EXCL))
    except FileExistsError:
        return
    print(f'{time.strftime("%H:%M:%S")} {t}: running', flush=True)
    raw, wall = shear(work, nu, np_, seed, code, cmp)
    red = reduce_run(work, nu, np_, seed, wall, code, cmp)
    r = red['result']
    ell = red['vortex']['ell_over_l'] if 'vortex' in red else float('nan')
    print(f'{time.strftime("%H:%M:%S")} {t}: F/(PLd) {r["F_PLd"]:.4f} +- {r["F_PLd_err"]:.4f} I_M {r["I_M"]:.3g} '
          f'l/L {ell:.3f} wall {wall:.0f} s', flush=True)
    for f in ('cav_contacts.txt', 'slices.csv'):
        os.remove(os.path.join(raw, f))


if __name__ == '__main__':
    main()
