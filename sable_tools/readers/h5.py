"""sable's HDF5 outputs: text attributes, and the series files of fix ave/time (step, values, columns)."""
import h5py
import numpy as np


def text(values):
    """An attribute's values as strings (h5py gives bytes or numpy strings)."""
    return [v.decode() if isinstance(v, bytes) else str(v) for v in values]


def read_series(path):
    """(column names, values [rows, columns], steps) of a fix ave/time HDF5 file."""
    with h5py.File(path, 'r') as h:
        return text(h.attrs['columns']), np.asarray(h['values']), np.asarray(h['step'])
