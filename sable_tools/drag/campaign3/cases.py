#!/usr/bin/python3
"""Campaign 3's runs, from one table: writes one case file per figure into cases/.

    /usr/bin/python3 -m sable_tools.drag.campaign3.cases      # (re)writes cases/*.json

Every case file lists every run its figure uses (all seeds, both codes), so that
`run_drag.py --cases cases/FIG.json --chunk 2 --out OUT` reruns that figure; a case
that several figures use has the same name and variables in each (its runs are shared).
"""
import json, os

from sable_tools.paths import repo_path

HERE = repo_path('reference_runs', 'drag', 'campaign3')  # cases/*.json are written there
SEEDS = [49979687, 67867967, 86028121, 104395301, 122949823]  # run_drag.SEEDS[:5]
BED = {'Wd': 20, 'Ld': 8, 'Dd': 2, 'zcL': 1, 'muprep': 0.2, 'turns': 6, 'dtf': 0.17}
E = {'soft': 5e6, 'E4e5': 1.47e7, 'stiff': 3.68e7, 'E3e6': 1.1e8, 'E1e7': 3.68e8, 'E4e7': 1.5e9}  # E* = E / 36.79 Pa
DEPTHS = (1, 2, 3.7, 5)  # nominal h/L; the measured one is ~0.2 L more
FIG3 = 3.7               # measured ~3.9 L: the paper's Fig. 3 depth


def case(kind, h, sable, liggghts=0, **extra):
    v = dict(BED, E=E['stiff' if kind == 'wall' else kind], hL=h, **extra)
    seeds = {'sable': SEEDS[:sable]}
    if liggghts:
        seeds['liggghts'] = SEEDS[:liggghts]
    return {'name': f'{kind}_h{h}', 'vars': {k: str(x) for k, x in v.items()}, 'codes': list(seeds), 'seeds': seeds}


def all_cases():
    """Every run of the campaign, in the order they are run (cheapest first within a code;
    E4e7 last and only if the ledger leaves room: PLAN.md)."""
    # dtf 0.15 for the soft beads: sable's 10 % Hertz check refuses 0.17 for their second pour
    # at h >= 2 L (PLAN.md, amendment 1)
    soft = [case('soft', h, 4, 2 if h == 5 else 0, dtf=0.15) for h in DEPTHS]
    # seeds at the minima (4 stiff, 3 wall, 2 per Fig. 3 stiffness): the campaign's own CPU
    # speed projected the plan's seeds past the budget (PLAN.md, amendment 2)
    # deepest first: if the budget drops LIGGGHTS' last run, it is the shallow control's (amendment 2)
    stiff = [case('stiff', h, 4, 3 if h in (1, FIG3, 5) else 0) for h in reversed(DEPTHS)]
    wall = [case('wall', h, 3, muside=0) for h in DEPTHS[1:]]
    fig3 = [case('E4e5', FIG3, 2), case('E3e6', FIG3, 2), case('E1e7', FIG3, 2), case('E4e7', FIG3, 1)]
    return soft + stiff + fig3[:1] + wall + fig3[1:]


def figures():
    c = {x['name']: x for x in all_cases()}
    at = lambda *names: [c[n] for n in names]
    return {
        'fig_turns': at('stiff_h1', 'stiff_h5', 'soft_h5'),
        'fig_depth': at(*[f'{k}_h{h}' for k in ('soft', 'stiff') for h in DEPTHS]),
        'fig_wall': at(*[f'{k}_h{h}' for k in ('stiff', 'wall') for h in DEPTHS[1:]], 'stiff_h1'),
        'fig_stiffness': at(*[f'{k}_h{FIG3}' for k in ('soft', 'E4e5', 'stiff', 'E3e6', 'E1e7', 'E4e7')]),
        'all': all_cases(),
    }


def main():
    for name, cases in figures().items():
        with open(os.path.join(HERE, 'cases', name + '.json'), 'w') as f:
            json.dump({'cases': cases}, f, indent=1)
        print(f'cases/{name}.json: {len(cases)} cases, '
              f"{sum(len(s) for x in cases for s in x['seeds'].values())} runs")


if __name__ == '__main__':
    main()
