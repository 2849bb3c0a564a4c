#!/usr/bin/python3
"""The cavity sweep's report and figures (reference_runs/cavity/sweep/PLAN.md, kneib2017, issue 43).

    /usr/bin/python3 -m sable_tools.cavity.sweep_figures [--runs DIR] [--work DIR] [--out DIR]

Reads every reduced.json under --runs (the sweep: NU*_NP*_s*/; the code comparison: compare/sable/
and compare/yade/, or an older yade/ against the sweep's runs) and the
normalised force samples sweep.py keeps under --work (F_norm.npy, Fi_norm.npy, f_norm.npy),
works on whatever runs exist (the plan's points and seeds that are missing are listed), and
writes --out/REPORT.md and --out/figures/*.png. Every statistic sable-analyze offers comes from
it (fit-sigmoid, fit-linear, fit-lognormal, ks, pdf); Python adds only the seed means, the
Welch and TOST tests (seedstats) and the paper's curves drawn for comparison. The Eq. 7 fits are
cached under --work/sweep_figures_cache (reused while newer than their samples).
"""
import argparse, glob, json, os, sys, tempfile, time

import numpy as np

from sable_tools import figstyle, runner, seedstats  # figures' style; sable-analyze; statistics over seeds
from sable_tools.cavity import sweep  # the plan's points, seeds and run names live there once
from sable_tools.paths import REPO as ROOT
from sable_tools.readers import analyze as analyze_csv  # sable-analyze's outputs: fit rows, curves

PAPER_EQ4 = {'r1': 0.53, 'r2': 0.86, 'I0': 0.02}
PAPER_EQ5 = {'c1': 0.88, 'c2': 0.5}
PAPER_EQ20 = {'mu1': 0.12, 'mu2': 0.40, 'I0': 0.13}
PAIRS = {'A': ((1, 1), (2, 4)), 'B': ((10, 1), (1, 0.01))}
MARGIN, ALPHA = 0.05, 0.05
EQ5_IM_MIN = 1e-2
YADE_TOL = 2.0  # combined seed SEs
FIT_MAX = 20000  # values per Eq. 7 fit (a fixed-seed random draw): fit-lognormal takes ~8 min on 5e5
# (name, label, file, fixed bins for the PDFs)
SCALES = [('f', r'$f/\bar f$', 'f_norm.npy', (0, 8)),
          ('F', r'$F/\bar F$', 'F_norm.npy', (0, 5)),
          ('Fi', r'$F_i/\bar F_i$', 'Fi_norm.npy', (0, 10))]
NBINS = 40
# run groups under --runs (and --work, sweep.raw_dir's layout): the sweep's sable runs at the top, the
# code comparison (sweep.py yade: H/d sweep.YADE_HD, both codes from the same deposits) in compare/CODE
GROUPS = ['sable', 'compare/sable', 'compare/yade']
GS, GY = 'compare/sable', 'compare/yade'


# ---------------------------------------------------------------- small tools

def analyze(*args):
    """Run sable-analyze (niced: the sweep shares the CPUs); stdout, or stop with its message."""
    r = runner.analyze(args, nice=True)
    if r.returncode != 0:
        sys.exit(f'sweep_figures: sable-analyze {" ".join(map(str, args))} failed: {r.stderr.strip()}')
    return r.stdout


def write_csv(path, **cols):
    np.savetxt(path, np.column_stack(list(cols.values())), delimiter=',', header=','.join(cols),
               comments='', fmt='%.9g')
    return path


def mean_se(x):
    """Seed mean and seed-to-seed SE of the finite values (seedstats.summary; SE nan for one)."""
    s = seedstats.summary([v for v in np.asarray(x, float) if np.isfinite(v)])
    return s.mean, s.se


def sigmoid(x, a, b, x0):
    """Eqs. 4 and 20's form, only to draw and compare with the paper's published parameters."""
    return a + (b - a) / (1 + x0 / np.asarray(x, float))


def fmt(v, e=None, p=3):
    if v is None or not np.isfinite(v):
        return '—'
    s = f'{v:.{p}f}' if 1e-2 <= abs(v) < 10 else f'{v:.{p}g}'
    if e is None:
        return s
    return s + ' ± ' + (f'{e:.2g}' if np.isfinite(e) else '—')


def ptag(pt):
    return f'NU{pt[0]:g}_NP{pt[1]:g}'


# ---------------------------------------------------------------- runs

def load_runs(runs_dir):
    """{group: {(NU, NP): [reduced.json dicts, by seed]}} for each of GROUPS (runs_dir/GROUP/TAG,
    the sweep's sable runs in runs_dir/TAG)."""
    out = {g: {} for g in GROUPS}
    for g in GROUPS:
        for p in sorted(glob.glob(os.path.join(runs_dir, sub(g), 'NU*_NP*_s*', 'reduced.json'))):
            r = json.load(open(p))
            out[g].setdefault((float(r['NU']), float(r['NP'])), []).append(r)
    for by_pt in out.values():
        for runs in by_pt.values():
            runs.sort(key=lambda r: r['seed'])
    return out


def sub(group):
    return '' if group == 'sable' else group


def missing(runs):
    """The plan's (group, point, seed) that have no reduced.json yet; extra runs outside the plan."""
    want = {('sable', p, s) for p in sweep.POINTS for s in sweep.SEEDS}
    want |= {(g, p, s) for g in (GS, GY) for p in sweep.YADE_POINTS for s in sweep.SEEDS}
    have = {(c, p, r['seed']) for c in runs for p in runs[c] for r in runs[c][p]}
    order = sweep.POINTS + sweep.YADE_POINTS + [p for c in runs for p in runs[c]]
    key = lambda t: (t[0], order.index(t[1]), t[2])
    return sorted(want - have, key=key), sorted(have - want, key=key)


def listing(triples):
    """(code, point, seed) triples as 'code point: seeds' per point, in the given order."""
    by = {}
    for c, p, sd in triples:
        by.setdefault((c, p), []).append(str(sd))
    return '; '.join(f'{c} {ptag(p)} s{",".join(v)}' for (c, p), v in by.items()) or 'none'


def summary(runs):
    """Seed means ± SE of one point's observables."""
    res = lambda k: [r['result'][k] for r in runs]
    s = {'n': len(runs), 'seeds': [r['seed'] for r in runs], 'I_M': runs[0]['result']['I_M'], 'Hd': runs[0]['Hd'],
         'U': runs[0]['result']['U'], 'd': runs[0]['result']['d'], 'F_seeds': np.array(res('F_PLd')),
         'F': mean_se(res('F_PLd')), 'F_blk': float(np.mean(res('F_PLd_err'))), 'phi': mean_se(res('phi3D')),
         'cv': mean_se(res('F_cv')), 'zero': mean_se(res('F_zero')),
         'dtc': mean_se([r['acf']['F']['dt_c'] for r in runs]),
         'dtc_sl': mean_se([np.nanmean([r['acf'][f'F{i}']['dt_c'] for i in range(3, 10)]) for r in runs]),
         'wall': float(np.mean(res('wall_s')))}
    s['ell'] = mean_se([r['vortex']['ell_over_l'] for r in runs]) if 'vortex' in runs[0] else (np.nan, np.nan)
    return s


def raw_dir(work, group, run):
    return sweep.raw_dir(work, run['NU'], run['NP'], run['seed'], group.split('/')[-1], group.startswith('compare/'))


def pooled(work, code, runs, fname):
    """The seeds' normalised samples concatenated, and the seeds whose raw file is absent."""
    parts, absent = [], []
    for r in runs:
        p = os.path.join(raw_dir(work, code, r), fname)
        if os.path.exists(p):
            parts.append(np.load(p))
        else:
            absent.append(r['seed'])
    return (np.concatenate(parts) if parts else np.array([])), absent


def decorrelated_n(runs, scale, work, code):
    """Sum over seeds of n/g (PLAN: KS critical values with the decorrelated sizes). F: the
    series' g; F_i: each slice's length over its g; f (contact rows): no g, n itself."""
    n = 0.0
    for r in runs:
        T = r['samples']
        if scale == 'F':
            n += T / r['acf']['F']['g']
        elif scale == 'Fi':
            n += sum(T / r['acf'][f'F{i}']['g'] for i in range(3, 10) if np.isfinite(r['acf'][f'F{i}']['g']))
        else:
            p = os.path.join(raw_dir(work, code, r), 'f_norm.npy')
            n += len(np.load(p, mmap_mode='r')) if os.path.exists(p) else 0
    return n


# ---------------------------------------------------------------- tests

def fit_sigmoid(tmp, x, y, yerr, names, tagname):
    """fit-sigmoid through sable-analyze: the parameter row and the curve (x, fit)."""
    cols = {'x': x, 'y': y} if yerr is None else {'x': x, 'y': y, 'e': yerr}
    src = write_csv(os.path.join(tmp, tagname + '.csv'), **cols)
    out, cur = os.path.join(tmp, tagname + '_fit.csv'), os.path.join(tmp, tagname + '_curve.csv')
    args = ['fit-sigmoid', src, '--x', 'x', '--y', 'y', '--names', ','.join(names), '--out', out, '--curve', cur]
    analyze(*(args + (['--yerr', 'e'] if yerr is not None else [])))
    return analyze_csv.one_row(out), analyze_csv.table(cur)


def eq4(tmp, S):
    """Eq. 4 refit on the seed means weighted by the seed SEs (points with >= 2 seeds); with
    fewer than 4 such points, an unweighted preliminary fit of all the points."""
    pts = sorted(S, key=lambda p: S[p]['I_M'])
    good = [p for p in pts if np.isfinite(S[p]['F'][1]) and S[p]['F'][1] > 0]
    weighted = len(good) >= 4
    use = good if weighted else pts
    if len(use) < 4:
        return None
    x = [S[p]['I_M'] for p in use]
    y = [S[p]['F'][0] for p in use]
    row, curve = fit_sigmoid(tmp, x, y, [S[p]['F'][1] for p in use] if weighted else None,
                             ['r1', 'r2', 'I0'], 'eq4')
    z = {p: (S[p]['F'][0] - sigmoid(S[p]['I_M'], *PAPER_EQ4.values())) / S[p]['F'][1] for p in good}
    # outside the plan, a check of the weights: the same means unweighted, errors from the scatter
    row_u = fit_sigmoid(tmp, x, y, None, ['r1', 'r2', 'I0'], 'eq4u')[0] if weighted else None
    return {'row': row, 'row_u': row_u, 'curve': curve, 'weighted': weighted, 'points': use, 'z': z,
            'chi2n': float(np.mean([v ** 2 for v in z.values()])) if z else np.nan}


def welch_tost(a, b):
    """Welch t (two-sided) on a - b and TOST with margin ±MARGIN (each side at ALPHA): seedstats."""
    d = seedstats.welch_diff(a, b, level=1 - 2 * ALPHA)
    e = seedstats.tost(d, MARGIN, alpha=ALPHA)
    t = d.est / d.se
    return {'d': d.est, 'se': d.se, 'df': d.df, 't': t, 'p_diff': seedstats.two_sided_p(d),
            'p_tost': e.p, 'ci90': (e.lo, e.hi)}


def ks(tmp, a, b, name, n_dec_a, n_dec_b):
    """sable-analyze ks of two samples; its critical D rescaled to the decorrelated sizes."""
    pa = write_csv(os.path.join(tmp, name + '_a.csv'), x=a)
    pb = write_csv(os.path.join(tmp, name + '_b.csv'), x=b)
    out = os.path.join(tmp, name + '_ks.csv')
    analyze('ks', pa, pb, '--column', 'x', '--alpha', ALPHA, '--out', out)
    r = analyze_csv.one_row(out)
    n_eff = r['n_a'] * r['n_b'] / (r['n_a'] + r['n_b'])
    n_dec = n_dec_a * n_dec_b / (n_dec_a + n_dec_b)
    r['critical_dec'] = r['critical'] * np.sqrt(n_eff / n_dec)
    r['n_dec_a'], r['n_dec_b'] = n_dec_a, n_dec_b
    return r


def pair_tests(tmp, work, runs, S):
    out = {}
    for name, (pa, pb) in PAIRS.items():
        if pa not in S or pb not in S or S[pa]['n'] < 2 or S[pb]['n'] < 2:
            out[name] = None
            continue
        t = welch_tost(S[pa]['F_seeds'], S[pb]['F_seeds'])
        Fa, _ = pooled(work, 'sable', runs[pa], 'F_norm.npy')
        Fb, _ = pooled(work, 'sable', runs[pb], 'F_norm.npy')
        if len(Fa) and len(Fb):
            t['ks'] = ks(tmp, Fa, Fb, 'pair' + name, decorrelated_n(runs[pa], 'F', work, 'sable'),
                         decorrelated_n(runs[pb], 'F', work, 'sable'))
        t['dtc'] = [(S[q]['dtc'][0], S[q]['U'] / S[q]['d'] * S[q]['dtc'][0]) for q in (pa, pb)]
        out[name] = t
    return out


def eq5(tmp, S):
    pts = [p for p in S if S[p]['I_M'] > EQ5_IM_MIN and np.isfinite(S[p]['ell'][0])]
    if len(pts) < 3:
        return None
    src = write_csv(os.path.join(tmp, 'eq5.csv'), x=[S[p]['ell'][0] for p in pts], y=[S[p]['F'][0] for p in pts])
    out = os.path.join(tmp, 'eq5_fit.csv')
    analyze('fit-linear', src, '--x', 'x', '--y', 'y', '--names', 'c1,c2', '--out', out)
    return {'row': analyze_csv.one_row(out), 'points': pts}


def eq20(tmp, runs):
    I, mu = [], []
    for rs in runs.values():
        for r in rs:
            if 'rheology' in r:
                I += r['rheology']['I']
                mu += r['rheology']['mu_loc']
    I, mu = np.array(I, float), np.array(mu, float)
    ok = np.isfinite(I) & np.isfinite(mu) & (I > 0)
    if ok.sum() < 4:
        return None
    row, curve = fit_sigmoid(tmp, I[ok], mu[ok], None, ['mu1', 'mu2', 'I0'], 'eq20')
    return {'row': row, 'curve': curve, 'I': I[ok], 'mu': mu[ok], 'n': int(ok.sum())}


def eq7(work, code, pt, runs, scale, fname):
    """fit-lognormal of a point's pooled positive samples (at most FIT_MAX, drawn at random with a
    fixed seed), --raw so that x stays the value over the mean of all the values (zeros included);
    cached under work/sweep_figures_cache. Returns the row, the curve and the sample's facts."""
    x, absent = pooled(work, code, runs, fname)
    if len(x) == 0:
        return None
    cache = os.path.join(work, 'sweep_figures_cache')
    os.makedirs(cache, exist_ok=True)
    seeds = '-'.join(str(r['seed']) for r in runs if r['seed'] not in absent)
    key = f'{code.replace("/", "-")}_{ptag(pt)}_{scale}_s{seeds}'
    out, cur = os.path.join(cache, key + '_fit.csv'), os.path.join(cache, key + '_curve.csv')
    srcs = [os.path.join(raw_dir(work, code, r), fname) for r in runs if r['seed'] not in absent]
    pos = x[x > 0]
    if not (os.path.exists(out) and os.path.getmtime(out) > max(map(os.path.getmtime, srcs))):
        sub = np.random.default_rng(43).choice(pos, FIT_MAX, replace=False) if len(pos) > FIT_MAX else pos
        src = write_csv(os.path.join(cache, key + '.csv'), x=sub)
        analyze('fit-lognormal', src, '--column', 'x', '--raw', '--out', out, '--curve', cur, '--nbins', NBINS)
        os.remove(src)
    return {'row': analyze_csv.one_row(out), 'curve': analyze_csv.table(cur), 'n': len(x), 'n_pos': len(pos),
            'n_fit': min(len(pos), FIT_MAX), 'zero_frac': 1 - len(pos) / len(x), 'absent': absent,
            'neg_frac': float(np.mean(x < 0)), 'min': float(x.min())}


def eq7_all(work, runs, code):
    out = {}
    for pt in sorted(runs[code], key=lambda p: runs[code][p][0]['result']['I_M']):
        for scale, _, fname, _ in SCALES:
            r = eq7(work, code, pt, runs[code][pt], scale, fname)
            if r is not None:
                out[(pt, scale)] = r
    return out


def yade_compare(tmp, work, runs, gs, gy, S, Y):
    out = {}
    for pt in sorted(Y, key=lambda p: Y[p]['I_M']):
        if pt not in S:
            continue
        (ms, es), (my, ey) = S[pt]['F'], Y[pt]['F']
        comb = seedstats.combined_se(es, ey)
        c = {'diff': ms - my, 'comb': comb, 'ks': {}}
        c['pass'] = seedstats.agrees(ms - my, comb, YADE_TOL)  # None without an SE
        fy = {r['seed']: r['result']['F_PLd'] for r in runs[gy][pt]}
        c['paired'] = mean_se([r['result']['F_PLd'] - fy[r['seed']] for r in runs[gs][pt] if r['seed'] in fy])
        for scale, _, fname, _ in SCALES:
            a, _ = pooled(work, gs, runs[gs][pt], fname)
            b, _ = pooled(work, gy, runs[gy][pt], fname)
            if len(a) and len(b):
                c['ks'][scale] = ks(tmp, a, b, f'yade_{ptag(pt)}_{scale}',
                                    decorrelated_n(runs[gs][pt], scale, work, gs),
                                    decorrelated_n(runs[gy][pt], scale, work, gy))
        out[pt] = c
    return out


# ---------------------------------------------------------------- report

def verdict(row, name, paper):
    lo, hi = row[name + '_lo'], row[name + '_hi']
    return 'consistent' if lo <= paper <= hi else 'different'


def param_lines(row, paper):
    out = ['| parameter | fit | 95 % interval | paper | verdict |', '|---|---|---|---|---|']
    for k, v in paper.items():
        out.append(f'| {k} | {fmt(row[k], row[k + "_err"], 4)} | [{fmt(row[k + "_lo"], None, 4)}, '
                   f'{fmt(row[k + "_hi"], None, 4)}] | {v} | {verdict(row, k, v)} |')
    return out


def runs_section(runs, miss, extra):
    L = ['## Runs', '']
    for g in GROUPS:
        for pt in sorted(runs[g], key=lambda p: runs[g][p][0]['result']['I_M']):
            L.append(f'- {g} {ptag(pt)} (H/d {runs[g][pt][0]["Hd"]}): seeds '
                     f'{", ".join(str(r["seed"]) for r in runs[g][pt])}')
    L.append('- missing from the plan: ' + listing(miss))
    if extra:
        L.append('- outside the plan (included): ' + listing(extra))
    return L + ['']


def point_table(S):
    L = ['## Per point (seed mean ± SE = sd/sqrt(n); block error: the mean of the seeds\' own)', '',
         '| N_U | N_P | I_M | seeds | F̄/(PLd) | block err | ℓ/L | Φ* | F_cv | F_zero | Δt_c(F) ms | '
         'Δt_c(F3-9) ms | (U/d)Δt_c | wall s/run (deck) |', '|' + '---|' * 14]
    for pt in sorted(S, key=lambda p: S[p]['I_M']):
        s = S[pt]
        ud = s['U'] / s['d']
        L.append(f'| {pt[0]:g} | {pt[1]:g} | {s["I_M"]:.3g} | {",".join(map(str, s["seeds"]))} | '
                 f'{fmt(*s["F"])} | {fmt(s["F_blk"], None, 2)} | {fmt(*s["ell"])} | {fmt(*s["phi"])} | '
                 f'{fmt(*s["cv"])} | {fmt(*s["zero"])} | {fmt(s["dtc"][0] * 1e3, s["dtc"][1] * 1e3)} | '
                 f'{fmt(s["dtc_sl"][0] * 1e3, s["dtc_sl"][1] * 1e3)} | {fmt(ud * s["dtc"][0], ud * s["dtc"][1])} | '
                 f'{fmt(s["wall"])} |')
    return L + ['']


def fit_section(title, fit, missing, rows):
    """A fit's section: its title, then rows(fit, its row), or `missing` while there is no fit yet."""
    return [title, ''] + ([missing, ''] if fit is None else rows(fit, fit['row']))


def eq4_section(e4, S):
    return fit_section('## Eq. 4 refit (`fit-sigmoid`)', e4, 'Not enough points yet (4 needed).',
                       lambda e4, r: eq4_rows(e4, r, S))


def eq4_rows(e4, r, S):
    how = ('weighted by the seed SEs (1.96 intervals)' if e4['weighted'] else
           '**preliminary: fewer than 4 points have 2 seeds, so unweighted (errors from the scatter)**')
    L = [f'Over {len(e4["points"])} points, {how}; chi2 {r["chi2"]:.3g} / {r["dof"]:.0f} dof, '
          f'R² {r["r_squared"]:.3f}.', ''] + param_lines(r, PAPER_EQ4) + ['']
    if e4['row_u']:
        L += ['A check of the weights, outside the plan: the same means unweighted (errors from the scatter, '
              f'Student intervals): {against(e4["row_u"], PAPER_EQ4)}.', '']
    L += ['Each point against the paper\'s curve (r1 0.53, r2 0.86, I_M^0 0.02): z = (mean - Eq. 4)/SE.', '',
          '| N_U | N_P | I_M | mean | Eq. 4 (paper) | z |', '|---|---|---|---|---|---|']
    for pt, z in sorted(e4['z'].items(), key=lambda kv: S[kv[0]]['I_M']):
        L.append(f'| {pt[0]:g} | {pt[1]:g} | {S[pt]["I_M"]:.3g} | {fmt(*S[pt]["F"])} | '
                 f'{sigmoid(S[pt]["I_M"], *PAPER_EQ4.values()):.3f} | {z:+.2f} |')
    ns = sorted({S[p]['n'] for p in e4['z']})
    return L + ['', f'χ²/n of the paper\'s curve over these {len(e4["z"])} points: {e4["chi2n"]:.3g}. With '
                f'{"-".join(map(str, ns))} seeds per point a seed SE is itself uncertain by about 1/sqrt(2(n-1)) '
                '(50-70 %), and a point whose seeds '
                'happen to agree gets a small SE and a large weight and z: read z and χ² with the block errors '
                'beside '
                'them (table above).', '']


def pair_section(P, S):
    L = ['## Same I_M: pairs A ((1,1), (2,4)) and B ((10,1), (1,0.01))', '',
         f'Welch t on the seed values of F̄/(PLd), α {ALPHA} two-sided; TOST with margin ±{MARGIN}, α {ALPHA} '
         'each side (equivalent when the 90 % interval of the difference lies inside the margin). KS of the '
         'pooled F/F̄ samples (`ks`), critical D for the decorrelated sizes Σ n/g: descriptive, no pass/fail.', '',
         '| pair | points | difference | Welch t (df) | p | difference test | TOST p | 90 % CI | equivalence | '
         'KS D | critical D (n/g) | critical D (n) |', '|' + '---|' * 12]
    for name, (pa, pb) in PAIRS.items():
        t = P.get(name)
        if t is None:
            L.append(f'| {name} | {ptag(pa)} − {ptag(pb)} | not yet (2 seeds per point needed) |' + ' |' * 9)
            continue
        k = t.get('ks', {})
        L.append(f'| {name} | {ptag(pa)} − {ptag(pb)} | {t["d"]:+.4f} ± {t["se"]:.4f} | {t["t"]:+.2f} '
                 f'({t["df"]:.1f}) | {t["p_diff"]:.3g} | '
                 f'{"difference detected" if t["p_diff"] < ALPHA else "no difference detected"} | {t["p_tost"]:.3g} | '
                 f'[{t["ci90"][0]:+.4f}, {t["ci90"][1]:+.4f}] | '
                 f'{"equivalent within ±0.05" if t["p_tost"] < ALPHA else "equivalence not shown"} | '
                 f'{fmt(k.get("d", np.nan), None, 3)} | {fmt(k.get("critical_dec", np.nan), None, 3)} | '
                 f'{fmt(k.get("critical", np.nan), None, 3)} |')
    L.append('')
    for name, t in P.items():
        if t:
            (a, ua), (b, ub) = t['dtc']
            L.append(f'- {name}: Δt_c(F) {a * 1e3:.3g} and {b * 1e3:.3g} ms, (U/d)Δt_c {ua:.3g} and {ub:.3g}.')
    return L + ['']


def eq5_section(e5, S):
    return fit_section('## Eq. 5 (`fit-linear`, F̄/(PLd) = c1 - c2 ℓ/L over I_M > 1e-2)', e5,
                       'Not enough points yet (3 with ℓ/L and I_M > 1e-2).', eq5_rows)


def eq5_rows(e5, r):
    L = [f'Seed means of {len(e5["points"])} points, unweighted (ℓ/L carries its own scatter; errors from the '
          f'residuals, Student intervals); R² {r["r_squared"]:.3f} (paper 0.96).', '']
    return L + param_lines(r, PAPER_EQ5) + ['']


def eq20_section(e20):
    return fit_section('## Eq. 20 (local rheology)', e20, 'No rheology nodes yet.', eq20_rows)


def eq20_rows(e20, r):
    L = [f'`fit-sigmoid` (unweighted, the fit `local-rheology --fit` makes for one run) of the {e20["n"]} '
          'paper-region nodes (I, μ_loc) of all sable runs pooled, against the paper\'s (0.12, 0.40, 0.13). '
          'The nodes are not independent (neighbours share grains through the kernel; every seed\'s and every '
          'point\'s nodes), so the intervals are too narrow and nothing is tested (PLAN). The fields are planar '
          '(szz = 0, 2D stresses in N/m): Eq. 19 *as printed* then gives τ/P₂D exactly, P₂D = (sxx + syy)/2 (the '
          '1/3 and the 3D trace cancel; reference_runs/analysis/README.md, local-rheology notes), the friction '
          'the paper\'s μ1, μ2 describe; I is Eq. 18 with ρ_p d as the 2D density.', '',
          f'R² {r["r_squared"]:.3f}.', '']
    L += ['| parameter | fit | 95 % interval (nodes as independent) | paper | inside |', '|---|---|---|---|---|']
    for k, v in PAPER_EQ20.items():
        L.append(f'| {k} | {fmt(r[k], r[k + "_err"], 4)} | [{fmt(r[k + "_lo"], None, 4)}, {fmt(r[k + "_hi"], None, 4)}]'
                 f' | {v} | {"yes" if r[k + "_lo"] <= v <= r[k + "_hi"] else "no"} |')
    return L + ['']


def eq7_rows(E, S):
    L = ['| N_U | N_P | I_M | scale | n (zeros/negative) | n fitted | μ [95 %] | σ [95 %] | x0 [95 %] | '
         'Gaussian limit | KS D |', '|' + '---|' * 11]
    order = [s for s, *_ in SCALES]
    for (pt, scale), e in sorted(E.items(), key=lambda kv: (S[kv[0][0]]['I_M'], kv[0][0], order.index(kv[0][1]))):
        r = e['row']
        b = lambda v: fmt(v, None, 3) if np.isfinite(v) else 'open'
        iv = lambda k: f'{fmt(r[k], None, 3)} [{b(r[k + "_lo"])}, {b(r[k + "_hi"])}]'
        gl = 'yes' if r['gaussian_limit'] else 'no'
        L.append(f'| {pt[0]:g} | {pt[1]:g} | {S[pt]["I_M"]:.3g} | {scale} | {e["n"]} ({100 * e["zero_frac"]:.1f} %) | '
                 f'{e["n_fit"]} | {iv("mu")} | {iv("sigma")} | {iv("x0")} | {gl} | {r["ks_d"]:.3g} |')
    return L


def eq7_section(E, S):
    L = ['## Eq. 7 (`fit-lognormal`), per point, seeds pooled', '',
         'x = f/f̄ (every grain-wall contact row), F/F̄ (the 10 kHz wall force), F_i/F̄_i (slices 3-9, each over '
         'its own mean). Eq. 7 is a law of x > 0: the values ≤ 0 (no contact, or a tensile damped contact, see '
         'below) are left out of the fit (their share is given) and x keeps the mean of all the values '
         '(`--raw`), so the fitted law is P(x | x > 0) on the paper\'s axis. At most '
         f'{FIT_MAX} positive values per fit, drawn at random (fixed seed) from the pooled ones: fit-lognormal '
         'needs ~8 min on 5e5 values; the profile intervals take the values as independent, which the 10 kHz '
         'series are not (g in the ACF), so they are optimistic for F and F_i. "Gaussian limit": x0 = ∞ inside '
         'the 95 % region, μ, σ, x0 then not meaningful. Reported against I_M, no test (PLAN).', '']
    if not E:
        return L + ['No raw samples under --work: no fits.', '']
    L += eq7_rows(E, S) + ['']
    for scale, *_ in SCALES:
        L += eq7_scale_lines([(S[pt]['I_M'], e) for (pt, sc), e in E.items() if sc == scale], scale)
    return L + ['', 'Parameters against I_M: figure eq7_vs_IM.png; PDFs with the fits: pdf_NU*_NP*.png.', '']


def eq7_scale_lines(es, scale):
    """One scale's fits [(I_M, eq7 result)]: Gaussian-limit flags, σ against I_M, worst KS, tensile values."""
    if not es:
        return []
    es = sorted(es, key=lambda t: t[0])
    flagged = [f'{i:.3g} (truncated normal m {e["row"]["normal_m"]:.3g}, s {e["row"]["normal_s"]:.3g}' +
               (': its peak at x ≤ 0, a PDF decreasing from x = 0, not a Gaussian about the mean)'
                if e['row']['normal_m'] <= 0 else ')') for i, e in es if e['row']['gaussian_limit']]
    sig = ', '.join(f'{i:.3g}: {e["row"]["sigma"]:.2f}' for i, e in es if not e['row']['gaussian_limit'])
    wi, we = max(es, key=lambda t: t[1]['row']['ks_d'])
    ni, ne = max(es, key=lambda t: t[1]['neg_frac'])
    return [f'- {scale}: Gaussian limit at I_M ' + (', '.join(flagged) if flagged else 'none') + f'; σ by I_M: {sig}; '
            f'largest KS D of a fit {we["row"]["ks_d"]:.3f} (I_M {wi:.3g}).',
            f'- {scale} < 0 (tensile; the normal force is not clamped at zero, presumably the dashpot pulling as '
            f'grains leave the wall fast): at most {100 * ne["neg_frac"]:.1f} % of the values (I_M {ni:.3g}, down to '
            f'{ne["min"]:.2f} times the mean).']


def yade_section(C, S, Y, EY, ES, gs):
    hd = next(iter(S.values()))['Hd'] if S else '?'
    L = ['## sable against YADE (issue 43 item 5)', '',
         f'The same sable deposits (H/d {hd}) sheared by sable (runs `{gs}/`) and by YADE (sweep.py `yade`: the deck '
         'exported by `sable --export-yade`, fields off), seed by seed. Criterion, the harness\'s tolerance '
         f'(sable_tools/compare_seeds.py: |mean_s − mean_ref| ≤ K SE) with K = {YADE_TOL:g}: '
         '|F̄_sable − F̄_YADE| ≤ 2 sqrt(SE_s² + SE_y²), the seed SEs.', '',
         '| N_U | N_P | code | seeds | F̄/(PLd) | F_cv | F_zero | Φ* | difference | combined SE | |d|/SE | verdict |',
         '|' + '---|' * 12]
    for pt, c in C.items():
        for code, X in (('sable', S), ('YADE', Y)):
            s = X[pt]
            tail = (f'{c["diff"]:+.4f} | {c["comb"]:.4f} | {abs(c["diff"]) / c["comb"]:.2f} | '
                    f'{"pass" if c["pass"] else "fail" if c["pass"] is not None else "— (1 seed)"}'
                    if code == 'sable' else ' | | | ')
            L.append(f'| {pt[0]:g} | {pt[1]:g} | {code} | {",".join(map(str, s["seeds"]))} | {fmt(*s["F"])} | '
                     f'{fmt(*s["cv"])} | {fmt(*s["zero"])} | {fmt(*s["phi"])} | {tail} |')
    L += ['', 'Outside the criterion, as both codes start from the same deposit per seed: the seed-by-seed '
          'differences sable − YADE, mean ± SE: ' + ', '.join(f'{ptag(pt)} {fmt(*c["paired"], 4)}'
                                                          for pt, c in C.items()) + '.']
    L += ['', 'KS distances sable vs YADE of the pooled samples (all values); critical D for the decorrelated '
          'sizes (contact rows f: n itself, their correlation is not measured):', '',
          '| N_U | N_P | scale | D | critical D (n/g) | critical D (n) | n sable | n YADE |', '|' + '---|' * 8]
    for pt, c in C.items():
        for scale, k in c['ks'].items():
            L.append(f'| {pt[0]:g} | {pt[1]:g} | {scale} | {k["d"]:.4f} | {k["critical_dec"]:.4f} | '
                     f'{k["critical"]:.4f} | {k["n_a"]:.0f} | {k["n_b"]:.0f} |')
    L += ['', 'Eq. 7 per code (as in the Eq. 7 section):', '']
    both = {k: v for k, v in ES.items() if k[0] in C}
    L += ['sable:', ''] + eq7_rows(both, S) + ['', 'YADE:', ''] + eq7_rows(EY, Y)
    return L + ['']


def dtc_words(S):
    """The spread of Δt_c and (U/d)Δt_c over I_M, in one sentence (None with fewer than 2 points)."""
    pts = sorted(S, key=lambda p: S[p]['I_M'])
    dt = np.array([S[p]['dtc'][0] for p in pts]) * 1e3
    ud = np.array([S[p]['U'] / S[p]['d'] * S[p]['dtc'][0] for p in pts])
    if len(pts) < 2 or not np.isfinite(dt).any():
        return None
    k = int(np.nanargmin(ud))
    return (f'Δt_c of F spans {np.nanmin(dt):.3g}-{np.nanmax(dt):.3g} ms ({np.nanmax(dt) / np.nanmin(dt):.1f}-fold) '
            f'and (U/d)Δt_c {np.nanmin(ud):.3g}-{np.nanmax(ud):.3g} ({np.nanmax(ud) / np.nanmin(ud):.1f}-fold, '
            'smallest at '
            f'I_M {S[pts[k]]["I_M"]:.3g}) over I_M {S[pts[0]]["I_M"]:.3g}-{S[pts[-1]]["I_M"]:.3g}: a dependence on '
            'I_M, where the plan records the paper as finding no clear one')


def phi_words(S):
    """Φ*'s drop up to I_M 0.03 against its drop beyond, against Fig. 15a's plateau then decrease."""
    ph = [(S[p]['I_M'], S[p]['phi'][0]) for p in sorted(S, key=lambda p: S[p]['I_M'])]
    lo = [m for i, m in ph if i <= 0.03]
    if len(lo) < 2 or ph[-1][0] <= 0.1:
        return None
    a, b = lo[0] - lo[-1], lo[-1] - ph[-1][1]
    return (f'Φ* falls by {a:.4f} up to I_M 0.03 and by {b:.4f} from there to I_M {ph[-1][0]:.3g}: ' +
            ('a near-plateau then a decrease, the shape of the paper\'s Fig. 15a' if a < 0.5 * b else
             'no clear plateau at small I_M, unlike the paper\'s Fig. 15a'))


def dtc_phi_section(S):
    pts = sorted(S, key=lambda p: S[p]['I_M'])
    L = ['## Δt_c and Φ* against I_M', '']
    w = dtc_words(S)
    if w:
        L.append(f'- {w} (first lag with C < 0.15, seed means, table above; figures dtc_vs_IM.png, acf_F.png). The '
                 'same-I_M pairs (section above) tell Δt_c apart from (U/d)Δt_c.')
        L.append('- C_F(Δt) has peaks at multiples of d/U (acf_F.png: (U/d)Δt = 1, 2, 3): the lid\'s grains, one '
                 'diameter apart, pass the wall at U; Δt_c is the first crossing, before the first peak.')
    L.append('- Φ* (phi3D, seed means) by I_M: ' +
             ', '.join(f'{S[p]["I_M"]:.3g}: {fmt(*S[p]["phi"], 4)}' for p in pts) +
             ' (figure phi_vs_IM.png).')
    w = phi_words(S)
    if w:
        L.append(f'- {w}.')
    return L + ['']


def against(row, paper):
    return ', '.join(f'{k} {row[k]:.3g} [{row[k + "_lo"]:.3g}, {row[k + "_hi"]:.3g}] '
                     f'({"consistent with" if verdict(row, k, v) == "consistent" else "different from"} {v})'
                     for k, v in paper.items())


def pair_words(t):
    eqv, dif = t['p_tost'] < ALPHA, t['p_diff'] < ALPHA
    if eqv and dif:
        return ('a difference is detected, but it lies within the ±0.05 margin (equivalent): the I_M scaling of '
                'the paper holds to within the margin, not exactly')
    if eqv:
        return 'agrees with the paper (F̄/(PLd) a function of I_M alone): equivalent within ±0.05'
    if dif:
        return 'disagrees with the paper: the two (N_U, N_P) at one I_M differ'
    return 'inconclusive: no difference detected, equivalence within ±0.05 not shown'


def summary_section(e4, e5, e20, P, C, S):
    L = ['## Against the paper, in short', '']
    if e4:
        L.append('- Eq. 4' + (' (preliminary, unweighted)' if not e4['weighted'] else '') + ': ' +
                 against(e4['row'], PAPER_EQ4) +
            (f'; the paper\'s curve gives χ²/n {e4["chi2n"]:.3g} on our seed SEs' if e4['z'] else '') +
            ('; unweighted (a check outside the plan): ' + ', '.join(
                f'{k} {verdict(e4["row_u"], k, v)}' for k, v in PAPER_EQ4.items()) if e4['row_u'] else '') + '.')
    if e5:
        L.append('- Eq. 5: ' + against(e5['row'], PAPER_EQ5) + '.')
    if e20:
        L.append('- Eq. 20 (no test): ' + ', '.join(f'{k} {e20["row"][k]:.3g} (paper {v})'
                                                   for k, v in PAPER_EQ20.items()) + '.')
    for name, t in P.items():
        if t:
            (a, ua), (b, ub) = t['dtc']
            L.append(f'- Pair {name}: {pair_words(t)} (difference {t["d"]:+.3f}, Welch p {t["p_diff"]:.3g}, TOST p '
                     f'{t["p_tost"]:.3g}). Its Δt_c(F) differ {max(a, b) / min(a, b):.2f}-fold, (U/d)Δt_c by '
                     f'{100 * abs(ua - ub) / min(ua, ub):.0f} %.')
    for w in (dtc_words(S), phi_words(S)):
        if w:
            L.append(f'- {w}.')
    for pt, c in C.items():
        v = 'pass' if c['pass'] else 'fail' if c['pass'] is not None else 'not tested (1 seed)'
        L.append(f'- YADE {ptag(pt)}: sable − YADE {c["diff"]:+.3f}, {abs(c["diff"]) / c["comb"]:.2f} combined SE: '
                 f'{v}.')
    return L + ['']


def departures():
    return ['## How the analysis departs from the plan\'s wording', '',
            '- Eq. 7: fitted to the positive values only (Eq. 7 is a law of x > 0; fit-lognormal refuses x ≤ 0) '
            f'with `--raw`, and to at most {FIT_MAX} of them drawn at random per point and scale (run time).',
            '- Eq. 20: `fit-sigmoid --names mu1,mu2,I0` on the pooled nodes of all runs (the unweighted fit that '
            '`local-rheology --fit` makes of one field file).',
            '- Eq. 5: unweighted (the plan names no weights; ℓ/L has its own seed scatter).',
            '- Eq. 4: while fewer than 4 points have two seeds, an unweighted preliminary fit of all points '
            '(marked as such); the plan\'s weighted fit once 4 points have seed SEs.', '']


# ---------------------------------------------------------------- figures

def colour(S, pt):
    import matplotlib.pyplot as plt
    lo, hi = np.log10(2e-3), np.log10(0.5)
    return plt.cm.viridis(np.clip((np.log10(S[pt]['I_M']) - lo) / (hi - lo), 0, 0.9))


def xy(S, key, pts=None):
    pts = sorted(S, key=lambda p: S[p]['I_M']) if pts is None else pts
    return (np.array([S[p]['I_M'] for p in pts]), np.array([S[p][key][0] for p in pts]),
            np.array([S[p][key][1] for p in pts]))


def errorbar(ax, x, y, e, fmt='o', **kw):
    ax.errorbar(x, y, yerr=np.where(np.isfinite(e), e, 0), fmt=fmt, capsize=2, **kw)


def fig_eq4(figs, S, SC, Y, e4):
    fig, ax = figstyle.figure()
    x, y, e = xy(S, 'F')
    errorbar(ax, x, y, e, color=figstyle.COLOURS[0], zorder=3,
             label=f'sable, $H/d$ {next(iter(S.values()))["Hd"]} (seed mean ± SE)')
    for p in S:
        ax.plot([S[p]['I_M']] * S[p]['n'], S[p]['F_seeds'], '.', color='0.6', ms=2)
    if SC:
        xs, ys, es = xy(SC, 'F')
        errorbar(ax, xs, ys, es, color=figstyle.COLOURS[3], fmt='s', mfc='none',
                 label=f'sable, $H/d$ {next(iter(SC.values()))["Hd"]}')
    if Y:
        xy_, yy, ey = xy(Y, 'F')
        errorbar(ax, xy_ * 1.08, yy, ey, color=figstyle.COLOURS[2], mfc='none',
                 label=f'YADE, $H/d$ {next(iter(Y.values()))["Hd"]}')
    g = np.geomspace(1e-3, 1, 200)
    ax.plot(g, sigmoid(g, *PAPER_EQ4.values()), '--', color=figstyle.COLOURS[1], label='Eq. 4, paper')
    if e4:
        ax.plot(e4['curve']['x'], e4['curve']['fit'], '-', color=figstyle.COLOURS[1],
                label='Eq. 4, refit' + ('' if e4['weighted'] else ' (unweighted)'))
    ax.set(xscale='log', xlabel='$I_M$', ylabel=r'$\bar F/(PLd)$')
    ax.legend()
    figstyle.save(fig, os.path.join(figs, 'F_vs_IM.png'))


def fig_vs_im(figs, S, key, ylabel, name):
    fig, ax = figstyle.figure()
    x, y, e = xy(S, key)
    ok = np.isfinite(y)
    errorbar(ax, x[ok], y[ok], e[ok], color=figstyle.COLOURS[0])
    ax.set(xscale='log', xlabel='$I_M$', ylabel=ylabel)
    figstyle.save(fig, os.path.join(figs, name))


def fig_eq5(figs, S, e5):
    pts = [p for p in S if np.isfinite(S[p]['ell'][0])]
    if not pts:
        return
    fig, ax = figstyle.figure()
    for p in pts:
        inside = S[p]['I_M'] > EQ5_IM_MIN
        ax.errorbar(S[p]['ell'][0], S[p]['F'][0], xerr=np.nan_to_num(S[p]['ell'][1]),
                    yerr=np.nan_to_num(S[p]['F'][1]), fmt='o' if inside else 's', mfc=None if inside else 'none',
                    color=colour(S, p), capsize=2, ms=4)
    g = np.linspace(0, 1, 50)
    ax.plot(g, PAPER_EQ5['c1'] - PAPER_EQ5['c2'] * g, '--', color=figstyle.COLOURS[1], label='Eq. 5, paper')
    if e5:
        ax.plot(g, e5['row']['c1'] - e5['row']['c2'] * g, '-', color=figstyle.COLOURS[1], label='fit, $I_M>10^{-2}$')
    ax.set(xlabel=r'$\ell/L$', ylabel=r'$\bar F/(PLd)$', xlim=(0, 1))
    ax.legend(title='colour: $I_M$; open squares: $I_M\\leq10^{-2}$')
    figstyle.save(fig, os.path.join(figs, 'F_vs_ell.png'))


def hist(tmp, x, lims, name):
    """sable-analyze pdf of the positive values on fixed bins (--raw: x as given)."""
    name = os.path.join(tmp, os.path.basename(name))
    src = write_csv(name + '.csv', x=x[x > 0])
    out = name + '_pdf.csv'
    analyze('pdf', src, '--column', 'x', '--raw', '--lo', lims[0], '--hi', lims[1], '--nbins', NBINS, '--out', out)
    return analyze_csv.table(out)


def pdf_panels(tmp, work, series, name, title):
    """2 x 3 panels (linear, log-linear) x (f, F, F_i); series: [(label, colour, code, runs, {scale: eq7})]."""
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 3, figsize=(2 * figstyle.WIDTH_IN, figstyle.WIDTH_IN * 0.95), layout='constrained')
    for j, (scale, lab, fname, lims) in enumerate(SCALES):
        for label, c, code, runs, E in series:
            x, _ = pooled(work, code, runs, fname)
            if not len(x):
                continue
            h = hist(tmp, x, lims, f'{name}_{code}_{scale}')
            e = E.get(scale)
            for ax in axes[:, j]:
                ax.plot(h['x'], h['pdf'], 'o', ms=2, color=c, mfc='none', label=label)
                if e:
                    ax.plot(e['curve']['x'], e['curve']['fit'], '-', color=c,
                            label=label + (', Gaussian limit' if e['row']['gaussian_limit'] else ', Eq. 7'))
        axes[0, j].set(xlim=lims)
        axes[1, j].set(xlabel=lab, yscale='log', xlim=lims)
    for ax in axes[:, 0]:
        ax.set_ylabel(r'$P(x\,|\,x>0)$')
    axes[0, 0].legend(fontsize=5)
    fig.suptitle(title, fontsize=8)
    figstyle.save(fig, name)


def fig_pdfs(figs, tmp, work, runs, S, ES):
    for pt in sorted(runs['sable'], key=lambda p: S[p]['I_M']):
        E = {s: ES.get((pt, s)) for s, *_ in SCALES}
        pdf_panels(tmp, work, [('sable', figstyle.COLOURS[0], 'sable', runs['sable'][pt], E)],
                   os.path.join(figs, f'pdf_{ptag(pt)}.png'),
                   f'$N_U$ {pt[0]:g}, $N_P$ {pt[1]:g}, $I_M$ {S[pt]["I_M"]:.3g}, seeds pooled')


def fig_yade_pdfs(figs, tmp, work, runs, gs, gy, S, ES, EY):
    for pt in runs[gy]:
        if pt not in runs[gs]:
            continue
        ser = [('sable', figstyle.COLOURS[0], gs, runs[gs][pt], {s: ES.get((pt, s)) for s, *_ in SCALES}),
               ('YADE', figstyle.COLOURS[2], gy, runs[gy][pt], {s: EY.get((pt, s)) for s, *_ in SCALES})]
        pdf_panels(tmp, work, ser, os.path.join(figs, f'pdf_yade_{ptag(pt)}.png'),
                   f'sable and YADE, $H/d$ {S[pt]["Hd"]}, $N_U$ {pt[0]:g}, $N_P$ {pt[1]:g}, $I_M$ {S[pt]["I_M"]:.3g}')


def fig_acf(figs, runs, S):
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(2 * figstyle.WIDTH_IN, figstyle.WIDTH_IN * 0.7), layout='constrained')
    for pt in sorted(runs['sable'], key=lambda p: S[p]['I_M']):
        rs = runs['sable'][pt]
        c = np.mean([r['acf']['F']['c'] for r in rs], axis=0)
        t = np.arange(len(c)) * rs[0]['sample_dt']
        kw = dict(color=colour(S, pt), label=f'{S[pt]["I_M"]:.3g}')
        axes[0].plot(t * 1e3, c, **kw)
        axes[1].plot(t * S[pt]['U'] / S[pt]['d'], c, **kw)
    for ax in axes:
        ax.axhline(0.15, color='0.6', lw=0.6, ls=':')
    axes[0].set(xlabel=r'$\Delta t$ (ms)', ylabel=r'$C_F(\Delta t)$ (seed mean)')
    axes[1].set(xlabel=r'$(U/d)\,\Delta t$', xscale='log')
    axes[0].legend(title='$I_M$', fontsize=5)
    figstyle.save(fig, os.path.join(figs, 'acf_F.png'))


def fig_acf_slices(figs, runs, S):
    """kneib2017 Fig. 9: C^i of each slice's force (seed mean) at the lowest, a middle and the
    highest I_M, against (U/d) dt; slices no grain touched in a seed have no C and are left out."""
    import matplotlib.pyplot as plt
    pts = sorted(runs['sable'], key=lambda p: S[p]['I_M'])
    pick = [pts[0], pts[len(pts) // 2], pts[-1]]
    fig, axes = plt.subplots(1, 3, figsize=(3 * figstyle.WIDTH_IN, figstyle.WIDTH_IN * 0.7), layout='constrained',
                             sharey=True)
    cmap = plt.get_cmap('viridis')
    for ax, pt in zip(axes, pick):
        rs = runs['sable'][pt]
        for i in range(1, 11):
            cs = [r['acf'][f'F{i}']['c'] for r in rs if r['acf'][f'F{i}']['c']]
            if not cs:
                continue
            c = np.mean(cs, axis=0)
            t = np.arange(len(c)) * rs[0]['sample_dt'] * S[pt]['U'] / S[pt]['d']
            ax.plot(t, c, color=cmap((i - 1) / 9), lw=0.8, label=f'{i}')
        ax.axhline(0.15, color='0.6', lw=0.6, ls=':')
        ax.set(xlabel=r'$(U/d)\,\Delta t$', xscale='log',
               title=f'$N_U$ {pt[0]:g}, $N_P$ {pt[1]:g}, $I_M$ {S[pt]["I_M"]:.3g}')
    axes[0].set(ylabel=r'$C^i(\Delta t)$ (seed mean)')
    axes[-1].legend(title='slice $i$', fontsize=5, ncol=2)
    figstyle.save(fig, os.path.join(figs, 'acf_slices.png'))


def fig_dtc(figs, S):
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(2 * figstyle.WIDTH_IN, figstyle.WIDTH_IN * 0.7), layout='constrained')
    x, y, e = xy(S, 'dtc')
    _, ys, es = xy(S, 'dtc_sl')
    ud = np.array([S[p]['U'] / S[p]['d'] for p in sorted(S, key=lambda p: S[p]['I_M'])])
    for ax, f in ((axes[0], 1e3), (axes[1], ud)):
        errorbar(ax, x, y * f, e * f, color=figstyle.COLOURS[0], label='$F$')
        errorbar(ax, x * 1.06, ys * f, es * f, color=figstyle.COLOURS[2], mfc='none', label='$F_i$, 3-9 (mean)')
        ax.set(xscale='log', xlabel='$I_M$', yscale='log')
    axes[0].set(ylabel=r'$\Delta t_c$ (ms), $C<0.15$')
    axes[1].set(ylabel=r'$(U/d)\,\Delta t_c$', yscale='log')
    axes[0].legend()
    figstyle.save(fig, os.path.join(figs, 'dtc_vs_IM.png'))


def fig_eq7(figs, E, S):
    """mu, sigma, x0 of Eq. 7 against I_M per scale; fits in the Gaussian limit (parameters not meaningful)
    are left out."""
    import matplotlib.pyplot as plt
    if not E:
        return
    fig, axes = plt.subplots(1, 3, figsize=(2 * figstyle.WIDTH_IN, figstyle.WIDTH_IN * 0.6), layout='constrained')
    for k, (scale, lab, *_) in enumerate(SCALES):
        es = sorted(((S[pt]['I_M'], e['row']) for (pt, sc), e in E.items()
                     if sc == scale and not e['row']['gaussian_limit']), key=lambda t: t[0])
        for ax, par in zip(axes, ('mu', 'sigma', 'x0')):
            for i, r in es:
                hi = r[par + '_hi'] if np.isfinite(r[par + '_hi']) else r[par]
                ax.errorbar(i * 1.04 ** k, r[par], yerr=[[r[par] - r[par + '_lo']], [max(hi - r[par], 0)]],
                            fmt='os^'[k], color=figstyle.COLOURS[k], capsize=1.5, label=lab if i == es[0][0] else None)
            ax.set(xscale='log', xlabel='$I_M$', title={'mu': 'μ', 'sigma': 'σ', 'x0': '$x_0$'}[par],
                   yscale='log' if par == 'x0' else 'linear')
    axes[0].legend(fontsize=6, title='Gaussian limits left out', title_fontsize=6)
    figstyle.save(fig, os.path.join(figs, 'eq7_vs_IM.png'))


def fig_rheology(figs, e20):
    if e20 is None:
        return
    fig, ax = figstyle.figure()
    ax.plot(e20['I'], e20['mu'], '.', ms=1, color='0.6', alpha=0.5, label='nodes, all runs', rasterized=True)
    g = np.geomspace(e20['I'].min(), e20['I'].max(), 200)
    ax.plot(g, sigmoid(g, *PAPER_EQ20.values()), '--', color=figstyle.COLOURS[1], label='Eq. 20, paper')
    ax.plot(e20['curve']['x'], e20['curve']['fit'], '-', color=figstyle.COLOURS[1], label='Eq. 20, fit')
    ax.set(xscale='log', xlabel='$I$ (Eq. 18)', ylabel=r'$\mu_{loc}$ (Eq. 19)')
    ax.legend()
    figstyle.save(fig, os.path.join(figs, 'mu_vs_I.png'))


# ---------------------------------------------------------------- main

def report(R):
    miss, extra = missing(R.runs)
    n = {g: sum(len(v) for v in R.runs[g].values()) for g in GROUPS}
    L = ['# Cavity sweep (kneib2017, issue 43 items 4 and 5): report', '',
         f'Written by `python3 -m sable_tools.cavity.sweep_figures` ({time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}) '
         'from the runs under `runs/` (' + ', '.join(f'{g}: {k}' for g, k in n.items() if k) + '), following '
         '`PLAN.md` (points, seeds, tests and margins fixed before the runs). Figures: `figures/`.', '']
    L += summary_section(R.e4, R.e5, R.e20, R.P, R.C, R.S) + runs_section(R.runs, miss, extra) + point_table(R.S)
    L += eq4_section(R.e4, R.S) + pair_section(R.P, R.S) + eq5_section(R.e5, R.S) + eq20_section(R.e20)
    L += eq7_section(R.ES, R.S) + dtc_phi_section(R.S)
    if R.C:
        L += yade_section(R.C, R.SC, R.Y, R.EY, R.ESC, R.gs)
    return '\n'.join(L + departures())


def figures(figs, tmp, work, R):
    os.makedirs(figs, exist_ok=True)
    fig_eq4(figs, R.S, R.SC, R.Y, R.e4)
    fig_vs_im(figs, R.S, 'ell', r'$\ell/L$', 'ell_vs_IM.png')
    fig_vs_im(figs, R.S, 'phi', r'$\Phi^*$', 'phi_vs_IM.png')
    fig_eq5(figs, R.S, R.e5)
    fig_acf(figs, R.runs, R.S)
    fig_acf_slices(figs, R.runs, R.S)
    fig_dtc(figs, R.S)
    fig_rheology(figs, R.e20)
    fig_eq7(figs, R.ES, R.S)
    fig_pdfs(figs, tmp, work, R.runs, R.S, R.ES)
    fig_yade_pdfs(figs, tmp, work, R.runs, R.gs, R.gy, R.SC, R.ESC, R.EY)


def analyse(tmp, work, runs):
    """Every number of the report, as attributes of one namespace."""
    R = argparse.Namespace(runs=runs)
    R.S = {pt: summary(rs) for pt, rs in runs['sable'].items()}
    R.gs, R.gy = GS, GY
    R.SC = {pt: summary(rs) for pt, rs in runs[GS].items()}
    R.Y = {pt: summary(rs) for pt, rs in runs[R.gy].items()}
    R.e4, R.e5, R.e20 = eq4(tmp, R.S), eq5(tmp, R.S), eq20(tmp, runs['sable'])
    R.P = pair_tests(tmp, work, runs['sable'], R.S)
    R.ES = eq7_all(work, runs, 'sable')
    R.ESC = eq7_all(work, runs, GS)
    R.EY = eq7_all(work, runs, R.gy)
    R.C = yade_compare(tmp, work, runs, R.gs, R.gy, R.SC, R.Y)
    return R


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--runs', default=os.path.join(ROOT, 'reference_runs', 'cavity', 'sweep', 'runs'))
    p.add_argument('--work', default='/work/cavity_sweep')
    p.add_argument('--out', default=os.path.join(ROOT, 'reference_runs', 'cavity', 'sweep'))
    a = p.parse_args()
    runs = load_runs(a.runs)
    if not runs['sable']:
        sys.exit(f'sweep_figures: no sable runs under {a.runs}')
    print('missing from the plan: ' + listing(missing(runs)[0]))
    figstyle.use()
    import matplotlib.pyplot as plt
    plt.rcParams['savefig.dpi'] = 150  # committed after every batch of runs: small PNGs (figstyle's 300 is for papers)
    with tempfile.TemporaryDirectory() as tmp:
        R = analyse(tmp, a.work, runs)
        os.makedirs(a.out, exist_ok=True)
        with open(os.path.join(a.out, 'REPORT.md'), 'w') as f:
            f.write(report(R) + '\n')
        figures(os.path.join(a.out, 'figures'), tmp, a.work, R)
    print(f'wrote {a.out}/REPORT.md and {a.out}/figures/')


if __name__ == '__main__':
    main()
