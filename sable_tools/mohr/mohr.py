#!/usr/bin/env python3
"""petit2017 Mohr study: run mohr.in, reduce a run, run the pre-registered sweep.

    mohr.py run  DIR [--var K V ...]     run the deck in DIR, reduce, print RESULT
    mohr.py reduce-run DIR               reduce an existing run (result.json)
    mohr.py sweep [--only NAME,...] [--chunk K] [--dry] [--reverse]
                                         the runs of reference_runs/mohr/sweep/PLAN.md
                                         not started yet (K at most; one at a time; a
                                         second worker with --reverse takes them from the end)
    mohr.py reduce [--root R]            per point mean +- seed SE, the plan's tests,
                                         REPORT.md, points.csv (figures: mohr_figures.py)

A run's reduction (result.json): the deck's RESULT; sable-analyze mohr-cycles (mu_M and C
of every cycle's loading circles, the +-0.5 % limit cycle); bulk-modulus (Eq. 6) on the
last cycle's loading states and fit-offset-power (Eq. 7: K0, a, alpha; sigma0 = the
smallest sigma_yy of those increments); Z, porosity, S and the overlaps at the last peak.
"""
import argparse
import json
import os
import shutil
import sys
import time

from sable_tools.readers.yade import read_states  # the states files' one reader
from sable_tools import runner  # sable's run into its log
from sable_tools.paths import REPO as ROOT
from sable_tools.readers import analyze as analyze_csv, dump, screen  # sable-analyze's CSV; the peak's contacts; the RESULT line

HERE = os.path.join(ROOT, "input_scripts", "mohr")  # mohr.in
DECK = os.path.join(HERE, "mohr.in")
SWEEP = os.path.join(ROOT, "reference_runs", "mohr", "sweep")

# ---- the pre-registered design (reference_runs/mohr/sweep/PLAN.md says why)
SEEDS = [32452843, 15485867, 49979687, 86028121, 67867967]
BASE = {"N": 1000, "mu": 0.3, "rotation": 0, "delta": 0.5, "cycles": 15, "damp": "cundall"}
# the damping follow-up (PLAN_damping.md): 10 new seeds, both damping choices
SEEDS_DAMPING2 = [10000019, 10000079, 10000103, 10000121, 10000139, 10000141, 10000169, 10000189, 10000223,
                  10000229]
SWEEP_SEEDS = {"damping2": SEEDS_DAMPING2}
SWEEP_ROOT = {"damping2": os.path.join(SWEEP, "damping2"),  # kept apart: the main plan's points keep their 5 seeds
              "clumps": os.path.join(SWEEP, "clumps")}
SWEEPS = {
    # cheapest and most important first: the locked-rotation friction series (Fig. 9)
    "mu_locked": [dict(mu=m) for m in (0.1, 0.3, 0.5, 1.0)],
    "damping": [dict(damp="restitution")],
    "delta": [dict(delta=d) for d in (0.0, 0.2, 0.7)],
    "mu_free": [dict(mu=m, rotation=1) for m in (0.1, 0.3, 0.5, 1.0)],
    "damping2": [dict(), dict(damp="restitution")],
    # Fig. 16 (PLAN_clumps.md): rigid 3-disk clumps, 400 of them (1200 disks)
    "clumps": [dict(beta=b, rotation=1, mu=m, N=400) for b in (0.25, 0.62, 0.90) for m in (0.1, 0.3, 0.5, 1.0)],
}


def point_name(v):
    name = "mu{mu}_rot{rotation}_d{delta}_{damp}_N{N}_c{cycles}".format(**v)
    return name + (f"_beta{v['beta']}" if v.get("beta", 0) else "")


def sweep_runs(only=None):
    """(name, vars, seed, root) in the plan's order: sweep by sweep, seed-major inside one."""
    out, seen = [], set()
    for sname, points in SWEEPS.items():
        if only and sname not in only:
            continue
        for seed in SWEEP_SEEDS.get(sname, SEEDS):
            for p in points:
                v = dict(BASE, **p)
                key = (point_name(v), seed, sname in SWEEP_ROOT)
                if key in seen:
                    continue
                seen.add(key)
                out.append((key[0], v, seed, SWEEP_ROOT.get(sname, SWEEP)))
    return out


def tool(name):
    p = runner.built(name)
    if not os.path.exists(p):
        sys.exit(f"mohr.py: {name} not found under {ROOT}/build (build the project first)")
    return p


def read_result(log):
    with open(log) as f:
        lines = screen.key_lines(f.read(), "RESULT")
    if not lines:
        raise RuntimeError(f"{log}: no RESULT line (the run did not finish)")
    return {k: (float(v) if k not in ("cycles", "states", "capped", "steps") else int(float(v)))
            for k, v in lines[-1].items()}


def analyze(args, cwd):
    tool("sable-analyze")  # stops with the build hint when absent
    r = runner.analyze(args, cwd)
    if r.returncode:
        raise RuntimeError(f"sable-analyze {' '.join(args)}: {r.stderr.strip()}")
    return r.stdout


BIG = ("log.txt", "mohr_states.txt", "mohr_peak_c1.txt", "mohr_peak_last.txt")


KEEP = ("STATE ", "PEAK ", "RESULT ", "ERROR", "WARNING", "Warning", "fix halt")


def store(d):
    """A sweep run as committed: the big text files gzipped, the log trimmed to its set-up (up to
    the first run) and its STATE, PEAK, RESULT, halt and warning lines (the thermo tables of
    ~800 runs repeat what the states file holds), the packing (from the seed) dropped."""
    import gzip
    for n in BIG:
        p = os.path.join(d, n)
        if os.path.exists(p):
            with open(p, "rb") as f:
                data = f.read()
            if n == "log.txt":
                lines = data.decode(errors="replace").splitlines(True)
                first = next((i for i, l in enumerate(lines) if l.lstrip().startswith("step ")), len(lines))
                data = "".join(lines[:first] + [l for l in lines[first:] if l.startswith(KEEP)]).encode()
            with gzip.open(p + ".gz", "wb", compresslevel=9) as g:
                g.write(data)
            os.remove(p)
    for n in ("mohr_pack.dump", "bulk.csv"):
        if os.path.exists(os.path.join(d, n)):
            os.remove(os.path.join(d, n))


def unstore(d):
    import gzip
    for n in BIG:
        p = os.path.join(d, n)
        if os.path.exists(p + ".gz") and not os.path.exists(p):
            with gzip.open(p + ".gz", "rb") as g, open(p, "wb") as f:
                shutil.copyfileobj(g, f)


def reduce_run(d, out="mohr"):
    """Reduce the run in folder d (deck outputs with prefix out) into d/result.json."""
    unstore(d)
    res = read_result(os.path.join(d, "log.txt"))
    meta, rows = read_states(os.path.join(d, f"{out}_states.txt"))
    st = f"{out}_states.txt"
    analyze(["mohr-cycles", st, "--sxx", "sxx", "--syy", "syy", "--cycle", "cycle", "--loading", "loading",
             "--out", "cycles.csv"], d)
    cyc = analyze_csv.rows(os.path.join(d, "cycles.csv"))
    with open(os.path.join(d, "cycles.csv")) as f:
        lim = [l.split(":", 1)[1].strip() for l in f if l.startswith("# limit_cycle:")]
    analyze(["bulk-modulus", st, "--syy", "syy", "--sxx", "sxx", "--eyy", "eps", "--cycle", "cycle",
             "--loading", "loading", "--out", "bulk.csv"], d)
    bulk = analyze_csv.rows(os.path.join(d, "bulk.csv"))
    last = max(int(float(r["cycle"])) for r in rows)
    kl = [r for r in bulk if int(float(r["cycle"])) == last]
    with open(os.path.join(d, "bulk_last.csv"), "w") as f:
        f.write("syy,K\n" + "".join(f"{r['syy']},{r['K']}\n" for r in kl))
    fit = {}
    try:
        analyze(["fit-offset-power", "bulk_last.csv", "--x", "syy", "--y", "K", "--out", "eq7.csv"], d)
        fit = {k: float(v) for k, v in analyze_csv.rows(os.path.join(d, "eq7.csv"))[0].items()}
    except RuntimeError as e:  # too few increments or no convergence: reported, not hidden
        fit = {"error": str(e)}
    phimin = {}
    for tag, f, mu_m in (("c1", f"{out}_peak_c1.txt", float(cyc[0]["mu_M"])), ("last", f"{out}_peak_last.txt",
                                                                              float(cyc[-1]["mu_M"]))):
        phimin[tag] = phi_min_eq9(d, f, float(meta["mu"]), mu_m)
    peak = [r for r in rows if int(r["cycle"]) == last and r["loading"] == 1][-1]
    first_peak = [r for r in rows if int(r["cycle"]) == 1 and r["loading"] == 1][-1]
    red = {
        "dir": os.path.relpath(d, ROOT), "meta": meta, "result": res,
        "mu_M": [float(c["mu_M"]) for c in cyc], "mu_M_err": [float(c["mu_M_err"]) for c in cyc],
        "C": [float(c["C"]) for c in cyc],
        "limit_cycle": lim[0] if lim else "none",
        "mu_M_first": float(cyc[0]["mu_M"]), "mu_M_last": float(cyc[-1]["mu_M"]),
        "mu_M_last3": sum(float(c["mu_M"]) for c in cyc[-3:]) / len(cyc[-3:]),
        "K_peak": float(kl[-1]["K"]) if kl else float("nan"),
        "syy_peak": peak["syy"], "sxx_peak": peak["sxx"],
        "Z_peak": peak["Z"], "porosity_peak": peak["porosity"], "S_peak": peak["S"],
        "dmax_peak": peak["dmax"], "dmean_peak": peak["dmean"],
        "Z_end": rows[-1]["Z"], "porosity_end": rows[-1]["porosity"], "syy_end": rows[-1]["syy"],
        "Z_first_peak": first_peak["Z"], "S_first_peak": first_peak["S"],
        "Z_initial": rows[0]["Z"], "porosity_initial": rows[0]["porosity"], "S_initial": rows[0]["S"],
        "K0": fit.get("K0", float("nan")), "a": fit.get("a", float("nan")), "alpha": fit.get("alpha", float("nan")),
        "alpha_err": fit.get("alpha_err", float("nan")), "eq7_r_squared": fit.get("r_squared", float("nan")),
        "eq7_error": fit.get("error", ""),
        "capped": res["capped"], "states": res["states"], "PS_per_s": res["PS_per_s"],
        "phi_min_c1_deg": phimin["c1"], "phi_min_last_deg": phimin["last"],
    }
    with open(os.path.join(d, "result.json"), "w") as f:
        json.dump(red, f, indent=1)
    return red


def phi_min_eq9(d, peak, mu, mu_m):
    """Eq. 9 inverted (sable-analyze phi-min-eq9) with P(phi) from a peak's contact rows (dump
    local: phi is the third value); nan where no phi_min reaches mu_m."""
    path = os.path.join(d, peak)
    if not os.path.exists(path):
        return float("nan")
    with open(os.path.join(d, "phi.csv"), "w") as f:
        f.write("phi\n" + "".join(repr(x) + "\n" for x in dump.local_column(path, 2).tolist()))
    try:
        analyze(["phi-min-eq9", "--mu", repr(mu), "--mu-m", repr(mu_m), "phi.csv", "--phi", "phi", "--out", "phimin.csv"], d)
        v = float(analyze_csv.rows(os.path.join(d, "phimin.csv"))[0]["phi_min_deg"])
    except RuntimeError:
        v = float("nan")
    for n in ("phi.csv", "phimin.csv"):
        if os.path.exists(os.path.join(d, n)):
            os.remove(os.path.join(d, n))
    return v


def run_case(d, var, sable=None, quiet=False):
    os.makedirs(d, exist_ok=True)
    cmd = [sable or tool("sable"), "-in", DECK, "-log", "none"]
    for k, v in var.items():
        cmd += ["-var", str(k), str(v)]
    t0 = time.time()
    rc = runner.run_logged(cmd, d, os.path.join(d, "log.txt"))
    if rc:
        raise RuntimeError(f"{d}: sable exited {rc} (see log.txt)")
    red = reduce_run(d)
    red["wall_s"] = time.time() - t0
    with open(os.path.join(d, "result.json"), "w") as f:
        json.dump(red, f, indent=1)
    for p in ("log.sable",):
        if os.path.exists(os.path.join(d, p)):
            os.remove(os.path.join(d, p))
    return red


def result_line(red):
    r = red["result"]
    return ("RESULT muM={:.6g} muM_last={:.6g} C={:.6g} K0={:.6g} a={:.6g} alpha={:.6g} Z={:.5g} porosity={:.6g} "
            "S={:.6g} limit_cycle={} cycles={} states={} capped={} PS_per_s={:.4g}").format(
        red["mu_M_first"], red["mu_M_last"], red["C"][-1], red["K0"], red["a"], red["alpha"], r["Z"],
        r["porosity"], r["S"], red["limit_cycle"], r["cycles"], r["states"], r["capped"], r["PS_per_s"])


def cmd_sweep(a):
    runs = sweep_runs(a.only.split(",") if a.only else None)
    todo = [(n, v, s, r) for n, v, s, r in runs if not os.path.exists(os.path.join(r, "runs", n, f"s{s}"))]
    print(f"sweep: {len(runs)} runs in the plan, {len(todo)} to do" + (f", this chunk {a.chunk}" if a.chunk else ""))
    if a.dry:
        for n, v, s, r in todo:
            print(" ", os.path.relpath(r, SWEEP), n, s)
        return
    sable = os.path.join("/tmp", f"sable_mohr_sweep{os.getpid()}")  # a copy: a relink of build/sable must not kill a run
    shutil.copy2(tool("sable"), sable)
    if a.reverse:
        todo.reverse()
    done = 0
    for i, (n, v, s, r) in enumerate(todo):
        if a.chunk and done >= a.chunk:
            break
        d = os.path.join(r, "runs", n, f"s{s}")
        try:  # a second worker (--reverse) may have taken or finished it
            os.makedirs(d)
        except FileExistsError:
            continue
        done += 1
        t0 = time.time()
        try:
            red = run_case(d, dict(v, seed=s, out="mohr"), sable=sable)
        except RuntimeError as e:  # the run stopped: kept (log) and reported, the sweep goes on
            with open(os.path.join(d, "failed.txt"), "w") as f:
                f.write(str(e) + "\n")
            store(d)
            print(f"[{i + 1}/{len(todo)}] {n} seed {s}: FAILED ({e})", flush=True)
            continue
        store(d)
        print(f"[{i + 1}/{len(todo)}] {n} seed {s}: mu_M {red['mu_M_first']:.4f} -> {red['mu_M_last']:.4f}, "
              f"Z {red['Z_peak']:.3f}, alpha {red['alpha']:.3f}, capped {red['capped']}, {time.time() - t0:.0f} s",
              flush=True)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("dir")
    r.add_argument("--var", nargs=2, action="append", default=[], metavar=("K", "V"))
    rr = sub.add_parser("reduce-run")
    rr.add_argument("dir")
    s = sub.add_parser("sweep")
    s.add_argument("--only", default="")
    s.add_argument("--chunk", type=int, default=0)
    s.add_argument("--dry", action="store_true")
    s.add_argument("--reverse", action="store_true", help="from the plan's end (a second worker)")
    rd = sub.add_parser("reduce")
    rd.add_argument("--root", default=SWEEP)
    rd.add_argument("--rereduce", action="store_true", help="reduce every stored run again first")
    a = p.parse_args()
    if a.cmd == "run":
        print(result_line(run_case(os.path.abspath(a.dir), dict(a.var))))
    elif a.cmd == "reduce-run":
        print(result_line(reduce_run(os.path.abspath(a.dir))))
    elif a.cmd == "sweep":
        cmd_sweep(a)
    else:
        import glob
        from sable_tools.mohr import mohr_report
        if a.rereduce:
            for f in sorted(glob.glob(os.path.join(a.root, "runs", "*", "s*", "result.json"))):
                d = os.path.dirname(f)
                with open(f) as fh:
                    wall = json.load(fh).get("wall_s")
                red = reduce_run(d)
                red["wall_s"] = wall
                with open(f, "w") as fh:
                    json.dump(red, fh, indent=1)
                store(d)
        mohr_report.report(a.root, {k: v for k, v in SWEEPS.items() if k not in SWEEP_ROOT}, BASE, SEEDS, point_name)
        if os.path.isdir(os.path.join(a.root, "damping2")):
            mohr_report.report_damping(a.root, SEEDS_DAMPING2, SEEDS, point_name, BASE)
        if os.path.isdir(os.path.join(a.root, "clumps")):
            mohr_report.report_clumps(a.root, point_name, BASE)


if __name__ == "__main__":
    main()
