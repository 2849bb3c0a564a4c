#!/usr/bin/python3
"""Campaign 3's design numbers, from runs already made (PLAN.md quotes this output).

    /usr/bin/python3 -m sable_tools.drag.campaign3.power

Reads the intermediate bed's runs (muprep 0.2, E* 1e6, 3 turns; dense_prep/runs/mid0.2_*):
the seed-to-seed scatter of F_stat and F_first per depth and code, and each code's speed
(CPU seconds per particle-step). Prints (1) the scatter, (2) the core-hours of every
planned case from run_drag.scene's particle-step count, (3) the power of each
pre-registered test for the planned seeds.
"""
import glob, json, math, os

from sable_tools import seedstats as S
from sable_tools.drag import run_drag
from sable_tools.paths import repo_path

HERE = repo_path('reference_runs', 'drag', 'campaign3')

PAST = os.path.join(HERE, '..', 'dense_prep', 'runs')
L = 0.012  # the cylinder's length in these runs (8 d)


def past_runs():
    out = {}
    for f in sorted(glob.glob(os.path.join(PAST, 'mid0.2_E3.68e7_hL*', '*', 'run.json'))):
        r = json.load(open(f))
        if r.get('status') != 'ok':
            continue
        h = r['vars']['hL']
        out.setdefault((r['code'], h), []).append(r)
    return out


def scatter(runs):
    print('1. Seed scatter of the intermediate bed (E* 1e6, 3 turns; F_stat over turns 1.5-3)')
    print('| code | h/L nominal (measured) | seeds | F_stat mean | sd | sd/mean | F_first mean | sd | sd/mean |')
    print('|---|---|---|---|---|---|---|---|---|')
    deep = {'F_stat': [], 'F_first': []}
    for (code, h), rs in sorted(runs.items(), key=lambda k: (k[0][0], float(k[0][1]))):
        hm = sum(r['result']['h_meas'] for r in rs) / len(rs) / L
        fs = S.summary([r['result']['F_stat'] for r in rs])
        ff = S.summary([r['result']['F_first'] for r in rs])
        print(f'| {code} | {h} ({hm:.2f}) | {fs.n} | {fs.mean:.2f} | {fs.sd:.2f} | {fs.sd / fs.mean:.3f} | '
              f'{ff.mean:.1f} | {ff.sd:.1f} | {ff.sd / ff.mean:.3f} |')
        if float(h) >= 4:  # pooled relative variance at the deep depths, both codes
            for key, s in (('F_stat', fs), ('F_first', ff)):
                deep[key].append(((s.sd / s.mean) ** 2, s.n - 1))
    cv = {k: math.sqrt(sum(v * d for v, d in x) / sum(d for _, d in x)) for k, x in deep.items()}
    print(f"pooled sd/mean at h >= 4 L (both codes): F_stat {cv['F_stat']:.3f}, F_first {cv['F_first']:.3f}")
    return cv


def speeds(runs):
    rate = {}
    for code in ('sable', 'liggghts'):
        ps = [(r['estimate']['particle_steps'], r['cpu_s']) for (c, _), rs in runs.items() if c == code for r in rs]
        rate[code] = sum(p for p, _ in ps) / sum(t for _, t in ps)
    print(f"speeds (CPU): sable {rate['sable']:.3g}, LIGGGHTS {rate['liggghts']:.3g} particle-steps/s; "
          f'ratio {rate["sable"] / rate["liggghts"]:.2f}')
    return rate


def ledger(rate):
    from sable_tools.drag.campaign3 import cases as C  # the campaign's case files, built from one table
    print('\n2. Core-hours (CPU), every planned run, cheapest first within each code')
    print('| case | E* | h/L | grains | steps/turn | sable seeds | sable core-h | LIGGGHTS seeds | LIGGGHTS core-h |')
    print('|---|---|---|---|---|---|---|---|---|')
    tot = {'sable': 0.0, 'liggghts': 0.0}
    for c in C.all_cases():
        s = run_drag.scene(c['vars'])
        ns, nl = len(c['seeds'].get('sable', [])), len(c['seeds'].get('liggghts', []))
        hs = ns * s['particle_steps'] / rate['sable'] / 3600
        hl = nl * s['particle_steps'] / rate['liggghts'] / 3600
        tot['sable'] += hs
        tot['liggghts'] += hl
        print(f"| {c['name']} | {s['Estar']:.3g} | {c['vars']['hL']} | {s['grains']} | {100 * s['Nrec']} | "
              f'{ns} | {hs:.2f} | {nl} | {hl:.2f} |')
    print(f"total: sable {tot['sable']:.1f} core-h (budget 30), LIGGGHTS {tot['liggghts']:.1f} core-h (budget 20)")


def planned_diff(sd, na, nb):
    """(se, Welch-Satterthwaite df) of the difference of two means of na and nb seeds of this sd."""
    d = S.welch_diff(S.planned(0.0, sd, na), S.planned(0.0, sd, nb))
    return d.se, d.df


def power(cv, runs):
    from sable_tools.drag.campaign3 import cases as C
    """The tests' standard errors under the scatter measured, and their power."""
    print('\n3. Power of the pre-registered tests (alpha 0.05; the estimate normal, its estimated error'
          ' sampled as chi^2 over the Satterthwaite df: seedstats.tost_power)')
    m = {float(h): S.summary([r['result']['F_stat'] for r in rs]).mean for (c, h), rs in runs.items() if c == 'sable'}
    hm = {1: 1.16, 2: 2.17, 3.7: 3.9, 5: 5.22}  # measured depth of each nominal one, in L
    F = {1: m[1], 2: m[2], 3.7: m[4] + (m[4] - m[3]) * (3.9 - 4.22) / (4.22 - 3.19), 5: m[5]}
    cv_shallow = 0.03  # measured 0.014-0.031 at 1-2 L: the larger, rounded up

    def group(h, n, c):
        return S.planned(F[h], c * F[h], n)

    def r_se(n, c):
        b = S.slope([hm[h] for h in (2, 3.7, 5)], [group(h, n, c) for h in (2, 3.7, 5)])
        g1 = group(1, n, cv_shallow)
        b0 = S.interval(g1.mean / hm[1], g1.se / hm[1], g1.df)
        r = S.ratio(S.interval(0.0, b.se, b.df), b0)  # the ratio's error at a true slope of 0
        return r.se, r.df, b0.est

    n = {c['name']: {k: len(v) for k, v in c['seeds'].items()} for c in C.all_cases()}
    ns, nw, nl = n['stiff_h5']['sable'], n['wall_h5']['sable'], n['stiff_h5']['liggghts']
    fig3 = [n[f'{k}_h3.7']['sable'] for k in ('soft', 'E4e5', 'stiff', 'E3e6', 'E1e7')]
    print('| test | seeds | se | df | margin | power |')
    print('|---|---|---|---|---|---|')
    for k in sorted({4, ns}):
        se, df, b0 = r_se(k, cv['F_stat'])
        for true in (0.0, 0.05):
            print(f'| T1 stiff: r inside +-0.15, true r {true} | {k} | {se:.3f} | {df:.1f} | 0.15 | '
                  f'{S.tost_power(se, df, 0.15, true):.2f} |')
    se, df, _ = r_se(n['soft_h5']['sable'], cv['F_stat'])
    print(f"| T2 soft: r > 0.15, true r 0.4 | {n['soft_h5']['sable']} | {se:.3f} | {df:.1f} | - | "
          f'{S.one_sided_power(se, df, 0.25):.2f} |')
    se3, df3, _ = r_se(nw, cv['F_stat'])
    print(f'| T4 wall: r inside +-0.15, true r 0 | {nw} | {se3:.3f} | {df3:.1f} | 0.15 | '
          f'{S.tost_power(se3, df3, 0.15):.2f} |')
    for key, marg in (('F_stat', 0.15), ('F_first', 0.20)):
        for a, b in ((ns, nl), (n['soft_h5']['sable'], n['soft_h5']['liggghts'])):
            se, df = planned_diff(cv[key], a, b)
            print(f'| T6 sable - LIGGGHTS {key} (fraction of the mean), true 0 | {a} vs {b} | {se:.3f} | '
                  f'{df:.1f} | {marg} | {S.tost_power(se, df, marg):.2f} |')
    # Fig. 3: F_first slope against log10 E* over 1.36e5, 4e5, 1e6, 3e6, 1e7
    x = [math.log10(e) for e in (1.36e5, 4e5, 1e6, 3e6, 1e7)]
    b = S.slope(x, [S.planned(1.0, cv['F_first'], k) for k in fig3])
    print(f"| T7a F_first per decade of E* (fraction of the mean), true 0 | {','.join(map(str, fig3))} | {b.se:.3f} | "
          f"{b.df:.1f} | 0.10 | {S.tost_power(b.se, b.df, 0.10):.2f} |")
    se, df = planned_diff(cv['F_stat'], fig3[2], fig3[4])
    print(f"| T7c F_stat(1e7) - F_stat(1e6) (fraction), true 0 | {fig3[2]} vs {fig3[4]} | {se:.3f} | {df:.1f} | 0.15 | "
          f"{S.tost_power(se, df, 0.15):.2f} |")
    se, df = planned_diff(cv['F_stat'], fig3[0], fig3[2])
    print(f"| T7b F_stat(1.4e5) - F_stat(1e6) > 0 (fraction), true 0.15 | {fig3[0]} vs {fig3[2]} | {se:.3f} | {df:.1f} | - | "
          f"{S.one_sided_power(se, df, 0.15):.2f} |")


def campaign_ledger():
    """The ledger at the campaign's own CPU speed: core-hours spent so far (every record in runs/ and
    runs_set_aside/, finished or not) plus the planned runs left, each at the speed measured on the
    campaign's runs of the nearest bed size by the same code (CPU time and particle-steps only)."""
    from sable_tools.drag.campaign3 import cases as C
    recs = [json.load(open(f)) for d in ('runs', 'runs_set_aside')
            for f in glob.glob(os.path.join(HERE, d, '*', '*', 'run.json'))]
    cpu = lambda r: r.get('cpu_s') or sum(p.get('cpu_s', 0.0) for p in r.get('state', {}).get('pieces', []))
    print("\n4. Ledger at the campaign's own CPU speed (runs/ and runs_set_aside/ so far)")
    print('| code | bed (grains) | runs | particle-steps/s (CPU) |')
    print('|---|---|---|---|')
    rate = {}
    for r in recs:
        if r.get('status') == 'ok':
            rate.setdefault((r['code'], r['estimate']['grains']), []).append((r['estimate']['particle_steps'], cpu(r)))
    for (code, g), x in sorted(rate.items()):
        rate[(code, g)] = sum(p for p, _ in x) / sum(t for _, t in x)
        print(f'| {code} | {g} | {len(x)} | {rate[(code, g)]:.3g} |')
    for code, budget in (('sable', 30), ('liggghts', 20)):
        spent = sum(cpu(r) for r in recs if r['code'] == code) / 3600
        done = {(r['case'], r['seed']) for r in recs if r['code'] == code and r.get('status') == 'ok'}
        left, opt = 0.0, 0.0
        for c in C.all_cases():
            s = run_drag.scene(c['vars'])
            sizes = [g for (k, g) in rate if k == code]
            if not sizes:
                continue
            speed = rate[(code, min(sizes, key=lambda g: abs(g - s['grains'])))]
            h = sum(s['particle_steps'] / speed / 3600 for seed in c['seeds'].get(code, [])
                    if (c['name'], seed) not in done)
            if c['name'] == 'E4e7_h3.7':
                opt += h
            else:
                left += h
        print(f'{code}: spent {spent:.2f} core-h, planned runs left {left:.2f}, projected {spent + left:.1f} '
              f'(budget {budget}; optional E4e7 {opt:.2f} more)')


def main():
    runs = past_runs()
    cv = scatter(runs)
    rate = speeds(runs)
    ledger(rate)
    power(cv, runs)
    campaign_ledger()


if __name__ == '__main__':
    main()
