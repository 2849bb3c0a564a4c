#!/usr/bin/python3
"""Rigid clumps against their grains free (issue 22: "thousands of small bodies
(3-disk clumps) cost about what their grains cost").

Runs clumps_2d.in (2D, the Mohr study's 3-disk clumps) and clumps.in (3D,
tumbling 3-sphere clumps) in sable, each as clumps (-var clumps 1: fix
rigid/small custom) and as the same grains free (-var clumps 0: nve/sphere),
interleaved, for each thread count. Prints particle-steps/s of the timed run
and the paired ratio free / clumps (1: a clump's grains cost what free grains
cost). The two scenes are not the same physics (clumps settle otherwise).

  python3 -m sable_tools.bench.bench_clumps [--repeats 3] [--threads 1,2] [--decks clumps_2d,clumps] [--grid NX,NY]
"""
import argparse
import os
import shutil
import statistics
import sys
import tempfile

from sable_tools import runner  # find_sable
from sable_tools.bench import bench  # run_engine, fmt_rate


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--decks", default="clumps_2d,clumps")
    ap.add_argument("--sable", default=None)
    ap.add_argument("--grid", default=None, metavar="NX,NY",
                    help="clumps_2d's lattice (nx, ny; default 128,16): a larger scene (use with --decks clumps_2d)")
    args = ap.parse_args()
    sable = runner.find_sable(args.sable)
    threads = [int(t) for t in args.threads.split(",")]
    decks = args.decks.split(",")
    tmp = tempfile.mkdtemp(prefix="sable-benchclumps-")
    rates = {}
    for rep in range(args.repeats):
        for deck in decks:
            for t in threads:
                for clumps in (1, 0):
                    wd = os.path.join(tmp, "%s_%d_%d_%d" % (deck, t, clumps, rep))
                    size = dict(clumps=clumps)
                    if args.grid:
                        size["nx"], size["ny"] = args.grid.split(",")
                    r = bench.run_engine("sable", sable, dict(deck=deck + ".in"), size, t, wd, 3600,
                                         "final.dump")
                    if not r["ok"]:
                        print("FAILED %s clumps %d:\n%s" % (deck, clumps, r.get("tail")))
                        return 1
                    rates.setdefault((deck, t, clumps), []).append(r["psps"])
                    print("repeat %d %-9s %d thread(s) %-6s %s particle-steps/s (%d atoms, load %.1f)" %
                          (rep + 1, deck, t, "clumps" if clumps else "free", bench.fmt_rate(r["psps"]),
                           r["atoms"], r["load_before"]), flush=True)
    print("\nfree / clumps per grain-step, paired by repeat (median; repeats):")
    for deck in decks:
        for t in threads:
            ratios = [f / c for f, c in zip(rates[(deck, t, 0)], rates[(deck, t, 1)])]
            print("  %-9s %d thread(s): %.2f (%s); clumps %s, free %s particle-steps/s" %
                  (deck, t, statistics.median(ratios), ", ".join("%.2f" % x for x in ratios),
                   bench.fmt_rate(statistics.median(rates[(deck, t, 1)])),
                   bench.fmt_rate(statistics.median(rates[(deck, t, 0)]))))
    shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
