#!/usr/bin/env python3
"""ctest cavity.hard_np100, cavity.hard_nu20, cavity.hard_dilute: short versions of the hard
cases of the kneib2017 lid-driven cavity study (issue 43, item 7), input_scripts/cavity/cavity.in
at H/d 8, seed 7, `-var fields 0`, judged against what is known without the deck.
(The fourth hard case, a deposit missing H/d by more than 5 %, is baddeck.cavity_bad_deposit.)

Every case:
- every run ends (exit 0); the atom count is constant: the deposit's and the shear's grain
  count is round(0.80 L H / (pi/4 d^2 (1 + 0.15^2/3))) and the shear holds grains + L/d floor
  grains + ceil(L/d) + 4 lid grains in every run of the shear (its "Loop time" lines);
- the lid keeps U: its speed at the end within 1e-12 U, every sample's |u - U| under 1e-12 U
  (the rigid body's speed is its members' mean, U up to rounding; cavity.small);
- momentum balance along y with gravity off: over the recording the floor row carries Fc and
  the lid's net y force averages 0, each within 3 standard errors of its block means (the
  time averages are exactly Fc and 0 up to the bed's and the lid's momentum change over the
  recording; the block means of 10 kHz samples scatter about them as a mean's error, and
  with 10 blocks (t, 9 degrees of freedom) 3 errors is a 1.5 % false alarm per check for
  Gaussian block means: the recordings below are long enough that every case sits within
  2.1 errors, and a 10 % stronger push fails the floor check by 7 to 14 errors, in the
  short nu20 run only by 1.2);
- no NaN or inf in any RESULT value.

hard_np100 (NP 100, NU 10: I_M 0.044, cavity.small's I_M with 100x the stiffness and 1/10 dt;
tshear 0.1 s, trec 0.01 s, 81k shear steps):
- E = 2 N0 P, P = NP Phi rho_p g H, f_c = omega_d / 2 pi of two grains of diameter d (k_n =
  E d/2, m* = m/2, beta from e) and dt = dtfrac / f_c, evaluated here, against the deck's
  printed values to 1e-12 (a few ulps of the same formulas); the time step the run used (its
  time-step check line, 6 digits) against dt to 1e-5;
- H/d within 5 % of Hd, in the deposit and under shear (cavity.small: the grain count is set
  for H at the deposit's packing fraction 0.80; measured 8.153 and 8.041);
- the balances over 0.09 s of recording: at NP 100 the contacts are short (about 8 steps)
  and the 10 kHz samples of the lid's net force are skewed by impacts (skewness 0.8), so a
  short recording's mean sits below 0 by a few errors (-0.025 +- 0.009 over 0.04 s); over
  0.09 s the floor carries 0.9956 +- 0.0055 Fc and the lid's net force is -0.0052 +- 0.0063 Fc;
- the overlap stays small: the largest overlap / d of every grain-grain (bed, floor, lid) and
  grain-wall contact, evaluated every step of a continuation of the shear (a wrapper deck
  written into the work folder includes cavity.in unchanged and then runs 8100 more steps
  with compute pair/gran/local and wall/gran/local delta), under 5 Fc / (k_n d) =
  5 (L/d) / N0 = 1.33e-2. Why: Fc / k_n = (L/d) d / N0 whatever NP (k_n and Fc are both
  proportional to P) is the overlap of a contact carrying the lid's whole load; the softest
  pair (two grains of 0.85 d, or a 0.85 d grain on a wall, k_n = E r) is 1/0.85 softer;
  impacts at up to the lid's speed add U / omega_0 (grain-grain, m* = m/2) to sqrt(2) U /
  omega_0 (grain-wall, m* = m), 0.72 to 1.0 Fc / k_n at NU 10, NP 100, Hd 8: about
  2.2 Fc / k_n together, and a factor of about 2 for chains carrying more than the mean
  load for a moment. Measured: 1.72 Fc / k_n between grains and 1.87 on the walls (4.6e-3 d,
  5.0e-3 d); 1.7 to 3.2 over other stretches of this shear (a continuation from 0.03 s: 1.98
  and 2.74; with a 10 % stronger push: 3.21 and 2.74). With E / 10: 13.4.

hard_nu20 (NU 20, NP 100: U = 1.98 m/s, I_M 0.088; NP 100 for the most steps per d of
travel): one deposit, then the same shear for two durations (tshear 0.0252 s and 0.101 s,
trec 0.01 s: the lid travels 39.7 d and 198.7 d, 0.9 and 4.5 times its period of 44 d).
The cost of a step must not grow with the lid's travel; what sets it is compared between the
two runs (counts, no wall-clock time):
- the atoms: the same count in both runs, every run of the shear (lid grains included);
- the box: every record of the grain-wall contact dump (`-var contacts 1`, one record per
  10 kHz sample; 101 and 901 records) has the same box bounds in both runs, the ones the
  deck's formulas give whatever the travel: x over the lid's period n_lid d = L + 4 d centred
  on the cavity, y from 0 to 3 d over the deposit's starting lattice (18.75 d here);
- neighbour-list rebuilds per step over the recording within 20 % between the two runs, and
  each at least the rate the lid alone forces (its grains move U dt a step, a rebuild once any
  atom moved more than half the skin d/2: one at least every ceil(d/4 / (U dt)) steps) and
  under 1.5 times it (bed grains thrown faster than U trigger some earlier). Measured: 91
  builds in 8100 steps and 856 in 72900 (0.01123 and 0.01174 a step, 1.146 and 1.198 times
  the lid's 1/102; long / short 1.045);
- the neighbour pairs at the end within 20 % between the runs (the pair loop's length;
  1071 and 1038);
- the lid's travel U t = U_lid_end x steps x dt (every sample's speed is U, above), at least
  150 d in the long run and 4x the short run's;
- H/d within 5 % of Hd (deposit and both shears), the balances and lid speed in both runs.

hard_dilute (NU 11.3137, NP 1: I_M = NU (d/H)^1.5 / sqrt(NP) = 0.5000, the dilute top; tshear
0.5 s, trec 0.1 s: 0.4 s of recording, 4000 samples):
- I_M from the formula, to 1e-12 against the deck and within 1e-5 of 0.5;
- the lid's contacts are intermittent: in the recording (${out}_series.h5, v_flid) the fraction
  of samples in which the lid touches nothing (its net y force is the push -Fc alone, to 1e-9)
  is over 0.2 (measured 0.535; 0.30 at I_M 0.22; 0.000 in a dense bed, NU 1, I_M 0.044);
- the right wall's contacts are intermittent too: F_zero over 0.15 (measured 0.30; 0.27-0.28
  at I_M 0.22; 0.045-0.056 at I_M 0.044, README's seed table and cavity.small's setting);
- the lid moves: the std of its centre's y (v_yl) over the recording over 0.1 d (measured
  0.285 d; 0.055-0.058 d on a dense bed at NU 1, where the lid follows the surface grains'
  rearrangements). The scale: the lid falls back under a = Fc / M_lid = 6 NP Phi g H / (pi d)
  = 90 m/s^2 here, a hop at the bed's fluctuation speed c U reaching
  c^2 pi NU^2 / (12 Phi NP Hd) d = 7 c^2 d (0.28 d for c = 0.2);
- the bed dilates but stays in the box: H (from the bed's mass centre) over the deposit's H
  and under 1.15 of it, and so under 2 Hd (measured H/d 8.402 against 8.090 deposited,
  +3.9 %, the lid's gap 9.46 d; +3.0 % at I_M 0.22, -0.4 to -0.7 % at I_M 0.044: the bed
  dilates with I; 1.15 leaves about 4x the measured dilation);
- the balances as above (1.0105 +- 0.0133 and -0.0100 +- 0.0151).

Controls (run by hand with a changed copy of the deck as DECK, or of this script; not in the
suite; each made the named checks FAIL): hard_np100 with E = 2 N0 P / 10 (E, f_c, dt, dt used,
overlap 13.4 Fc / k_n), with a 10 % stronger push (floor: 1.098 +- 0.007), with NP 99 in this
script's formulas (P, E, Fc, f_c, dt); hard_nu20 with a box wider by U tshear / 400 (box),
with `neigh_modify every 1 check no` (rebuilds a step: 102x the lid's), with a skin shrinking
as 1/tshear (rebuilds and neighbour pairs differ between the runs: 3.45x), with the stronger
push (floor, long run: 7.2 errors); hard_dilute with NU 1 (I_M, lid and wall intermittency,
lid motion, dilation), with the stronger push (floor: 7.1 errors; the lid's free samples,
whose net force is then -1.1 Fc).
usage: PYTHONPATH=REPO cavity_hard.py SABLE DECK WORKDIR np100|nu20|dilute"""
import math
import os
import re
import subprocess
import sys

import numpy as np

from sable_tools.readers import h5, screen  # the series file; the RESULT and DEPOSIT lines

sable, deck, work, case = sys.argv[1:5]
deck = os.path.abspath(deck)
os.makedirs(work, exist_ok=True)
CASES = {
    "np100": {"NU": 10, "NP": 100, "tshear": 0.1, "trec": 0.01},
    "nu20": {"NU": 20, "NP": 100, "trec": 0.01},
    "dilute": {"NU": 11.3137, "NP": 1, "tshear": 0.5, "trec": 0.1},
}
if case not in CASES:
    sys.exit("cavity_hard.py: case %r: expected np100, nu20 or dilute" % case)
V = dict({"Hd": 8, "seed": 7, "dtfrac": 0.1, "nblk": 10, "fields": 0}, **CASES[case])
name = "cavity.hard_" + case
failures = []

# kneib2017, evaluated independently of the deck (as cavity_small.py)
d, rhop, g, Phi, e, N0 = 1e-3, 2500.0, 9.81, 0.6, 0.5, 1.5e4
H = V["Hd"] * d
L = 5 * H                                   # Sec. II
P = V["NP"] * Phi * rhop * g * H            # Eq. 1
E = 2 * N0 * P                              # App. B
U = V["NU"] * math.sqrt(g * d)              # Eq. 2
Fc = P * L * d                              # Sec. II
IM = d * math.sqrt(Phi * rhop / P) * U / H  # Eq. 3, rho = Phi rho_p
m = rhop * math.pi * d ** 3 / 6
kn = E * d / 2                              # App. B, Eq. 12
beta = abs(math.log(e)) / math.sqrt(math.log(e) ** 2 + math.pi ** 2)
fc = math.sqrt(kn / (m / 2) * (1 - beta ** 2)) / (2 * math.pi)  # Sec. IV A: 1 / period
dt = V["dtfrac"] / fc
ngr = round(0.80 * L * H / (math.pi / 4 * d * d * (1 + 0.15 ** 2 / 3)))
nfl = round(L / d)
nlid = math.ceil(L / d - 1e-6) + 4
natoms = ngr + nfl + nlid


def check(label, ok, detail):
    print("%-34s %s  %s" % (label, "ok  " if ok else "FAIL", detail))
    if not ok:
        failures.append(label)


def rel(label, got, want, tol):
    check(label, abs(got - want) <= tol * abs(want), "%.17g vs %.17g (rel %.1e, tol %.0e)" % (got, want, abs(got / want - 1), tol))


def run(extra, tag, inp=None):
    """Runs the deck (or a wrapper) with V and extra; returns RESULT/DEPOSIT values, floats, stdout."""
    args = [sable, "-in", inp or deck, "-log", "none"]
    for k, v in list(V.items()) + list(extra.items()):
        args += ["-var", k, str(v)]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    p = subprocess.run(args, cwd=work, capture_output=True, text=True, env=env)
    check(tag + ": exit 0", p.returncode == 0, "rc %d" % p.returncode)
    if p.returncode != 0:
        sys.exit("%s: %s failed (%d):\n%s\n%s" % (name, " ".join(args), p.returncode, p.stdout[-3000:], p.stderr))
    res = {}  # strings, as printed; a key printed again: the later value
    for kv in screen.key_lines(p.stdout, "DEPOSIT"):
        res.update({"DEPOSIT." + k: v for k, v in kv.items()})
    for kv in screen.key_lines(p.stdout, "RESULT"):
        res.update(kv)
    f = {}
    bad = []
    for k, v in res.items():
        try:
            f[k] = float(v)
        except ValueError:
            bad.append(k)
            continue
        if not math.isfinite(f[k]):
            bad.append(k)
    check(tag + ": RESULT values finite", not bad and len(res) > 0, "%d values%s" % (len(res), (", bad: %s" % bad) if bad else ""))
    return res, f, p.stdout


def loops(out):
    """(steps, atoms, neighbour builds) of each run's 'Loop time' line and the 'Total # of neighbors' values."""
    lp = [(int(n), int(m), int(b)) for _, n, m, _, b in screen.SABLE_LOOP.findall(out)]
    nb = [int(x) for x in re.findall(r"Total # of neighbors = (\d+)", out)]
    return lp, nb


def shear_checks(tag, f, out, with_deposit=True):
    """Atoms, lid speed, balances: every case's checks of one shear run."""
    lp, _ = loops(out.split("RESULT lid_Fy_Fc=")[0])
    shear_atoms = [a for _, a, _ in lp[-2:]]  # the deck's last two runs: the shear's transient and recording
    check(tag + ": atoms constant", int(f["grains"]) == ngr and int(f["atoms"]) == natoms and shear_atoms == [natoms] * 2
          and (not with_deposit or int(f["DEPOSIT.grains"]) == ngr),
          "grains %d atoms %d, shear runs %s (want %d + %d + %d)" % (f["grains"], f["atoms"], shear_atoms, ngr, nfl, nlid))
    rel(tag + ": lid speed (end)", f["U_lid_end"], U, 1e-12)
    check(tag + ": lid speed (samples)", f["U_lid_dev"] <= 1e-12 * U, "mean |u - U| %.3g m/s" % f["U_lid_dev"])
    fl, fle = f["floor_Fy_Fc"], f["floor_Fy_Fc_err"]
    check(tag + ": floor carries Fc", fle > 0 and abs(fl - 1) <= 3 * fle, "%.5f +- %.5f (%.2f errors)" % (fl, fle, abs(fl - 1) / fle))
    li, lie = f["lid_Fy_Fc"], f["lid_Fy_Fc_err"]
    check(tag + ": lid net force 0", lie > 0 and abs(li) <= 3 * lie, "%.5f +- %.5f (%.2f errors)" % (li, lie, abs(li) / lie))


def hd_within(tag, f, key, tol):
    check("%s: %s within %g %%" % (tag, key, 100 * tol), abs(f[key] / V["Hd"] - 1) <= tol, "%.4f vs %d" % (f[key], V["Hd"]))


for fn in os.listdir(work):
    if fn.endswith(".restart") or fn.endswith(".h5") or fn.endswith(".txt"):
        os.remove(os.path.join(work, fn))

if case == "np100":
    wrapper = os.path.join(work, "np100_overlap.in")
    with open(wrapper, "w") as w:
        w.write("# written by tests/cavity_hard.py: the deck unchanged, then 8100 more steps recording the\n"
                "# largest grain-grain and grain-wall overlap of every step\n"
                "include %s\n"
                "compute ovp all pair/gran/local delta\n"
                "compute ovw all wall/gran/local delta\n"
                "compute ovm all reduce max c_ovp c_ovw\n"
                "fix ovr all ave/time 1 1 1 c_ovm[1] c_ovm[2] file np100_overlap.txt\n"
                "run 8100\n" % deck)
    r, f, out = run({"out": "np100"}, "np100", wrapper)
    for k, want in [("P", P), ("E", E), ("U", U), ("Fc", Fc), ("fc", fc), ("dt", dt)]:
        rel("np100: " + k, f[k], want, 1e-12)
    used = [float(x) for x in re.findall(r"Time-step check: dt = (\S+) s", out)]
    check("np100: dt used", len(used) > 0 and all(abs(u / dt - 1) < 1e-5 for u in used), "%s vs %.6g" % (used[:1], dt))
    shear_checks("np100", f, out)
    for k in ("DEPOSIT.H/d", "Hd_measured"):
        hd_within("np100", f, k, 0.05)
    ov = np.loadtxt(os.path.join(work, "np100_overlap.txt"))
    bound = 5 * Fc / kn / d
    gg, gw = ov[:, 1].max() / d, ov[:, 2].max() / d
    check("np100: max overlap / d", len(ov) >= 8100 and max(gg, gw) < bound,
          "grains %.3e (%.2f Fc/k_n), wall %.3e (%.2f Fc/k_n), bound 5 Fc/(k_n d) = %.3e, %d steps"
          % (gg, gg * d * kn / Fc, gw, gw * d * kn / Fc, bound, len(ov)))
    print("RESULT F_PLd=%s F_PLd_err=%s Hd_measured=%s overlap_max_d=%.4g steps=%s" %
          (r["F_PLd"], r["F_PLd_err"], r["Hd_measured"], max(gg, gw), r["steps"]))

elif case == "nu20":
    r0, f0, _ = run({"phase": "deposit", "tshear": 0.101}, "nu20 deposit")
    hd_within("nu20 deposit", f0, "DEPOSIT.H/d", 0.05)
    check("nu20 deposit: grains", int(f0["DEPOSIT.grains"]) == ngr, "%d vs %d" % (f0["DEPOSIT.grains"], ngr))
    runs = {}
    for tag, ts in (("short", 0.0252), ("long", 0.101)):
        r, f, out = run({"phase": "shear", "tshear": ts, "contacts": 1, "out": "nu20_" + tag}, "nu20 " + tag)
        shear_checks("nu20 " + tag, f, out, with_deposit=False)
        hd_within("nu20 " + tag, f, "Hd_measured", 0.05)
        lp, nb = loops(out)
        boxes = re.findall(r"ITEM: BOX BOUNDS[^\n]*\n([^\n]*)\n([^\n]*)\n([^\n]*)\n", open(os.path.join(work, "nu20_%s_contacts.txt" % tag)).read())
        runs[tag] = {"f": f, "loops": lp, "neigh": nb, "boxes": boxes,
                     "travel_d": f["U_lid_end"] * f["steps"] * f["dt"] / d}
    s, l = runs["short"], runs["long"]
    check("nu20: atoms same in both runs", [a for _, a, _ in s["loops"][-2:]] == [a for _, a, _ in l["loops"][-2:]] == [natoms] * 2,
          "%s / %s" % ([a for _, a, _ in s["loops"][-2:]], [a for _, a, _ in l["loops"][-2:]]))
    # the box the deck's formulas give whatever the travel: x, the lid's period n_lid d = L + 4 d
    # centred on the cavity; y, 0 to 3 d over the deposit's starting lattice (or H + 3 d)
    a0 = 1.25 * d
    ytop = 2 * d + math.ceil(ngr / math.floor((L - 1.2 * d) / a0)) * a0
    want = [(L - nlid * d) / 2, (L + nlid * d) / 2, 0.0, max(ytop, H + 3 * d) + 3 * d]
    allb = s["boxes"] + l["boxes"]
    got = [float(x) for x in (allb[0][0] + " " + allb[0][1]).split()] if allb else [0.0] * 4
    check("nu20: box fixed, same in both runs", len(s["boxes"]) > 10 and len(l["boxes"]) > 4 * len(s["boxes"]) - 50
          and len(set(allb)) == 1 and all(abs(a - b) <= 1e-6 * L for a, b in zip(got, want)),
          "%d + %d records, %d distinct box(es): x %s, y %s; want x %.6g %.6g, y %.6g %.6g"
          % (len(s["boxes"]), len(l["boxes"]), len(set(allb)), allb[0][0] if allb else "-", allb[0][1] if allb else "-", *want))
    lid_rate = 1 / math.ceil(0.25 * d / (U * dt))  # the lid's grains alone: a rebuild every ceil(skin/2 / (U dt)) steps
    rate = {}
    for tag, x in runs.items():
        steps, _, builds = x["loops"][-1]  # the recording's run
        rate[tag] = builds / steps
        check("nu20 %s: rebuilds/step vs lid's" % tag, 1.0 <= rate[tag] / lid_rate <= 1.5,
              "%d builds / %d steps = %.5f, the lid's %.5f (x%.3f)" % (builds, steps, rate[tag], lid_rate, rate[tag] / lid_rate))
    check("nu20: rebuilds/step same (20 %)", abs(rate["long"] / rate["short"] - 1) <= 0.2,
          "long / short %.4f" % (rate["long"] / rate["short"]))
    nbs, nbl = s["neigh"][-1], l["neigh"][-1]
    check("nu20: neighbour pairs same (20 %)", abs(nbl / nbs - 1) <= 0.2, "%d vs %d" % (nbs, nbl))
    check("nu20: lid travel", l["travel_d"] >= 150 and l["travel_d"] >= 4 * s["travel_d"],
          "%.1f d and %.1f d (U t, lid period %d d)" % (s["travel_d"], l["travel_d"], nlid))
    print("RESULT travel_d=%.1f,%.1f rebuilds_per_step=%.5f,%.5f lid_rate=%.5f neighbours=%d,%d F_PLd=%s,%s" %
          (s["travel_d"], l["travel_d"], rate["short"], rate["long"], lid_rate, nbs, nbl, s["f"]["F_PLd"], l["f"]["F_PLd"]))

else:  # dilute
    r, f, out = run({"out": "dil"}, "dilute")
    rel("dilute: I_M (formula)", f["I_M"], IM, 1e-12)
    check("dilute: I_M = 0.5", abs(IM - 0.5) <= 1e-5, "%.7f" % IM)
    shear_checks("dilute", f, out)
    hd_within("dilute", f, "DEPOSIT.H/d", 0.05)
    cols, vals, _ = h5.read_series(os.path.join(work, "dil_series.h5"))
    yl, flid = vals[:, cols.index("v_yl")], vals[:, cols.index("v_flid")]
    free = float(np.mean(np.abs(flid / Fc + 1) < 1e-9))
    check("dilute: lid contacts intermittent", free > 0.2, "lid touches nothing in %.3f of %d samples" % (free, len(flid)))
    check("dilute: wall contacts intermittent", f["F_zero"] > 0.15, "F_zero %.4f" % f["F_zero"])
    check("dilute: lid moves", np.std(yl) / d > 0.1, "std of the lid's y %.4f d" % (np.std(yl) / d))
    dil = f["Hd_measured"] / f["DEPOSIT.H/d"]
    check("dilute: bed dilates, stays in", 1.0 < dil < 1.15 and f["Hd_measured"] < 2 * V["Hd"],
          "H/d %.4f under shear, %.4f deposited (x%.4f), lid gap %.3f d" % (f["Hd_measured"], f["DEPOSIT.H/d"], dil, f["Hd_lid"]))
    print("RESULT I_M=%s F_zero=%s lid_free=%.4f yl_std_d=%.4f Hd=%s F_PLd=%s" %
          (r["I_M"], r["F_zero"], free, np.std(yl) / d, r["Hd_measured"], r["F_PLd"]))

sys.exit("%s: failed: %s" % (name, ", ".join(failures)) if failures else 0)
