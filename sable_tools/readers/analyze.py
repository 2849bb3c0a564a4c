"""The outputs of sable-analyze: CSV ('# key: value' lines of metadata, a header line, rows of
numbers) or HDF5 (.h5/.hdf5: one 1-D dataset per column, the root attribute `columns`, the
metadata as string attributes).

    rows(path)     one dict of strings per row (CSV)
    columns(path)  {column: array of floats} (CSV)
    one_row(path)  the first row as {column: float} (a fit's parameters; a repeated name gets '_2')
    table(path)    Table: the columns and .meta, CSV or HDF5
"""
import csv

import numpy as np


def rows(path):
    """One dict of strings per row, keyed by the header's names."""
    with open(path) as f:
        return list(csv.DictReader([l for l in f if not l.startswith('#')]))


def columns(path):
    """{column: array of floats}."""
    lines = [l.strip() for l in open(path) if l.strip() and not l.startswith('#')]
    names = lines[0].split(',')
    values = np.array([[float(v) for v in l.split(',')] for l in lines[1:]]).reshape(-1, len(names))
    return {n: values[:, k] for k, n in enumerate(names)}


def one_row(path):
    """The first row of a one-row CSV (a fit's parameters) as {column: float}; a name repeated in
    the header gets '_2' on its second occurrence (sable-analyze ks writes two 'n')."""
    lines = [l.strip() for l in open(path) if l.strip() and not l.startswith('#')]
    out = {}
    for k, v in zip(lines[0].split(','), lines[1].split(',')):
        out[k + '_2' if k in out else k] = float(v)
    return out


class Table(dict):
    """Columns by name (lists of floats from CSV, numpy arrays from HDF5) and .meta (dict of strings)."""
    meta = None


def table(path):
    """A sable-analyze output, CSV or HDF5 (by its name's ending), as a Table."""
    t = Table()
    t.meta = {}
    if str(path).endswith((".h5", ".hdf5")):
        import h5py
        from sable_tools.readers import h5
        with h5py.File(path, "r") as f:
            for k, v in f.attrs.items():
                v = h5.text(v)
                t.meta[k] = v[0] if len(v) == 1 else v
            for name in t.meta.get("columns", []):
                t[name] = f[name][()]
        return t
    with open(path) as f:
        lines = f.read().splitlines()
    body = []
    for line in lines:
        if line.startswith("# ") and ": " in line:
            k, v = line[2:].split(": ", 1)
            t.meta[k] = v
        elif line.strip():
            body.append(line)
    table_rows = list(csv.reader(body))
    if not table_rows:
        raise SystemExit(f"{path}: no header line")
    for j, name in enumerate(table_rows[0]):
        t[name] = [float(r[j]) for r in table_rows[1:]]
    return t


def need(t, path, *names):
    """Stop with a message naming the file and the missing column."""
    for n in names:
        if n not in t:
            raise SystemExit(f"{path}: no column '{n}' (it has: {', '.join(t)})")
