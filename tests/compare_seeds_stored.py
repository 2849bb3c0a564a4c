#!/usr/bin/python3
"""sable_tools/compare_seeds.py's stored references (--store, --ref *-stored) and
--tolerances, through compare.py's parse_header / deck_hashes / load_stored / store.

    PYTHONPATH=. /usr/bin/python3 tests/compare_seeds_stored.py SABLE    (from the repository root)

1. Round trip on a tiny seeded deck: the reference is stored from a live run (a
   stand-in `liggghts` on PATH that runs sable, so no LIGGGHTS is needed), then read
   back with --ref liggghts-stored: the same table, and the reference is not run.
2. Refusals, before anything runs: a copy of the deck with one command changed, other
   -var values, other seeds, no --results, a --prepare run; comments added are accepted.
   A deck edited while the reference runs is not stored.
3. --tolerances: a run directive in the file is refused; a line that decides no
   observable fails the comparison.
4. The committed cavity reference (reference_runs/reference/cavity/yade/): it loads
   for input_scripts/cavity/cavity.in with the main job's settings; a copy of the deck
   with one command changed, and -var Hd 9, are refused.
"""
import contextlib, io, json, os, shutil, stat, sys, tempfile

from sable_tools import compare, compare_seeds
from sable_tools.paths import REPO

TINY = '''#@ seeds seed 1 2 3
variable seed index 1
variable k index 1
variable a equal ${seed}*2*${k}
variable b equal v_a+0.5+v_k*${seed}^2
print "OBSERVABLE twice $(v_a)"
print "RESULT x=$(v_b) t=$(v_k)"
'''
TOL = '#@ tolerance twice abs 0\n#@ tolerance x sigma 3\n#@ unjudged t the input k\n'
failures = []


def check(cond, what):
    print(('ok   ' if cond else 'FAIL ') + what, flush=True)
    if not cond:
        failures.append(what)


def run(argv):
    """(exit code or message, stdout) of compare_seeds.main() with these arguments."""
    out = io.StringIO()
    sys.argv = ['compare_seeds.py'] + argv
    code = 0
    with contextlib.redirect_stdout(out):
        try:
            compare_seeds.main()
        except SystemExit as e:
            code = e.code
    return code, out.getvalue()


def main():
    sable = os.path.abspath(sys.argv[1])
    tmp = tempfile.mkdtemp(prefix='compare_seeds_stored.')
    real_stored = compare.STORED
    compare.STORED = os.path.join(tmp, 'reference')  # never the repository's references
    # a stand-in LIGGGHTS: sable reads the same deck the same way
    fake = os.path.join(tmp, 'bin', 'liggghts')
    os.makedirs(os.path.dirname(fake))
    open(fake, 'w').write(f'#!/bin/sh\nexec "{sable}" "$@"\n')
    os.chmod(fake, os.stat(fake).st_mode | stat.S_IXUSR)
    os.environ['PATH'] = os.path.dirname(fake) + os.pathsep + os.environ['PATH']
    deck = os.path.join(tmp, 'a', 'tiny.in')
    os.makedirs(os.path.dirname(deck))
    open(deck, 'w').write(TINY)
    tol = os.path.join(tmp, 'tiny.tol')
    open(tol, 'w').write(TOL)
    common = ['--sable', sable, '--results', '--tolerances', tol, '--var', 'k', '1']

    # 1. round trip
    rc, text = run([deck, '--ref', 'liggghts', '--store', '--out', os.path.join(tmp, 'live')] + common)
    path = os.path.join(compare.STORED, 'tiny', 'liggghts', 'results.json')
    check(rc == 0 and os.path.exists(path), f'live run with --store passes and writes {path} (exit {rc!r})')
    if rc != 0 or not os.path.exists(path):
        sys.exit(f'stopped: {text[-2000:]}')
    rec = json.load(open(path))
    check(rec['seeds'] == {'seed': ['1', '2', '3']} and rec['vars'] == {'k': '1'} and rec['results'] is True
          and rec['prepare'] == {} and rec['made_from']['commands_sha256'] == compare.deck_hashes(deck)['commands_sha256'],
          'the stored record names its seeds, -var values, --results, --prepare and the deck\'s sha256')
    check(rec['values']['x'] == [3.5, 8.5, 15.5] and abs(rec['std']['x'] - 6.027713773341708) < 1e-12,
          f'the stored per-seed values and sd: x = {rec["values"].get("x")}')
    rc, text = run([deck, '--ref', 'liggghts-stored', '--out', os.path.join(tmp, 'stored')] + common)
    live = json.load(open(os.path.join(tmp, 'live', 'tiny', 'seeds.json')))
    back = json.load(open(os.path.join(tmp, 'stored', 'tiny', 'seeds.json')))
    check(rc == 0 and 'LIGGGHTS (stored)' in text, f'--ref liggghts-stored passes (exit {rc!r})')
    check(back['rows'] == live['rows'] and back['values']['liggghts'] == live['values']['liggghts'],
          'the stored run gives the live run\'s table, row for row')
    check(not os.path.exists(os.path.join(tmp, 'stored', 'tiny', 'liggghts')), 'the stored reference was not run')

    # 2. refusals (nothing runs: no sable folder appears)
    def refused(argv, deck_, needle, what, ref='liggghts-stored'):
        out = os.path.join(tmp, 'refused')
        shutil.rmtree(out, ignore_errors=True)
        rc, text = run([deck_, '--ref', ref, '--out', out] + argv)
        check(isinstance(rc, str) and needle in rc and not os.path.exists(out),
              f'{what}: refused before anything runs ({str(rc)[:160]!r})')

    changed = os.path.join(tmp, 'b', 'tiny.in')
    os.makedirs(os.path.dirname(changed))
    open(changed, 'w').write(TINY.replace('variable a equal ${seed}*2*${k}', 'variable a equal ${seed}*3*${k}'))
    refused(common, changed, 'its commands differ', 'a copy of the deck with one command changed')
    refused(['--sable', sable, '--results', '--tolerances', tol, '--var', 'k', '2'], deck, 'was made with -var',
            'other -var values (k 2)')
    refused(['--sable', sable, '--results', '--tolerances', tol], deck, 'was made with -var', 'no -var k')
    refused(common + ['--seeds', '2'], deck, 'was made with seeds', 'other seeds (the first 2)')
    refused(['--sable', sable, '--tolerances', tol, '--var', 'k', '1'], deck, 'was made with results',
            'without --results')
    refused(common + ['--prepare', 'k', '1'], deck, 'was made with prepare', 'with a --prepare run')
    commented = os.path.join(tmp, 'c', 'tiny.in')
    os.makedirs(os.path.dirname(commented))
    open(commented, 'w').write('# a comment added\n' + TINY + '# and another\n')
    rc, text = run([commented, '--ref', 'liggghts-stored', '--out', os.path.join(tmp, 'commented')] + common)
    check(rc == 0 and 'deck file edited since, in comments' in text,
          f'a copy with comments added is still the reference (exit {rc!r})')
    rc, text = run([deck, '--ref', 'liggghts-stored', '--store', '--out', os.path.join(tmp, 'x')] + common)
    check(isinstance(rc, str) and '--store writes the reference from a run' in rc, '--store with a stored reference')

    # 3. --tolerances
    bad = os.path.join(tmp, 'bad.tol')
    open(bad, 'w').write(TOL + '#@ seeds seed 4 5\n')
    rc, text = run([deck, '--ref', 'liggghts-stored', '--out', os.path.join(tmp, 'bad')] + common[:-5]
                   + ['--tolerances', bad, '--var', 'k', '1'])
    check(isinstance(rc, str) and 'holds #@ tolerance and #@ unjudged lines only' in rc,
          f'a run directive in a tolerances file is refused ({str(rc)[:100]!r})')
    dead = os.path.join(tmp, 'dead.tol')
    open(dead, 'w').write(TOL + '#@ tolerance nosuch abs 0\n')
    rc, text = run([deck, '--ref', 'liggghts-stored', '--out', os.path.join(tmp, 'dead')] + common[:-5]
                   + ['--tolerances', dead, '--var', 'k', '1'])
    check(rc == 1 and 'dead.tol:4 `#@ tolerance nosuch` decides no observable' in text,
          f'a tolerances line that decides no observable fails the comparison (exit {rc!r})')

    # a deck edited while the reference runs is not stored (a stand-in that edits it)
    racing = os.path.join(tmp, 'd', 'tiny.in')
    os.makedirs(os.path.dirname(racing))
    open(racing, 'w').write(TINY)
    editor = os.path.join(tmp, 'bin2', 'liggghts')
    os.makedirs(os.path.dirname(editor))
    open(editor, 'w').write(f'#!/bin/sh\necho "variable z index 1" >> "{racing}"\nexec "{sable}" "$@"\n')
    os.chmod(editor, os.stat(editor).st_mode | stat.S_IXUSR)
    path_before = os.environ['PATH']
    os.environ['PATH'] = os.path.dirname(editor) + os.pathsep + path_before
    shutil.rmtree(os.path.join(compare.STORED, 'tiny'))
    rc, text = run([racing, '--ref', 'liggghts', '--store', '--out', os.path.join(tmp, 'racing')] + common)
    os.environ['PATH'] = path_before
    check(isinstance(rc, str) and 'changed while liggghts ran' in rc
          and not os.path.exists(os.path.join(compare.STORED, 'tiny')),
          f'a deck edited while the reference ran is not stored ({str(rc)[:120]!r})')

    # 4. the committed cavity reference
    compare.STORED = real_stored
    cavity = os.path.join(REPO, 'input_scripts', 'cavity', 'cavity.in')
    smoke = ['--sable', sable, '--prepare', 'phase', 'deposit', '--results', '--seed-var', 'seed', '--seed-values',
             '7', '8', '9', '--var', 'phase', 'shear', '--var', 'NU', '1', '--var', 'NP', '1', '--var', 'tshear', '0.3',
             '--var', 'trec', '0.1', '--var', 'fields', '0']
    made_with = {'seeds': {'seed': ['7', '8', '9']}, 'prepare': {'phase': 'deposit'}, 'results': True}
    smoke_vars = {'Hd': '8', 'phase': 'shear', 'NU': '1', 'NP': '1', 'tshear': '0.3', 'trec': '0.1', 'fields': '0'}
    try:
        rec, note = compare.load_stored(cavity, 'cavity', smoke_vars, 'yade', made_with)
        check(len(rec['values']['F_PLd']) == 3, f'the committed cavity YADE reference loads ({note})')
    except SystemExit as e:
        check(False, f'the committed cavity YADE reference loads: {e.code}')
    copy = os.path.join(tmp, 'cavity', 'cavity.in')
    os.makedirs(os.path.dirname(copy))
    text = open(cavity).read()
    assert 'variable        nblk index 10\n' in text
    open(copy, 'w').write(text.replace('variable        nblk index 10\n', 'variable        nblk index 11\n'))
    refused(['--var', 'Hd', '8'] + smoke, copy, 'its commands differ', 'cavity.in with nblk 11 (a copy)', 'yade-stored')
    refused(['--var', 'Hd', '9'] + smoke, cavity, 'was made with -var', 'cavity.in with -var Hd 9', 'yade-stored')

    shutil.rmtree(tmp, ignore_errors=True)
    print(f'{len(failures)} failed' if failures else 'all passed')
    sys.exit(1 if failures else 0)


if __name__ == '__main__':
    main()
