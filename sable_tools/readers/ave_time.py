"""fix ave/time text files (mode scalar), as sable and LIGGGHTS write them."""
import numpy as np


def read_rows(path):
    """(the header's column names, rows [n, 1 + columns] of floats, the step first) of a
    fix ave/time text file in mode scalar (two '#' header lines, then one row per output)."""
    lines = open(path).read().splitlines()
    cols = lines[1].split()[2:]
    return cols, np.array([[float(x) for x in l.split()] for l in lines[2:] if l.strip()]).reshape(-1, len(cols) + 1)


def ave_time_file(path, name):
    """A fix ave/time text file (mode scalar) as observables NAME_rows,
    NAME_first_step, NAME_last_step and per column NAME_COL (last row) and
    NAME_COL_mean (mean over rows), COL the header word without v_/c_/f_ and
    [I] as _I; and its columns as series NAME_COL."""
    cols, rows = read_rows(path)
    cols = [c[2:] if c[:2] in ('v_', 'c_', 'f_') else c for c in cols]
    cols = [c.replace('[', '_').replace(']', '') for c in cols]
    obs = {f'{name}_rows': float(len(rows))}
    if len(rows):
        obs.update({f'{name}_first_step': rows[0, 0], f'{name}_last_step': rows[-1, 0]})
    series = {}
    for j, c in enumerate(cols, 1):
        if len(rows):
            obs.update({f'{name}_{c}': float(rows[-1, j]), f'{name}_{c}_mean': float(rows[:, j].mean())})
        series[f'{name}_{c}'] = [rows[:, 0].tolist(), rows[:, j].tolist()]
    return obs, series
