#!/usr/bin/env python3
"""ctest mohr.small: input_scripts/mohr/mohr.in (petit2017's loading-unloading cycles of a
2D disk packing between two pistons of grains) at a small size, N 300 disks, pistons of
8 R_av, 2 cycles (1.6 s on one core), judged against what is known without the deck. Each
check names its tolerance and source; where a check could pass whatever the run did, a
control beside it shows that it fails on data that are wrong in one way.

(a) static balance at every relaxed state (force balance of the mobile grains): the bed's
    net y force is the difference of the pistons' forces, W t (syy_top - syy_bot), and is at
    most the sum of the grains' |net force| = N_m ub <|f|> (ub: compute unbalanced/force,
    mean |net| over mean |contact force| <|f|> over the N_c contacts touching the grains).
    <|f|> is bounded by the row's Love-Weber trace: sum |f_n| |l| = A t (sxx_lw + syy_lw)
    (A = W Hc, the tangential part does no work along l), |l| >= 2 R_av (1 - delta)(1 - dmax),
    |f| <= sqrt(1 + mu^2) |f_n| (Coulomb), and N_c >= Z N_m (1 - rattlers) / 2 (Z: contacts of
    the non-rattlers, a piston contact counted once). So
        |syy_top - syy_bot| <= 2 ub sqrt(1 + mu^2) Hc (sxx_lw + syy_lw) / (l_min Z (1 - rattlers))
    row by row, with ub < thr in every uncapped row. No margin is added: it is a bound (the
    10-digit printing is 1e-9 of it). Measured: the worst gap is 0.21 of the bound, 1.5 % of
    syy (at the last unloading state, 4.6 MPa); over 4 seeds, mu 0.1/1, rotation, delta 0
    and 0.7 at most 0.24 of it (2.4 % of syy). The bound is 0.8 % to 8.2 % of syy here: control,
    syy_top of one state against syy_bot of the next breaks it (in all 55 pairs).
(b) sigma_xx across the midline (sxx: the mobile-mobile contacts crossing x = W/2, per Hc)
    against the Love-Weber sxx_lw of the mobile grains (all their contacts, pistons' too, over
    W Hc): averaged over every vertical line x = X, the midline force equals the Love-Weber
    sum over the mobile-mobile contacts exactly (periodic x); they differ by the mobile-piston
    contacts' share (in sxx_lw only) and by how one line differs from the mean (the pistons'
    rough faces push the strips sideways; ~20 contacts cross a line at N 300). Neither is
    printed, so the tolerance is measured: 30 % at every state with contacts (this run:
    -8.6 % to -1.0 %; 9 packings (4 seeds, mu 0.1, 1, rotation, delta 0, 0.7): -19 % to
    +21.5 %, a per-packing offset that stays through the cycles). It catches a wrong
    component, height or factor 2. Control: sxx against syy_lw fails it.
(c) the deck's in-deck envelope against `sable-analyze mohr-cycles` (the same least-squares
    line through the loading circles, petit2017 Eq. 8) on the states file: RESULT muM (cycle 1),
    muM_last and C (last cycle) to half a unit of their 6th printed digit plus 1e-6 relative
    (the states file holds 10 digits); each PEAK line's muM to its 4 decimals. K0 (Eq. 6
    between the last cycle's first two loading states), Z, porosity and S (the last peak's
    row) to the printing of both. Control: mohr-cycles without --loading (unloading circles
    in the fit) gives another muM.
(d) the strain path (Sec. III): every row's eps is the previous one's +- deps (1e-9), the
    loading of every cycle ends at eps = 0.15 (1e-9) and is its largest eps; each unloading
    stops at its first row with syy < smin = 5 MPa E / 95.04 GPa (or eps 0), the last row of
    the cycle. Control: the same rule with smin x 2 or smin / 2 fails.
(e) the counts: data rows = RESULT states = STATE lines, RESULT capped = the capped column's
    sum, cycles = RESULT cycles (1, 2, in order), steps = the steps column's sum + states x
    nramp; capped = (ub >= thr) in every row (the halt's condition).
(f) determinism: the same -var twice gives the same states, peak and packing files, bit for
    bit. Control: another deposition seed gives another states file.
(g) the packing ${out}_pack.dump (ballistic_deposit): N grains, ids 1..N, no overlap (centre
    distance >= (r_i + r_j)(1 - 1e-12), periodic in x), radii within R_av (1 +- delta) (the
    +-1 sigma cut; 1e-12), mass = pi r^2 rho thick R_av (2D disks, 1e-12), box width
    W = sqrt(N pi R_av^2 (1 + 0.291 delta^2) / 1.6) (the header's to 1e-12, the dump's to its 6
    digits, 5e-6), H and the mobile count from the pistons' cut lines (y = piston R_av, top centre -
    piston R_av). Controls: one grain moved onto its neighbour is found; a radius window of
    0.8 delta is broken.
usage: PYTHONPATH=REPO mohr_small.py SABLE DECK WORKDIR [SABLE_ANALYZE]"""
import math
import os
import re
import subprocess
import sys

import numpy as np

from sable_tools.readers import dump, screen, yade  # the dumps, the RESULT line, the states file

RAV = 1e-3          # mohr.in: mean radius (m)
RHO = 2650.0        # quartz (Table I)


class Checks:
    def __init__(self, name):
        self.name = name
        self.failures = []

    def check(self, what, ok, detail):
        print("%-40s %s  %s" % (what, "ok  " if ok else "FAIL", detail))
        if not ok:
            self.failures.append(what)

    def control(self, what, fails, detail):
        """A control: the check applied to data wrong in one way must fail."""
        self.check("control: " + what, fails, detail)

    def done(self):
        sys.exit("%s: failed: %s" % (self.name, ", ".join(self.failures)) if self.failures else 0)


def run_deck(sable, deck, work, var, timeout=120):
    """Runs the deck in WORK with -var K V; returns (stdout, RESULT dict of strings)."""
    os.makedirs(work, exist_ok=True)
    args = [sable, "-in", deck, "-log", "none"]
    for k, v in var.items():
        args += ["-var", k, str(v)]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    try:
        p = subprocess.run(args, cwd=work, capture_output=True, text=True, env=env, timeout=timeout)
    except subprocess.TimeoutExpired:
        sys.exit("%s did not end within %d s (a hang)" % (" ".join(args), timeout))
    if p.returncode != 0:
        sys.exit("%s failed (%d):\n%s\n%s" % (" ".join(args), p.returncode, p.stdout[-3000:], p.stderr))
    lines = screen.key_lines(p.stdout, "RESULT")  # strings, as printed
    res = lines[-1] if lines else {}
    if not res:
        sys.exit("%s: no RESULT line" % " ".join(args))
    return p.stdout, res


def start_runs(sable, deck, jobs):
    """Starts several runs side by side: jobs = [(work, var)]; returns the Popen list."""
    procs = []
    for work, var in jobs:
        os.makedirs(work, exist_ok=True)
        args = [sable, "-in", deck, "-log", "none"]
        for k, v in var.items():
            args += ["-var", k, str(v)]
        procs.append(subprocess.Popen(args, cwd=work, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                      env=dict(os.environ, OMP_NUM_THREADS="1")))
    return procs


def wait_runs(procs, timeout=120):
    outs = []
    for p in procs:
        try:
            o, e = p.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            p.kill()
            sys.exit("%s did not end within %d s (a hang)" % (" ".join(p.args), timeout))
        if p.returncode != 0:
            sys.exit("%s failed (%d):\n%s" % (" ".join(p.args), p.returncode, e))
        outs.append(o)
    return outs


def read_states(path):
    """${out}_states.txt (sable_tools.readers.yade): the header's k=v, the rows as floats and as printed."""
    hdr, raw = yade.read_states(path, text=True)
    return hdr, [{k: float(v) for k, v in r.items()} for r in raw], raw


def read_dump(path):
    """A one-snapshot dump of atoms or local rows (sable_tools.readers.dump): (box [[lo, hi]] x3,
    column names, rows of floats)."""
    cols, box, _ = dump.read_last_dump(path)
    return box.tolist(), list(cols), np.column_stack([cols[c] for c in cols]).tolist() if cols else []


def hulp(s):
    """Half a unit in the last printed digit of the number string s."""
    m = re.fullmatch(r"[-+]?(\d*)\.?(\d*)(?:[eE]([-+]?\d+))?", s.strip())
    if not m:
        return 0.0
    return 0.5 * 10.0 ** (-len(m.group(2)) + int(m.group(3) or 0))


def finite(x):
    return not (math.isnan(x) or math.isinf(x))


# ---- checks shared with mohr_hard.py -------------------------------------------------

def check_balance(c, hdr, rows, tag=""):
    """(a): |syy_top - syy_bot| under the force-balance bound, row by row."""
    H = float(hdr["H_Rav"]) * RAV
    mu, delta = float(hdr["mu"]), float(hdr["delta"])
    worst_b = worst_s = 0.0
    rel_bounds = []
    bad = []
    shifted_bad = 0
    used = 0
    bounds = []
    for i, r in enumerate(rows):
        if r["capped"] or r["Z"] <= 0:
            bounds.append(None)
            continue
        used += 1
        lmin = 2 * RAV * (1 - delta) * (1 - r["dmax"])
        b = (2 * r["ub"] * math.sqrt(1 + mu * mu) * H * (1 - r["eps"]) * (r["sxx_lw"] + r["syy_lw"])
             / (lmin * r["Z"] * (1 - r["rattlers"])))
        bounds.append(b)
        gap = abs(r["syy_top"] - r["syy_bot"])
        worst_b = max(worst_b, gap / b)
        worst_s = max(worst_s, gap / r["syy"])
        rel_bounds.append(b / r["syy"])
        if gap > b:
            bad.append(int(r["state"]))
    for i in range(len(rows) - 1):
        if bounds[i] is not None and abs(rows[i]["syy_top"] - rows[i + 1]["syy_bot"]) > bounds[i]:
            shifted_bad += 1
    c.check("(a) piston balance%s" % tag, used > 0 and not bad,
            "%d states; worst gap %.3f of the bound, %.4f of syy; bound %.3f..%.3f of syy%s" %
            (used, worst_b, worst_s, min(rel_bounds or [0]), max(rel_bounds or [0]),
             (", over it at states %s" % bad[:5]) if bad else ""))
    c.control("(a) next state's syy_bot%s" % tag, shifted_bad > 0, "over the bound in %d of %d pairs" %
              (shifted_bad, len(rows) - 1))
    return worst_b, worst_s


def check_strain_path(c, hdr, rows, deps, E, tag=""):
    """(d): eps steps, peaks at 0.15, unloading ends at the first syy < smin; returns the
    number of rule violations with smin scaled by each factor given (controls)."""
    smin = 5e6 * E / 95.04e9
    ok_step = True
    prev = 0.0
    for r in rows:
        want = prev + (deps if r["loading"] else -deps)
        if abs(r["eps"] - want) > 1e-9:
            ok_step = False
        prev = r["eps"]
    c.check("(d) eps steps of deps%s" % tag, ok_step, "every row's eps = previous +- %g (1e-9)" % deps)
    cycles = sorted(set(int(r["cycle"]) for r in rows))
    peaks = []
    order_ok = True

    def rule(s):
        broken = 0
        for cy in cycles:
            un = [r for r in rows if int(r["cycle"]) == cy and not r["loading"]]
            if not un:
                broken += 1
                continue
            for r in un[:-1]:
                if not (r["syy"] >= s and r["eps"] > 1e-9):
                    broken += 1
            if not (un[-1]["syy"] < s or un[-1]["eps"] <= 1e-9):
                broken += 1
        return broken

    for cy in cycles:
        rs = [r for r in rows if int(r["cycle"]) == cy]
        ld = [r for r in rs if r["loading"]]
        flags = [int(r["loading"]) for r in rs]
        if flags != sorted(flags, reverse=True) or not ld:
            order_ok = False
            continue
        peaks.append(ld[-1]["eps"])
        if max(r["eps"] for r in rs) != ld[-1]["eps"]:
            order_ok = False
    c.check("(d) peaks at eps 0.15%s" % tag, order_ok and len(peaks) == len(cycles) and
            all(abs(p - 0.15) <= 1e-9 for p in peaks), "cycle peaks %s (1e-9)" % ["%.12g" % p for p in peaks])
    n = rule(smin)
    c.check("(d) unloading ends below smin%s" % tag, n == 0,
            "smin %.6g Pa; last unloading syy %s" % (smin, ["%.4g" % [r for r in rows if int(r["cycle"]) == cy
                                                                     and not r["loading"]][-1]["syy"]
                                                         for cy in cycles]))
    return rule


def check_pack(c, hdr, path, N, delta, thick, piston, tag=""):
    """(g): the deposit's dump."""
    box, cols, atoms = read_dump(path)
    ix = {k: cols.index(k) for k in ("id", "radius", "mass", "x", "y")}
    ids = sorted(int(a[ix["id"]]) for a in atoms)
    c.check("(g) pack: N grains%s" % tag, len(atoms) == N and ids == list(range(1, N + 1)), "%d grains" % len(atoms))
    r = [a[ix["radius"]] for a in atoms]
    lo, hi = RAV * (1 - delta), RAV * (1 + delta)
    c.check("(g) pack: radii in R_av(1 +- delta)%s" % tag,
            min(r) >= lo * (1 - 1e-12) and max(r) <= hi * (1 + 1e-12),
            "%.4f..%.4f R_av, window %.3f..%.3f" % (min(r) / RAV, max(r) / RAV, 1 - delta, 1 + delta))
    mbad = max(abs(a[ix["mass"]] / (math.pi * a[ix["radius"]] ** 2 * RHO * thick * RAV) - 1) for a in atoms)
    c.check("(g) pack: mass pi r^2 rho t%s" % tag, mbad <= 1e-12, "worst rel %.1e (1e-12)" % mbad)
    Wd = box[0][1] - box[0][0]                  # the dump's bounds: 6 digits
    W = float(hdr["W_Rav"]) * RAV                # the header's: 20 digits
    Wwant = math.sqrt(N * math.pi * RAV ** 2 * (1 + 0.291 * delta ** 2) / 1.6)
    c.check("(g) pack: box width W%s" % tag, abs(W / Wwant - 1) <= 1e-12 and abs(Wd - Wwant) <= 5e-6 * Wwant,  # %g: half a unit in 6 digits
            "header %s R_av, formula %.17g, dump %.6g" % (hdr["W_Rav"], Wwant / RAV, Wd / RAV))
    def overlaps(xy):
        worst, n = 1e300, 0
        for i in range(len(xy)):
            xi, yi, ri = xy[i]
            for j in range(i + 1, len(xy)):
                xj, yj, rj = xy[j]
                dx = xi - xj
                dx -= W * round(dx / W)
                dy = yi - yj
                s = ri + rj
                if abs(dy) >= s or abs(dx) >= s:
                    continue
                q = math.sqrt(dx * dx + dy * dy) / s
                worst = min(worst, q)
                if q < 1 - 1e-12:
                    n += 1
        return n, worst

    xy = [(a[ix["x"]], a[ix["y"]], a[ix["radius"]]) for a in atoms]
    n, worst = overlaps(xy)
    c.check("(g) pack: no overlap%s" % tag, n == 0, "closest pair at %.15f (r_i + r_j)" % worst)
    # control: the grain farthest from the floor moved to touch-minus-1e-9 its nearest neighbour
    k = max(range(len(xy)), key=lambda i: xy[i][1])
    j = min((i for i in range(len(xy)) if i != k),
            key=lambda i: math.hypot(xy[i][0] - xy[k][0] - W * round((xy[i][0] - xy[k][0]) / W), xy[i][1] - xy[k][1]))
    moved = list(xy)
    moved[k] = (xy[j][0] + (xy[j][2] + xy[k][2]) * (1 - 1e-9), xy[j][1], xy[k][2])
    c.control("(g) a grain moved into its neighbour%s" % tag, overlaps(moved)[0] > 0, "overlap found")
    if delta > 0:
        d8 = 0.8 * delta
        c.control("(g) radius window of 0.8 delta%s" % tag, min(r) < RAV * (1 - d8) or max(r) > RAV * (1 + d8),
                  "radii outside %.2f..%.2f R_av" % (1 - d8, 1 + d8))
    ytop = max(a[ix["y"]] for a in atoms)
    H = ytop - 2 * piston * RAV
    c.check("(g) pack: H between the cut lines%s" % tag, abs(float(hdr["H_Rav"]) * RAV / H - 1) <= 1e-12,
            "header %s R_av, dump %.17g" % (hdr["H_Rav"], H / RAV))
    mob = sum(1 for a in atoms if piston * RAV < a[ix["y"]] < ytop - piston * RAV)
    c.check("(g) pack: mobile grains%s" % tag, int(hdr["mobile"]) == mob and int(hdr["N"]) == N,
            "header %s, dump %d" % (hdr["mobile"], mob))
    return atoms


def main():
    sable, deck, work = sys.argv[1:4]
    analyze = sys.argv[4] if len(sys.argv) > 4 else os.path.join(os.path.dirname(sable), "sable-analyze")
    if not os.access(analyze, os.X_OK):
        sys.exit("mohr.small: no sable-analyze at %s (give its path as the 4th argument)" % analyze)
    V = {"N": 300, "piston": 8, "cycles": 2, "out": "m"}
    c = Checks("mohr.small")
    # three runs side by side (2 cores): the run, the same again, another seed
    procs = start_runs(sable, deck, [(os.path.join(work, "a"), V), (os.path.join(work, "b"), V),
                                     (os.path.join(work, "seed"), dict(V, seed=15485867))])
    out, _, _ = wait_runs(procs)
    res = {}
    for line in out.splitlines():
        if line.startswith("RESULT "):
            res = dict(re.findall(r"(\S+)=(\S+)", line))
    a = os.path.join(work, "a")
    hdr, rows, raw = read_states(os.path.join(a, "m_states.txt"))
    E, deps, thr = float(hdr["E"]), 0.01, float(hdr["thr"])

    # (a)
    check_balance(c, hdr, rows)
    c.check("(a) ub < thr in uncapped states", all(r["ub"] < thr for r in rows if not r["capped"]),
            "largest ub %.4g, thr %g" % (max(r["ub"] for r in rows), thr))

    # (b)
    dev = [r["sxx"] / r["sxx_lw"] - 1 for r in rows if r["Z"] > 0]
    c.check("(b) sxx (midline) vs sxx_lw (30 %)", len(dev) > 0 and max(abs(d) for d in dev) <= 0.30,
            "sxx/sxx_lw - 1 from %.4f to %.4f over %d states" % (min(dev), max(dev), len(dev)))
    sw = [r["sxx"] / r["syy_lw"] - 1 for r in rows if r["Z"] > 0]
    c.control("(b) sxx vs syy_lw", max(abs(d) for d in sw) > 0.30, "sxx/syy_lw - 1 down to %.3f" % min(sw))

    # (c)
    csv = os.path.join(work, "mohr_cycles.csv")
    csv2 = os.path.join(work, "mohr_cycles_all.csv")
    sf = os.path.join(a, "m_states.txt")
    p1 = subprocess.run([analyze, "mohr-cycles", sf, "--sxx", "sxx", "--syy", "syy", "--cycle", "cycle", "--loading",
                         "loading", "--out", csv], capture_output=True, text=True)
    p2 = subprocess.run([analyze, "mohr-cycles", sf, "--sxx", "sxx", "--syy", "syy", "--cycle", "cycle", "--out", csv2],
                        capture_output=True, text=True)
    if p1.returncode or p2.returncode:
        sys.exit("sable-analyze mohr-cycles failed:\n%s\n%s" % (p1.stderr, p2.stderr))

    def fits(path):
        L = [l for l in open(path).read().splitlines() if l and not l.startswith("#")]
        cols = L[0].split(",")
        return [dict(zip(cols, map(float, l.split(",")))) for l in L[1:]]

    f1, f2 = fits(csv), fits(csv2)
    ncyc = int(res["cycles"])
    for key, want in (("muM", f1[0]["mu_M"]), ("muM_last", f1[-1]["mu_M"]), ("C", f1[-1]["C"])):
        tol = hulp(res[key]) + 1e-6 * abs(want)
        got = float(res[key])
        c.check("(c) RESULT %s = mohr-cycles" % key, abs(got - want) <= tol,
                "%s vs %.10g (diff %.2g, tol %.2g)" % (res[key], want, abs(got - want), tol))
    pk = re.findall(r"^PEAK cycle (\d+) muM (\S+)", out, re.M)
    c.check("(c) PEAK muM = mohr-cycles, each cycle", len(pk) == ncyc == len(f1) and
            all(abs(float(m) - f["mu_M"]) <= hulp(m) + 1e-9 for (_, m), f in zip(pk, f1)),
            "%s vs %s" % ([m for _, m in pk], ["%.6f" % f["mu_M"] for f in f1]))
    c.control("(c) unloading circles in the fit", abs(f2[0]["mu_M"] - float(res["muM"])) > hulp(res["muM"]) + 1e-6,
              "muM %.6f with unloading rows vs %s" % (f2[0]["mu_M"], res["muM"]))
    last = [r for r in rows if int(r["cycle"]) == ncyc and r["loading"]]
    lraw = [q for q in raw if int(q["cycle"]) == ncyc and q["loading"] == "1"]
    K0 = (last[1]["syy"] - last[0]["syy"] + 2 * (last[1]["sxx"] - last[0]["sxx"])) / (3 * (last[1]["eps"] - last[0]["eps"]))
    c.check("(c) K0 (Eq. 6, last cycle's first pair)", abs(float(res["K0"]) - K0) <= hulp(res["K0"]) + 1e-6 * abs(K0),
            "%s vs %.10g" % (res["K0"], K0))
    for key, col in (("Z", "Z"), ("porosity", "porosity"), ("S", "S")):
        got, want = float(res[key]), last[-1][col]
        c.check("(c) RESULT %s = last peak row" % key, abs(got - want) <= hulp(res[key]) + hulp(lraw[-1][col]),
                "%s vs %s" % (res[key], lraw[-1][col]))

    # (d)
    rule = check_strain_path(c, hdr, rows, deps, E)
    smin = 5e6 * E / 95.04e9
    c.control("(d) the rule with smin x 2 or smin / 2", rule(2 * smin) > 0 or rule(smin / 2) > 0,
              "broken %d times with 2 smin, %d with smin/2" % (rule(2 * smin), rule(smin / 2)))

    # (e)
    nstate = len(re.findall(r"^STATE ", out, re.M))
    c.check("(e) states = rows = STATE lines", int(res["states"]) == len(rows) == nstate and
            [int(r["state"]) for r in rows] == list(range(1, len(rows) + 1)),
            "RESULT %s, %d rows, %d STATE lines" % (res["states"], len(rows), nstate))
    c.check("(e) capped = sum of the column", int(res["capped"]) == sum(int(r["capped"]) for r in rows),
            "RESULT %s" % res["capped"])
    cyc = [int(r["cycle"]) for r in rows]
    c.check("(e) cycles", int(res["cycles"]) == V["cycles"] == max(cyc) and cyc == sorted(cyc) and
            set(cyc) == set(range(1, V["cycles"] + 1)), "RESULT %s, rows' cycles %s" % (res["cycles"], sorted(set(cyc))))
    nramp = int(hdr["nramp"])
    steps = sum(int(r["steps"]) for r in rows) + len(rows) * nramp
    c.check("(e) steps = relaxations + moves", int(res["steps"]) == steps, "RESULT %s, %d" % (res["steps"], steps))
    cap = 200000
    c.check("(e) capped = (ub >= thr)", all(bool(r["capped"]) == (r["ub"] >= thr) and
                                            (r["steps"] == cap) == bool(r["capped"]) for r in rows),
            "%d capped rows" % sum(int(r["capped"]) for r in rows))

    # (f)
    same = all(open(os.path.join(a, f), "rb").read() == open(os.path.join(work, "b", f), "rb").read()
               for f in ("m_states.txt", "m_pack.dump", "m_peak_c1.txt", "m_peak_last.txt"))
    c.check("(f) same -var twice: same files", same, "states, packing and peak files compared byte for byte")
    other = open(os.path.join(work, "seed", "m_states.txt")).read().splitlines()[2:]
    c.control("(f) another seed", other != open(os.path.join(a, "m_states.txt")).read().splitlines()[2:],
              "seed 15485867's rows differ")

    # (g)
    check_pack(c, hdr, os.path.join(a, "m_pack.dump"), V["N"], float(hdr["delta"]), 2.0, V["piston"])

    print("RESULT muM=%s muM_last=%s states=%s worst_sxx_dev=%.4f" % (res["muM"], res["muM_last"], res["states"],
                                                                       max(abs(d) for d in dev)))
    c.done()


if __name__ == "__main__":
    main()
