#!/usr/bin/env python3
"""Summarise a pair-pass trace (SABLE_PAIR_TRACE=file sable -in deck): where
the threaded pair pass's wall time goes and how the threads' finishing times
scatter from pass to pass.

    SABLE_PAIR_TRACE=trace.txt OMP_NUM_THREADS=2 build/sable -in deck -log none
    python3 -m sable_tools.bench.pair_trace [--last N] trace.txt

--last N: only the last N passes (a benchmark deck's timed run: its steps + 1).

Shares are of the threads' capacity (threads x wall time of the passes):
  plan     choosing the split (kept, re-split or new list) before the threads start
  phase A  cross entries, each by the thread of j's range (the later one); a
           barrier followed it until the i-side waited on a flag instead
  phase B  each thread's own range
  waiting  a thread done with phase B while another still works
"""
import sys

import numpy as np


def load(path):
    rows = [list(map(float, l.split())) for l in open(path) if l.strip() and not l.startswith("#")]
    d = np.array(rows)
    if d.ndim != 2 or d.shape[1] < 7 or (d.shape[1] - 3) % 4:
        sys.exit("%s: not a pair trace (plan kind wall, then 4 columns per thread)" % path)
    nt = (d.shape[1] - 3) // 4
    return d[:, 0], d[:, 1].astype(int), d[:, 2], d[:, 3:].reshape(len(d), nt, 4)


def autocorr(x, lag):
    x = x - x.mean()
    return float(np.corrcoef(x[:-lag], x[lag:])[0, 1]) if len(x) > lag + 2 else float("nan")


def summary(path, last=0):
    plan, kind, wall, th = (a[-last:] for a in load(path)) if last else load(path)
    n, nt = th.shape[0], th.shape[1]
    start, a_end, b_start, end = (th[:, :, k] for k in range(4))
    cap = nt * wall.sum()
    busy_a = (a_end - start).sum()
    busy_b = (end - b_start).sum()
    last = end.max(axis=1)  # the last thread done, per pass
    wait_b = (last[:, None] - end).sum()
    out = ["pair trace %s: %d passes, %d threads, wall %.3f ms per pass (median %.3f)"
           % (path, n, nt, 1e3 * wall.mean(), 1e3 * np.median(wall))]
    for k, name in ((0, "kept"), (1, "re-split"), (2, "new list")):
        m = kind == k
        if m.any():
            out.append("  plan %-8s %5d passes, %.4f ms each" % (name, m.sum(), 1e3 * plan[m].mean()))
    out.append("  share of the threads' capacity: plan %.1f %%, phase A (+ barrier) %.1f %% (phase A busy %.1f %%), "
               "phase B busy %.1f %%, phase B waiting %.1f %%, after the last thread %.1f %%"
               % (100 * nt * plan.sum() / cap, 100 * (b_start - plan[:, None]).sum() / cap, 100 * busy_a / cap,
                  100 * busy_b / cap, 100 * wait_b / cap, 100 * nt * (wall - last).sum() / cap))
    if nt >= 2:
        b = end - b_start  # phase B seconds per thread
        rel = (b[:, 0] - b[:, 1]) / b[:, :2].mean(axis=1)
        p = np.percentile(rel, [5, 25, 50, 75, 95])
        out.append("  phase B, thread 0 against thread 1, (b0 - b1) / mean per pass: percentiles 5/25/50/75/95 "
                   "%+.3f %+.3f %+.3f %+.3f %+.3f; std %.3f" % (*p, rel.std()))
        out.append("  its autocorrelation at lags 1, 2, 5, 10, 50 passes: %s"
                   % ", ".join("%.2f" % autocorr(rel, l) for l in (1, 2, 5, 10, 50)))
    return "\n".join(out)


if __name__ == "__main__":
    args = sys.argv[1:]
    last = 0
    if args[:1] == ["--last"] and len(args) >= 2:
        last, args = int(args[1]), args[2:]
    if not args:
        sys.exit(__doc__)
    for f in args:
        print(summary(f, last))
