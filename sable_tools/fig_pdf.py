#!/usr/bin/env python3
"""Example figure: a PDF normalised by the mean with its fits, from the --curve output of
`sable-analyze fit-lognormal` (Eq. 7 or, flagged, its Gaussian limit) or `fit-forms` (Eqs. 7-10).

    fig_pdf.py curve.csv|curve.h5 -o pdf.png [--log]
"""
import argparse

from sable_tools import figstyle
from sable_tools.readers import analyze  # the curve file, CSV or HDF5

LABELS = {"fit": "fit", "eq7": "Eq. 7 truncated log-normal", "normal": "truncated normal",
          "eq8": "Eq. 8", "eq9": "Eq. 9", "eq10": "Eq. 10"}


def draw(t, log=False):
    """The figure of table t (readers.analyze.table of a --curve output): data markers where the
    PDF is positive, one line per fit; returns (fig, ax)."""
    fig, ax = figstyle.figure()
    keep = [i for i, p in enumerate(t["pdf"]) if p > 0]
    ax.plot([t["x"][i] for i in keep], [t["pdf"][i] for i in keep], "o", mfc="none", label="data")
    limit = t.meta.get("gaussian_limit") == "1"
    curves = ["fit"] if "fit" in t else [k for k in ("eq7", "normal", "eq8", "eq9", "eq10") if k in t]
    for k in curves:
        label = LABELS[k] + (" (Gaussian limit)" if k == "fit" and limit else "")
        ax.plot(t["x"], t[k], "-", label=label)
    ax.set_xlabel(r"$f/\bar f$")
    ax.set_ylabel(r"$\mathcal{P}(f/\bar f)$")
    if log:
        ax.set_yscale("log")
    ax.legend()
    return fig, ax


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("curve")
    ap.add_argument("-o", "--out", required=True)
    ap.add_argument("--log", action="store_true", help="log y axis (tails)")
    a = ap.parse_args()
    figstyle.use()
    t = analyze.table(a.curve)
    analyze.need(t, a.curve, "x", "pdf")
    fig, _ = draw(t, a.log)
    figstyle.save(fig, a.out)
    print("wrote", a.out)


if __name__ == "__main__":
    main()
