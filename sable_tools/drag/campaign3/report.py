#!/usr/bin/python3
"""Drag campaign 3's report: the pre-registered tests of PLAN.md on the runs made so far.

    /usr/bin/python3 -m sable_tools.drag.campaign3.report --out RUNS_DIR [--report DIR]
        [--cases cases/all.json]

Reads every OUT/<case>/<code>_s<seed>/run.json of the campaign's cases (--cases, default
cases/all.json: the plan's runs and seeds) and writes DIR/REPORT.md (default DIR: this folder)
and DIR/drag_turns.png, drag_depth.png, drag_stiffness.png. A run counts when its status is
ok and its seed is a planned one; runs not (yet) finished, failed runs and seeds beyond the
plan are listed, never an error (the campaign spans many sessions), and a test whose inputs
are not all finished says 'incomplete: N of M runs' instead of a verdict. Every mean, error,
interval and test is sable_tools/seedstats.py's (α 0.05; 90 % intervals); the
torque curves are report_drag.py's reader. REPORT.md ends with the departures from the plan
that this script detects and, verbatim, DIR/departures.md (written by hand) if present.
"""
import argparse, datetime, glob, json, math, os

from sable_tools import seedstats as S  # every statistic over seeds
from sable_tools.drag import run_drag  # the deck's numbers and the runs' folders
from sable_tools.drag.report_drag import torque_curve, seed_mean_curve  # F*(turns) of a run; mean and sd over seeds
from sable_tools.paths import repo_path
import matplotlib.pyplot as plt  # noqa: E402  (report_drag chose the Agg backend)

HERE = repo_path('reference_runs', 'drag', 'campaign3')  # the campaign's cases, runs and report

CODES = ('sable', 'liggghts')
NAMES = {'sable': 'sable', 'liggghts': 'LIGGGHTS'}
BUDGET = {'sable': 30.0, 'liggghts': 20.0}  # core-hours (PLAN.md)
SPEED = {'sable': 1.38e7, 'liggghts': 4.03e6}  # CPU particle-steps/s of the earlier runs (PLAN.md's ledger, power.py)
OPTIONAL, OPTIONAL_LEDGER = 'E4e7_h3.7', 26.2  # run only if the sable ledger after every other run is at most this
FIG3 = 3.7  # nominal h/L of the stiffness cases (measured ~3.9)
DEEP = ('2', '3.7', '5')  # nominal depths of the slope above 2 L
TURNS_CASES = ('stiff_h1', 'stiff_h5', 'soft_h5')
T6_CASES = ('stiff_h1', 'stiff_h3.7', 'stiff_h5', 'soft_h5')
T6_MARGIN = {'F_stat': 0.15, 'F_first': 0.20}
T7_CASES = ('soft_h3.7', 'E4e5_h3.7', 'stiff_h3.7', 'E3e6_h3.7', 'E1e7_h3.7')
SERIES = {'soft': 'tab:orange', 'stiff': 'tab:blue', 'wall': 'tab:green'}
QLABEL = {'F_stat': 'F_stat: F* over turns 3-6', 'F_first': 'F_first: F* over the first half-turn'}
IGNORED_VARS = ('seed', 'stl', 'out')


# ---------------------------------------------------------------- reading runs
def read_json(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def load_cases(path):
    cases = json.load(open(path))['cases']
    for c in cases:
        c['scene'] = run_drag.scene(c['vars'])
    return cases


def found_seeds(out, case, code):
    """The seeds of the run folders OUT/<case>/<code>_s<seed>/ there are."""
    tails = [os.path.basename(p).split('_s', 1)[1] for p in glob.glob(os.path.join(out, case['name'], f'{code}_s*'))]
    return sorted(int(t) for t in tails if t.isdigit())


def read_run(out, case, code, seed):
    """One run folder: (status, record); status ok, failed, unfinished (a folder, no verdict yet) or missing."""
    folder = run_drag.run_dir(out, case, code, seed)
    rec = read_json(os.path.join(folder, 'run.json')) or {}
    rec.update(seed=seed, folder=folder, state=read_json(os.path.join(folder, 'pieces.json')))
    status = rec.get('status') if rec.get('status') in ('ok', 'failed') else None
    return status or ('unfinished' if os.path.isdir(folder) else 'missing'), rec


def read_group(out, case, code):
    """A case's runs by one code: 'ok' (planned seeds only: the ones the tests use), 'extra'
    (finished, seeds beyond the plan), 'failed', 'unfinished', 'missing' (planned, no folder)."""
    planned = case['seeds'].get(code, [])
    g = {'case': case, 'name': case['name'], 'code': code, 'planned': planned,
         'ok': [], 'extra': [], 'failed': [], 'unfinished': [], 'missing': []}
    for seed in planned + [s for s in found_seeds(out, case, code) if s not in planned]:
        status, rec = read_run(out, case, code, seed)
        key = 'extra' if status == 'ok' and seed not in planned else status
        if key != 'missing' or seed in planned:
            g[key].append(rec)
    return g


class Groups(dict):
    """(case name, code) -> its group; a case that the case file lacks reads as an absent group."""
    def __missing__(self, key):
        return {'case': None, 'name': key[0], 'code': key[1], 'absent': True, 'planned': [], 'ok': [], 'extra': [],
                'failed': [], 'unfinished': [], 'missing': []}


def read_all(out, cases):
    return Groups({(c['name'], code): read_group(out, c, code) for c in cases for code in CODES})


# ---------------------------------------------------------------- per group
def values(g, q):
    return [r['result'][q] for r in g['ok']]


def stat(g, q):
    return S.summary(values(g, q))


def depth(g):
    """Seed mean of the measured depth h_meas, in L."""
    return S.summary([r['result'].get('h_meas') for r in g['ok']]).mean / g['case']['scene']['L']


def window(rec):
    """The run's window half-turn means (6 in this campaign)."""
    return rec.get('blocks') or (rec.get('halves') or [])[-int(rec['result']['turns']):]


def trend(rec):
    """T0 per run: the least-squares slope of the window's half-turn means against their index
    (each block a group of one: the plain slope of the values), times n - 1 half-turns (5 for 6
    blocks), as a fraction of F_stat."""
    b = window(rec)
    if len(b) < 2:
        return math.nan
    return S.slope(list(range(len(b))), [[x] for x in b]).est * (len(b) - 1) / rec['result']['F_stat']


def cpu_spent(rec):
    """CPU seconds a run has cost so far: a finished run's, else its finished pieces'."""
    if rec.get('status') == 'ok' or not rec.get('state'):
        return rec.get('cpu_s') or 0.0
    return sum(p.get('cpu_s', 0.0) for p in rec['state'].get('pieces', []))


def estimate_h(g):
    """The plan's core-hours for one run of the group (run_drag.scene's particle-steps at SPEED)."""
    return g['case']['scene']['particle_steps'] / SPEED[g['code']] / 3600


def progress(groups):
    """(runs finished, runs planned) over the groups."""
    return sum(len(g['ok']) for g in groups), sum(len(g['planned']) for g in groups)


# ---------------------------------------------------------------- the tests
def per_depth(g, q):
    """A seed mean over its measured depth (the depth as known: the seed error is the mean's)."""
    s, h = stat(g, q), depth(g)
    return S.interval(s.mean / h, s.se / h, s.df)


def difference(a, b):
    """a - b of two independent estimates (Welch-Satterthwaite df)."""
    return S.interval(a.est - b.est, math.hypot(a.se, b.se), S.satterthwaite([(a.se ** 2, a.df), (b.se ** 2, b.df)]))


def depth_slope(deep):
    """The least-squares slope of the seed-mean F_stat against the measured h/L."""
    return S.slope([depth(g) for g in deep], [stat(g, 'F_stat') for g in deep])


def depth_ratio(deep, shallow):
    """T1's r = b / b0, b the slope over the deep groups, b0 = F_stat / (h/L) of the shallow one."""
    b, b0 = depth_slope(deep), per_depth(shallow, 'F_stat')
    return S.ratio(b, b0), f'b {b.est:.2f} ± {b.se:.2f}, b0 {b0.est:.2f} ± {b0.se:.2f} per L'


def row(test, what, groups, margin, compute, words=('pass', 'not shown'), note=''):
    """One line of the tests' table. compute() -> (estimate, test result or None, detail); run
    only when every group has two finished seeds; the verdict only when every planned run is in."""
    n, m = progress(groups)
    r = {'test': test, 'what': what, 'margin': margin, 'groups': groups, 'note': note, 'pass': None, 'e': None,
         't': None, 'detail': ''}
    if all(len(g['ok']) >= 2 for g in groups):
        r['e'], r['t'], r['detail'] = compute()
    if any(g.get('absent') for g in groups):
        r['verdict'] = 'not in the case file: ' + ', '.join(sorted({g['name'] for g in groups if g.get('absent')}))
    elif n < m:
        r['verdict'] = f'incomplete: {n} of {m} runs'
    elif r['t'] is None:
        r['verdict'] = 'reported, not judged' if r['e'] else 'not testable (under 2 seeds)'
    else:
        r['pass'] = bool(getattr(r['t'], 'equivalent', getattr(r['t'], 'significant', False)))
        r['verdict'] = words[0] if r['pass'] else words[1]
    return r


def t0_rows(G, cases):
    rows = []
    for c in cases:
        for code in CODES:
            g = G[(c['name'], code)]
            if g['planned']:
                rows.append(row('T0', f"{c['name']} {NAMES[code]}: window trend / F_stat", [g], '± 0.15',
                                lambda g=g: t0(g), ('stationary', 'not shown stationary')))
    return rows


def t0(g):
    s = S.summary([trend(r) for r in g['ok']])
    e = S.interval(s.mean, s.se, s.df)
    return e, S.tost(e, 0.15), ''


def t1_t4_rows(G):
    sg = lambda kind, code='sable': [G[(f'{kind}_h{h}', code)] for h in DEEP]
    s1 = G[('stiff_h1', 'sable')]
    r = lambda kind, base: depth_ratio(sg(kind), base)
    rows = [row('T1', 'r_stiff = b / b0 (stiff levels, C1)', sg('stiff') + [s1], '± 0.15',
                lambda: eq(r('stiff', s1), 0.15), ('levels', 'not shown level')),
            row('T2', 'r_soft (soft keeps growing, C2)', sg('soft') + [G[('soft_h1', 'sable')]], '> 0.15',
                lambda: above(r('soft', G[('soft_h1', 'sable')]), 0.15), ('keeps growing', 'not shown growing')),
            row('T3', 'r_soft − r_stiff', sg('soft') + [G[('soft_h1', 'sable')]] + sg('stiff') + [s1], '> 0',
                lambda: above_diff(r('soft', G[('soft_h1', 'sable')]), r('stiff', s1)),
                ('soft grows more', 'not shown')),
            row('T4', 'r_wall (b0 from stiff_h1; frictionless side wall)', sg('wall') + [s1], '± 0.15',
                lambda: eq(r('wall', s1), 0.15), ('levels without wall friction', 'not shown level')),
            row('T4', 'r_wall − r_stiff = (b_wall − b_stiff) / b0', sg('wall') + sg('stiff') + [s1], '',
                lambda: (S.ratio(difference(depth_slope(sg('wall')), depth_slope(sg('stiff'))),
                                 per_depth(s1, 'F_stat')), None, ''))]
    return rows


def eq(rd, margin, hi=None):
    """(estimate, TOST, detail) of an (estimate, detail) pair: equivalent to 0 within ± margin
    (or inside (margin, hi))."""
    e, detail = rd
    return e, S.tost(e, margin, margin_hi=hi), detail


def reported(rd):
    """(estimate, no test, detail): shown, not judged."""
    return rd[0], None, rd[1]


def above(rd, threshold):
    e, detail = rd
    return e, S.one_sided(e, threshold), detail


def above_diff(a, b):
    d = difference(a[0], b[0])
    return d, S.one_sided(d, 0.0), f'r_soft {a[0].est:.3f}, r_stiff {b[0].est:.3f}'


def t5_rows(G):
    rows = []
    for kind in ('soft', 'stiff'):
        gs = [G[(f'{kind}_h{h}', 'sable')] for h in ('1', '2', '3.7', '5')]
        per = lambda gs=gs: ', '.join(f'{depth(g):.2f} L: {per_depth(g, "F_first").est:.2f}' for g in gs if g['ok'])
        rows.append(row('T5', f'{kind}: [F_first/h](5 L) / [F_first/h](2 L) (C3, depth)', [gs[1], gs[3]], '1 ± 0.25',
                        lambda gs=gs, per=per: eq((S.ratio(per_depth(gs[3], 'F_first'), per_depth(gs[1], 'F_first')),
                                                   'F_first/h per depth: ' + per()), 0.75, 1.25),
                        ('linear', 'not shown linear')))
        rows.append(row('T5', f'{kind}: slope of F_first against h/L, all four depths', gs, '',
                        lambda gs=gs: (S.slope([depth(g) for g in gs], [stat(g, 'F_first') for g in gs]), None, '')))
    return rows


def t6_rows(G):
    rows = []
    for name in T6_CASES:
        a, b = G[(name, 'sable')], G[(name, 'liggghts')]
        for q, m in T6_MARGIN.items():
            note = 'underpowered (power 0.40 F_stat, 0.53 F_first: 4 against 2 seeds)' if name == 'soft_h5' else ''
            rows.append(row('T6', f'{name} {q}: (sable − LIGGGHTS) / LIGGGHTS', [a, b], f'± {m:g}',
                            lambda a=a, b=b, q=q, m=m: eq((S.scale(S.welch_diff(values(a, q), values(b, q)),
                                                                   1 / stat(b, q).mean), ''), m),
                            ('equivalent', 'not shown equivalent'), note))
    lig, l1 = [G[(f'stiff_h{h}', 'liggghts')] for h in ('3.7', '5')], G[('stiff_h1', 'liggghts')]
    rows.append(row('T6', "LIGGGHTS' own r_stiff (two depths at h ≥ 2 L)", lig + [l1], '',
                    lambda: reported(depth_ratio(lig, l1))))
    return rows


def t7_rows(G):
    gs = [G[(n, 'sable')] for n in T7_CASES]
    soft, stiff, e1e7 = G[('soft_h3.7', 'sable')], G[('stiff_h3.7', 'sable')], G[('E1e7_h3.7', 'sable')]

    def a():
        b = S.slope([math.log10(g['case']['scene']['Estar']) for g in gs], [stat(g, 'F_first') for g in gs])
        mean = sum(stat(g, 'F_first').mean for g in gs) / len(gs)
        return eq((S.scale(b, 1 / mean), f'slope {b.est:.2f} ± {b.se:.2f} per decade, mean F_first {mean:.2f}'), 0.10)

    def b():
        d = S.welch_diff(values(soft, 'F_stat'), values(stiff, 'F_stat'))
        return d, S.one_sided(d, 0.0), f"{100 * d.est / stat(stiff, 'F_stat').mean:+.1f} % of F_stat(1e6)"
    c = lambda: eq((S.scale(S.welch_diff(values(e1e7, 'F_stat'), values(stiff, 'F_stat')),
                            1 / stat(stiff, 'F_stat').mean), ''), 0.15)
    return [row('T7a', 'F_first against log10 E*: slope / mean F_first, per decade (C3, stiffness)', gs, '± 0.10',
                a, ('no E* dependence', 'not shown independent')),
            row('T7b', 'F_stat(E* 1.36e5) − F_stat(1e6) (C4: falls)', [soft, stiff], '> 0', b,
                ('falls', 'not shown falling')),
            row('T7c', '[F_stat(1e7) − F_stat(1e6)] / F_stat(1e6) (C4: plateau)', [e1e7, stiff], '± 0.15', c,
                ('plateau', 'not shown flat'))]


def all_rows(G, cases):
    return t0_rows(G, cases) + t1_t4_rows(G) + t5_rows(G) + t6_rows(G) + t7_rows(G)


def unsteady(rows):
    """The (case, code) groups whose T0 did not show them stationary (complete and judged)."""
    return {(r['groups'][0]['name'], r['groups'][0]['code']) for r in rows
            if r['test'] == 'T0' and r['pass'] is False}


def claims(rows):
    """The plan's conclusions from the verdicts (pending while any input is incomplete)."""
    v = lambda test, what='': [r['pass'] for r in rows if r['test'] == test and r['what'].startswith(what)][0]
    said = lambda tests, yes, no: (' pending' if None in tests else f' {yes}' if all(tests) else f' {no}')
    return ['- C1 with C2 (T1, T2, T3: the paper\'s depth claim):' + said([v('T1'), v('T2'), v('T3')],
                                                                        'reproduced on this bed', 'not reproduced'),
            '- the levelling and the side wall (T1, T4):' + (
                ' pending' if None in (v('T1'), v('T4', 'r_wall (')) else
                " the container's, not the paper's effect (T1 passes, T4 fails)" if v('T1') and not v('T4', 'r_wall (')
                else ' survives without wall friction' if v('T1') else ' no levelling to attribute (T1 fails)'),
            '- C3, depth (T5, both series):' + said([v('T5', 'soft: ['), v('T5', 'stiff: [')], 'linear', 'not shown'),
            '- C3, stiffness (T7a):' + said([v('T7a')], 'reproduced', 'not reproduced'),
            '- C4 (T7b and T7c):' + said([v('T7b'), v('T7c')], 'reproduced', 'not reproduced')]


# ---------------------------------------------------------------- formatting
def num(x, f='.3f'):
    return '—' if x is None or x != x else format(x, f)


def mean_se(s, f='.2f'):
    if not s.n:
        return '—'
    return f'{s.mean:{f}}' + ('' if s.se != s.se else f' ± {s.se:{f}}')


def interval_text(r):
    e, t = r['e'], r['t']
    if e is None:
        return '—'
    if isinstance(t, S.OneSided):
        return f'> {num(t.bound)} (95 % one-sided)'
    lo, hi = (t.lo, t.hi) if t is not None else (e.lo, e.hi)
    return f'[{num(lo)}, {num(hi)}]'


def test_line(r, flagged):
    e, t = r['e'], r['t']
    bad = [] if r['test'] == 'T0' else sorted({(g['name'], g['code']) for g in r['groups']} & flagged)
    verdict = r['verdict'] + ''.join(f'; uses {n} {NAMES[c]}, not shown stationary' for n, c in bad)
    detail = '; '.join(x for x in (r['detail'], r['note']) if x)
    return (f"| {r['test']} | {r['what']} | {num(e.est if e else None)} | {interval_text(r)} | "
            f"{num(e.df if e else None, '.1f')} | {r['margin'] or '—'} | {num(t.p if t else None)} | {verdict} | "
            f"{detail} |")


def tests_table(rows):
    flagged = unsteady(rows)
    return (['| test | quantity | estimate | 90 % interval or bound | df | margin | p | verdict | detail |',
             '|---|---|---|---|---|---|---|---|---|'] + [test_line(r, flagged) for r in rows])


def case_line(g, t0row, sable):
    """One (case, code) row of the per-case table."""
    n, m = len(g['ok']), len(g['planned'])
    seeds = f'{n}/{m}' + (f" (+{len(g['extra'])} beyond the plan)" if g['extra'] else '')
    cpu = S.summary([r.get('cpu_s') for r in g['ok']]).mean
    s_cpu = S.summary([r.get('cpu_s') for r in sable['ok']]).mean
    ratio = num(cpu / s_cpu, '.2f') if g['code'] == 'liggghts' and n and sable['ok'] else ''
    e = t0row['e']
    trend_txt = '—' if e is None else f"{e.est:+.3f} [{num(t0row['t'].lo, '+.3f')}, {num(t0row['t'].hi, '+.3f')}]"
    return (f"| {g['name']} | {NAMES[g['code']]} | {seeds} | {num(depth(g) if n else None, '.2f')} | "
            f"{mean_se(stat(g, 'F_first'))} | {mean_se(stat(g, 'F_stat'))} | "
            f"{num(S.block_check([r['result']['F_stat_err'] for r in g['ok']], values(g, 'F_stat')), '.2f')} | "
            f"{trend_txt} | {t0row['verdict']} | {num(cpu if n else None, '.0f')} | {ratio} |")


def case_table(G, cases, rows):
    t0 = {(r['groups'][0]['name'], r['groups'][0]['code']): r for r in rows if r['test'] == 'T0'}
    lines = ['| case | code | seeds done/planned | h/L measured | F_first | F_stat | block/sd (F_stat) | '
             'T0 trend/F_stat [90 %] | T0 | CPU s per run | CPU LIGGGHTS/sable |', '|---' * 11 + '|']
    for c in cases:
        for code in CODES:
            if (c['name'], code) in t0:
                lines.append(case_line(G[(c['name'], code)], t0[(c['name'], code)], G[(c['name'], 'sable')]))
    return lines


# ---------------------------------------------------------------- ledger
def ledger(G, cases):
    """Per code: core-hours spent (finished runs, and pieces of unfinished or failed ones), the plan's
    estimate of the finished runs and of the runs left (in the order of the case file), the plan's total."""
    out = {}
    for code in CODES:
        gs = [G[(c['name'], code)] for c in cases]
        led = {'runs': sum(len(g['ok']) for g in gs),
               'done_h': sum(cpu_spent(r) for g in gs for r in g['ok'] + g['extra']) / 3600,
               'other_h': sum(cpu_spent(r) for g in gs for r in g['failed'] + g['unfinished']) / 3600,
               'est_done': sum(estimate_h(g) * len(g['ok']) for g in gs),
               'plan': sum(estimate_h(g) * len(g['planned']) for g in gs if g['name'] != OPTIONAL),
               'optional': sum(estimate_h(g) * len(g['planned']) for g in gs if g['name'] == OPTIONAL),
               'left': [(g['name'], s, estimate_h(g)) for g in gs if g['name'] != OPTIONAL
                        for s in g['planned'] if s not in [r['seed'] for r in g['ok']]]}
        led['spent'] = led['done_h'] + led['other_h']
        led['projected'] = led['spent'] + sum(h for *_, h in led['left'])
        out[code] = led
    return out


def dropped(led, budget):
    """The runs left that the budget would drop: from the first that would pass it, all after it."""
    total = led['spent']
    for i, (_, _, h) in enumerate(led['left']):
        total += h
        if total > budget:
            return led['left'][i:]
    return []


def ledger_table(led):
    lines = ['| code | runs finished | core-h spent (finished runs + unfinished/failed pieces) | plan\'s estimate of '
             'the finished runs | spent / estimate | estimate of the planned runs left | projected total | '
             'plan\'s total | budget |', '|---|---|---|---|---|---|---|---|---|']
    for code, x in led.items():
        opt = f" (+{x['optional']:.1f} for {OPTIONAL}, optional)" if x['optional'] else ''
        lines.append(f"| {NAMES[code]} | {x['runs']} | {x['spent']:.2f} ({x['done_h']:.2f} + {x['other_h']:.2f}) | "
                     f"{x['est_done']:.2f} | {num(x['spent'] / x['est_done'] if x['est_done'] else None, '.2f')} | "
                     f"{sum(h for *_, h in x['left']):.2f} ({len(x['left'])} runs) | {x['projected']:.2f} | "
                     f"{x['plan']:.1f}{opt} | {BUDGET[code]:g} |")
    return lines


# ---------------------------------------------------------------- commits and departures
def harness_keys(rec):
    """(commit, uncommitted changes?) of the harness for the run and each of its pieces."""
    h = rec.get('harness')
    keys = {(h['commit'], bool(h.get('dirty')))} if h else {('not recorded', False)}
    for p in (rec.get('state') or {}).get('pieces', []):
        if p.get('harness'):
            keys.add((p['harness'], bool(p.get('harness_dirty'))))
    return keys


def binary_key(rec):
    v = rec.get('version') or {}
    if rec.get('code') == 'liggghts':
        return f"LIGGGHTS {v.get('package', '?')}, sha256 {str(v.get('sha256', 'not recorded'))[:16]}"
    if 'commit' in v:
        return f"sable {v['commit'][:12]} (sha256 {v['sha256'][:16]})"
    return f"sable commit not recorded (sha256 {str(v.get('sha256', '?'))[:16]})"


def tally(items):
    out = {}
    for x in items:
        out[x] = out.get(x, 0) + 1
    return out


def finished(G):
    return [r for g in G.values() for r in g['ok'] + g['extra']]


def commits_section(G):
    runs = finished(G)
    bins = tally(binary_key(r) for r in runs)
    hs = tally(f"{c[:12]}{' with uncommitted changes' if d else ''}" for r in runs for c, d in harness_keys(r))
    decks = tally(str((r.get('harness') or {}).get('deck_sha256', 'not recorded'))[:16] for r in runs)
    return (['- binaries: ' + ('; '.join(f'{k}: {n} runs' for k, n in sorted(bins.items())) or 'no runs')] +
            ['- harness commits (run_drag.py and the deck), runs per commit (a run whose pieces were made at '
             'several counts under each): ' +
             ('; '.join(f'{k}: {n}' for k, n in sorted(hs.items())) or '—')] +
            ['- deck sha256: ' + ('; '.join(f'{k}: {n} runs' for k, n in sorted(decks.items())) or '—')])


def run_name(r):
    return f"{r.get('case', '?')} {NAMES.get(r.get('code'), r.get('code'))} s{r['seed']}"


def not_finished(G):
    lines = []
    for (name, code), g in G.items():
        if name == OPTIONAL:
            continue
        left = [f"s{r['seed']} (in progress: {(r['state'] or {}).get('done', 0)} half-turns done)"
                for r in g['unfinished'] if r['seed'] in g['planned']]
        left += [f"s{r['seed']} (not started)" for r in g['missing']]
        left += [f"s{r['seed']} (failed)" for r in g['failed'] if r['seed'] in g['planned']]
        if left:
            lines.append(f'- planned, not finished: {name} {NAMES[code]}: ' + ', '.join(left))
    return lines


def extra_and_failed(G):
    lines = [f'- beyond the plan (not used by the tests): {name} {NAMES[code]} ' +
             ', '.join(f"s{r['seed']}" for r in g['extra']) for (name, code), g in G.items() if g['extra']]
    for g in G.values():
        for r in g['failed']:
            tail = (r.get('error_tail') or ['no error recorded'])[-1]
            lines.append(f'- failed: {run_name(dict(r, case=g["case"]["name"], code=g["code"]))}: {tail}')
    return lines


def var_diff(g, r):
    """A finished run's deck variables that differ from its case's, as text ('' when none)."""
    want = {k: str(v) for k, v in g['case']['vars'].items()}
    got = {k: v for k, v in r.get('vars', {}).items() if k not in IGNORED_VARS}
    keys = sorted(k for k in set(want) | set(got)
                  if got.get(k) != want.get(k) and not _same_number(got.get(k), want.get(k)))
    return ', '.join(f"{k} {got.get(k, '(unset)')} (case {want.get(k, '(unset)')})" for k in keys)


def listed(what, runs):
    """One line naming the runs that share a departure ([] when none)."""
    if not runs:
        return []
    return [f"- {what}: {len(runs)} run{'s' * (len(runs) != 1)}: " + ', '.join(run_name(r) for r in runs)]


def other_vars(G):
    """Finished runs whose deck variables differ from their case's, grouped by the difference."""
    by = {}
    for g in G.values():
        for r in g['ok'] + g['extra']:
            by.setdefault(var_diff(g, r), []).append(r)
    return [line for d, runs in by.items() if d for line in listed(f'other variables than the case\'s ({d})', runs)]


def _same_number(a, b):
    try:
        return float(a) == float(b)
    except (TypeError, ValueError):
        return False


def provenance(G):
    runs = finished(G)
    sable = tally(binary_key(r) for r in runs if r.get('code') == 'sable')
    decks = {(r.get('harness') or {}).get('deck_sha256') for r in runs}
    lines = [f'- {len(sable)} sable builds: ' + '; '.join(f'{k}: {n} runs' for k, n in sorted(sable.items()))
             ] if len(sable) > 1 else []
    lines += [f'- {len(decks)} deck versions (sha256) among the finished runs'] if len(decks) > 1 else []
    lines += listed('harness (commit, deck) not recorded', [r for r in runs if not r.get('harness')])
    lines += listed('sable built with uncommitted source changes', [r for r in runs if 'uncommitted' in
                                                                     (r.get('version') or {}).get('commit_source', '')])
    lines += listed('sable commit not recorded', [r for r in runs if r.get('code') == 'sable' and
                                                  'commit' not in (r.get('version') or {})])
    dirty = [r for r in runs if any(d for _, d in harness_keys(r))]
    lines += listed('uncommitted harness changes (' + '; '.join(sorted({c for r in dirty for c in
                    (r.get('harness') or {}).get('changes', [])}) or ['in a piece']) + ')', dirty)
    untracked = [r for r in runs if (r.get('harness') or {}).get('untracked')]
    lines += listed('untracked files under the harness paths (' + ', '.join(sorted({f for r in untracked for f in
                    r['harness']['untracked']})) + ')', untracked)
    return lines


def optional_case(G, led):
    """The plan's rule for E4e7: run only if the sable ledger after every other run is at most 26.2 core-h."""
    g = G.get((OPTIONAL, 'sable'))
    if g is None:
        return []
    rest_done = not led['sable']['left']
    spent = led['sable']['spent'] - sum(cpu_spent(r) for r in g['ok'] + g['failed'] + g['unfinished']) / 3600
    if g['ok']:
        return [] if rest_done and spent <= OPTIONAL_LEDGER else [
            f'- {OPTIONAL} run although the sable ledger was {spent:.2f} core-h' +
            ('' if rest_done else ' with other planned runs not finished') +
            f' (rule: ≤ {OPTIONAL_LEDGER} after every other run)']
    if not rest_done:
        return [f'- {OPTIONAL} (optional): decided when every other sable run is finished (projected ledger '
                f"{led['sable']['projected']:.2f} core-h; runs if ≤ {OPTIONAL_LEDGER})"]
    return [f'- {OPTIONAL} not run for the budget (sable ledger {spent:.2f} > {OPTIONAL_LEDGER} core-h)' if
            spent > OPTIONAL_LEDGER else f'- {OPTIONAL} not (yet) run; the ledger ({spent:.2f} core-h) allows it']


def budget_lines(led):
    return [f"- {NAMES[code]}: projected {x['projected']:.2f} core-h > budget {BUDGET[code]:g}: the runs left from "
            + ', '.join(f'{n} s{s}' for n, s, _ in dropped(x, BUDGET[code])) + ' would be dropped (estimate)'
            for code, x in led.items() if dropped(x, BUDGET[code])]


def stray_folders(out, cases):
    names = {c['name'] for c in cases}
    return [f'- run folder of a case not in the case file: {os.path.relpath(p, out)}'
            for p in sorted(glob.glob(os.path.join(out, '*', '*_s*')))
            if os.path.isdir(p) and os.path.basename(os.path.dirname(p)) not in names]


def departures(G, cases, out, led, folder):
    auto = (not_finished(G) + extra_and_failed(G) + other_vars(G) + provenance(G) + optional_case(G, led) +
            budget_lines(led) + stray_folders(out, cases))
    hand = os.path.join(folder, 'departures.md')
    lines = ['## Departures from the plan', '', '### Detected by report.py', ''] + (auto or ['- none'])
    lines += ['', '### Written by hand (departures.md)', '']
    return lines + ([open(hand).read().rstrip('\n')] if os.path.exists(hand) else ['(no departures.md)'])


# ---------------------------------------------------------------- figures
def errorbar(ax, gs, x, q, color, label, lig=False, line=True):
    pts = [(x(g), stat(g, q)) for g in gs if g['ok']]
    if not pts:
        return
    xs, ss = [p[0] for p in pts], [p[1] for p in pts]
    ax.errorbar(xs, [s.mean for s in ss], [0 if s.se != s.se else s.se for s in ss], color=color, capsize=3,
                marker='s' if lig else 'o', mfc='none' if lig else color, ms=6 if lig else 5,
                ls='-' if line and not lig else 'none', lw=0.8, label=label)


def fig_turns(G, path):
    fig, axes = plt.subplots(1, len(TURNS_CASES), figsize=(4.2 * len(TURNS_CASES), 3.4))
    for ax, name in zip(axes, TURNS_CASES):
        for code, color in zip(CODES, ('tab:blue', 'tab:red')):
            g = G[(name, code)]
            m = seed_mean_curve([{'curve': curve(r)} for r in g['ok']])
            if m is not None:
                t, f, sd = m
                ax.plot(t, f, color=color, lw=0.8, label=f"{NAMES[code]} ({len(g['ok'])} seeds)")
                ax.fill_between(t, f - sd, f + sd, color=color, alpha=0.25, lw=0)
        if G[(name, 'sable')].get('absent'):
            ax.set_title(f'{name}: not in the case file', fontsize=9)
            continue
        sc = G[(name, 'sable')]['case']['scene']
        ax.axvspan(sc['turns'] / 2, sc['turns'], color='0.9', zorder=0, label='F_stat window')
        ax.set_title(f"{name}: E* {sc['Estar']:.2g}, h/L {sc['hL']:g} nominal", fontsize=9)
        ax.set_xlabel('turns')
        legend(ax)
    axes[0].set_ylabel('F* (seed mean; band ± sd over seeds)')
    save(fig, path)


def curve(r):
    return torque_curve(r['folder'], r) if (r.get('settled') or {}).get('step0') is not None else None


def fig_depth(G, path):
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, q in zip(axes, ('F_stat', 'F_first')):
        for kind in ('soft', 'stiff') + (('wall',) if q == 'F_stat' else ()):
            names = [n for n in {n for n, _ in G} if n.startswith(kind + '_h')]
            for code in CODES:
                gs = sorted((G[(n, code)] for n in names), key=lambda g: g['case']['scene']['hL'])
                wall = ' (frictionless side wall)' if kind == 'wall' else ''
                estar = f" E* {gs[0]['case']['scene']['Estar']:.2g}" if gs else ''
                errorbar(ax, gs, depth, q, SERIES[kind], f'{kind}{wall}{estar}, {NAMES[code]}', code == 'liggghts')
        ax.set_xlabel('h/L (measured, seed mean)')
        ax.set_ylabel(f'{QLABEL[q]} (± seed SE)')
        ax.set_xlim(left=0)
        ax.set_ylim(bottom=0)
        legend(ax)
    save(fig, path)


def fig_stiffness(G, path):
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    estar = lambda g: g['case']['scene']['Estar']
    for ax, q in zip(axes, ('F_first', 'F_stat')):
        errorbar(ax, [G[(n, 'sable')] for n in T7_CASES], estar, q, 'tab:blue', 'sable (T7)')
        errorbar(ax, [G[(OPTIONAL, 'sable')]] if (OPTIONAL, 'sable') in G else [], estar, q, 'tab:purple',
                 f'sable {OPTIONAL} (shown, not tested)', line=False)
        errorbar(ax, [G[(n, 'liggghts')] for n in T7_CASES], estar, q, 'tab:red', 'LIGGGHTS', lig=True)
        ax.set_xscale('log')
        ax.set_xlabel('E* = E / (ρ_g g d)')
        ax.set_ylabel(f'{QLABEL[q]} (± seed SE)')
        ax.set_title(f'h/L {FIG3:g} nominal (measured ≈ 3.9)', fontsize=9)
        legend(ax)
    save(fig, path)


def legend(ax):
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7)
    else:
        ax.text(0.5, 0.5, 'no finished runs', ha='center', va='center', transform=ax.transAxes, color='0.5')


def save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


FIGURES = {'drag_turns.png': fig_turns, 'drag_depth.png': fig_depth, 'drag_stiffness.png': fig_stiffness}


# ---------------------------------------------------------------- the report
def header(G, out, cases_path):
    done = {code: progress([g for (n, c), g in G.items() if c == code and n != OPTIONAL]) for code in CODES}
    return [f'# Drag campaign 3: report ({datetime.date.today().isoformat()})', '',
            f'Written by `report.py` from `{out}` and `{os.path.relpath(cases_path, HERE)}`; the plan, tests and '
            'margins: [PLAN.md](PLAN.md). F* = F / (ρ_g g D L²), F = 4 |M_z| / L. F_first: the first half-turn; '
            'F_stat: the mean of the 6 half-turn means of turns 3-6. Per case: the mean over the planned seeds '
            '± the seed-to-seed SE (`seedstats.summary`; none for one seed); block/sd: the runs\' rms block error '
            'over the seed sd (`seedstats.block_check`, expected < 1, never added to the SE). Intervals are 90 % '
            '(two one-sided tests at α 0.05); measured depth h/L: the seed mean of h_meas over L. A test whose '
            'runs are not all finished says "incomplete" instead of a verdict.', '',
            'Finished planned runs (without the optional ' + OPTIONAL + '): ' +
            ', '.join(f'{NAMES[c]} {n} of {m}' for c, (n, m) in done.items()) + '.', '']


def write_report(G, cases, out, folder, cases_path):
    rows = all_rows(G, cases)
    led = ledger(G, cases)
    lines = (header(G, out, cases_path) + ['## Cases', ''] + case_table(G, cases, rows) +
             ['', 'T0 trend: the least-squares slope of a run\'s 6 window half-turn means against the half-turn index '
              'times 5, over its F_stat; seed mean and 90 % interval; stationary if inside ± 0.15. '
              'CPU: user + system seconds per finished run.', '', '## Tests T0-T7', ''] + tests_table(rows) +
             ['', '## What the tests say (PLAN.md)', ''] + claims(rows) +
             ['', '## Ledger (CPU core-hours)', ''] + ledger_table(led) +
             ['', f"Plan's estimate: run_drag.scene's particle-steps at sable {SPEED['sable']:.3g}, LIGGGHTS "
              f"{SPEED['liggghts']:.3g} particle-steps per CPU second.", '', '## Commits the runs were made with', ''] +
             commits_section(G) + [''] + departures(G, cases, out, led, folder) +
             ['', '## Figures', ''] + [f'![{f}]({f})' for f in FIGURES])
    with open(os.path.join(folder, 'REPORT.md'), 'w') as f:
        f.write('\n'.join(lines) + '\n')
    return rows


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--out', required=True, help='the runs folder (OUT of run_drag.py, or runs/ here)')
    p.add_argument('--report', default=HERE, help='where REPORT.md and the figures go (default: this folder)')
    p.add_argument('--cases', default=os.path.join(HERE, 'cases', 'all.json'), help='the campaign\'s case file')
    a = p.parse_args()
    os.makedirs(a.report, exist_ok=True)
    if not os.path.isdir(a.out):
        print(f'note: {a.out} does not exist: no runs yet')
    cases = load_cases(a.cases)
    G = read_all(a.out, cases)
    rows = write_report(G, cases, a.out, a.report, os.path.abspath(a.cases))
    for name, fig in FIGURES.items():
        fig(G, os.path.join(a.report, name))
    n, m = progress(list(G.values()))
    print(f"{n} of {m} planned runs finished; {sum(r['pass'] is not None for r in rows)} of {len(rows)} test rows "
          f"judged; written {os.path.join(a.report, 'REPORT.md')} and {', '.join(FIGURES)}")


if __name__ == '__main__':
    main()
