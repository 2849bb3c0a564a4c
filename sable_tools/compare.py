#!/usr/bin/python3
"""Run one deck unchanged in several DEM codes and compare what it declares.

    /usr/bin/python3 -m sable_tools.compare DECK [--codes sable,liggghts[,yade]]
        [--out DIR] [--var NAME VALUE ...] [--sable PATH] [--update-reference]

The conventions (OBSERVABLE lines, thermo series, #@ directives) and the
output layout are described in reference_runs/README.md. Exit status: 0 when
every judged observable passes, 1 otherwise: also when an observable has no
#@ tolerance or #@ unjudged line, when such a line decides no observable, and
(before anything runs) when a stored result was made from other deck commands.
"""
import argparse, datetime, fnmatch, hashlib, json, math, os, re, shutil, sys

import numpy as np

from sable_tools import runner, seedstats  # running the codes; statistics over seeds
from sable_tools.readers.ave_time import ave_time_file
from sable_tools.readers.dump import read_last_dump
from sable_tools.readers.screen import parse_screen  # OBSERVABLE lines and thermo tables
from sable_tools.paths import REPO

STORED = os.path.join(REPO, 'reference_runs', 'reference')


def show(path):
    """A path relative to the repository when inside it, else absolute."""
    path = os.path.abspath(path)
    return os.path.relpath(path, REPO) if path.startswith(REPO + os.sep) else path


# ---------------------------------------------------------------- deck header
def parse_header(deck, tolerances=None):
    """#@ tolerance PATTERN rel X | abs X | sigma K | offset D | none (keys combine),
    #@ unjudged PATTERN REASON..., #@ seeds VAR V1 V2 ..., #@ coordination NAME
    DUMPFILE, #@ avetime NAME FILE. Tolerance and unjudged lines form one list
    (h['rules']: pattern, spec or None, reason, 'file:line') in deck order, then
    those of the file tolerances (its #@ tolerance / #@ unjudged lines only:
    judgement kept next to a deck, e.g. for one comparison of it; later lines win)."""
    h = {'rules': [], 'seeds': None, 'coord': [], 'files': []}
    lines = [(deck, n, line) for n, line in enumerate(open(deck), 1)]
    if tolerances:
        lines += [(tolerances, n, line) for n, line in enumerate(open(tolerances), 1)]
    for path, n, line in lines:
        if not line.startswith('#@'):
            continue
        where, w = f'{os.path.basename(path)}:{n}', line[2:].split()
        if path == tolerances and w[:1] not in (['tolerance'], ['unjudged']):
            sys.exit(f'{path}:{n}: a tolerances file holds #@ tolerance and #@ unjudged lines only '
                     f'(what a run does belongs in the deck): {line.strip()}')
        if w[0] == 'tolerance' and len(w) >= 3:
            if w[2:] == ['none']:
                h['rules'].append((w[1], None, 'tolerance none', where))
                continue
            if len(w) % 2:
                sys.exit(f'{path}:{n}: tolerance PATTERN then KEY VALUE pairs (rel, abs, sigma, offset) or none')
            try:
                spec = dict(zip(w[2::2], map(float, w[3::2])))
            except ValueError:
                sys.exit(f'{path}:{n}: tolerance values must be numbers: {line.strip()}')
            if not set(spec) <= {'rel', 'abs', 'sigma', 'offset'} or set(spec) == {'offset'}:
                sys.exit(f'{path}:{n}: tolerance keys are rel, abs, sigma, offset (with rel or abs), or none')
            h['rules'].append((w[1], spec, None, where))
        elif w[0] == 'unjudged' and len(w) >= 3:
            h['rules'].append((w[1], None, ' '.join(w[2:]), where))
        elif w[0] == 'seeds' and len(w) >= 3:
            h['seeds'] = (w[1], w[2:])
        elif w[0] == 'coordination' and len(w) == 3:
            h['coord'].append((w[1], w[2]))
        elif w[0] == 'avetime' and len(w) == 3:
            h['files'].append((w[1], w[2]))
        else:
            sys.exit(f'{path}:{n}: unknown or incomplete directive (unjudged needs a reason): {line.strip()}')
    return h


def rule(h, name):
    """Index in h['rules'] of the last #@ tolerance / #@ unjudged line whose
    pattern matches name; None when no line does (an error: every observable
    is judged or explicitly left unjudged)."""
    found = None
    for k, (pat, _, _, _) in enumerate(h['rules']):
        if fnmatch.fnmatchcase(name, pat):
            found = k
    return found


def dead_rules(h, names):
    """The rules that decide no observable: their pattern matches none, or a
    later line overrides every match (e.g. *floor_3 where the names end in _mean)."""
    used = {rule(h, n) for n in names}
    return [r for k, r in enumerate(h['rules']) if k not in used]


# ---------------------------------------------------------------- output parsing
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
def deck_vars(code, deck, variables):
    # deckdir: the deck's folder, for files next to it (STL meshes): every code opens names from the run folder.
    out = ['-var', 'engine', code, '-var', 'deckdir', os.path.dirname(os.path.abspath(deck))]
    for k, v in variables.items():
        out += ['-var', k, v]
    return out


def run_yade(deck, rundir, variables, args):
    """sable --export-yade writes script.py from the deck; YADE runs it (one thread, no GUI)."""
    cmd = runner.export_yade(args.sable, os.path.abspath(deck), deck_vars('yade', deck, variables), 'script.py')
    print('[yade] ' + ' '.join(cmd) + f'   (in {show(rundir)})', flush=True)
    text, rc = runner.execute(cmd, rundir, args.timeout)
    if rc != 0:
        return 'sable --export-yade failed:\n' + text, rc
    cmd = runner.yade('script.py', shutil.which('yade'))
    print('[yade] ' + ' '.join(cmd), flush=True)
    return runner.execute(cmd, rundir, args.timeout, runner.one_thread())


def run_once(code, deck, rundir, variables, h, args):
    os.makedirs(rundir, exist_ok=True)
    if code == 'yade':
        text, rc = run_yade(deck, rundir, variables, args)
    else:
        cmd = runner.code_command(code, args.sable) + ['-in', os.path.abspath(deck), '-log', 'none'] + deck_vars(code, deck, variables)
        print(f'[{code}] ' + ' '.join(cmd) + f'   (in {show(rundir)})', flush=True)
        text, rc = runner.execute(cmd, rundir, args.timeout)
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
    # seed means and sds (seedstats.summary); a seed without the observable leaves both nan
    seeds_stat = {n: seedstats.summary(v) for n, v in values.items()}
    full = {n: s.n == len(values[n]) for n, s in seeds_stat.items()}
    rec['observables'] = {n: s.mean if full[n] else math.nan for n, s in seeds_stat.items()}
    if len(results) > 1:
        rec['std'] = {n: s.sd if full[n] else math.nan for n, s in seeds_stat.items()}
        rec['values'] = values
    rec['series'] = results[0][1]
    rec['errors'] = [r[2] for r in results if r[2]]
    rec['log_tail'] = results[0][3]
    with open(os.path.join(outdir, 'results.json'), 'w') as f:
        json.dump(rec, f, indent=1, allow_nan=True)
    return rec


PACKAGE = {'liggghts': 'liggghts', 'yade': 'yade'}


def sha256(data):
    return hashlib.sha256(data).hexdigest()


# #@ directives that change what is run or read; the others (tolerance,
# unjudged) and plain comments only change how results are judged or explained.
RUN_DIRECTIVES = ('#@ seeds', '#@ coordination', '#@ avetime')


def deck_hashes(deck):
    """What a stored reference was made from: sha256 of the deck file, of its
    commands (the deck without comment lines other than RUN_DIRECTIVES), and
    of each file next to it that it names (STL meshes, data files)."""
    folder, raw = os.path.dirname(os.path.abspath(deck)), open(deck, 'rb').read()
    text = raw.decode(errors='replace')
    commands = '\n'.join(l.rstrip() for l in text.splitlines()
                         if not l.lstrip().startswith('#') or l.startswith(RUN_DIRECTIVES))
    files = {}
    for f in sorted(os.listdir(folder)):
        p = os.path.join(folder, f)
        if f != os.path.basename(deck) and not f.endswith('.in') and os.path.isfile(p) \
                and re.search(r'(?<![\w.-])' + re.escape(f) + r'(?![\w.-])', commands):
            files[f] = sha256(open(p, 'rb').read())
    return {'deck': os.path.basename(deck), 'deck_sha256': sha256(raw),
            'commands_sha256': sha256(commands.encode()), 'files_sha256': files}


# What a stored record was run with, besides the deck: a record that lacks a key was
# made with its default here (compare.py runs no --prepare and reads no RESULT lines).
MADE_WITH = {'vars': {}, 'prepare': {}, 'results': False}


def load_stored(deck, deckname, variables, code='liggghts', made_with=None):
    """The stored results of code for this deck; refused when they were made
    from other commands or files (a stored result of another deck is not a
    reference), or with other -var values or other settings made_with names
    (compare_seeds.py: seeds, prepare, results; a record made after a
    --prepare run is never one for a run without it). Returns (record, note)."""
    path = os.path.join(STORED, deckname, code, 'results.json')
    redo = (f'run {code} on it and store it (compare.py --update-reference, compare_seeds.py --store; '
            f'apt-get install {PACKAGE[code]})')
    if not os.path.exists(path):
        sys.exit(f'no stored {code} reference for {deckname} ({show(path)}); {redo}')
    rec = json.load(open(path))
    for key, want in {**MADE_WITH, 'vars': variables, **(made_with or {})}.items():
        had = rec.get(key, MADE_WITH.get(key))
        if had != want:
            what = '-var' if key == 'vars' else key
            sys.exit(f'the stored reference {show(path)} was made with {what} {had}, '
                     f'not {want}; run {code} itself for other values')
    stored, now = rec.get('made_from'), deck_hashes(deck)
    if stored is None:
        sys.exit(f'the stored reference {show(path)} records no sha256 of the deck it came from, so nothing '
                 f'says it is a reference for {show(deck)}; {redo}')
    changed = (['its commands'] if stored.get('commands_sha256') != now['commands_sha256'] else []) + \
        sorted(f for f in set(stored.get('files_sha256', {})) | set(now['files_sha256'])
               if stored.get('files_sha256', {}).get(f) != now['files_sha256'].get(f))
    if changed:
        sys.exit(f'the stored reference {show(path)} was made from another deck: {", ".join(changed)} differ '
                 f'by sha256 from {show(deck)} today (deck file {stored.get("deck_sha256", "?")[:12]} then, '
                 f'{now["deck_sha256"][:12]} now); it is not a reference for this deck; {redo}')
    note = ('same deck file (sha256 ' + now['deck_sha256'][:12] + ')' if stored.get('deck_sha256') == now['deck_sha256']
            else 'deck file edited since, in comments or #@ tolerance/unjudged lines only (its commands\' sha256 '
                 + now['commands_sha256'][:12] + ' is the stored one)')
    rec['code'] = code + '-stored'
    return rec, note


def store(rec, deck, deckname, code='liggghts', before=None):
    """Write rec as the stored reference; before: deck_hashes(deck) taken before the
    runs, which must still hold (a deck edited while it ran is not what was run)."""
    made_from = deck_hashes(deck)
    if before is not None and before != made_from:
        sys.exit(f'{show(deck)} (or a file it names) changed while {code} ran: reference not stored; rerun')
    d = os.path.join(STORED, deckname, code)
    os.makedirs(d, exist_ok=True)
    rec_tail = rec['log_tail']
    rec = {k: v for k, v in rec.items() if k != 'log_tail'}
    rec['made_from'] = made_from
    with open(os.path.join(d, 'results.json'), 'w') as f:
        json.dump(rec, f, indent=1, allow_nan=True)
    open(os.path.join(d, 'log_tail.txt'), 'w').write(rec_tail + '\n')
    print(f'stored the {code} reference in {show(d)}')


# ---------------------------------------------------------------- comparison
def fmt(v):
    return '—' if v is None or (isinstance(v, float) and math.isnan(v)) else f'{v:.10g}'


def judge(h, name, val, ref):
    """(difference, |difference - offset|, allowed, tolerance text, verdict) of code value vs reference record."""
    k = rule(h, name)
    r = ref['observables'].get(name)
    missing = val is None or r is None or math.isnan(val) or math.isnan(r)
    if k is None:
        return (None if missing else val - r, None, None, 'no #@ tolerance or #@ unjudged line matches', 'FAIL (no tolerance)')
    spec, reason = h['rules'][k][1], h['rules'][k][2]
    if spec is None:
        return (None if missing else val - r, None, None, f'unjudged: {reason}', 'unjudged')
    if missing:
        return (None, None, None, '', 'FAIL (missing)')
    # offset: a known, signed difference value - reference (e.g. YADE's velocity half a step behind)
    allowed, text, off = spec.get('abs', 0.0), [], spec.get('offset', 0.0)
    if 'rel' in spec:
        allowed += spec['rel'] * abs(r)
        text.append(f'rel {spec["rel"]:g}')
    if 'sigma' in spec:
        std = ref.get('std', {}).get(name)
        if std is None:
            return (val - r, None, None, f'{spec["sigma"]:g} sigma', 'FAIL (reference has one run, no sigma)')
        allowed += spec['sigma'] * std
        text.append(f'{spec["sigma"]:g} x std {std:.3g}')
    if 'abs' in spec:
        text.append(f'abs {spec["abs"]:g}')
    text = ' + '.join(text) + f' = {allowed:.3g}'
    if 'offset' in spec:
        text = f'offset {off:g} ± ({text}); gap - offset {val - r - off:.3g}'
    return (val - r, abs(val - r - off), allowed, text, 'pass' if abs(val - r - off) <= allowed else 'FAIL')


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
    for pat, spec, reason, n in dead_rules(h, names):
        kind = 'unjudged' if spec is None else 'tolerance'
        lines.append(f'- **FAIL: {n} `#@ {kind} {pat}` decides no observable** '
                     '(its pattern matches none, or later lines override every match)')
        failed = True
    if any(rule(h, n) is None for n in names):
        lines.append('- **FAIL: observables with no #@ tolerance or #@ unjudged line** (below)')
    lines.append('')
    for rec in recs[:-1]:
        lines += [f'| observable | {rec["code"]} | {ref["code"]} | difference | rel. difference | tolerance | result |',
                  '|---|---|---|---|---|---|---|']
        for n in names:
            val, r = rec['observables'].get(n), ref['observables'].get(n)
            diff, excess, allowed, text, verdict = judge(h, n, val, ref)
            rshow = fmt(r) + (f' ± {ref["std"][n]:.3g}' if n in ref.get('std', {}) else '')
            rel = fmt(diff / abs(r)) if diff is not None and r else '—'
            lines.append(f'| {n} | {fmt(val)} | {rshow} | {fmt(diff)} | {rel} | {text} | {verdict} |')
            failed |= verdict.startswith('FAIL')
            # unjudged rows show the gap but never count, and stay out of the ratio plot
            if allowed:
                ratios.setdefault(rec['code'], {})[n] = excess / allowed
        lines.append('')
    for rec in recs:
        for e in rec.get('errors', []):
            lines.append(f'- **{rec["code"]} run failed**: `{e}`')
            failed = True
    judged = sum(1 for n in names if rule(h, n) is not None and h['rules'][rule(h, n)][1] is not None)
    unjudged = sum(1 for n in names if rule(h, n) is not None and h['rules'][rule(h, n)][1] is None)
    lines.append(f'\n{judged} observables judged, {unjudged} shown unjudged (not counted)')
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
    p.add_argument('--sable', default=runner.built('sable'), help='sable binary')
    p.add_argument('--timeout', type=float, default=1800, help='seconds per run')
    p.add_argument('--update-reference', action='store_true',
                   help='store the LIGGGHTS and YADE results under reference_runs/reference/')
    args = p.parse_args()
    args.sable = os.path.abspath(args.sable)
    deck = args.deck
    deckname = os.path.splitext(os.path.basename(deck))[0]
    h = parse_header(deck)
    hashes = deck_hashes(deck)  # what runs now, for --update-reference
    variables = dict(args.var)
    outdir = os.path.join(args.out, deckname)
    notes, recs, codes = [], [], []
    for code in args.codes.split(','):
        if code in PACKAGE and not shutil.which(code):
            print(f'{code} is not on PATH: install it with `apt-get install {PACKAGE[code]}` (Debian/Ubuntu); '
                  'using the stored reference results instead', flush=True)
            code += '-stored'
        codes.append(code)
    # stored results first: one made from another deck stops the comparison before anything runs
    stored = {c: load_stored(deck, deckname, variables, c[:-7]) for c in codes if c.endswith('-stored') and c[:-7] in PACKAGE}
    for code in codes:
        if code in stored:
            rec, note = stored[code]
            recs.append(rec)
            notes.append(f'{code}: results stored in reference_runs/reference/{deckname}/{code[:-7]}/ '
                         f'({code[:-7]} run of {rec.get("date", "?")}; {note}), not run now')
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
            store(recs[-1], deck, deckname, code, hashes)
    if len(recs) < 2:  # one code: just ran it (e.g. to store a reference)
        sys.exit(1 if recs[0]['errors'] else 0)
    sys.exit(1 if report(deck, h, recs, outdir, notes) else 0)


if __name__ == '__main__':
    main()
