#!/usr/bin/python3
"""Run one deck unchanged in several DEM codes and compare what it declares.

    /usr/bin/python3 reference_runs/compare.py DECK [--codes sable,liggghts[,yade]]
        [--out DIR] [--var NAME VALUE ...] [--sable PATH] [--update-reference]

The conventions (OBSERVABLE lines, thermo series, #@ directives) and the
output layout are described in reference_runs/README.md. Exit status: 0 when
every judged observable passes, 1 otherwise.
"""
import argparse, datetime, fnmatch, json, math, os, shutil, subprocess, sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
STORED = os.path.join(HERE, 'reference')


def show(path):
    """A path relative to the repository when inside it, else absolute."""
    path = os.path.abspath(path)
    return os.path.relpath(path, REPO) if path.startswith(REPO + os.sep) else path


# ---------------------------------------------------------------- deck header
def parse_header(deck):
    """#@ tolerance PATTERN rel X | abs X | sigma K | none (keys combine),
    #@ seeds VAR V1 V2 ..., #@ coordination NAME DUMPFILE, #@ avetime NAME FILE."""
    h = {'tol': [], 'seeds': None, 'coord': [], 'files': []}
    for n, line in enumerate(open(deck), 1):
        if not line.startswith('#@'):
            continue
        w = line[2:].split()
        if w[0] == 'tolerance' and len(w) >= 3:
            spec = {} if w[2:] == ['none'] else dict(zip(w[2::2], map(float, w[3::2])))
            if not set(spec) <= {'rel', 'abs', 'sigma'}:
                sys.exit(f'{deck}:{n}: tolerance keys are rel, abs, sigma (or none)')
            h['tol'].append((w[1], spec))
        elif w[0] == 'seeds' and len(w) >= 3:
            h['seeds'] = (w[1], w[2:])
        elif w[0] == 'coordination' and len(w) == 3:
            h['coord'].append((w[1], w[2]))
        elif w[0] == 'avetime' and len(w) == 3:
            h['files'].append((w[1], w[2]))
        else:
            sys.exit(f'{deck}:{n}: unknown or incomplete directive: {line.strip()}')
    return h


def tolerance(h, name):
    """The last #@ tolerance line whose pattern matches name; None = not judged."""
    spec = None
    for pat, s in h['tol']:
        if fnmatch.fnmatchcase(name, pat):
            spec = s
    return spec or None


# ---------------------------------------------------------------- output parsing
def to_float(s):
    try:
        return float(s)
    except ValueError:
        return None


def parse_screen(text):
    """OBSERVABLE name value lines, and every thermo table (header starting
    with Step) as series keyed by lower-case column name, v_/c_/f_ dropped."""
    obs, series, header = {}, {}, None
    for line in text.splitlines():
        w = line.split()
        if len(w) == 3 and w[0] == 'OBSERVABLE':
            v = to_float(w[2])
            obs[w[1]] = v if v is not None else math.nan
        elif w and w[0].lower() == 'step' and len(w) > 1:
            header = [(c[2:] if c[:2] in ('v_', 'c_', 'f_') else c).lower() for c in w[1:]]
        elif line.startswith('Loop time'):
            header = None
        elif header and len(w) == len(header) + 1 and all(to_float(x) is not None for x in w):
            step = float(w[0])
            for c, v in zip(header, w[1:]):
                if abs(float(v)) < 1e19:  # LAMMPS' +-1e20 = empty group
                    series.setdefault(c, {})[step] = float(v)
    return obs, {c: [sorted(s), [s[k] for k in sorted(s)]] for c, s in series.items()}


def read_last_dump(path):
    """Last snapshot of a LIGGGHTS/LAMMPS text dump: columns, box, periodic flags."""
    lines = open(path).read().split('\n')
    i = max(k for k, l in enumerate(lines) if l.startswith('ITEM: TIMESTEP'))
    n = int(lines[i + 3])
    periodic = [f.startswith('p') for f in lines[i + 4].split()[3:6]]
    box = np.array([[float(v) for v in lines[i + 5 + d].split()[:2]] for d in range(3)])
    cols = lines[i + 8].split()[2:]
    data = np.array([[float(v) for v in l.split()] for l in lines[i + 9:i + 9 + n]]).reshape(n, len(cols))
    return {c: data[:, k] for k, c in enumerate(cols)}, box, periodic


def ave_time_file(path, name):
    """A fix ave/time text file (mode scalar) as observables NAME_rows,
    NAME_first_step, NAME_last_step and per column NAME_COL (last row) and
    NAME_COL_mean (mean over rows), COL the header word without v_/c_/f_ and
    [I] as _I; and its columns as series NAME_COL."""
    lines = open(path).read().splitlines()
    cols = [c[2:] if c[:2] in ('v_', 'c_', 'f_') else c for c in lines[1].split()[2:]]
    cols = [c.replace('[', '_').replace(']', '') for c in cols]
    rows = np.array([[float(x) for x in l.split()] for l in lines[2:] if l.strip()]).reshape(-1, len(cols) + 1)
    obs = {f'{name}_rows': float(len(rows))}
    if len(rows):
        obs.update({f'{name}_first_step': rows[0, 0], f'{name}_last_step': rows[-1, 0]})
    series = {}
    for j, c in enumerate(cols, 1):
        if len(rows):
            obs.update({f'{name}_{c}': float(rows[-1, j]), f'{name}_{c}_mean': float(rows[:, j].mean())})
        series[f'{name}_{c}'] = [rows[:, 0].tolist(), rows[:, j].tolist()]
    return obs, series


def coordination(path):
    """Mean number of grain-grain contacts (distance <= r_i + r_j, nearest
    periodic image), as LIGGGHTS' compute contact/atom + compute reduce ave."""
    a, box, periodic = read_last_dump(path)
    x = np.stack([a['x'], a['y'], a['z']], 1)
    r = a['radius'] if 'radius' in a else 0.5 * a['diameter']
    length = box[:, 1] - box[:, 0]
    count = np.zeros(len(r))
    for i in range(len(r) - 1):
        d = x[i + 1:] - x[i]
        for k in range(3):
            if periodic[k]:
                d[:, k] -= length[k] * np.round(d[:, k] / length[k])
        touch = (d * d).sum(1) <= (r[i] + r[i + 1:]) ** 2
        count[i] += touch.sum()
        count[i + 1:] += touch
    return float(count.mean()) if len(r) else math.nan


# ---------------------------------------------------------------- running codes
def command(code, args):
    if code == 'sable':
        return [args.sable]
    exe = shutil.which('liggghts')
    return (['stdbuf', '-o0', '-e0'] if shutil.which('stdbuf') else []) + [exe]


def execute(cmd, rundir, args, env=None):
    """(screen text, exit status) of one command run in rundir."""
    try:
        p = subprocess.run(cmd, cwd=rundir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           text=True, errors='replace', timeout=args.timeout, env=env)
        return p.stdout, p.returncode
    except subprocess.TimeoutExpired as e:
        out = e.stdout.decode(errors='replace') if isinstance(e.stdout, bytes) else e.stdout or ''
        return out + f'\n(timed out after {args.timeout} s)', -1
    except OSError as e:
        return str(e), -1


def deck_vars(code, deck, variables):
    # deckdir: the deck's folder, for files next to it (STL meshes): every code opens names from the run folder.
    out = ['-var', 'engine', code, '-var', 'deckdir', os.path.dirname(os.path.abspath(deck))]
    for k, v in variables.items():
        out += ['-var', k, v]
    return out


def run_yade(deck, rundir, variables, args):
    """sable --export-yade writes script.py from the deck; YADE runs it (one thread, no GUI)."""
    cmd = [args.sable, '--export-yade', os.path.abspath(deck)] + deck_vars('yade', deck, variables) + ['-o', 'script.py']
    print('[yade] ' + ' '.join(cmd) + f'   (in {show(rundir)})', flush=True)
    text, rc = execute(cmd, rundir, args)
    if rc != 0:
        return 'sable --export-yade failed:\n' + text, rc
    cmd = [shutil.which('yade'), '-j1', '-n', '-x', 'script.py']
    print('[yade] ' + ' '.join(cmd), flush=True)
    env = {**os.environ, 'OMP_NUM_THREADS': '1'}
    return execute(cmd, rundir, args, env)


def run_once(code, deck, rundir, variables, h, args):
    os.makedirs(rundir, exist_ok=True)
    if code == 'yade':
        text, rc = run_yade(deck, rundir, variables, args)
    else:
        cmd = command(code, args) + ['-in', os.path.abspath(deck), '-log', 'none'] + deck_vars(code, deck, variables)
        print(f'[{code}] ' + ' '.join(cmd) + f'   (in {show(rundir)})', flush=True)
        text, rc = execute(cmd, rundir, args)
    open(os.path.join(rundir, 'screen.txt'), 'w').write(text)
    obs, series = parse_screen(text)
    for name, dump in h['coord']:
        path = os.path.join(rundir, dump)
        obs[name] = coordination(path) if rc == 0 and os.path.exists(path) else math.nan
    for name, f in h['files']:
        path = os.path.join(rundir, f)
        if rc == 0 and os.path.exists(path):
            o, s = ave_time_file(path, name)
            obs.update(o)
            series.update(s)
        else:
            obs[name + '_rows'] = math.nan
    error = None if rc == 0 else f'exit status {rc}: ' + ' | '.join(text.strip().splitlines()[-3:])
    return obs, series, error, '\n'.join(text.splitlines()[-40:])


def run_code(code, deck, outdir, variables, h, args):
    """Run the deck (once per seed for a LIGGGHTS reference, when it declares
    seeds) and return the result record (mean, std over seeds)."""
    rec = {'code': code, 'deck': os.path.basename(deck), 'vars': variables,
           'date': datetime.date.today().isoformat(), 'errors': []}
    seeds = h['seeds'] if h['seeds'] and h['seeds'][0] not in variables else None
    if seeds and code == 'liggghts':
        runs = [(os.path.join(outdir, f'{seeds[0]}_{s}'), {**variables, seeds[0]: s}) for s in seeds[1]]
    else:
        runs = [(outdir, {**variables, seeds[0]: seeds[1][0]} if seeds else variables)]
    results = [run_once(code, deck, d, v, h, args) for d, v in runs]
    if seeds:
        rec['seeds'] = {seeds[0]: [v[seeds[0]] for _, v in runs]}
    names = list(dict.fromkeys(n for r in results for n in r[0]))
    values = {n: [r[0].get(n, math.nan) for r in results] for n in names}
    rec['observables'] = {n: float(np.mean(v)) for n, v in values.items()}
    if len(results) > 1:
        rec['std'] = {n: float(np.std(v, ddof=1)) for n, v in values.items()}
        rec['values'] = values
    rec['series'] = results[0][1]
    rec['errors'] = [r[2] for r in results if r[2]]
    rec['log_tail'] = results[0][3]
    with open(os.path.join(outdir, 'results.json'), 'w') as f:
        json.dump(rec, f, indent=1, allow_nan=True)
    return rec


PACKAGE = {'liggghts': 'liggghts', 'yade': 'yade'}


def load_stored(deckname, variables, code='liggghts'):
    path = os.path.join(STORED, deckname, code, 'results.json')
    if not os.path.exists(path):
        sys.exit(f'no stored {code} reference for {deckname} ({show(path)}); '
                 f'install it (apt-get install {PACKAGE[code]}) and rerun with --update-reference')
    rec = json.load(open(path))
    if rec.get('vars', {}) != variables:
        sys.exit(f'the stored reference {show(path)} was made with -var {rec.get("vars")}, '
                 f'not {variables}; run {code} itself for other values')
    rec['code'] = code + '-stored'
    return rec


def store(rec, deckname, code='liggghts'):
    d = os.path.join(STORED, deckname, code)
    os.makedirs(d, exist_ok=True)
    rec_tail = rec['log_tail']
    rec = {k: v for k, v in rec.items() if k != 'log_tail'}
    with open(os.path.join(d, 'results.json'), 'w') as f:
        json.dump(rec, f, indent=1, allow_nan=True)
    open(os.path.join(d, 'log_tail.txt'), 'w').write(rec_tail + '\n')
    print(f'stored the {code} reference in {show(d)}')


# ---------------------------------------------------------------- comparison
def fmt(v):
    return '—' if v is None or (isinstance(v, float) and math.isnan(v)) else f'{v:.10g}'


def judge(h, name, val, ref):
    """(difference, allowed, tolerance text, verdict) of code value vs reference record."""
    spec = tolerance(h, name)
    r = ref['observables'].get(name)
    if spec is None:
        return (None, None, 'none', 'info')
    if val is None or r is None or math.isnan(val) or math.isnan(r):
        return (None, None, '', 'FAIL (missing)')
    allowed, text = spec.get('abs', 0.0), []
    if 'rel' in spec:
        allowed += spec['rel'] * abs(r)
        text.append(f'rel {spec["rel"]:g}')
    if 'sigma' in spec:
        std = ref.get('std', {}).get(name)
        if std is None:
            return (val - r, None, f'{spec["sigma"]:g} sigma', 'FAIL (reference has one run, no sigma)')
        allowed += spec['sigma'] * std
        text.append(f'{spec["sigma"]:g} x std {std:.3g}')
    if 'abs' in spec:
        text.append(f'abs {spec["abs"]:g}')
    text = ' + '.join(text) + f' = {allowed:.3g}'
    return (val - r, allowed, text, 'pass' if abs(val - r) <= allowed else 'FAIL')


def report(deck, h, recs, outdir, notes):
    ref = recs[-1]
    names = list(dict.fromkeys(n for r in [ref] + recs[:-1] for n in r['observables']))
    lines = [f'# {os.path.basename(deck)}: {", ".join(r["code"] for r in recs)}', '']
    lines += [f'- {n}' for n in notes]
    if ref.get('std'):
        seeds = '; '.join(k + ' = ' + ' '.join(v) for k, v in ref.get('seeds', {}).items())
        nruns = len(next(iter(ref['values'].values())))
        lines.append(f'- reference {ref["code"]}: mean ± standard deviation over {nruns} runs ({seeds}); '
                     'the other codes ran once; a "sigma" tolerance allows K standard deviations')
    lines.append('')
    failed, ratios = False, {}
    for rec in recs[:-1]:
        lines += [f'| observable | {rec["code"]} | {ref["code"]} | difference | rel. difference | tolerance | result |',
                  '|---|---|---|---|---|---|---|']
        for n in names:
            val, r = rec['observables'].get(n), ref['observables'].get(n)
            diff, allowed, text, verdict = judge(h, n, val, ref)
            rshow = fmt(r) + (f' ± {ref["std"][n]:.3g}' if n in ref.get('std', {}) else '')
            rel = fmt(diff / abs(r)) if diff is not None and r else '—'
            lines.append(f'| {n} | {fmt(val)} | {rshow} | {fmt(diff)} | {rel} | {text} | {verdict} |')
            failed |= verdict.startswith('FAIL')
            if allowed:
                ratios.setdefault(rec['code'], {})[n] = abs(diff) / allowed
        lines.append('')
    for rec in recs:
        for e in rec.get('errors', []):
            lines.append(f'- **{rec["code"]} run failed**: `{e}`')
            failed = True
    lines.append(f'\n**{"FAIL" if failed else "PASS"}**')
    os.makedirs(outdir, exist_ok=True)
    open(os.path.join(outdir, 'comparison.md'), 'w').write('\n'.join(lines) + '\n')
    figure(deck, recs, ratios, os.path.join(outdir, 'comparison.png'))
    print('\n'.join(lines))
    print(f'\nwrote {show(os.path.join(outdir, "comparison.md"))} and comparison.png')
    return failed


def figure(deck, recs, ratios, path):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    names = list(dict.fromkeys(n for r in recs for n in r.get('series', {})))
    npan = len(names) + (1 if ratios else 0)
    if not npan:
        return
    ncol = min(3, npan)
    nrow = -(-npan // ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.5 * ncol, 3.2 * nrow), squeeze=False)
    axes = axes.ravel()
    styles = ['-', '--', ':', '-.']
    for ax, n in zip(axes, names):
        for k, r in enumerate(recs):
            if n in r.get('series', {}):
                x, y = r['series'][n]
                ax.plot(x, y, styles[k % 4], label=r['code'])
        ax.set_title(n, fontsize=9)
        ax.set_xlabel('step', fontsize=8)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=7)
    if ratios:
        ax = axes[len(names)]
        for k, (code, rat) in enumerate(ratios.items()):
            ax.bar(np.arange(len(rat)) + 0.8 * k / len(ratios), list(rat.values()), 0.8 / len(ratios), label=code)
        ax.axhline(1.0, color='r', lw=0.8)
        ax.set_xticks(range(len(rat)))
        ax.set_xticklabels(list(rat), rotation=90, fontsize=5 if len(rat) > 20 else 7)
        ax.set_yscale('symlog', linthresh=1e-3)
        ax.set_title('|difference| / tolerance (fail above 1)', fontsize=9)
        ax.legend(fontsize=7)
    for ax in axes[npan:]:
        ax.axis('off')
    fig.suptitle(os.path.basename(deck))
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---------------------------------------------------------------- main
def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('deck')
    p.add_argument('--codes', default='sable,liggghts',
                   help='comma-separated: sable, liggghts, liggghts-stored, yade, yade-stored; the last is the reference')
    p.add_argument('--out', default=os.path.join(REPO, 'build-compare'), help='output folder')
    p.add_argument('--var', nargs=2, action='append', default=[], metavar=('NAME', 'VALUE'))
    p.add_argument('--sable', default=os.path.join(REPO, 'build', 'sable'), help='sable binary')
    p.add_argument('--timeout', type=float, default=1800, help='seconds per run')
    p.add_argument('--update-reference', action='store_true',
                   help='store the LIGGGHTS and YADE results under reference_runs/reference/')
    args = p.parse_args()
    args.sable = os.path.abspath(args.sable)
    deck = args.deck
    deckname = os.path.splitext(os.path.basename(deck))[0]
    h = parse_header(deck)
    variables = dict(args.var)
    outdir = os.path.join(args.out, deckname)
    notes, recs = [], []
    for code in args.codes.split(','):
        if code in PACKAGE and not shutil.which(code):
            print(f'{code} is not on PATH: install it with `apt-get install {PACKAGE[code]}` (Debian/Ubuntu); '
                  'using the stored reference results instead', flush=True)
            code += '-stored'
        if code.endswith('-stored') and code[:-7] in PACKAGE:
            recs.append(load_stored(deckname, variables, code[:-7]))
            notes.append(f'{code}: results stored in reference_runs/reference/{deckname}/{code[:-7]}/ '
                         f'({code[:-7]} run of {recs[-1].get("date", "?")}), not run now')
            continue
        if code not in ('sable', 'liggghts', 'yade'):
            sys.exit(f'unknown code {code}: use sable, liggghts, liggghts-stored, yade or yade-stored')
        if code in ('sable', 'yade') and not os.access(args.sable, os.X_OK):
            sys.exit(f'no sable binary at {args.sable}: build it (cmake) or pass --sable PATH')
        recs.append(run_code(code, deck, os.path.join(outdir, code), variables, h, args))
        exe = args.sable if code == 'sable' else shutil.which(code)
        notes.append(f'{code}: ran `{exe}` now (output in {show(os.path.join(outdir, code))})'
                     + (' on the script written by sable --export-yade' if code == 'yade' else ''))
        if code in PACKAGE and args.update_reference:
            if recs[-1]['errors']:
                sys.exit(f'{code} failed, reference not stored: ' + '; '.join(recs[-1]['errors']))
            store(recs[-1], deckname, code)
    if len(recs) < 2:  # one code: just ran it (e.g. to store a reference)
        sys.exit(1 if recs[0]['errors'] else 0)
    sys.exit(1 if report(deck, h, recs, outdir, notes) else 0)


if __name__ == '__main__':
    main()
