"""Text dumps of sable and LIGGGHTS (LAMMPS' ITEM: layout)."""
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
