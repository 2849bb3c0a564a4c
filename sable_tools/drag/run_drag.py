#!/usr/bin/python3
"""Run the drag study's deck (input_scripts/drag/drag.in) in sable and LIGGGHTS.

    /usr/bin/python3 -m sable_tools.drag.run_drag (--preset NAME | --cases FILE.json)
        [--out DIR] [-j N] [--sable PATH] [--sable-commit HASH] [--liggghts PATH] [--only CASE ...] [--dry-run]
    /usr/bin/python3 -m sable_tools.drag.run_drag --freeze-sable DIR

A case is a name, deck variables, codes and seeds (and optionally a speed-against-
error `series` name). Each run gets its own folder OUT/<case>/<code>_s<seed>/ with
the cylinder STL, log.txt, stdout.txt, drag_torque.txt and run.json (the parsed
SCENE, SETTLED, BLOCK and RESULT lines, wall and CPU time, code version, status).
Every run.json names the commits it was made with: `harness` (this checkout's HEAD, its
uncommitted changes under input_scripts/drag and reference_runs/drag, the deck's sha256)
and, for sable, the binary's sha256 and the commit it was built from (--sable-commit, else
BINARY.commit, else the HEAD of the checkout whose build folder holds it when the binary is
newer than the sources there); without one the campaign refuses to start. --freeze-sable DIR
copies build/sable to DIR/sable_<HEAD> with its .commit file, for campaigns.
Runs whose run.json says "ok" are skipped, so a cut campaign resumes where it
stopped; failed runs are run again and reported with their error tail.

-j N runs N at once. Keep the default 1 for campaigns whose wall times feed the
speed-against-error plot: those must come from runs alone on the machine.
Case file: {"cases": [{"name": ..., "vars": {"hL": 2, ...}, "codes": ["sable", "liggghts"],
"seeds": [49979687, ...], "series": "dt" (or a list)}, ...]}; "seeds" may also give each code
its own list: {"sable": [...], "liggghts": [...]} (codes default to its keys). Exit status 1
if any run failed.
"""
import argparse, concurrent.futures, datetime, hashlib, json, math, os, re, shutil, subprocess, sys, threading, time

from sable_tools import runner  # LIGGGHTS unbuffered
from sable_tools.drag import make_cylinder_stl
from sable_tools.paths import REPO
from sable_tools.readers import screen  # KEY k=v lines

HERE = os.path.join(REPO, 'reference_runs', 'drag')  # the stored runs
DECK = os.path.join(REPO, 'input_scripts', 'drag', 'drag.in')
STORED = os.path.join(HERE, 'stored')  # LIGGGHTS runs kept for machines without it
SEEDS = [49979687, 67867967, 86028121, 104395301, 122949823, 141650939, 160481183, 179424673]
SPEED = {'sable': 1.5e7, 'liggghts': 5e6}  # particle-steps/s on one core, for the time estimate
SMOKE = {'Wd': 15, 'Ld': 6, 'Dd': 2, 'hL': 1, 'zcL': 1, 'turns': 2}
BOTH = ['sable', 'liggghts']


def preset(name):
    """The named list of cases."""
    if name == 'smoke':  # ~1 min in sable, ~3 min in LIGGGHTS
        return [dict(name='smoke', vars=SMOKE, codes=BOTH, seeds=SEEDS[:1])]
    if name == 'speed-smoke':  # the smoke scene at two time steps: checks the speed/error path
        return [dict(name=f'smoke_dtf{f}', vars={**SMOKE, 'dtf': f}, codes=BOTH, seeds=SEEDS[:1], series='dt')
                for f in (0.15, 0.08)]
    if name == 'small':  # three depths at E 5e6 (E* = 1.4e5), 2 seeds
        return [dict(name=f'small_hL{h}', vars={**SMOKE, 'hL': h, 'turns': 4}, codes=BOTH, seeds=SEEDS[:2])
                for h in (1, 2, 3)]
    if name == 'speed':  # speed against error on the smoke scene: time step, stiffness, container width
        dt = [dict(name=f'speed_dtf{f}', vars={**SMOKE, 'turns': 3, 'dtf': f}, codes=BOTH, seeds=SEEDS[:2],
                   series='dt') for f in (0.17, 0.15, 0.1, 0.05)]
        # E >= 5 MPa: both codes refuse softer SI grains (soft_particles); speed_E5e6 (Wd 15) is also the W series' middle
        stiff = [dict(name=f'speed_E{e}', vars={**SMOKE, 'turns': 3, 'E': e}, codes=BOTH, seeds=SEEDS[:2],
                      series=['E', 'W'] if e == '5e6' else 'E') for e in ('5e6', '1e7', '2e7', '8e7')]
        size = [dict(name=f'speed_Wd{w}', vars={**SMOKE, 'turns': 3, 'Wd': w}, codes=BOTH, seeds=SEEDS[:2],
                     series='W') for w in (12, 20)]
        return dt + stiff + size
    sys.exit(f'unknown preset {name} (smoke, speed-smoke, small, speed)')


PRESETS = ['smoke', 'speed-smoke', 'small', 'speed']


# ---------------------------------------------------------------- the deck's numbers
def deck_defaults():
    """The deck's `variable NAME index VALUE` lines."""
    out = {}
    for line in open(DECK):
        w = line.split()
        if len(w) >= 4 and w[0] == 'variable' and w[2] == 'index':
            out[w[1]] = w[3]
    return out


def scene(variables):
    """Deck variables (defaults + case) as floats, with the quantities the deck derives
    from them: lengths, Nrec, dt, grain counts and the particle-steps of a run."""
    raw = {k: str(x) for k, x in {**deck_defaults(), **variables}.items() if k not in ('stl', 'out')}
    for k, x in raw.items():  # a default given as another variable: `variable muprep index ${mu}`
        if x.startswith('${') and x.endswith('}'):
            raw[k] = raw[x[2:-1]]
    v = {k: float(x) for k, x in raw.items()}
    d, r = v['d'], 0.5 * v['d']
    L, D, R = v['Ld'] * d, v['Dd'] * d, 0.5 * v['Wd'] * d
    zc, h, g = v['zcL'] * L, v['hL'] * L, 9.81
    vg = math.pi * d ** 3 / 6
    n1 = round(0.6 * math.pi * R * R * zc / vg)
    ntot = round(0.6 * (math.pi * R * R * (zc + h) - math.pi * 0.25 * D * D * L) / vg)
    G = v['E'] / (2 * (1 + v['nu']))
    t_r = math.pi * r * math.sqrt(v['rho'] / G) / (0.1631 * v['nu'] + 0.8766)
    nrec = math.ceil(v['period'] / 100 / (v['dtf'] * t_r))
    dt = v['period'] / 100 / nrec
    h2 = h * 0.6 / 0.25 + 2 * d
    fill1 = math.ceil((math.sqrt(2 * zc * 0.6 / 0.25 / g) + v['settle']) / dt)
    # second fill from just above the cylinder's top, then on average half of the half-turn alignment
    fill2 = math.ceil((math.sqrt(2 * (0.5 * D + 2 * d + h2 - h) / g) + v['settle']) / dt) + 25 * nrec
    steps_rot = round(v['turns'] * 100 * nrec)
    return dict(v, L=L, D=D, Nrec=nrec, dt=dt, grains=ntot, Fscale=v['rho'] * g * D * L * L,
                Estar=v['E'] / (v['rho'] * g * d), particle_steps=n1 * fill1 + ntot * (fill2 + steps_rot))


# ---------------------------------------------------------------- what made a run
SOURCES = ['core', 'fixes', 'computes', 'contact_models', 'tools', 'CMakeLists.txt']  # what build/sable is made of
HARNESS_PATHS = ['input_scripts/drag', 'reference_runs/drag', 'sable_tools']
HEX = re.compile(r'^[0-9a-fA-F]{7,40}$')


def git(top, *a):
    """git's stdout in the checkout top (trailing blanks cut), or None when it fails. --no-optional-locks:
    `status` does not take the index lock of a checkout others work in."""
    p = subprocess.run(['git', '--no-optional-locks', '-C', top, *a], capture_output=True, text=True)
    return p.stdout.rstrip() if p.returncode == 0 else None


def sha256(path):
    h = hashlib.sha256()
    with open(path, 'rb') as f:
        for b in iter(lambda: f.read(1 << 20), b''):
            h.update(b)
    return h.hexdigest()


def porcelain(top, paths):
    """`git status --porcelain -- paths`: (tracked changes, untracked) as lists of lines."""
    lines = (git(top, 'status', '--porcelain', '--', *paths) or '').splitlines()
    return [l for l in lines if not l.startswith('??')], [l[3:] for l in lines if l.startswith('??')]


def harness(out=None):
    """The checkout that holds this script and the deck: its HEAD (full hash), uncommitted
    changes under input_scripts/drag and reference_runs/drag (`dirty`: tracked files changed;
    `untracked`: new files there, run folders under `out` left out) and the deck's sha256.
    Exits when the checkout is not a git checkout: a run must name its commit."""
    head = git(REPO, 'rev-parse', 'HEAD')
    if not head:
        sys.exit(f'{REPO} is not a git checkout: the runs could not name the commit of run_drag.py and the deck')
    changed, new = porcelain(REPO, HARNESS_PATHS)
    o = os.path.relpath(os.path.abspath(out), REPO).rstrip('/') + '/' if out else None
    new = [n for n in new if not (o and (o.startswith(n) or n.startswith(o)))]
    return {'commit': head, 'dirty': bool(changed), 'changes': changed[:20], 'untracked': new[:20],
            'deck': os.path.relpath(DECK, REPO), 'deck_sha256': sha256(DECK)}


def full_hash(h, top=REPO):
    """h as a full hash where a checkout knows it, else h itself."""
    return git(top, 'rev-parse', '--verify', '--quiet', h + '^{commit}') or h


def sable_commit(exe, given=None):
    """(commit, how it was established) of the sable binary, in this order: --sable-commit;
    the file <binary>.commit (written by --freeze-sable or a campaign); the HEAD of the git
    checkout whose build folder holds the binary, if the binary is newer than HEAD or than
    the newest commit touching the sources (SOURCES: then HEAD's sources are the ones it was
    built from), with that checkout's uncommitted source changes named; or, with no such
    changes, if it is newer than every source file there (built, then committed). Exits otherwise."""
    if given:
        if not HEX.match(given):
            sys.exit(f'--sable-commit {given}: not a commit hash')
        return full_hash(given), '--sable-commit'
    tag = exe + '.commit'
    if os.path.exists(tag):
        words = open(tag).read().split()
        if not words or not HEX.match(words[0]):
            sys.exit(f'{tag}: no commit hash in it')
        return full_hash(words[0]), f'file {tag}'
    refuse = (f'sable: cannot establish the commit {exe} was built from: {{}}.\n'
              f'Give --sable-commit HASH, or write the hash into {tag}, or freeze a build with '
              f'`run_drag.py --freeze-sable DIR` and run with --sable DIR/sable_<hash>.')
    top = os.path.dirname(os.path.dirname(os.path.realpath(exe)))
    if git(top, 'rev-parse', '--show-toplevel') != top:
        sys.exit(refuse.format(f'no {os.path.basename(tag)} next to it and {top} is not the git checkout '
                               'whose build folder holds it'))
    head, how, why = built_from_head(top, exe)
    if how is None:
        sys.exit(refuse.format(why))
    return head, how


def built_from_head(top, exe):
    """Whether exe was built from the sources of HEAD of the checkout top: (HEAD, how, None) when
    exe is newer than HEAD, or than the newest commit touching SOURCES, or (with no uncommitted
    source changes) than every file under SOURCES (built, then committed), uncommitted source
    changes named in `how`; else (HEAD, None, why)."""
    head = git(top, 'rev-parse', 'HEAD')
    built = os.path.getmtime(exe)
    stamp = lambda t: time.strftime('%Y-%m-%d %H:%M', time.localtime(float(t)))
    head_t = float(git(top, 'log', '-1', '--format=%ct', 'HEAD'))
    src, src_t = (git(top, 'log', '-1', '--format=%H %ct', 'HEAD', '--', *SOURCES) or f'{head} {head_t}').split()
    changed, new = porcelain(top, SOURCES)
    files = (git(top, 'ls-files', '-z', '--', *SOURCES) or '').split('\0')
    newest = max((os.path.getmtime(os.path.join(top, f)) for f in files if f and os.path.exists(os.path.join(top, f))),
                 default=math.inf)
    srcs = ' '.join(SOURCES)
    if built >= head_t:
        how = f'HEAD of {top} (binary newer than HEAD)'
    elif built >= float(src_t):
        how = (f'HEAD of {top}: built from an older tree than HEAD ({stamp(built)} < {stamp(head_t)}), '
               f'after {src[:12]}, the newest commit touching {srcs}: same sources')
    elif not (changed or new) and built >= newest:
        how = (f'HEAD of {top}: binary older than {src[:12]}, the newest commit touching {srcs}, '
               f'but newer than every file there ({stamp(newest)}), which are as committed: built, then committed')
    else:
        return head, None, (f'built from an older tree than HEAD: the binary ({stamp(built)}) is older than '
                            f'{src[:12]} ({stamp(src_t)}), the newest commit touching {srcs}' +
                            (f', and older than files there ({stamp(newest)})' if newest != math.inf else '') +
                            (', which have uncommitted changes' if changed or new else ''))
    if changed or new:
        how += '; plus uncommitted source changes: ' + ', '.join(changed + ['?? ' + n for n in new])[:300]
    return head, how, None


def code_version(code, exe, commit=None):
    """What identifies the binary: for sable its sha256, build time and the commit it was
    built from (commit: (hash, how), from sable_commit); for LIGGGHTS the Debian package
    version and the binary's sha256."""
    path = exe if os.path.exists(exe) else shutil.which(exe) or exe
    if code == 'liggghts':
        p = subprocess.run(['dpkg-query', '-W', '-f', '${Version}', 'liggghts'], capture_output=True, text=True)
        return {'binary': exe, 'package': p.stdout.strip() or 'not a Debian package (dpkg-query: none)',
                'sha256': sha256(path)}
    c, how = commit or sable_commit(exe)
    return {'binary': exe, 'sha256': sha256(path), 'commit': c, 'commit_source': how,
            'built': time.strftime('%Y-%m-%d %H:%M', time.localtime(os.path.getmtime(path)))}


def freeze_sable(folder):
    """Copy build/sable to folder/sable_<short HEAD> with folder/sable_<short HEAD>.commit holding
    the full HEAD hash; refuses when the sources (SOURCES) have uncommitted changes or build/sable
    is older than the newest commit touching them (and than their files: built_from_head).
    Returns the copy's path."""
    src = runner.built('sable')
    if not os.path.exists(src):
        sys.exit(f'{src} not found: build sable first')
    changed, new = porcelain(REPO, SOURCES)
    if changed or new:
        sys.exit('refusing to freeze: uncommitted changes under ' + ' '.join(SOURCES) + ':\n  ' +
                 '\n  '.join(changed + ['?? ' + n for n in new]))
    head, how, why = built_from_head(REPO, src)
    if how is None:
        sys.exit(f'refusing to freeze {src}: {why}; rebuild it first')
    dst = os.path.join(os.path.abspath(folder), 'sable_' + head[:12])
    if os.path.exists(dst) and sha256(dst) != sha256(src):
        sys.exit(f'{dst} exists and differs from {src}: remove it or freeze into another folder')
    os.makedirs(folder, exist_ok=True)
    if not os.path.exists(dst):
        shutil.copy2(src, dst)
    with open(dst + '.commit', 'w') as f:
        f.write(head + '\n')
    return dst


# ---------------------------------------------------------------- one run
def parse_stdout(text):
    """SCENE/SETTLED/RESULT key=value lines, BLOCK values, summed Loop times."""
    rec = {'blocks': [float(kv['F']) for _, kv in screen.numbered(text, 'BLOCK') if 'F' in kv],
           'loop_time_s': sum(screen.loop_times(text))}
    for key in ('SCENE', 'SETTLED', 'RESULT', 'PIECE'):
        lines = screen.key_lines(text, key)
        if lines:
            rec[key.lower()] = {k: float(v) for k, v in lines[-1].items()}
    return rec


def run_dir(out, case, code, seed):
    return os.path.join(out, case['name'], f'{code}_s{seed}')


def is_done(folder):
    try:
        return json.load(open(os.path.join(folder, 'run.json'))).get('status') == 'ok'
    except (OSError, ValueError):
        return False


def launch(cmd, folder, stdout_name, threads):
    """Run cmd in folder with stdout to stdout_name; returns (exit code, wall s, CPU s, text).
    runner.measured: os.wait4, the run's own CPU time, whatever else runs."""
    m = runner.measured(cmd, folder, os.path.join(folder, stdout_name),
                        env={**os.environ, 'OMP_NUM_THREADS': str(threads)})
    return m.rc, m.wall, m.cpu, m.text


def run_one(case, code, seed, folder, exe, threads=1, chunk=0, version=None, out=None):
    """Run the deck in its folder and write run.json; returns the record. sable runs on
    `threads` OpenMP threads (default 1, as LIGGGHTS' one process, so that times compare per core).
    chunk > 0: in pieces of that many half-turns (run_pieces). version: code_version's record,
    established when the campaign started (the run fails if the binary changed since); the
    record also gets the harness (run_drag.py's and the deck's commit, `harness()`)."""
    os.makedirs(folder, exist_ok=True)
    v = {**{k: str(x) for k, x in case['vars'].items()}, 'seed': str(seed), 'stl': 'cylinder.stl', 'out': 'drag'}
    s = scene(v)
    if not os.path.exists(os.path.join(folder, 'cylinder.stl')) or not chunk:
        make_cylinder_stl.write(os.path.join(folder, 'cylinder.stl'), s['D'], s['L'])
    cmd = runner.unbuffered([exe, '-in', DECK]) if code == 'liggghts' else [exe, '-in', DECK]
    cmd += (['-echo', 'none'] if code == 'liggghts' else []) + [w for k, x in v.items() for w in ('-var', k, x)]
    rec = {'case': case['name'], 'code': code, 'seed': seed, 'vars': v, 'series': case.get('series'),
           'command': ' '.join(cmd), 'started': datetime.datetime.now().isoformat(timespec='seconds'),
           'threads': threads if code == 'sable' else 1,
           'version': version or code_version(code, exe), 'harness': harness(out), 'estimate': {'grains': s['grains'], 'particle_steps': s['particle_steps']}}
    now = sha256(exe if os.path.exists(exe) else shutil.which(exe) or exe)
    if now != rec['version']['sha256']:
        rec.update(returncode=None, status='failed', error_tail=[
            f"{exe} changed since the campaign started (sha256 {now[:16]}, was {rec['version']['sha256'][:16]})"])
    elif chunk:
        run_pieces(rec, cmd, folder, threads, chunk, int(s['turns']))
    else:
        rc, rec['wall_s'], rec['cpu_s'], text = launch(cmd + ['-log', 'log.txt'], folder, 'stdout.txt', threads)
        rec.update(parse_stdout(text))
        rec['returncode'] = rc
        rec['status'] = 'ok' if rc == 0 and 'result' in rec else 'failed'
        if rec['status'] != 'ok':
            rec['error_tail'] = text.strip().splitlines()[-15:]
    with open(os.path.join(folder, 'run.json'), 'w') as f:
        json.dump(rec, f, indent=1)
    return rec


def run_pieces(rec, cmd, folder, threads, chunk, turns):
    """The run as pieces of `chunk` half-turns (the deck's halves/resume: each piece ends with a
    restart file, the next reads it). pieces.json keeps the half-turn means and times of the
    pieces done, so that a cut campaign goes on from the last finished piece. The result is
    the deck's: F_first the first half-turn, F_stat the mean of the last `turns` half-turns."""
    state_file = os.path.join(folder, 'pieces.json')
    try:
        st = json.load(open(state_file))
    except (OSError, ValueError):
        st = {'done': 0, 'halves': [], 'pieces': []}
    total = 2 * turns
    sha = rec['version']['sha256']
    other = [p['sha256'] for p in st['pieces'] if p.get('sha256', sha) != sha]
    if other:
        rec.update(returncode=None, status='failed', pieces_done=st['done'], error_tail=[
            f"the finished pieces were run by another binary (sha256 {other[0][:16]}, now {sha[:16]}): "
            f"run it with that one, or remove {folder} to start over"])
        return
    while st['done'] < total:
        k, n = st['done'], min(chunk, total - st['done'])
        name = f'piece{k}'
        rc, wall, cpu, text = launch(cmd + ['-log', f'log_{name}.txt', '-var', 'halves', str(n), '-var', 'resume', str(k)],
                                     folder, f'stdout_{name}.txt', threads)
        halves = [(i, float(kv['F'])) for i, kv in screen.numbered(text, 'HALF') if 'F' in kv]
        piece = parse_stdout(text)
        ok = rc == 0 and [h[0] for h in halves] == list(range(k + 1, k + n + 1)) and 'piece' in piece
        if not ok:
            rec.update(returncode=rc, status='failed', error_tail=text.strip().splitlines()[-15:], pieces_done=k)
            return
        if k == 0:
            st['scene'], st['settled'] = piece.get('scene'), piece.get('settled')
        st['halves'] += [h[1] for h in halves]
        st['pieces'].append({'from': k, 'halves': n, 'wall_s': wall, 'cpu_s': cpu,
                             'loop_time_s': piece['loop_time_s'], 'step': piece['piece']['step'], 'sha256': sha,
                             'harness': rec['harness']['commit'], 'harness_dirty': rec['harness']['dirty']})
        st['done'] = k + n
        st['last'] = piece['piece']
        with open(state_file, 'w') as f:
            json.dump(st, f, indent=1)
    h = st['halves']
    blocks = h[total - turns:]
    mean = sum(blocks) / turns
    var = abs(sum(b * b for b in blocks) / turns - mean * mean)
    rec.update({k: st[k] for k in ('scene', 'settled') if st.get(k)})
    rec['halves'], rec['blocks'] = h, blocks
    rec['result'] = {'F_first': h[0], 'F_stat': mean, 'F_stat_err': math.sqrt(var / (turns - 1)), 'turns': turns,
                     'grains': st['last']['grains'], 'h_meas': (st.get('settled') or {}).get('h_meas'),
                     'dt': st['last']['dt'], 'steps_per_turn': st['last']['steps_per_turn']}
    for key in ('wall_s', 'cpu_s', 'loop_time_s'):
        rec[key] = sum(p[key] for p in st['pieces'])
    rec['pieces'] = len(st['pieces'])
    rec['returncode'], rec['status'] = 0, 'ok'


def use_stored(case, code, seed, folder):
    """Without the code's binary: its stored run (run.json, torque) if there is one."""
    src = os.path.join(STORED, case['name'], f'{code}_s{seed}')
    if not os.path.exists(os.path.join(src, 'run.json')):
        return False
    shutil.copytree(src, folder, dirs_exist_ok=True)
    rec = json.load(open(os.path.join(folder, 'run.json')))
    if rec['vars'] != {**case['vars'], 'seed': str(seed), 'stl': 'cylinder.stl', 'out': 'drag'}:
        sys.exit(f'{src} was run with other variables: {rec["vars"]}')
    rec['stored'] = True
    json.dump(rec, open(os.path.join(folder, 'run.json'), 'w'), indent=1)
    return True


def store(runs):
    """Keep the finished LIGGGHTS runs' run.json and torque in STORED."""
    for c, code, seed, folder, _ in runs:
        if code == 'liggghts' and is_done(folder):
            dst = os.path.join(STORED, c['name'], f'{code}_s{seed}')
            os.makedirs(dst, exist_ok=True)
            for f in ('run.json', 'drag_torque.txt'):
                shutil.copy(os.path.join(folder, f), dst)
            print(f'stored {dst}')


# ---------------------------------------------------------------- the campaign
def load_cases(args):
    cases = preset(args.preset) if args.preset else json.load(open(args.cases))['cases']
    if args.only:
        cases = [c for c in cases if c['name'] in args.only]
    for c in cases:
        if isinstance(c.get('seeds'), dict):
            c.setdefault('codes', list(c['seeds']))
        c.setdefault('codes', BOTH)
        if args.codes:
            c['codes'] = [x for x in c['codes'] if x in args.codes.split(',')]
        c.setdefault('seeds', SEEDS[:1])
        c['vars'] = {k: str(x) for k, x in c['vars'].items()}
    return cases


def seeds_of(case, code):
    """The case's seeds for one code (a case gives one list for all codes, or one per code)."""
    s = case['seeds']
    return s.get(code, []) if isinstance(s, dict) else s


def save_cases(out, cases):
    """OUT/cases.json: every case run into OUT so far (report_drag.py reads it). A case
    run again with the same variables keeps the codes and seeds it was run with before."""
    path = os.path.join(out, 'cases.json')
    known = {c['name']: c for c in json.load(open(path))['cases']} if os.path.exists(path) else {}
    for c in cases:
        old = known.pop(c['name'], None)
        if old is not None and old['vars'] == c['vars']:
            codes = old['codes'] + [x for x in c['codes'] if x not in old['codes']]
            merged = lambda a, b: a + [x for x in b if x not in a]
            if isinstance(old['seeds'], dict) or isinstance(c['seeds'], dict):
                seeds = {k: merged(seeds_of(old, k), seeds_of(c, k)) for k in codes}
            else:
                seeds = merged(old['seeds'], c['seeds'])
            c = dict(c, codes=codes, seeds=seeds)
        known[c['name']] = c
    with open(path, 'w') as f:
        json.dump({'cases': list(known.values())}, f, indent=1)


def plan(cases, out):
    """(case, code, seed, folder) of every run, and the estimated time of those still to do."""
    runs, todo_s = [], 0.0
    for c in cases:
        s = scene(c['vars'])
        for code in c['codes']:
            for seed in seeds_of(c, code):
                folder = run_dir(out, c, code, seed)
                done = is_done(folder)
                runs.append((c, code, seed, folder, done))
                todo_s += 0 if done else s['particle_steps'] / SPEED[code]
        print(f"  {c['name']}: {' '.join(f'{k}={x}' for k, x in c['vars'].items())}; ~{s['grains']} grains, "
              f"dt {s['dt']:.3g} s, {s['particle_steps']:.3g} particle-steps per run; "
              f"est. {s['particle_steps'] / SPEED['sable'] / 60:.1f} min sable, "
              f"{s['particle_steps'] / SPEED['liggghts'] / 60:.1f} min LIGGGHTS per seed")
    return runs, todo_s


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument('--preset', choices=PRESETS)
    g.add_argument('--cases', help='JSON case file')
    g.add_argument('--freeze-sable', metavar='DIR', help='copy build/sable to DIR/sable_<HEAD> with the commit '
                   'in DIR/sable_<HEAD>.commit (refused with uncommitted sources or a build older than them); '
                   'prints the path for --sable')
    p.add_argument('--out', default=os.path.join(REPO, 'build', 'drag_runs'))
    p.add_argument('-j', type=int, default=1, help='runs at once (default 1: wall times measured alone)')
    p.add_argument('--sable', default=runner.built('sable'))
    p.add_argument('--sable-commit', metavar='HASH', help='the commit the sable binary was built from (default: '
                   'the file BINARY.commit, else the HEAD of the checkout whose build folder holds it)')
    p.add_argument('--liggghts', default=shutil.which('liggghts') or 'liggghts')
    p.add_argument('--threads', type=int, default=1, help="sable's OpenMP threads per run (default 1)")
    p.add_argument('--only', nargs='+', metavar='CASE', help='only these cases')
    p.add_argument('--codes', default=None, help='only these codes (comma-separated)')
    p.add_argument('--store', action='store_true', help=f'keep the LIGGGHTS runs in {os.path.relpath(STORED, REPO)}')
    p.add_argument('--chunk', type=int, default=0, metavar='H',
                   help='run in pieces of H half-turns, each ended by a restart file (long runs: '
                        'a cut campaign goes on from the last finished piece); 0: whole runs')
    p.add_argument('--dry-run', action='store_true', help='print the plan and the time estimate only')
    args = p.parse_args()
    if args.freeze_sable:
        print(freeze_sable(args.freeze_sable))
        return
    exe = {'sable': os.path.abspath(args.sable), 'liggghts': args.liggghts}
    cases = load_cases(args)
    print(f'drag campaign: {len(cases)} cases into {args.out}')
    runs, todo_s = plan(cases, args.out)
    todo = [r for r in runs if not r[4]]
    print(f'{len(runs)} runs, {len(runs) - len(todo)} already done; estimated {todo_s / 60:.1f} min of one core '
          f'(sable {SPEED["sable"]:.2g}, LIGGGHTS {SPEED["liggghts"]:.2g} particle-steps/s), '
          f'{todo_s / 60 / max(1, min(args.j, len(todo) or 1)):.1f} min at -j {args.j}', flush=True)
    if args.dry_run:
        if any(r[1] == 'sable' for r in todo) and os.path.exists(exe['sable']):
            try:
                print('sable commit: %s (%s)' % sable_commit(exe['sable'], args.sable_commit))
            except SystemExit as e:
                print(f'the run would refuse to start: {e}')
        return
    h = harness(args.out)  # both exit, before anything is written, when a commit cannot be named
    print(f"harness: {h['deck']} at {h['commit'][:12]}" + (', with uncommitted changes: ' + '; '.join(h['changes'])
                                                          if h['dirty'] else ''))
    commit = (sable_commit(exe['sable'], args.sable_commit)
              if any(r[1] == 'sable' for r in todo) and os.path.exists(exe['sable']) else None)
    os.makedirs(args.out, exist_ok=True)
    for code in {r[1] for r in todo}:
        if not (os.path.exists(exe[code]) or shutil.which(exe[code])):
            print(f'{code}: {exe[code]} not found; using its stored runs ({os.path.relpath(STORED, REPO)})')
            missing = [r for r in todo if r[1] == code and not use_stored(r[0], code, r[2], r[3])]
            if missing:
                sys.exit(f'{code}: no stored run for ' + ', '.join(f'{r[0]["name"]} s{r[2]}' for r in missing))
            todo = [r for r in todo if r[1] != code]
    versions = {code: code_version(code, exe[code], commit) for code in sorted({r[1] for r in todo})}
    for code, v in versions.items():
        print(f'{code}: ' + ', '.join(f'{k} {x}' for k, x in v.items() if k != 'binary'))
    save_cases(args.out, cases)
    failed, lock, t0, count = [], threading.Lock(), time.monotonic(), [0]

    def job(r):
        c, code, seed, folder, _ = r
        rec = run_one(c, code, seed, folder, exe[code], args.threads, args.chunk, versions[code], args.out)
        with lock:
            count[0] += 1
            res = rec.get('result', {})
            head = f"[{count[0]}/{len(todo)} {(time.monotonic() - t0) / 60:.1f} min] {c['name']} {code} s{seed}"
            if rec['status'] == 'ok':
                print(f"{head}: F_first {res['F_first']:.4g} F_stat {res['F_stat']:.4g} +- {res['F_stat_err']:.2g}"
                      f", {rec['wall_s']:.0f} s wall", flush=True)
            else:
                failed.append(rec)
                print(f"{head}: FAILED (exit {rec['returncode']}) in {folder}:\n    " +
                      '\n    '.join(rec['error_tail']), flush=True)
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.j)) as pool:
        list(pool.map(job, todo))
    if args.store:
        store(runs)
    print(f'done: {len(todo) - len(failed)} ran, {len(failed)} failed, {len(runs) - len(todo)} skipped; '
          f'{(time.monotonic() - t0) / 60:.1f} min')
    sys.exit(1 if failed else 0)


if __name__ == '__main__':
    main()
