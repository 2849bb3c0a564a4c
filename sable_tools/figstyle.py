"""One figure style for every study (issue 23): rcParams, colours, and a reader for
sable-analyze's outputs (CSV with '# key: value' lines, or HDF5 with one dataset per column).

    from sable_tools import figstyle
    figstyle.use()
    t = figstyle.read("curve.csv")      # t["x"], t["pdf"], ...; t.meta["source"]
    fig, ax = figstyle.figure()
    ...
    figstyle.save(fig, "out.png")
"""
import csv

# Colour-blind safe (Okabe-Ito), the same order in every figure: data, fit, alternatives.
COLOURS = ["#000000", "#D55E00", "#0072B2", "#009E73", "#CC79A7", "#E69F00", "#56B4E9"]
WIDTH_IN = 3.4  # one journal column


def use():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from cycler import cycler
    plt.rcParams.update({
        "figure.figsize": (WIDTH_IN, WIDTH_IN * 0.75),
        "figure.dpi": 150, "savefig.dpi": 300, "savefig.bbox": "tight",
        "font.size": 8, "axes.labelsize": 8, "legend.fontsize": 7, "xtick.labelsize": 7, "ytick.labelsize": 7,
        "axes.prop_cycle": cycler(color=COLOURS), "lines.linewidth": 1.0, "lines.markersize": 3,
        "axes.linewidth": 0.6, "xtick.direction": "in", "ytick.direction": "in",
        "xtick.top": True, "ytick.right": True, "legend.frameon": False, "mathtext.fontset": "cm",
    })


def figure(**kw):
    import matplotlib.pyplot as plt
    return plt.subplots(**kw)


def save(fig, path):
    fig.savefig(path)
    import matplotlib.pyplot as plt
    plt.close(fig)


class Table(dict):
    """Columns by name (lists of floats, or numpy arrays from HDF5) and .meta (dict of strings)."""
    meta = None


def read(path):
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
    rows = list(csv.reader(body))
    if not rows:
        raise SystemExit(f"{path}: no header line")
    for j, name in enumerate(rows[0]):
        t[name] = [float(r[j]) for r in rows[1:]]
    return t


def need(t, path, *names):
    """Stop with a message naming the file and the missing column."""
    for n in names:
        if n not in t:
            raise SystemExit(f"{path}: no column '{n}' (it has: {', '.join(t)})")
