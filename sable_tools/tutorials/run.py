#!/usr/bin/python3
"""Run LIGGGHTS-PUBLIC's tutorial decks unchanged in sable and LIGGGHTS, over seeds.

    /usr/bin/python3 -m sable_tools.tutorials.run [--out DIR] [--only NAME ...]
        [--codes sable,liggghts] [--seeds N] [-j N] [--timeout S] [--sable PATH] [--speed] [--list]

Each tutorial (Debian liggghts-doc: TUTORIALS below) is copied with its data
folder into OUT/<name>/<code>_s<seed>/ and run there as written, except for:
  - the insertion seed (`insert/... seed N`): run 0 keeps the deck's own (that
    run is the deck exactly as shipped), the others take primes from SEEDS
    that the deck does not use already (LIGGGHTS refuses a seed shared with
    a template or distribution);
  - a few lines appended to the deck's end that print the observables
    (after a `run 0` when the deck's last run is followed by write_restart)
    (OBSERVABLE lines as in compare.py): atoms, centre of mass, highest grain,
    kinetic energy at the end; the run-averaged kinetic energy comes from the
    deck's own thermo table (mean of the `ke` column); decks with fix heat/gran
    also print the mean, standard deviation, lowest and highest grain
    temperature (HEAT_OBSERVE);
  - the variants named in EDITS (packing_skin9), a line changed in both codes.
Decks that chain (a restart written by the one before) run in one folder in
order. Per tutorial and code the table gives: runs unchanged (yes/no and the
first error), then per observable the mean ± standard deviation over seeds,
the difference of the means in combined standard errors
SE = sqrt(sd_s^2/n_s + sd_l^2/n_l), and pass when |difference| <= K SE (K 2:
with K 1 two codes with the same physics would fail about a third of the
time) or both codes give the same value to 1e-9 (deterministic counts).
Writes OUT/tutorials.md and OUT/tutorials.json. Runs whose result.json exists
are reused: a cut campaign resumes. Each run records its CPU time (cpu_s: user +
system of the code's processes alone, os.wait4); --speed also writes OUT/speed.md,
the CPU time per code and their ratio (a speed table: run it with --threads 1).
"""
import argparse, concurrent.futures, json, math, os, re, shutil, sys, time

import numpy as np

from sable_tools import runner, seedstats  # running the codes; statistics over seeds
from sable_tools.readers.screen import error_lines, parse_screen  # ERROR lines; OBSERVABLE lines and thermo tables
from sable_tools.readers import vtk  # the mesh snapshots' wear
from sable_tools.paths import REPO

HERE = os.path.join(REPO, 'reference_runs', 'tutorials')  # the stored tutorial results

SOURCE = '/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public'
SEEDS = [49979687, 67867967, 86028121, 104395301, 122949823, 141650939, 160481183, 179424673,
         198491317, 217645177, 236887691, 256203161, 330000647, 340000673, 350000671, 360000689,
         370000711, 380000723, 390000749, 400000789, 410000797, 420000809, 430000853, 440000837,
         450000893, 460000903, 470000933, 480000929, 490000939, 500000951, 510001001, 520001039]
# name: (folder, decks run in order in one folder). The SPH decks are left out (issue 24).
TUTORIALS = {
    'chute_wear': ('chute_wear', ['in.chute_wear']),
    'cohesion': ('cohesion', ['in.cohesion']),
    'noCohesion': ('cohesion', ['in.noCohesion']),
    'newModels': ('contactModels', ['in.newModels']),
    'oldModels': ('contactModels', ['in.oldModels']),
    'conveyor': ('conveyor', ['in.conveyor']),
    'heatTransfer_1': ('heatTransfer_1', ['in.heatGran']),
    'heatTransfer_2': ('heatTransfer_2', ['in.heatGran']),
    'hydrogel_default': ('hydrogel_multicontact', ['in.hydrogel_default']),
    'hydrogel_multicontact': ('hydrogel_multicontact', ['in.hydrogel_multicontact']),
    'hysteresis': ('hysteresis', ['in.hysteresis']),
    'noHysteresis': ('hysteresis', ['in.noHysteresis']),
    'insert_stream': ('insert_stream', ['in.insert_stream']),
    'insert_stream_reset_timestep': ('insert_stream', ['in.insert_stream', 'in.insert_stream_reset_timestep']),
    'meshGran': ('meshGran', ['in.meshGran']),
    'mesh_tet': ('mesh_tet', ['in.mesh_tet']),
    'movingMeshGran': ('movingMeshGran', ['in.movingMeshGran']),
    'multisphere': ('multisphere_stone_restitution', ['in.multisphere']),
    'packing': ('packing', ['in.packing']),
    # The same deck with a 9 mm skin. LIGGGHTS 3.8 bins with the cutoff of the run's
    # start (2 r_max + skin) and misses contacts once fix adapt has grown grains past
    # it (radii 8 -> 11.1 mm here); a skin of 9 mm covers that growth. sable's
    # cutoff follows the radii at every build: its result does not depend on the skin.
    'packing_skin9': ('packing', ['in.packing']),
    'superquadric': ('superquadric', ['in.particle_particle']),  # Debian's LIGGGHTS 3.8: "Invalid atom style"
    # The ParScale decks need LIGGGHTS' ParScale coupling (fix couple/pascal), which the
    # Debian LIGGGHTS 3.8 lacks ("Invalid fix style"); heatTransferBed_paScal stops even
    # earlier there ("invalid radius random style" for `radius gaussian`), and
    # in.liggghts_run asks for 2 processes (`processors 2 1 *`). Kept to show that.
    'parscale_init_run': ('ParScale/fluidizedBedTempParScale', ['in.liggghts_init', 'in.liggghts_run']),
    # Its first deck alone runs in LIGGGHTS 3.8 (10 grains settling, fix momentum): counted.
    'parscale_init': ('ParScale/fluidizedBedTempParScale', ['in.liggghts_init']),
    'parscale_heatTransferBed': ('ParScale/heatTransferBed_paScal', ['in.liggghts']),
}
# The observables' print lines, after the variables tut_* that each deck kind defines.
OBSERVE_PRINTS = """print "OBSERVABLE atoms ${tut_atoms}"
print "OBSERVABLE xcm ${tut_xcm}"
print "OBSERVABLE ycm ${tut_ycm}"
print "OBSERVABLE zcm ${tut_zcm}"
print "OBSERVABLE zmax ${tut_zmax}"
print "OBSERVABLE ke_end ${tut_ke}"
"""
OBSERVE = """
# --- appended by sable_tools/tutorials/run.py: observables only ---
variable tut_atoms equal count(all)
variable tut_xcm equal xcm(all,x)
variable tut_ycm equal xcm(all,y)
variable tut_zcm equal xcm(all,z)
variable tut_zmax equal bound(all,zmax)
variable tut_ke equal ke
""" + OBSERVE_PRINTS
# LIGGGHTS refuses group functions in variables beside fix multisphere ("By default
# variable command 'group' may not be used together with fix multisphere"): there the
# centre is the plain mean of the sphere centres, from compute reduce, in both codes.
MS_OBSERVE = """
# --- appended by sable_tools/tutorials/run.py: observables only (multisphere deck) ---
compute tut_p all property/atom x y z
compute tut_m all reduce ave c_tut_p[1] c_tut_p[2] c_tut_p[3]
compute tut_zmax all reduce max c_tut_p[3]
thermo_style custom step atoms ke c_tut_m[1] c_tut_m[2] c_tut_m[3] c_tut_zmax
run 0
variable tut_atoms equal atoms
variable tut_xcm equal c_tut_m[1]
variable tut_ycm equal c_tut_m[2]
variable tut_zcm equal c_tut_m[3]
variable tut_zmax equal c_tut_zmax
variable tut_ke equal ke
""" + OBSERVE_PRINTS
# Decks with grain temperatures (fix heat/gran) also give the mean, standard deviation,
# lowest and highest grain temperature. LIGGGHTS evaluates a compute in a variable
# after the last run only if it ran at that step: a `run 0` whose thermo prints them
# does (it moves nothing, and repeats the last step, so the thermo series keep their values).
HEAT_OBSERVE = """variable tut_T2 atom f_Temp*f_Temp
compute tut_T all reduce ave f_Temp
compute tut_T2 all reduce ave v_tut_T2
compute tut_Tmin all reduce min f_Temp
compute tut_Tmax all reduce max f_Temp
thermo_style custom step c_tut_T c_tut_T2 c_tut_Tmin c_tut_Tmax
run 0
variable tut_T equal c_tut_T
variable tut_Tsd equal sqrt(abs(c_tut_T2-c_tut_T*c_tut_T))
variable tut_Tmin equal c_tut_Tmin
variable tut_Tmax equal c_tut_Tmax
print "OBSERVABLE T_mean ${tut_T}"
print "OBSERVABLE T_std ${tut_Tsd}"
print "OBSERVABLE T_min ${tut_Tmin}"
print "OBSERVABLE T_max ${tut_Tmax}"
"""
SEED_RE = re.compile(r'(insert/\S+\s+seed\s+)(\d+)')
# Decks run with an edit (name: (pattern, replacement)), in both codes.
EDITS = {'packing_skin9': (r'^neighbor\s+0\.002\s+bin', 'neighbor\t0.009 bin')}


def seeds_of(name, n):
    """The deck's own insertion seed (None when it inserts nothing), then n - 1 unused primes."""
    folder, decks = TUTORIALS[name]
    text = ''.join(open(os.path.join(SOURCE, folder, d)).read() for d in decks)
    own = [int(m.group(2)) for m in SEED_RE.finditer(text)]
    if not own:
        return [None]
    return [own[0]] + [s for s in SEEDS if str(s) not in text][:n - 1]


def prepare(name, code, seed, out):
    """Copy the tutorial folder, set the insertion seed, append the observables."""
    folder, decks = TUTORIALS[name]
    run = os.path.join(out, name, f'{code}_s{seed}')
    if os.path.exists(run):
        shutil.rmtree(run)
    shutil.copytree(os.path.join(SOURCE, folder), run, ignore=shutil.ignore_patterns('post'))
    os.makedirs(os.path.join(run, 'post'), exist_ok=True)
    for k, deck in enumerate(decks):
        text = open(os.path.join(run, deck)).read()
        if seed is not None:
            text = SEED_RE.sub(lambda m: m.group(1) + str(seed), text)
        if name in EDITS:
            text, n = re.subn(EDITS[name][0], EDITS[name][1], text, flags=re.M)
            assert n == 1, f'{name}: the edit {EDITS[name]} did not match'
        if k == len(decks) - 1:
            # After write_restart (its system init) LIGGGHTS refuses thermo keywords
            # in variables until a run: `run 0` makes them current (no step; its thermo row repeats the last).
            refresh = 'run 0\n' if 'write_restart' in text.split('\nrun')[-1] else ''
            multisphere = re.search(r'^\s*fix\s+\S+\s+\S+\s+multisphere\b', text, re.M)
            text = text.rstrip('\n') + '\n' + refresh + (MS_OBSERVE if multisphere else OBSERVE)
            if re.search(r'^\s*fix\s+\S+\s+\S+\s+heat/gran', text, re.M):
                text += HEAT_OBSERVE
        open(os.path.join(run, deck), 'w').write(text)
    return run, decks


def observables(text, ok):
    """The OBSERVABLE lines, and ke_mean: the mean of the thermo ke column."""
    obs, series = parse_screen(text)
    ke = series.get('ke', series.get('kineng'))  # sable's thermo header says ke, LIGGGHTS' KinEng
    if ke and ok:
        obs['ke_mean'] = float(np.mean(ke[1]))
    return obs


def mesh_observables(run):
    """Decks dumping mesh wear (chute_wear): the summed and largest triangle wear of the
    last mesh snapshot in post/ (per area, LIGGGHTS' `wear finnie`)."""
    post = os.path.join(run, 'post')
    snaps = [f for f in os.listdir(post) if re.fullmatch(r'mesh_\d+\.vtk', f)] if os.path.isdir(post) else []
    if not snaps:
        return {}
    last = max(snaps, key=lambda f: int(re.search(r'\d+', f).group()))
    wear = vtk.field(open(os.path.join(post, last)).read(), 'wear')
    return {'wear_sum': float(sum(wear)), 'wear_max': float(max(wear))} if wear else {}


def run_one(name, code, seed, args):
    """Run the tutorial's decks in order; return the result record (also result.json)."""
    path = os.path.join(args.out, name, f'{code}_s{seed}', 'result.json')
    if os.path.exists(path):
        rec = json.load(open(path))
        screen = os.path.join(os.path.dirname(path), 'screen.txt')
        if rec['ok'] and 'ke_mean' not in rec['observables'] and os.path.exists(screen):
            rec['observables'].update(observables(open(screen).read(), True))  # runs stored before KinEng was read
        return rec
    run, decks = prepare(name, code, seed, args.out)
    rec = {'tutorial': name, 'code': code, 'seed': seed, 'ok': True, 'error': None, 'wall_s': 0.0}
    text = ''
    env = {**os.environ, 'OMP_NUM_THREADS': str(args.threads)}
    rec['cpu_s'] = 0.0
    for k, deck in enumerate(decks):
        # os.wait4 (runner.measured): the process's own CPU time, whatever else runs beside it.
        try:
            m = runner.measured(runner.code_command(code, args.sable) + ['-in', deck], run,
                                os.path.join(run, f'screen{k}.txt'), env, args.timeout)
            out, rc = m.text + ('\n(timed out)' if m.timed_out else ''), m.rc
            rec['wall_s'] += m.wall
            rec['cpu_s'] += m.cpu
        except OSError as e:
            out, rc = str(e), -1
        text += out
        if rc != 0 or 'ERROR' in out:
            rec['ok'] = False
            errs = error_lines(out)
            last = out.strip().splitlines()[-1] if out.strip() else ''
            rec['error'] = (errs[0] if errs else f'{deck}: exit status {rc}: {last}')[:300]
            break
    open(os.path.join(run, 'screen.txt'), 'w').write(text)
    rec['observables'] = observables(text, rec['ok'])
    if rec['ok']:
        rec['observables'].update(mesh_observables(run))
    print(f'[{name} {code} s{seed}] {"ok" if rec["ok"] else "FAILED: " + rec["error"]} '
          f'({rec["wall_s"]:.0f} s)', flush=True)
    json.dump(rec, open(path, 'w'), indent=1, allow_nan=True)
    return rec


def stats(values):
    """(mean, seed-to-seed sd, n) over the seeds (seedstats.summary); sd 0 for one seed."""
    s = seedstats.summary(values)
    return s.mean, 0.0 if s.n == 1 else s.sd, s.n


def table(results, codes, k):
    """Markdown: one block per tutorial; returns (lines, summary)."""
    lines, summary = [], {}
    for name in TUTORIALS:
        recs = {c: [r for r in results if r['tutorial'] == name and r['code'] == c] for c in codes}
        if not any(recs.values()):
            continue
        runs = {c: (all(r['ok'] for r in recs[c]) if recs[c] else None) for c in codes}
        lines.append(f'## {name}')
        for c in codes:
            bad = [r for r in recs[c] if not r['ok']]
            state = 'not run' if runs[c] is None else 'runs' if runs[c] else f'fails: `{bad[0]["error"]}`'
            wall = np.mean([r['wall_s'] for r in recs[c]]) if recs[c] else 0
            lines.append(f'- {c}: {state} ({len(recs[c])} seeds, {wall:.0f} s per run)')
        verdicts = []
        if len(codes) == 2 and all(runs.values()):
            a, b = codes
            lines += ['', f'| observable | {a} | {b} | diff / SE | result |', '|---|---|---|---|---|']
            names = sorted({n for r in recs[a] + recs[b] for n in r['observables']})
            for n in names:
                ma, sa, na = stats([r['observables'].get(n) for r in recs[a]])
                mb, sb, nb = stats([r['observables'].get(n) for r in recs[b]])
                se = math.sqrt(sa ** 2 / max(na, 1) + sb ** 2 / max(nb, 1))
                d = abs(ma - mb)
                ok = d <= k * se or d <= 1e-9 * max(abs(ma), abs(mb))
                verdicts.append(ok)
                z = d / se if se > 0 else (0.0 if ok else math.inf)
                lines.append(f'| {n} | {ma:.6g} ± {sa:.2g} | {mb:.6g} ± {sb:.2g} | {z:.2f} | '
                             f'{"pass" if ok else "FAIL"} |')
        summary[name] = {'runs': runs, 'agree': all(verdicts) if verdicts else None}
        lines.append('')
    return lines, summary


def speed_table(results, codes):
    """Markdown: per tutorial the whole process's CPU time per code (mean over its seeds,
    one core: OMP_NUM_THREADS=1) and the ratio of the second code's to the first's."""
    a, b = codes[:2]
    rows = ['| tutorial | seeds | %s CPU s | %s CPU s | %s / %s |' % (a, b, b, a), '|---|---|---|---|---|']
    ratios = []
    for name in TUTORIALS:
        t = {}
        for c in (a, b):
            recs = [r for r in results if r['tutorial'] == name and r['code'] == c and r['ok'] and 'cpu_s' in r]
            t[c] = (np.mean([r['cpu_s'] for r in recs]), len(recs)) if recs else None
        if not t[a] and not t[b]:
            continue
        cell = lambda c: f'{t[c][0]:.2f}' if t[c] else 'n/a'
        ratio = t[b][0] / t[a][0] if t[a] and t[b] and t[a][0] > 0 else None
        if ratio:
            ratios.append(ratio)
        n = min(x[1] for x in t.values() if x)
        rows.append(f'| {name} | {n} | {cell(a)} | {cell(b)} | ' + (f'{ratio:.2f}' if ratio else 'n/a') + ' |')
    if ratios:
        rows += ['', f'median {b} / {a}: {float(np.median(ratios)):.2f} over {len(ratios)} tutorials '
                 f'(min {min(ratios):.2f}, max {max(ratios):.2f})']
    return rows


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--out', default=os.path.join(REPO, 'build-tutorials'))
    p.add_argument('--only', nargs='+', default=None, choices=list(TUTORIALS), metavar='NAME')
    p.add_argument('--codes', default='sable,liggghts')
    p.add_argument('--seeds', type=int, default=3)
    p.add_argument('-j', type=int, default=1, help='runs at once')
    p.add_argument('--threads', type=int, default=1, help='OMP_NUM_THREADS for sable')
    p.add_argument('--timeout', type=float, default=3600)
    p.add_argument('--sigma', type=float, default=2.0, help='K in |difference| <= K SE')
    p.add_argument('--sable', default=runner.built('sable'))
    p.add_argument('--list', action='store_true', help='list the tutorials and stop')
    p.add_argument('--speed', action='store_true',
                   help='also write OUT/speed.md: CPU time per code and their ratio (run with --threads 1)')
    args = p.parse_args()
    if args.list:
        for n, (f, d) in TUTORIALS.items():
            print(f'{n:30s} {f}/{" + ".join(d)}')
        return 0
    if not os.path.isdir(SOURCE):
        sys.exit(f'{SOURCE} is missing: apt-get install liggghts-doc')
    codes = args.codes.split(',')
    args.out, args.sable = os.path.abspath(args.out), os.path.abspath(args.sable)
    jobs = [(n, c, s) for n in (args.only or TUTORIALS) for c in codes for s in seeds_of(n, args.seeds)]
    with concurrent.futures.ThreadPoolExecutor(args.j) as pool:
        results = list(pool.map(lambda job: run_one(*job, args), jobs))
    lines, summary = table(results, codes, args.sigma)
    both = [n for n, s in summary.items() if all(s['runs'].values())]
    agree = [n for n in both if summary[n]['agree']]
    sable_ok = [n for n, s in summary.items() if s['runs'].get('sable')]
    head = [f'# LIGGGHTS-PUBLIC tutorials in {", ".join(codes)}', '',
            f'{len(summary)} tutorials; sable runs {len(sable_ok)} unchanged; '
            f'{len(both)} run in every code, of which {len(agree)} agree (|diff| <= {args.sigma:g} SE).', '']
    open(os.path.join(args.out, 'tutorials.md'), 'w').write('\n'.join(head + lines) + '\n')
    json.dump({'summary': summary, 'runs': results}, open(os.path.join(args.out, 'tutorials.json'), 'w'),
              indent=1, allow_nan=True)
    if args.speed and len(codes) >= 2:
        load = os.getloadavg()
        speed = [f'# Tutorials: CPU time of the whole process, {codes[1]} / {codes[0]}', '',
                 f'{time.strftime("%Y-%m-%d %H:%M")}, {runner.code_command(codes[0], args.sable)[0]}, '
                 f'OMP_NUM_THREADS={args.threads}, load average at the end {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}', '']
        speed += speed_table(results, codes)
        open(os.path.join(args.out, 'speed.md'), 'w').write('\n'.join(speed) + '\n')
        print('\n'.join(speed))
    print('\n'.join(head).strip())
    print(f'table: {os.path.join(args.out, "tutorials.md")}')
    return 0 if len(agree) == len(both) else 1


if __name__ == '__main__':
    sys.exit(main())
