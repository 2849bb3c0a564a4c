#!/usr/bin/env python3
"""sable-analyze end to end. Mode 'cli': every subcommand's --help, a fit on a known
sample through the text reader, the named errors. Mode 'figure': fig_pdf.py draws the fit
(exit 77, skipped, without matplotlib).

    cli_and_figure.py cli|figure SABLE_ANALYZE WORKDIR
"""
import csv
import math
import os
import random
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SUBS = ["pdf", "fit-lognormal", "fit-forms", "ks", "acf", "block-error", "mohr-envelope", "power-law", "quad-eq9"]


def run(exe, *args, ok=True):
    p = subprocess.run([exe, *args], capture_output=True, text=True)
    if ok and p.returncode != 0:
        sys.exit(f"FAIL: {' '.join(args)} exited {p.returncode}:\n{p.stderr}")
    if not ok and p.returncode == 0:
        sys.exit(f"FAIL: {' '.join(args)} should have failed")
    return p


def sample(work):
    # Eq. 7 truth mu = 0.2, sigma = 0.5, x0 = 0.6; written as a fix ave/time text file.
    rng = random.Random(3)
    xs = []
    while len(xs) < 2000:
        y = rng.lognormvariate(0.2, 0.5)
        if y > 0.6:
            xs.append(y - 0.6)
    path = os.path.join(work, "force.txt")
    with open(path, "w") as f:
        f.write("# Time-averaged data for fix fw\n# TimeStep f_fw\n")
        for i, v in enumerate(xs):
            f.write(f"{10 * i} {v:.12g}\n")
    return path


def params(path):
    with open(path) as f:
        rows = list(csv.reader(l for l in f if not l.startswith("#")))
    return {k: float(v) for k, v in zip(rows[0], rows[1])}


def cli(exe, work):
    for s in SUBS:
        p = run(exe, s, "--help")
        if "usage: sable-analyze " + s not in p.stdout:
            sys.exit(f"FAIL: {s} --help says:\n{p.stdout}")
    data = sample(work)
    out = os.path.join(work, "params.csv")
    run(exe, "fit-lognormal", data, "--column", "f_fw", "--raw", "--out", out, "--curve", os.path.join(work, "curve.csv"))
    p = params(out)
    # The same check as the unit test: truth within 1.5 x the profile interval's half-width.
    for name, truth in (("mu", 0.2), ("sigma", 0.5), ("x0", 0.6)):
        half = p[name] - p[name + "_lo"] if truth < p[name] else p[name + "_hi"] - p[name]
        if not (abs(truth - p[name]) < 1.5 * half and math.isfinite(half)):
            sys.exit(f"FAIL: {name} = {p[name]} [{p[name + '_lo']}, {p[name + '_hi']}] misses the truth {truth}")
    if p["gaussian_limit"] != 0:
        sys.exit("FAIL: a clear log-normal flagged as the Gaussian limit")
    e = run(exe, "pdf", data, "--column", "f_nope", ok=False).stderr
    if "force.txt" not in e or "f_nope" not in e or "f_fw" not in e:
        sys.exit(f"FAIL: the bad-column error should name the file, the column and the columns there:\n{e}")
    e = run(exe, "pdf", data, "--column", "7", ok=False).stderr
    if "out of range" not in e:
        sys.exit(f"FAIL: column 7 of 2: {e}")
    e = run(exe, "acf", data, "--column", "2", "--bogus", "1", ok=False).stderr
    if "--bogus" not in e:
        sys.exit(f"FAIL: unknown option: {e}")
    e = run(exe, "pdf", os.path.join(work, "missing.txt"), "--column", "1", ok=False).stderr
    if "missing.txt" not in e:
        sys.exit(f"FAIL: missing file: {e}")
    print("cli: all subcommands answer --help; Eq. 7 fit through the CLI recovers the truth; errors name file and column")


def figure(exe, work):
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("matplotlib absent: figure test skipped")
        sys.exit(77)
    data = sample(work)
    curve = os.path.join(work, "forms.csv")
    run(exe, "fit-forms", data, "--column", "2", "--curve", curve)
    png = os.path.join(work, "pdf.png")
    p = subprocess.run([sys.executable, os.path.join(HERE, "..", "fig_pdf.py"), curve, "-o", png, "--log"],
                       capture_output=True, text=True)
    if p.returncode != 0 or not os.path.getsize(png) > 1000:
        sys.exit(f"FAIL: fig_pdf.py: {p.stderr}")
    print("figure:", png)


def main():
    mode, exe, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    {"cli": cli, "figure": figure}[mode](exe, work)


if __name__ == "__main__":
    main()
