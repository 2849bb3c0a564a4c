"""One figure style for every study (issue 23): rcParams and colours. sable-analyze's outputs
are read by sable_tools.readers.analyze.table.

    from sable_tools import figstyle
    from sable_tools.readers import analyze
    figstyle.use()
    t = analyze.table("curve.csv")      # t["x"], t["pdf"], ...; t.meta["source"]
    fig, ax = figstyle.figure()
    ...
    figstyle.save(fig, "out.png")
"""
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
