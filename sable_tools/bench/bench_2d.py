#!/usr/bin/python3
"""The 2D and frozen-rotation kernels on one scene (issue 22, item 4).

Runs the shear_2d bench deck (input_scripts/bench/shear_2d.in: a dense 2D layer
sheared between a floor and a moving lid, periodic in x) in sable four ways:

  full3d      3D contact kernel + enforce2d      (-var kernels full)
  plane2d     2D kernel                          (the default in 2D)
  full_nve    3D kernel, fix nve (no rotation)   (-var kernels full -var integ nve)
  frozen2d    2D kernel without rotation, fix nve (-var integ nve)

full3d and plane2d are the same physics (bit for bit, tests/unit/test_two_d.cpp),
as are full_nve and frozen2d; frozen against free rotation (frozen2d vs plane2d)
is a different scene (grains that cannot turn). Prints particle-steps/s of the
timed run (median of the repeats, repeats interleaved) and the ratios, and checks
that the equivalent pairs end in the same final state (dumps compared).

  python3 -m sable_tools.bench.bench_2d [--repeats 3] [--threads 1] [--nx 100] [--ny 25]
"""
import argparse
import os
import shutil
import statistics
import sys
import tempfile

from sable_tools import runner  # find_sable
from sable_tools.bench import bench  # run_engine, compare_dumps

MODES = [
    ("full3d", dict(kernels="full", integ="nve/sphere")),
    ("plane2d", dict(kernels="auto", integ="nve/sphere")),
    ("full_nve", dict(kernels="full", integ="nve")),
    ("frozen2d", dict(kernels="auto", integ="nve")),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--nx", type=int, default=100, help="hex cells along x (2 grains each)")
    ap.add_argument("--ny", type=int, default=25)
    ap.add_argument("--prep", type=int, default=15000)
    ap.add_argument("--shear0", type=int, default=2000)
    ap.add_argument("--steps", type=int, default=4000, help="timed steps")
    ap.add_argument("--sable", default=None)
    ap.add_argument("--keep", action="store_true")
    args = ap.parse_args()
    sable = runner.find_sable(args.sable)
    case = dict(deck="shear_2d.in")
    size = dict(nx=args.nx, ny=args.ny, prep=args.prep, shear0=args.shear0, steps=args.steps)
    tmp = tempfile.mkdtemp(prefix="sable-bench2d-")
    rates = {m: [] for m, _ in MODES}
    pair_s = {m: [] for m, _ in MODES}  # seconds in the contact pass (pair share of the timed run)
    dumps = {}
    for rep in range(args.repeats):
        for mode, extra in MODES:
            wd = os.path.join(tmp, "%s_%d" % (mode, rep))
            r = bench.run_engine("sable", sable, case, {**size, **extra}, args.threads, wd, 3600, "final.dump")
            if not r["ok"]:
                print("FAILED %s:\n%s" % (mode, r.get("tail")))
                return 1
            rates[mode].append(r["psps"])
            pair_s[mode].append(r["loop_s"] * r.get("split", {}).get("pair", float("nan")) / 100)
            dumps[mode] = r["dump"]
            print("repeat %d %-9s %s particle-steps/s  (%d atoms, %d steps, load %.1f)" %
                  (rep + 1, mode, bench.fmt_rate(r["psps"]), r["atoms"], r["steps"], r["load_before"]), flush=True)
    med = {m: statistics.median(v) for m, v in rates.items()}
    print("\nshear_2d nx %d ny %d, %d timed steps, %d thread(s), median of %d:" %
          (args.nx, args.ny, args.steps, args.threads, args.repeats))
    for m, _ in MODES:
        print("  %-9s %s particle-steps/s  (repeats: %s)" %
              (m, bench.fmt_rate(med[m]), ", ".join(bench.fmt_rate(x) for x in rates[m])))

    for m, _ in MODES:
        print("  %-9s contact pass %.3f s (median; repeats %s)" %
              (m, statistics.median(pair_s[m]), ", ".join("%.3f" % x for x in pair_s[m])))

    def paired(a, b, table=rates):  # per-repeat ratio (runs close in time), median
        return statistics.median(x / y for x, y in zip(table[a], table[b]))
    print("  2D kernel / 3D kernel + enforce2d    (same physics):   %.3f" % paired("plane2d", "full3d"))
    print("  frozen 2D / full 3D, both fix nve    (same physics):   %.3f" % paired("frozen2d", "full_nve"))
    print("  frozen 2D / 2D with rotation         (different scene): %.3f" % paired("frozen2d", "plane2d"))
    print("  frozen 2D / 3D kernel + enforce2d    (all savings):    %.3f" % paired("frozen2d", "full3d"))
    print("  contact pass time, full3d / plane2d: %.3f; full_nve / frozen2d: %.3f" %
          (paired("full3d", "plane2d", pair_s), paired("full_nve", "frozen2d", pair_s)))
    for a, b in (("full3d", "plane2d"), ("full_nve", "frozen2d")):
        same, nlines, maxd = bench.compare_dumps(dumps[a], dumps[b])
        print("  final state %s vs %s: %s" % (a, b, "identical dumps" if same else
                                             "%d lines differ, max |difference| %.3g" % (nlines, maxd)))
    if not args.keep:
        shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
