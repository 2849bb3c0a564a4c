"""The screen and log text of sable and LIGGGHTS (same layout): OBSERVABLE lines, thermo
tables, KEY k=v lines (RESULT, SCENE, ...), and the timing block after each run."""
import math
import re

# sable's run marker, LAMMPS' wording with its rates on the next line ("Loop time of 1.5 on 1 procs
# for 10 steps with 2 atoms\nPerformance: 13 particle-steps/s, 0 neighbor builds"), or on the
# same line as sable wrote it before 0.9.0 ("Loop time of 1.5 s on 1 process for ... atoms: 13 ...").
SABLE_LOOP = re.compile(
    r"Loop time of ([0-9.eE+-]+)(?: s)? on \d+ (?:procs|process(?:es)?) for (\d+) steps with (\d+) atoms"
    r"(?::|\nPerformance:) ([0-9.eE+-]+) particle-steps/s, (\d+) neighbor builds")
SABLE_SPLIT = re.compile(r"Time split: (.*)")
# "Thread balance (2 threads, busy min / mean / max): pair 0.95 / 0.96 / 0.97 s of 1.08 s (89%); per-atom ..."
SABLE_BALANCE = re.compile(r"(pair|per-atom passes) ([0-9.eE+-]+) / ([0-9.eE+-]+) / ([0-9.eE+-]+) s of ([0-9.eE+-]+) s")
LIG_LOOP = re.compile(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")
LIG_TIME = re.compile(r"^(\w+)\s+time \(%\) = ([0-9.eE+-]+) \(([0-9.eE+-]+)\)", re.M)


# LAMMPS' header words for the thermo keywords whose lower case is not the keyword itself
# (sable since 0.9.0 and LIGGGHTS print KinEng and Volume; the series keep the keyword).
HEADER_KEYWORD = {'kineng': 'ke', 'volume': 'vol'}


def to_float(s):
    try:
        return float(s)
    except ValueError:
        return None


def parse_screen(text):
    """OBSERVABLE name value lines, and every thermo table (header starting
    with Step) as series keyed by lower-case column name, v_/c_/f_ dropped
    (LAMMPS' KinEng and Volume as the keywords ke and vol)."""
    obs, series, header = {}, {}, None
    for line in text.splitlines():
        w = line.split()
        if len(w) == 3 and w[0] == 'OBSERVABLE':
            v = to_float(w[2])
            obs[w[1]] = v if v is not None else math.nan
        elif w and w[0].lower() == 'step' and len(w) > 1:
            header = [HEADER_KEYWORD.get(c.lower(), c.lower()) if c[:2] not in ('v_', 'c_', 'f_') else c[2:].lower()
                      for c in w[1:]]
        elif line.startswith('Loop time'):
            header = None
        elif header and len(w) == len(header) + 1 and all(to_float(x) is not None for x in w):
            step = float(w[0])
            for c, v in zip(header, w[1:]):
                if abs(float(v)) < 1e19:  # LAMMPS' +-1e20 = empty group
                    series.setdefault(c, {})[step] = float(v)
    return obs, {c: [sorted(s), [s[k] for k in sorted(s)]] for c, s in series.items()}


def error_lines(text):
    """The error messages of a screen, in order: sable's and LIGGGHTS' lines starting with ERROR
    (with more than the bare word) and YADE's (Python's) RuntimeError lines, stripped."""
    return [l.strip() for l in text.splitlines()
            if (l.startswith('ERROR') and len(l.strip()) > 6) or l.startswith('RuntimeError')]


def tagged(text, key):
    """The rest of each line that starts with the word KEY (a deck's print "KEY ..."), in order."""
    return [line[len(key) + 1:] for line in text.splitlines() if line.startswith(key + ' ')]


def key_lines(text, key):
    """The k=v words of each line that starts with KEY, one dict of strings a line, in order."""
    return [dict(w.split('=', 1) for w in rest.split() if '=' in w) for rest in tagged(text, key)]


def merged_keys(text, key):
    """The k=v words of all lines that start with KEY, merged into one dict of strings (a deck's
    RESULT lines); a key printed twice with different values raises ValueError."""
    out = {}
    for kv in key_lines(text, key):
        for k, v in kv.items():
            if out.get(k, v) != v:
                raise ValueError("%s key '%s' printed twice with different values (%s, %s)" % (key, k, out[k], v))
            out[k] = v
    return out


def numeric_keys(text, key):
    """The k=v words of all lines that start with KEY whose values are numbers, as floats (a key
    given twice: the last line's value), e.g. the RESULT lines of a deck."""
    out = {}
    for kv in key_lines(text, key):
        for k, v in kv.items():
            x = to_float(v)
            if x is not None:
                out[k] = x
    return out


def numbered(text, key):
    """Lines "KEY i k=v ...", i an integer (the drag deck's BLOCK and HALF lines): [(i, {k: v strings})]."""
    out = []
    for rest in tagged(text, key):
        w = rest.split()
        if w and w[0].isdigit():
            out.append((int(w[0]), dict(x.split('=', 1) for x in w[1:] if '=' in x)))
    return out


def loop_times(text):
    """The loop time (s) of every run, in order, from either code's "Loop time of T ..." lines."""
    return [float(t) for t in re.findall(r'^Loop time of (\S+)', text, re.M) if to_float(t) is not None]


def sable_loop(text):
    """The last run's timing block of sable's screen: steps, atoms, rates, time split, thread balance."""
    loops = SABLE_LOOP.findall(text)
    if not loops:
        return dict(psps=None)
    t, n, m, rate, builds = loops[-1]  # builds: during this run
    t, n, m = float(t), int(n), int(m)
    d = dict(loop_s=t, steps=n, atoms=m, psps=m * n / t if t > 0 else None, psps_printed=float(rate),
             builds=int(builds))
    nb = re.findall(r"Ave neighs/atom = ([0-9.eE+-]+)", text)
    if nb:
        d["neighs_per_atom"] = float(nb[-1])
    splits = SABLE_SPLIT.findall(text)
    if splits:
        d["split"] = {k: float(v) for k, v in re.findall(r"(\w+) ([0-9.]+)%", splits[-1])}
    ranks = [l for l in text.splitlines() if l.startswith("Rank balance")]
    if ranks:  # several MPI ranks: seconds and grains per rank, min / mean / max
        d["ranks"] = {k: dict(min=float(a), mean=float(b), max=float(c))
                      for k, a, b, c in re.findall(r"(\w+) ([0-9.eE+-]+) / ([0-9.eE+-]+) / ([0-9.eE+-]+)", ranks[-1])}
        share = re.search(r"comm ([0-9.]+)% of the loop", ranks[-1])
        d["comm_pct"] = float(share.group(1)) if share else None
    bal = [l for l in text.splitlines() if l.startswith("Thread balance")]
    if bal:  # the timed run's: the last one
        d["balance"] = {("pair" if k == "pair" else "atoms"): dict(min=float(a), mean=float(b), max=float(c),
                                                                 wall=float(w))
                        for k, a, b, c, w in SABLE_BALANCE.findall(bal[-1])}
    return d


def liggghts_loop(text):
    """The last run's timing block of LIGGGHTS' screen: steps, atoms, rate, time split, version."""
    loops = list(LIG_LOOP.finditer(text))
    if not loops:
        return dict(psps=None)
    last = loops[-1]
    t, procs, n, m = float(last.group(1)), int(last.group(2)), int(last.group(3)), int(last.group(4))
    tail = text[last.end():]
    d = dict(loop_s=t, procs=procs, steps=n, atoms=m, psps=m * n / t if t > 0 else None)
    d["split"] = {k: float(pct) for k, _, pct in LIG_TIME.findall(tail)}
    m1 = re.search(r"Ave neighs/atom = ([0-9.eE+-]+)", tail)
    m2 = re.search(r"Neighbor list builds = (\d+)", tail)
    if m1:
        d["neighs_per_atom"] = float(m1.group(1))
    if m2:
        d["builds"] = int(m2.group(1))
    v = re.search(r"LIGGGHTS \(Version ([^)]*)\)", text)
    if v:
        d["version"] = v.group(1).strip()
    return d
