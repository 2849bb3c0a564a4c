"""sable's HDF5 outputs: text attributes, the series files of fix ave/time (step, values, columns),
and the coarse-grained fields of fix ave/cg (windows averaged by their samples)."""
import h5py
import numpy as np


def text(values):
    """An attribute's values as strings (h5py gives bytes or numpy strings)."""
    return [v.decode() if isinstance(v, bytes) else str(v) for v in values]


def read_series(path):
    """(column names, values [rows, columns], steps) of a fix ave/time HDF5 file."""
    with h5py.File(path, 'r') as h:
        return text(h.attrs['columns']), np.asarray(h['values']), np.asarray(h['step'])


def cg_windows(path, windows=slice(None)):
    """The fields of a fix ave/cg HDF5 file (a killed run's too: swmr, complete windows only, i.e.
    those with a step, written last) averaged over the chosen windows, each weighted by its
    samples: {field: array [nx, ny, nz, ...]} plus x, y, z (the grid), step (the windows'),
    frame and support (the kernel's)."""
    with h5py.File(path, "r", swmr=True) as f:
        n = len(f["step"])
        w = np.arange(n)[windows]
        if len(w) == 0:
            raise SystemExit(f"{path}: no complete window in {windows}")
        s = f["samples"][:n][w]
        out = {k: np.tensordot(s, f[k][:n][w], axes=1) / s.sum() for k in text(f.attrs["fields"])}
        out.update({k: f[k][:] for k in ("x", "y", "z")})
        out["step"] = f["step"][:n][w]
        out["frame"] = text(f.attrs["frame"])[0]
        out["support"] = float(f["support"][0])
    return out
