#!/usr/bin/python3
"""Which contact laws the repository's decks select, against the compiled ones.

Finds every `pair_style gran model ...` and `fix ... wall/gran model ...`
selection in the decks (tests/decks, input_scripts, reference_runs; LIGGGHTS'
tutorials where liggghts-doc is installed) and in the tests' sources (deck
text in C++ strings, Python and shell scripts), resolves `${var}` from the
deck's own `variable var index|string ...` lines, and checks that each law of
built-in models is a line of contact_models/compiled_laws.txt: a law missing
there still runs, on the slower runtime-composed path, so a deck would be
slower without failing. Selections built in code (loops over models) are not
literal and are not seen: the unit tests that sweep models run composed.

    tests/compiled_laws.py [--root DIR]          check (exit 1: a deck's law is not compiled)
    tests/compiled_laws.py --list [--root DIR]   every law found, with the files that select it
"""
import argparse
import glob
import os
import re
import sys

AXES = ['normal', 'damping', 'tangential', 'rolling', 'cohesion']
KEYWORD = {'damping': 1, 'tangential': 2, 'rolling_friction': 3, 'cohesion': 4}
DEFAULT = ['', 'liggghts', 'off', 'off', 'off']  # LIGGGHTS' defaults (registry.h ModelSelection)
TUTORIALS = '/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public'  # as sable_tools/tutorials/run.py
SELECTION = re.compile(r'(?:pair_style\s+gran|wall/gran)\s+model\s+(.*)')
WORD = re.compile(r'[^\s"\'`(),;\\]+')


def model_names(root):
    """Names of the built-in models per axis (kName strings of contact_models/<axis>/*.h)."""
    names = []
    for axis in AXES:
        found = set()
        for h in glob.glob(os.path.join(root, 'contact_models', axis, '*.h')):
            found |= set(re.findall(r'kName\s*=\s*"([^"]+)"', open(h).read()))
        names.append(found)
    return names


def deck_lines(text, is_deck):
    """Lines of a file; in a deck, `&` continuations joined and comments dropped."""
    if not is_deck:
        return text.splitlines()
    out, cur = [], ''
    for line in text.splitlines():
        line = re.sub(r'(^|\s)#(?=(?:[^"]*"[^"]*")*[^"]*$).*', '', line)  # a # outside quotes
        if line.rstrip().endswith('&'):
            cur += line.rstrip()[:-1] + ' '
            continue
        out.append(cur + line)
        cur = ''
    return out + [cur]


def variables(lines):
    """variable NAME index|string|loop? V1 V2 ...: the values each name can take."""
    vals = {}
    for line in lines:
        w = line.split()
        if len(w) >= 4 and w[0] == 'variable' and w[2] in ('index', 'string'):
            vals[w[1]] = [v.strip('"\'') for v in w[3:]]
    return vals


def expand(word, vals):
    """A word with ${var} / $v replaced by each value; None if unresolved."""
    m = re.search(r'\$\{(\w+)\}|\$(\w)', word)
    if not m:
        return [word]
    name = m.group(1) or m.group(2)
    if name not in vals:
        return None
    out = []
    for v in vals[name]:
        rest = expand(word[:m.start()] + v + word[m.end():], vals)
        if rest is None:
            return None
        out += rest
    return out


def selections(words, vals):
    """The laws a selection's words name (several if a variable has several values); [] if incomplete."""
    if not words:
        return []
    laws = [[None] + DEFAULT[1:]]
    i, at = 1, [(0, words[0])]
    while i + 1 < len(words) and (words[i] in KEYWORD or words[i] == 'surface'):
        if words[i] in KEYWORD:
            at.append((KEYWORD[words[i]], words[i + 1]))
        i += 2
    if i < len(words) and words[i] in KEYWORD:  # an axis keyword without its model: built in code
        return []
    for axis, word in at:
        values = expand(word, vals)
        if values is None:
            return []
        laws = [law[:axis] + [v] + law[axis + 1:] for law in laws for v in values]
    return [tuple(law) for law in laws]


def scan_file(path, found):
    base = os.path.basename(path)
    is_deck = path.endswith('.in') or base.startswith('in.')
    try:
        text = open(path, errors='replace').read()
    except OSError:
        return
    lines = deck_lines(text, is_deck)
    vals = variables(lines)
    for line in lines:
        for m in SELECTION.finditer(line):
            words = []
            for w in re.finditer(r'\S+', m.group(1)):
                token = WORD.match(w.group(0))
                if not token:
                    break
                words.append(token.group(0))
                if token.end() < len(w.group(0)):  # a quote or bracket ends the selection
                    break
            for law in selections(words, vals):
                found.setdefault(law, set()).add(path)


def scan(root):
    pats = ['tests/decks/**/*.in', 'input_scripts/**/*.in', 'reference_runs/**/*.in', 'reference_runs/**/in.*',
            'tests/unit/*.cpp', 'tests/*.py', 'tests/*.sh', 'input_scripts/**/*.py', 'input_scripts/**/*.sh',
            'reference_runs/**/*.py', 'reference_runs/**/*.sh']
    files = set()
    for p in pats:
        files |= set(glob.glob(os.path.join(root, p), recursive=True))
    files |= set(glob.glob(os.path.join(TUTORIALS, '**', 'in.*'), recursive=True))
    skip = ('/tests/decks/bad/', '/tests/decks/bad_controls/', '/tests/decks/checker/', '/tests/fuzz/')
    found = {}
    for f in sorted(files):
        if not any(s in f for s in skip) and os.path.isfile(f) and not f.endswith(os.path.basename(__file__)):
            scan_file(f, found)
    return found


def compiled(root):
    laws = set()
    for line in open(os.path.join(root, 'contact_models', 'compiled_laws.txt')):
        w = line.split('#')[0].split()
        if w:
            laws.add(tuple(w))
    return laws


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--root', default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap.add_argument('--list', action='store_true')
    a = ap.parse_args()
    names = model_names(a.root)
    found = scan(a.root)
    builtin = {law: files for law, files in found.items() if all(law[k] in names[k] for k in range(5))}
    listed = compiled(a.root)
    rel = lambda f: os.path.relpath(f, a.root) if f.startswith(a.root) else f
    if a.list:
        for law in sorted(builtin):
            mark = 'compiled' if law in listed else 'COMPOSED'
            files = sorted(rel(f) for f in builtin[law])
            print(f"{mark:9} {' '.join(law):55} {len(files):3} files: {', '.join(files[:4])}"
                  + (' ...' if len(files) > 4 else ''))
        other = sorted({law[0] for law in found if law not in builtin})
        print('not built-in (plugins, typos in bad decks):', ', '.join(other))
        return 0
    missing = [law for law in builtin if law not in listed]
    for law in sorted(missing):
        print(f"not compiled: {' '.join(law)} (selected by {', '.join(sorted(rel(f) for f in builtin[law]))}):"
              " add it to contact_models/compiled_laws.txt, or the deck runs on the slower composed path")
    unused = sorted(law for law in listed if law not in builtin)
    for law in unused:
        print(f"note: compiled but no literal selection found: {' '.join(law)} (its line says why)")
    print(f"{len(builtin)} laws selected by the decks and tests, {len(listed)} compiled, {len(missing)} missing")
    return 1 if missing else 0


if __name__ == '__main__':
    sys.exit(main())
