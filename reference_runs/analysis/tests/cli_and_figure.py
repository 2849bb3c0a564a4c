#!/usr/bin/env python3
"""sable-analyze end to end. Mode 'cli': every subcommand's --help, a fit on a known
sample through the text reader, the named errors. Mode 'figure': fig_pdf.py draws the fit
forms; the test checks the drawn lines are the curve file's columns, the PNG has ink in the
fit colours, and a curve without its pdf column is refused
(exit 77, skipped, without matplotlib).

    cli_and_figure.py cli|figure SABLE_ANALYZE WORKDIR
"""
import csv
import math
import os
import random
import subprocess
import sys

SUBS = ["pdf", "fit-lognormal", "fit-forms", "ks", "acf", "block-error", "mohr-envelope", "power-law", "quad-eq9",
        "bulk-modulus", "fit-offset-power", "mohr-cycles", "phi-min-eq9", "entropy"]


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
    cavity(exe, work)
    petit(exe, work)
    print("cli: all subcommands answer --help; Eq. 7 fit through the CLI recovers the truth; errors name file and column")


def cavity(exe, work):
    """Issue 43's subcommands: --help, Eq. 4 through fit-sigmoid (truth r1 0.53, r2 0.86, I0 0.02
    inside the 95 % intervals) and vortex-centre on a solid-body field centred off the nodes."""
    for s in ("fit-sigmoid", "fit-linear", "vortex-centre", "local-rheology"):
        if "usage: sable-analyze " + s not in run(exe, s, "--help").stdout:
            sys.exit(f"FAIL: {s} --help")
    rng = random.Random(4)
    sig = os.path.join(work, "eq4.txt")
    with open(sig, "w") as f:
        f.write("# I_M F_over_PLd\n")
        for i in range(25):
            x = 1e-3 * 500 ** (i / 24)
            f.write(f"{x:.12g} {0.53 + 0.33 / (1 + 0.02 / x) + rng.gauss(0, 0.01):.12g}\n")
    out = os.path.join(work, "eq4.csv")
    run(exe, "fit-sigmoid", sig, "--x", "I_M", "--y", "F_over_PLd", "--names", "r1,r2,I0", "--out", out)
    p = params(out)
    header = [l for l in open(out) if not l.startswith("#")][0].strip().split(",")
    if len(header) != len(set(header)):  # Eq. 4's parameter r2 once clashed with R^2's column name
        sys.exit(f"FAIL: fit-sigmoid wrote a column name twice: {header}")
    for name, truth in (("r1", 0.53), ("r2", 0.86), ("I0", 0.02)):
        if not p[name + "_lo"] <= truth <= p[name + "_hi"]:
            sys.exit(f"FAIL: fit-sigmoid {name} = {p[name]} [{p[name + '_lo']}, {p[name + '_hi']}] misses {truth}")
    vel = os.path.join(work, "vel.csv")
    with open(vel, "w") as f:  # cells of [0, 0.6] x [0, 0.4], rotation about (0.3137, 0.2281)
        f.write("x,y,vx,vy\n")
        for i in range(30):
            for j in range(20):
                x, y = (i + 0.5) * 0.02, (j + 0.5) * 0.02
                f.write(f"{x!r},{y!r},{-2 * (y - 0.2281)!r},{2 * (x - 0.3137)!r}\n")
    out = os.path.join(work, "vortex.csv")
    run(exe, "vortex-centre", vel, "--out", out)
    p = params(out)
    if abs(p["x"] - 0.3137) > 1e-9 or abs(p["y"] - 0.2281) > 1e-9 or abs(p["ell_over_l"] - (0.6 - 0.3137) / 0.6) > 1e-9:
        sys.exit(f"FAIL: vortex-centre found {p['x']}, {p['y']} (l/L {p['ell_over_l']}), not 0.3137, 0.2281")


def meta(path):
    with open(path) as f:
        return dict(l[1:].strip().split(": ", 1) for l in f if l.startswith("# ") and ": " in l)


def petit(exe, work):
    """Issue 44's petit2017 subcommands on exact data: Eq. 7 with its offset, the limit cycle of
    mohr-cycles, Eq. 9 inverted on the uniform law, Eq. 10 of a triangular lattice from branch vectors."""
    kf = os.path.join(work, "eq7.txt")
    with open(kf, "w") as f:
        f.write("# s K\n")
        for i in range(25):
            s = 4.1 * 25 ** (i / 24)
            f.write(f"{s!r} {200 + 290 * (s / 4.1 - 1) ** 0.47!r}\n")
    out = os.path.join(work, "eq7.csv")
    run(exe, "fit-offset-power", kf, "--x", "s", "--y", "K", "--out", out)
    p = params(out)
    for name, truth in (("K0", 200), ("a", 290), ("alpha", 0.47)):
        if abs(p[name] - truth) > 1e-6 * truth:
            sys.exit(f"FAIL: fit-offset-power {name} = {p[name]}, not {truth}")
    mus = [0.40, 0.45, 0.49, 0.51, 0.525, 0.532, 0.536, 0.538, 0.539, 0.5395, 0.540, 0.5398, 0.5402, 0.5401, 0.5400]
    cf = os.path.join(work, "cycles.txt")
    with open(cf, "w") as f:
        f.write("# cycle loading s1 s3\n")
        for k, mu in enumerate(mus):
            for i in range(1, 9):
                c = 5.0 * i
                r = mu * c / math.sqrt(1 + mu * mu)
                f.write(f"{k + 1} 1 {c + r!r} {c - r!r}\n")
            for i in range(7, 0, -1):  # unloading circles, off the envelope
                f.write(f"{k + 1} 0 {5.0 * i + 0.2 * i!r} {5.0 * i - 0.2 * i!r}\n")
    out = os.path.join(work, "cycles.csv")
    run(exe, "mohr-cycles", cf, "--s1", "s1", "--s3", "s3", "--cycle", "cycle", "--loading", "loading", "--out", out)
    m = meta(out)
    if m.get("limit_cycle") != "8" or abs(float(m["limit_mu_M"]) - 0.538) > 1e-12:
        sys.exit(f"FAIL: mohr-cycles limit cycle {m.get('limit_cycle')} mu_M {m.get('limit_mu_M')}, not 8 and 0.538")
    out = os.path.join(work, "phimin.csv")
    run(exe, "phi-min-eq9", "--mu", "0.3", "--mu-m", "0.54", "--out", out)
    want = math.atan(0.3) + math.pi / 4 - 1.5 * math.acos(math.exp(-2 * math.pi * 0.54 / 3))
    if abs(params(out)["phi_min"] - want) > 1e-9:
        sys.exit(f"FAIL: phi-min-eq9 gave {params(out)['phi_min']}, not {want}")
    af = os.path.join(work, "branches.txt")
    with open(af, "w") as f:  # each grain's neighbours in the closed upper half-plane
        f.write("# dx dy\n")
        for _ in range(10):
            for a in (-90, -30, 30, 90):
                f.write(f"{math.sin(math.radians(a))!r} {math.cos(math.radians(a))!r}\n")
    out = os.path.join(work, "entropy.csv")
    run(exe, "entropy", af, "--dx", "dx", "--dy", "dy", "--out", out)
    if abs(params(out)["S"] - math.log(4)) > 1e-12:
        sys.exit(f"FAIL: entropy of the triangular lattice {params(out)['S']}, not ln 4")


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
    p = subprocess.run([sys.executable, "-m", "sable_tools.fig_pdf", curve, "-o", png, "--log"],
                       capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"FAIL: fig_pdf.py: {p.stderr}")
    check_drawn(curve)
    check_png(png)
    # Positive control: a curve file without its pdf column is refused, naming file and column.
    bad = os.path.join(work, "no_pdf.csv")
    with open(curve) as f:
        lines = f.read().splitlines()
    head = next(i for i, l in enumerate(lines) if l.strip() and not l.startswith("#"))
    if "pdf" not in lines[head].split(","):
        sys.exit(f"FAIL: {curve}'s header {lines[head]} has no pdf column")
    lines[head] = ",".join("qdf" if c == "pdf" else c for c in lines[head].split(","))
    with open(bad, "w") as g:
        g.write("\n".join(lines) + "\n")
    p = subprocess.run([sys.executable, "-m", "sable_tools.fig_pdf", bad, "-o", png + ".bad.png"],
                       capture_output=True, text=True)
    if p.returncode == 0 or "no_pdf.csv" not in p.stderr + p.stdout or "pdf" not in p.stderr + p.stdout:
        sys.exit(f"FAIL: a curve without 'pdf' should be refused naming the file and the column: {p.stderr}")
    print("figure:", png, "holds the data and every fit of", curve)


def check_drawn(curve):
    """What fig_pdf draws is the curve file: the data points where pdf > 0 and one line per fit form,
    each with its label, on a log y axis."""
    from sable_tools import fig_pdf, figstyle
    from sable_tools.readers import analyze
    figstyle.use()
    t = analyze.table(curve)
    fig, ax = fig_pdf.draw(t, log=True)
    lines = {l.get_label(): l for l in ax.get_lines()}
    forms = [k for k in ("eq7", "normal", "eq8", "eq9", "eq10") if k in t]
    if len(forms) < 2:
        sys.exit(f"FAIL: fit-forms wrote {forms}: expected several fit forms in {curve}")
    want = {"data": ([x for x, p in zip(t["x"], t["pdf"]) if p > 0], [p for p in t["pdf"] if p > 0])}
    for k in forms:
        want[fig_pdf.LABELS[k]] = (t["x"], t[k])
    if set(lines) != set(want):
        sys.exit(f"FAIL: the figure's lines {sorted(lines)} are not {sorted(want)}")
    for label, (xs, ys) in want.items():
        x, y = lines[label].get_data()
        if list(map(float, x)) != list(map(float, xs)) or list(map(float, y)) != list(map(float, ys)):
            sys.exit(f"FAIL: the line '{label}' does not plot the file's columns")
    if ax.get_yscale() != "log" or "bar f" not in ax.get_xlabel():
        sys.exit(f"FAIL: axes: y scale {ax.get_yscale()}, x label {ax.get_xlabel()}")
    import matplotlib.pyplot as plt
    plt.close(fig)


def check_png(png):
    """The PNG is a real picture of that size with ink in the fit colours, not an empty canvas."""
    import matplotlib.image as mpimg
    from sable_tools import figstyle
    img = mpimg.imread(png)
    h, w = img.shape[:2]
    if w < 300 or h < 200:
        sys.exit(f"FAIL: {png} is {w}x{h} pixels")
    rgb = (img[:, :, :3] * 255).round().astype(int)
    ink = (rgb.sum(axis=2) < 3 * 250).mean()
    if not 0.005 < ink < 0.5:
        sys.exit(f"FAIL: {png}: {ink:.3%} of the pixels are not white")
    for colour in figstyle.COLOURS[1:3]:  # the first two fit lines
        c = [int(colour[i:i + 2], 16) for i in (1, 3, 5)]
        near = (abs(rgb - c).sum(axis=2) < 30).sum()
        if near < 50:
            sys.exit(f"FAIL: {png}: only {near} pixels of the fit colour {colour}")


def main():
    mode, exe, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    {"cli": cli, "figure": figure}[mode](exe, work)


if __name__ == "__main__":
    main()
