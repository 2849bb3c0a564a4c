#!/usr/bin/env python3
"""The cost of fix ave/time ... hdf5 at one row a step (h5_record.in; issue 43 item 2).

For each sable binary given (e.g. before and after a change), runs h5_record.in
with rec 0 (no recorder), 1 (fix ave/time, no file) and 2 (the same writing HDF5),
interleaved, `--repeats` times, one thread, each in a fresh directory; prints the
loop times and the processes' CPU times (median, minimum and each repeat; on a
loaded machine the minima are the steadier) and the overheads (t2 - t1) / t1 and
(t2 - t0) / t0: the median of the repeats' and that of the minima. Not a test: timings vary
with the machine's load.
Usage: h5_record.py [--repeats 3] [--steps 100000] SABLE [SABLE ...]
"""
import argparse
import os
import shutil
import statistics
import tempfile

from sable_tools import runner  # the run and its own CPU time
from sable_tools.paths import repo_path
from sable_tools.readers import screen  # the loop times of sable's screen

DECK = repo_path("input_scripts", "bench", "h5_record.in")


def loop_time(sable, rec, steps):
    """The timed run's loop time (wall) and the whole process' CPU time (user + system)."""
    work = tempfile.mkdtemp(prefix="sable_h5rec_")
    try:
        m = runner.measured([sable, "-in", DECK, "-log", "none", "-var", "rec", str(rec), "-var", "steps", str(steps)],
                            work, os.path.join(work, "screen.txt"), env=runner.one_thread())
    finally:
        shutil.rmtree(work)
    if m.rc != 0:
        raise SystemExit(f"{sable} -var rec {rec}: exit status {m.rc}\n" + "\n".join(m.text.splitlines()[-15:]))
    return screen.loop_times(m.text)[-1], m.cpu  # the last run is the timed one


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("sable", nargs="+")
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--steps", type=int, default=100000)
    a = p.parse_args()
    t = {(s, r): [] for s in a.sable for r in (0, 1, 2)}
    c = {(s, r): [] for s in a.sable for r in (0, 1, 2)}
    for _ in range(a.repeats):
        for s in a.sable:
            for r in (0, 1, 2):
                wall, cpu = loop_time(s, r, a.steps)
                t[s, r].append(wall)
                c[s, r].append(cpu)
    for s in a.sable:
        print(s)
        report("loop time (wall)", t, s)
        report("process CPU time", c, s)


def report(what, t, s):
    print(" ", what)
    for r in (0, 1, 2):
        print("    rec %d: median %.3f s, min %.3f s (%s)" %
              (r, statistics.median(t[s, r]), min(t[s, r]), ", ".join("%.3f" % x for x in t[s, r])))
    for label, base in (("HDF5 over ave/time alone", 1), ("HDF5 + ave/time over none", 0)):
        o = [100 * (c - b) / b for b, c in zip(t[s, base], t[s, 2])]
        lo = 100 * (min(t[s, 2]) - min(t[s, base])) / min(t[s, base])
        print("    %s: median of repeats %.1f %%, of the minima %.1f %% (%s)" %
              (label, statistics.median(o), lo, ", ".join("%.1f" % x for x in o)))


if __name__ == "__main__":
    main()
