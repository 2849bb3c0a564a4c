"""Text dumps of sable and LIGGGHTS (LAMMPS' ITEM: layout): dump custom (atoms) and dump local
(contact pairs, one ENTRIES row each)."""
import gzip

import numpy as np


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


def local_snapshots(path):
    """The snapshots of a text dump local (plain or .gz), in order: yields (step, the ENTRIES
    header's column names, rows), each row the list of its words (strings, as in the file)."""
    op = gzip.open if str(path).endswith(".gz") else open
    step, names, rows, want = None, [], [], None
    with op(path, "rt") as f:
        for line in f:
            if line.startswith("ITEM:"):
                if line.startswith("ITEM: TIMESTEP"):
                    if step is not None:
                        yield step, names, rows
                    step, names, rows, want = None, [], [], "step"
                elif line.startswith("ITEM: ENTRIES"):
                    names, want = line.split()[2:], "rows"
                else:
                    want = None
            elif want == "step":
                step, want = int(line), None
            elif want == "rows" and line.strip():
                rows.append(line.split())
    if step is not None:
        yield step, names, rows


def local_column(path, j, first=None):
    """Column j (0-based) of every row of a dump local, as floats, from the snapshots whose step is
    at least `first` (all when None)."""
    return np.array([float(r[j]) for step, _, rows in local_snapshots(path) if first is None or step >= first
                     for r in rows], float)
