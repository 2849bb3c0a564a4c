"""Legacy VTK text files of sable and LIGGGHTS (dump custom/vtk, dump mesh/vtk): the POINTS
block and a cell or point field, LIGGGHTS' (FIELD arrays) or sable's (SCALARS) layout."""
import re

import numpy as np


def points(path):
    """The POINTS block of a legacy VTK file as an array [n, 3]."""
    with open(path) as f:
        lines = f.read().split('\n')
    i = next(k for k, l in enumerate(lines) if l.startswith('POINTS '))
    n = int(lines[i].split()[1])
    nums = []
    for line in lines[i + 1:]:
        if len(nums) >= 3 * n:
            break
        nums += [float(x) for x in line.split()]
    return np.array(nums[:3 * n]).reshape(-1, 3)


def field(text, name):
    """The values of the field `name` in a VTK file's text (a FIELD array 'name 1 N float' or
    'SCALARS name float 1' with its LOOKUP_TABLE), as a list of floats; None when absent."""
    m = re.search(r'^(?:SCALARS )?' + re.escape(name) + r' .*\n(?:LOOKUP_TABLE default\n)?((?:[-+0-9.eE ]+\n)+)',
                  text, re.M)
    return [float(x) for x in m.group(1).split()] if m else None
