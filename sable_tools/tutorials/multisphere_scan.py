#!/usr/bin/python3
"""The multisphere tutorial's stone dropped alone from a set height, in sable and LIGGGHTS.

    /usr/bin/python3 -m sable_tools.tutorials.multisphere_scan [--out DIR] [--sable PATH]
        [--heights 0.10:0.39:0.01] [-j 2]

The tutorial deck (in.multisphere) with one change: its insertion region becomes a
cylinder of radius 2 mm and height 2 mm at height h, so that exactly one stone falls
from (almost) a known height, at 1 m/s as in the deck, and the deck's 40 000 steps
run. On an infinite floor a stone's fate depends only on h (x, y do not matter), so
zcm(h) at step 40 000 is what insertion averages over in the tutorial. Then, from the
tutorial runs of run.py (OUT of --tutorials, the post/multi_200.vtk dumps), each code's
own insertion heights predict its mean final zcm through the scanned zcm(h).
Prints one row per height and the prediction; writes DIR/scan.json.
"""
import argparse, concurrent.futures, glob, json, os, re, shutil

import numpy as np

from sable_tools import runner, seedstats  # the codes' commands and their screen; the seed means
from sable_tools.readers import screen, vtk  # the thermo table; the VTK snapshots

SOURCE = '/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public/multisphere_stone_restitution'


def deck(h):
    text = open(os.path.join(SOURCE, 'in.multisphere')).read()
    text = re.sub(r'^region\s+bc .*$', f'region bc cylinder z 0.0 0.0 0.002 {h:.4f} {h + 0.002:.4f} units box',
                  text, flags=re.M)
    text = text.replace('volumefraction_region 0.0004', 'particles_in_region 1')
    text = re.sub(r'^dump.*$', '', text, flags=re.M)
    text = re.sub(r'^fix\s+ts .*$', '', text, flags=re.M)
    text = re.sub(r'^thermo_style.*$', 'compute tut_p all property/atom z\ncompute tut_z all reduce ave c_tut_p\n'
                  'thermo_style custom step atoms ke c_tut_z', text, flags=re.M)
    return re.sub(r'^thermo\s+\d+', 'thermo 40000', text, flags=re.M)


def run(code, h, args):
    d = os.path.join(args.out, f'{code}_{h:.4f}')
    os.makedirs(d, exist_ok=True)
    shutil.copytree(os.path.join(SOURCE, 'data'), os.path.join(d, 'data'), dirs_exist_ok=True)
    open(os.path.join(d, 'in.scan'), 'w').write(deck(h))
    out, _ = runner.execute(runner.code_command(code, args.sable) + ['-in', 'in.scan'], d, None, runner.one_thread())
    return final_zcm(out)


def final_zcm(text):
    """The grains' mean z at step 40000 with all 50 inserted, from the screen's thermo table
    (step atoms ke c_tut_z); nan when the run did not get there."""
    _, series = screen.parse_screen(text)
    atoms = dict(zip(*series.get('atoms', [[], []])))
    z = [v for step, v in zip(*series.get('tut_z', [[], []])) if step == 40000 and atoms.get(step) == 50]
    return z[-1] if z else float('nan')


def main():
    p = argparse.ArgumentParser()
    p.add_argument('--out', default='build/multisphere_scan')
    p.add_argument('--sable', default=os.path.abspath('build/sable'))
    p.add_argument('--heights', default='0.10:0.39:0.01')
    p.add_argument('--tutorials', default='build/tutorials', help='run.py OUT with multisphere runs')
    p.add_argument('-j', type=int, default=2)
    args = p.parse_args()
    a, b, s = (float(x) for x in args.heights.split(':'))
    hs = np.round(np.arange(a, b + s / 2, s), 4)
    with concurrent.futures.ThreadPoolExecutor(args.j) as ex:
        z = {c: list(ex.map(lambda h: run(c, h, args), hs)) for c in ('liggghts', 'sable')}
    print('h (m)  zcm LIGGGHTS  zcm sable  (step 40000)')
    for k, h in enumerate(hs):
        print(f'{h:.2f}  {z["liggghts"][k]:.6f}  {z["sable"][k]:.6f}')
    print(f'mean over heights: LIGGGHTS {np.nanmean(z["liggghts"]):.5f}, sable {np.nanmean(z["sable"]):.5f}')
    both = (np.array(z['liggghts']) + np.array(z['sable'])) / 2
    result = {'heights': hs.tolist(), 'zcm': z, 'prediction': {}}
    for code in ('liggghts', 'sable'):
        pred, final = [], []
        for d in sorted(glob.glob(os.path.join(args.tutorials, 'multisphere', f'{code}_s*'))):
            f0, f1 = os.path.join(d, 'post', 'multi_200.vtk'), os.path.join(d, 'post', 'multi_40000.vtk')
            if not (os.path.exists(f0) and os.path.exists(f1)):
                continue
            q0 = vtk.points(f0)
            # Release height: the centre at step 200 plus 200 steps of fall at ~1 m/s.
            h0 = [q0[k * 50:(k + 1) * 50, 2].mean() + 0.002 for k in range(len(q0) // 50)]
            pred.append(np.mean(np.interp(h0, hs, both)))
            final.append(vtk.points(f1)[:, 2].mean())
        if pred:
            mp, mf = seedstats.summary(pred).mean, seedstats.summary(final).mean  # seed means
            print(f'{code}: {len(pred)} seeds, zcm predicted from its insertion heights {mp:.5f}, actual {mf:.5f}')
            result['prediction'][code] = {'seeds': len(pred), 'predicted': mp, 'actual': mf}
    json.dump(result, open(os.path.join(args.out, 'scan.json'), 'w'), indent=1)


if __name__ == '__main__':
    main()
