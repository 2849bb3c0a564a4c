#!/usr/bin/python3
"""sable vs LIGGGHTS benchmark (issue 3, item 3). Standard library only.

Runs each benchmark deck of input_scripts/bench/ unchanged in sable and in
LIGGGHTS (one process each), several repeats, parses the LAST run's loop time
of each code, and prints / writes a table: particle-steps/s (median of the
repeats, per sable thread count), the ratio sable / LIGGGHTS, both codes' time
splits, peak memory (max RSS from os.wait4), neighbour builds and contacts per
grain of the final state.

    python3 -m sable_tools.bench.bench [--cases a,b,c,d] [--repeats 3]
        [--threads 1,2] [--sable build/sable] [--quick] [--determinism]

See input_scripts/bench/README.md.
"""

import argparse
import datetime
import hashlib
import json
import os
import re
import shutil
import socket
import statistics
import subprocess
import sys
import tempfile
import threading

from sable_tools import runner  # where sable is; LIGGGHTS unbuffered
from sable_tools.paths import REPO
from sable_tools.readers import screen  # the timing block of each code's screen
from sable_tools.readers.dump import read_last_dump

HERE = os.path.join(REPO, "input_scripts", "bench")  # the decks and the tables written beside them

# Benchmark cases. `vars` are the full sizes, `quick` tiny ones for a smoke test
# (seconds). The decks print a "BENCH ..." line at the end and write the final
# state to ${dumpfile} at full precision.
CASES = [
    dict(key="a", name="bed_30k", deck="bed.in",
         vars=dict(nxy=23, nz=14, prep=8000, steps=2000),
         quick=dict(nxy=5, nz=3, prep=300, steps=200),
         what="settled 3D Hertz-Mindlin bed, periodic x/y, floor wall"),
    dict(key="b", name="bed_200k", deck="bed.in",
         vars=dict(nxy=60, nz=14, prep=8000, steps=1000),
         quick=dict(nxy=8, nz=3, prep=300, steps=200),
         what="same bed, 200 k grains (DRAM-bound)"),
    dict(key="c", name="shear_2d", deck="shear_2d.in",
         vars=dict(nx=400, ny=25, prep=15000, shear0=5000, steps=2000),
         quick=dict(nx=30, ny=5, prep=1000, shear0=200, steps=200),
         what="2D dense layer sheared by a moving top wall"),
    dict(key="d", name="drum", deck="drum.in",
         vars=dict(R=0.06, nzc=7, prep=20000, steps=2000),
         quick=dict(R=0.015, nzc=2, prep=500, steps=200),
         what="rotating drum (spinning zcylinder wall), flowing bed"),
    dict(key="e", name="drag_6k", deck="drag.in",
         vars=dict(nl=24, prep=4000, steps=2000, stl=os.path.join(HERE, "drag_cylinder.stl")),
         quick=dict(nl=6, prep=200, steps=100, stl=os.path.join(HERE, "drag_cylinder.stl")),
         what="832-triangle STL cylinder turning at 0.5 rev/s in a bed in a cylindrical container"),
    dict(key="f", name="box_20k", deck="box.in",
         vars=dict(n=27, nz=28, prep=4000, steps=2000),
         quick=dict(n=8, nz=8, prep=500, steps=200),
         what="monodisperse bed collapsing from a lattice into a closed box (5 walls, ~2.6 half-neighbours)"),
    dict(key="g", name="mono_16k", deck="poly.in",
         vars=dict(pd=0, n=16, nz=16, prep=12000, steps=2000),
         quick=dict(pd=0, n=3, nz=3, prep=1500, steps=200),
         what="settled bed, equal radii 1 mm, periodic x/y, floor wall (the reference of poly70_16k)"),
    dict(key="h", name="poly70_16k", deck="poly.in",
         vars=dict(pd=0.7, n=16, nz=16, prep=12000, steps=2000),
         quick=dict(pd=0.7, n=3, nz=3, prep=1500, steps=200),
         what="the same bed with radii uniform in 0.3-1.7 x the mean (70 % polydispersity, same mean volume)"),
]


def log(msg):
    print(msg, flush=True)


def fmt_rate(x):
    return "-" if x is None else "%.3g" % x


# ---------------------------------------------------------------- running ---

def run_engine(engine, exe, case, size_vars, threads, workdir, timeout, dumpname, launcher=()):
    """Runs one deck once (under `launcher`, e.g. mpirun -np 2, if given); returns the parsed numbers."""
    deck = os.path.join(HERE, case["deck"])
    args = [*launcher, exe, "-in", deck, "-log", "none"]
    for k, v in size_vars.items():
        args += ["-var", k, str(v)]
    args += ["-var", "dumpfile", dumpname]
    if engine == "sable":
        args += ["-var", "sable", "1"]  # decks with sable-only lines guard them with it
    cmd = runner.unbuffered(args)
    env = dict(os.environ)
    env["OMP_NUM_THREADS"] = str(threads)
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")  # mpirun in a root container
    os.makedirs(workdir, exist_ok=True)
    out_path = os.path.join(workdir, "out.txt")
    load0 = os.getloadavg()[0]
    hwm = [0]  # the peak resident set read while it runs (peak_rss_kb)
    comm = os.path.basename(exe)[:15]
    m = runner.measured(cmd, workdir, out_path, env=env, timeout=timeout,
                        watch=lambda pid: hwm.__setitem__(0, max(hwm[0], peak_rss_kb(pid, comm))))
    hwm_kb, ru, text = hwm[0], m.rusage, m.text
    r = dict(engine=engine, threads=threads, rc=m.rc, timed_out=m.timed_out, wall_s=round(m.wall, 3),
             cpu_s=round(m.cpu, 3),  # the process tree's user + system (mpirun: its ranks too)
             # run too short to be caught by the /proc polling: ru_maxrss, an upper bound
             maxrss_mb=round((hwm_kb or ru.ru_maxrss) / 1024.0, 1), maxrss_from="VmHWM" if hwm_kb else "ru_maxrss",
             ru_maxrss_mb=round(ru.ru_maxrss / 1024.0, 1),
             load_before=round(load0, 2),
             load_after=round(os.getloadavg()[0], 2), cmd=" ".join(args))
    r.update(screen.sable_loop(text) if engine == "sable" else screen.liggghts_loop(text))
    b = screen.tagged(text, "BENCH")  # the deck's last line: "BENCH natoms N ke ... "
    r["bench_line"] = b[-1] if b else None
    r["ok"] = r["rc"] == 0 and not m.timed_out and r.get("psps") is not None
    if not r["ok"]:
        r["tail"] = "\n".join(text.strip().splitlines()[-15:])
    r["dump"] = os.path.join(workdir, dumpname)
    return r


def peak_rss_kb(pid, comm):
    """VmHWM (peak resident set) of the running engine, read from /proc while it runs.

    os.wait4's ru_maxrss is not used for the table: Linux carries the peak RSS of
    the process image before exec (a fork of this Python process, which holds the
    dumps it parsed) into the child's ru_maxrss. VmHWM belongs to the address space
    of the exec'd program; readings are taken only once /proc/PID/comm names it."""
    try:
        with open("/proc/%d/comm" % pid) as f:
            if f.read().strip() != comm:
                return 0
        with open("/proc/%d/status" % pid) as f:
            m = re.search(r"VmHWM:\s*(\d+) kB", f.read())
        return int(m.group(1)) if m else 0
    except OSError:
        return 0


# ------------------------------------------------------------ final state ---

def read_dump(path):
    """Last snapshot of a text dump: box, periodic flags, atoms (id, radius, x, y, z)."""
    a, box, periodic = read_last_dump(path)
    atoms = list(zip(a["id"].astype(int).tolist(), a["radius"].tolist(), a["x"].tolist(), a["y"].tolist(),
                     a["z"].tolist()))
    return [tuple(b) for b in box.tolist()], periodic, atoms


def contacts_per_grain(path):
    """Grain-grain contacts (distance <= ri + rj, periodic images included) per grain."""
    box, per, atoms = read_dump(path)
    if not atoms:
        return None
    rmax = max(a[1] for a in atoms)
    L = [box[k][1] - box[k][0] for k in range(3)]
    cell = 2.0 * rmax * 1.0000001
    nc = [max(1, int(L[k] / cell)) for k in range(3)]
    size = [L[k] / nc[k] for k in range(3)]
    grid = {}
    pos = []
    for idx, (_, r, x, y, z) in enumerate(atoms):
        c = []
        for k, v in enumerate((x, y, z)):
            ck = int((v - box[k][0]) / size[k])
            ck = min(max(ck, 0), nc[k] - 1) if not per[k] else ck % nc[k]
            c.append(ck)
        c = tuple(c)
        grid.setdefault(c, []).append(idx)
        pos.append(c)
    offs = [(a, b, c) for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1)]
    pairs = 0
    for c, members in grid.items():
        seen = set()
        for o in offs:
            nb = []
            ok = True
            for k in range(3):
                v = c[k] + o[k]
                if per[k]:
                    v %= nc[k]
                elif v < 0 or v >= nc[k]:
                    ok = False
                nb.append(v)
            nb = tuple(nb)
            if not ok or nb in seen or nb not in grid:
                continue
            seen.add(nb)
            others = grid[nb]
            for i in members:
                _, ri, xi, yi, zi = atoms[i]
                for j in others:
                    if j <= i:
                        continue
                    _, rj, xj, yj, zj = atoms[j]
                    d = [xi - xj, yi - yj, zi - zj]
                    for k in range(3):
                        if per[k]:
                            d[k] -= L[k] * round(d[k] / L[k])
                    s = ri + rj
                    if d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= s * s:
                        pairs += 1
    return 2.0 * pairs / len(atoms)


def compare_dumps(a, b):
    """(identical bytes?, number of differing atom lines, max |difference| of any number)."""
    with open(a, "rb") as f:
        ba = f.read()
    with open(b, "rb") as f:
        bb = f.read()
    if ba == bb:
        return True, 0, 0.0
    la, lb = ba.decode().splitlines(), bb.decode().splitlines()
    ndiff, maxd = 0, 0.0
    for x, y in zip(la, lb):
        if x == y:
            continue
        ndiff += 1
        for u, v in zip(x.split(), y.split()):
            try:
                maxd = max(maxd, abs(float(u) - float(v)))
            except ValueError:
                pass
    ndiff += abs(len(la) - len(lb))
    return False, ndiff, maxd


# ---------------------------------------------------------------- context ---

def machine_info(sable, liggghts):
    info = dict(date=datetime.datetime.now().isoformat(timespec="seconds"), host=socket.gethostname(),
                nproc=os.cpu_count(), loadavg_start=os.getloadavg())
    try:
        with open("/proc/cpuinfo") as f:
            m = re.search(r"model name\s*:\s*(.*)", f.read())
            info["cpu"] = m.group(1).strip() if m else None
        with open("/proc/meminfo") as f:
            m = re.search(r"MemTotal:\s*(\d+)", f.read())
            info["mem_gb"] = round(int(m.group(1)) / 1048576, 1) if m else None
    except OSError:
        pass
    info["sable"] = sable
    info["liggghts"] = liggghts
    try:
        g = ["git", "--no-optional-locks", "-C", REPO]
        info["sable_commit"] = subprocess.run(g + ["rev-parse", "--short", "HEAD"], capture_output=True,
                                              text=True).stdout.strip()
        dirty = subprocess.run(g + ["status", "--porcelain", "--untracked-files=no"], capture_output=True,
                               text=True).stdout.strip()
        info["sable_tree"] = "modified" if dirty else "clean"
    except OSError:
        pass
    return info


def core_probe(sable):
    """sable_core_probe (built next to sable, input_scripts/bench/core_probe.cpp): what synchronising two
    threads costs now (cache-line round trip, OpenMP barrier and region, us); None where absent."""
    exe = os.path.join(os.path.dirname(sable), "sable_core_probe") if sable else None
    if not exe or not os.access(exe, os.X_OK):
        return None
    out, rc = runner.execute([exe], None, 120, env=dict(os.environ, OMP_NUM_THREADS="2"))
    if rc == -1:  # timed out or did not start
        return None
    m = re.search(r"round_trip_us ([\d.]+) barrier_us ([\d.]+) region_us ([\d.]+)", out)
    if not m:
        return None
    probe = dict(round_trip_us=float(m.group(1)), barrier_us=float(m.group(2)), region_us=float(m.group(3)))
    log("    core probe: round trip %(round_trip_us).3f us, barrier %(barrier_us).2f us, region %(region_us).2f us"
        % probe)
    return probe


def probe_cell(probes):
    """'0.09, 0.09, 0.34': the cache-line round trip of each repeat (us)."""
    trips = ["%.2f" % p["round_trip_us"] if p else "-" for p in probes or []]
    return ", ".join(trips) if any(t != "-" for t in trips) else "-"


def deck_hash(case):
    """SHA-1 of the deck's commands (comments and blank lines left out)."""
    with open(os.path.join(HERE, case["deck"])) as f:
        cmds = [" ".join(l.split("#")[0].split()) for l in f]
    return hashlib.sha1("\n".join(c for c in cmds if c).encode()).hexdigest()[:12]


# ---------------------------------------------------------------- reports ---

def split_str(split, keys):
    if not split:
        return "-"
    return " / ".join("%s %.0f" % (k, split.get(k, 0.0)) for k in keys if k in split)


def median_or_none(xs):
    xs = [x for x in xs if x is not None]
    return statistics.median(xs) if xs else None


def spread(xs):
    xs = [x for x in xs if x is not None]
    if len(xs) < 2:
        return ""
    m = statistics.median(xs)
    return " (±%.0f%%)" % (100.0 * (max(xs) - min(xs)) / 2 / m) if m else ""


def paired_speedup(runs, t, t1):
    """Median over repeats of PS/s with t threads / PS/s with t1 threads in the same repeat (run one
    after the other): less sensitive to the slow drifts of a shared machine than a ratio of medians."""
    by = {(r["repeat"], r["threads"]): r["psps"] for r in runs if r.get("psps")}
    q = [by[(k, t)] / by[(k, t1)] for (k, tt) in by if tt == t and (k, t1) in by]
    return dict(median=statistics.median(q), all=q) if q and t != t1 else None


def busy_pct(run, kind):
    b = (run.get("balance") or {}).get(kind)
    return 100.0 * b["mean"] / b["wall"] if b and b["wall"] > 0 else None


def summarize(results, threads):
    rows = []
    for name, res in results.items():
        row = dict(case=name, what=res["what"], vars=res["vars"])
        s_runs = [r for r in res["runs"] if r["engine"] == "sable" and r["ok"]]
        l_runs = [r for r in res["runs"] if r["engine"] == "liggghts" and r["ok"]]
        any_run = (s_runs or l_runs or [{}])[0]
        row["atoms"] = any_run.get("atoms")
        row["steps"] = any_run.get("steps")
        row["sable"] = {}
        for t in threads:
            rs = [r for r in s_runs if r["threads"] == t]
            if not rs:
                continue
            best = min(rs, key=lambda r: abs(r["psps"] - median_or_none([x["psps"] for x in rs])))
            row["sable"][t] = dict(psps=median_or_none([r["psps"] for r in rs]),
                                   spread=spread([r["psps"] for r in rs]), n=len(rs), split=best.get("split"),
                                   maxrss_mb=max(r["maxrss_mb"] for r in rs), builds=best.get("builds"),
                                   neighs_per_atom=best.get("neighs_per_atom"),
                                   paired=paired_speedup(s_runs, t, min(threads)),
                                   pair_busy=median_or_none([busy_pct(r, "pair") for r in rs]))
        if l_runs:
            best = min(l_runs, key=lambda r: abs(r["psps"] - median_or_none([x["psps"] for x in l_runs])))
            row["liggghts"] = dict(psps=median_or_none([r["psps"] for r in l_runs]),
                                   spread=spread([r["psps"] for r in l_runs]), n=len(l_runs),
                                   split=best.get("split"), maxrss_mb=max(r["maxrss_mb"] for r in l_runs),
                                   builds=best.get("builds"), neighs_per_atom=best.get("neighs_per_atom"),
                                   reused=res.get("liggghts_reused"))
        row["contacts"] = res.get("contacts", {})
        row["probes"] = res.get("probes")
        row["failures"] = [dict(engine=r["engine"], threads=r["threads"], rc=r["rc"], tail=r.get("tail"))
                           for r in res["runs"] if not r["ok"]]
        rows.append(row)
    return rows


def table_md(rows, threads, info, args):
    h = ["case", "atoms", "steps"]
    h += ["sable PS/s %dt" % t for t in threads]
    h += ["LIGGGHTS PS/s", *["ratio %dt" % t for t in threads]]
    multi = [t for t in threads if t != min(threads)]
    h += ["%dt / %dt paired (pair busy)" % (t, min(threads)) for t in multi]
    h += ["sable split (%)", "LIGGGHTS split (%)", "max RSS sable / LIGGGHTS (MB)",
          "nbr builds sable / LIGGGHTS", "contacts/grain sable / LIGGGHTS", "neighs/atom sable / LIGGGHTS"]
    if multi:
        h.append("core round trip, us (per repeat)")
    out = ["| " + " | ".join(h) + " |", "|" + "---|" * len(h)]
    for row in rows:
        lg = row.get("liggghts") or {}
        c = [row["case"], str(row["atoms"] or "-"), str(row["steps"] or "-")]
        for t in threads:
            s = row["sable"].get(t)
            c.append(fmt_rate(s["psps"]) + s["spread"] if s else "-")
        c.append(fmt_rate(lg.get("psps")) + lg.get("spread", "") + (" (reused)" if lg.get("reused") else ""))
        for t in threads:
            s = row["sable"].get(t)
            c.append("%.2f" % (s["psps"] / lg["psps"]) if s and lg.get("psps") else "-")
        for t in multi:
            s = row["sable"].get(t) or {}
            p = s.get("paired")
            c.append(("%.2f" % p["median"] + " (" + ", ".join("%.2f" % q for q in p["all"]) + ")" if p else "-") +
                     (" (%.0f%%)" % s["pair_busy"] if s.get("pair_busy") is not None else ""))
        tst = min(row["sable"]) if row["sable"] else None  # the split of the one-thread run
        st = row["sable"].get(tst)
        c.append(split_str(st and st["split"], ["pair", "neigh", "integrate", "fixes", "output"]) +
                 (" (%dt)" % tst if st and len(threads) > 1 else ""))
        c.append(split_str(lg.get("split"), ["Pair", "Neigh", "Comm", "Outpt", "Modify", "Other"]))
        srss = max((s["maxrss_mb"] for s in row["sable"].values()), default=None)
        c.append("%s / %s" % (srss if srss is not None else "-", lg.get("maxrss_mb", "-")))
        sb = st["builds"] if st else "-"
        c.append("%s / %s" % (sb, lg.get("builds", "-")))
        ct = row["contacts"]
        c.append("%s / %s" % (("%.2f" % ct["sable"]) if ct.get("sable") is not None else "-",
                              ("%.2f" % ct["liggghts"]) if ct.get("liggghts") is not None else "-"))
        nbs = st.get("neighs_per_atom") if st else None
        c.append("%s / %s" % ("%.2f" % nbs if nbs is not None else "-",
                              "%.2f" % lg["neighs_per_atom"] if lg.get("neighs_per_atom") is not None else "-"))
        if multi:
            c.append(probe_cell(row.get("probes")))
        out.append("| " + " | ".join(c) + " |")
    return "\n".join(out)


def write_report(path_md, path_json, rows, results, threads, info, args, title):
    md = [f"# {title}", "",
          f"Generated by `python3 -m sable_tools.bench.bench {' '.join(sys.argv[1:])}` on {info['date']}.", "",
          f"- machine: {info.get('host')}, {info.get('cpu')}, {info.get('nproc')} cores, "
          f"{info.get('mem_gb')} GB; load average at start {info['loadavg_start'][0]:.2f}, "
          f"at end {info.get('loadavg_end', [0])[0]:.2f}"
          + (" (the machine was busy: timings are noisy)" if max(info['loadavg_start'][0],
             info.get('loadavg_end', [0])[0]) > 0.5 else ""),
          f"- sable: `{info.get('sable')}` (commit {info.get('sable_commit')}, tree {info.get('sable_tree')}); "
          f"OMP_NUM_THREADS = {', '.join(map(str, threads))}",
          f"- LIGGGHTS: `{info.get('liggghts')}` {info.get('liggghts_version', '')}, one MPI process",
          f"- repeats: {args.repeats} (sable), {args.liggghts_repeats} (LIGGGHTS); PS/s = atoms x steps / loop "
          "time of the LAST run of the deck, median of the repeats (± half the spread)",
          "- ratio = sable PS/s / LIGGGHTS PS/s; split = each code's own timer breakdown of the timed run "
          "(sable: the one-thread run; LIGGGHTS' 'Other' holds its fixes: integration, gravity, walls); "
          "nbr builds = list builds in the timed run; contacts/grain from the final dump "
          "(distance <= ri + rj); neighs/atom = each code's 'Ave neighs/atom' (half lists); "
          "Nt / 1t paired = median over repeats of the speed-up between the runs of one repeat (each one's in "
          "brackets), pair busy = median share of the pair passes' wall time each thread was busy (the rest it "
          "waited for the other; sable's 'Thread balance' line); core round trip = `sable_core_probe` before "
          "each repeat: the time a cache line takes to go to the other core and back (about 0.1 us where the two "
          "cores share an L3, 0.3 us and more where they do not: then every barrier and shared line costs more "
          "and the thread speed-up drops)", "",
          table_md(rows, threads, info, args), ""]
    kept = [(k, v["measured"]) for k, v in results.items() if v.get("measured")]
    if kept:
        md.insert(-3, "- kept from the previous report (--update): " +
                  ", ".join("%s (measured %s)" % kv for kv in kept))
    md.append("| case | scene | deck variables |")
    md.append("|---|---|---|")
    for row in rows:
        md.append("| %s | %s | %s |" % (row["case"], row["what"],
                                        " ".join("-var %s %s" % kv for kv in row["vars"].items())))
    fails = [(row["case"], f) for row in rows for f in row["failures"]]
    if fails:
        md += ["", "## Failed runs", ""]
        for case, f in fails:
            md += [f"- {case}, {f['engine']} ({f['threads']} thread(s)), exit {f['rc']}:", "",
                   "```", f["tail"] or "", "```"]
    with open(path_md, "w") as f:
        f.write("\n".join(md) + "\n")
    with open(path_json, "w") as f:
        json.dump(dict(info=info, threads=threads, rows=rows, results=results), f, indent=1, default=str)
    return "\n".join(md)


# ------------------------------------------------------------------ modes ---

def select_cases(spec):
    out = []
    for w in spec.split(","):
        w = w.strip()
        m = [c for c in CASES if w in (c["key"], c["name"])]
        if not m:
            sys.exit("unknown case '%s' (known: %s)" % (w, ", ".join("%s=%s" % (c["key"], c["name"])
                                                                        for c in CASES)))
        out += m
    return out


def load_reuse(path):
    with open(path) as f:
        data = json.load(f)
    return data.get("results", {})


def bench(args, cases, threads, sable, liggghts, tmp):
    results = {}
    reuse = load_reuse(args.liggghts_from) if args.liggghts_from else {}
    for case in cases:
        v = dict(case["quick"] if args.quick else case["vars"])
        res = dict(what=case["what"], deck=case["deck"], deck_sha=deck_hash(case), vars=v, runs=[])
        results[case["name"]] = res
        old = reuse.get(case["name"])
        lig_reuse = bool(old and old.get("vars") == {k: v[k] for k in v} and old.get("deck_sha") == res["deck_sha"])
        if old and not lig_reuse:
            log(f"[{case['name']}] LIGGGHTS results in {args.liggghts_from} are for other variables or another "
                "deck version: running LIGGGHTS again")
        if lig_reuse:
            res["runs"] += [r for r in old["runs"] if r["engine"] == "liggghts"]
            res["liggghts_reused"] = args.liggghts_from
        nrep = max(args.repeats, args.liggghts_repeats)
        res["probes"] = []
        for rep in range(nrep):
            if sable and rep < args.repeats and max(threads) > 1:
                res["probes"].append(core_probe(sable))
            configs = []
            if sable and rep < args.repeats:
                configs += [("sable", sable, t) for t in threads]
            if liggghts and not lig_reuse and rep < args.liggghts_repeats:
                configs.append(("liggghts", liggghts, 1))
            for eng, exe, t in configs:
                wd = os.path.join(tmp, case["name"], f"{eng}_t{t}_r{rep}")
                log(f"[{case['name']}] {eng} threads={t} repeat {rep + 1}/{nrep} ...")
                r = run_engine(eng, exe, case, v, t, wd, args.timeout, "final.dump")
                r["repeat"] = rep
                res["runs"].append(r)
                if r["ok"]:
                    log(f"    {r['atoms']} atoms x {r['steps']} steps in {r['loop_s']:.3g} s: "
                        f"{r['psps']:.3g} PS/s, max RSS {r['maxrss_mb']} MB, load {r['load_before']}")
                else:
                    log(f"    FAILED (exit {r['rc']}{', timed out' if r['timed_out'] else ''}):\n" + r.get("tail", ""))
        # contacts per grain of the final state (last good run of each code)
        res["contacts"] = {}
        if not args.no_contacts:
            for eng in ("sable", "liggghts"):
                good = [r for r in res["runs"] if r["engine"] == eng and r["ok"] and os.path.exists(r["dump"])]
                if good:
                    try:
                        res["contacts"][eng] = contacts_per_grain(good[-1]["dump"])
                    except (OSError, ValueError, IndexError) as e:
                        log(f"    (contacts from {good[-1]['dump']} failed: {e})")
            if not args.no_contacts and "liggghts" not in res["contacts"] and lig_reuse:
                res["contacts"]["liggghts"] = (old.get("contacts") or {}).get("liggghts")
    return results


def determinism(args, cases, threads, sable, tmp):
    rows = []
    for case in cases:
        v = dict(case["quick"] if args.quick else case["vars"])
        dumps = {}
        for t in threads:
            for rep in range(2):
                wd = os.path.join(tmp, case["name"], f"det_t{t}_r{rep}")
                log(f"[{case['name']}] determinism: sable threads={t} run {rep + 1}/2 ...")
                r = run_engine("sable", sable, case, v, t, wd, args.timeout, "final.dump")
                if not r["ok"]:
                    log("    FAILED:\n" + r.get("tail", ""))
                    dumps[(t, rep)] = None
                    continue
                log(f"    {r['psps']:.3g} PS/s")
                dumps[(t, rep)] = r["dump"]
        row = dict(case=case["name"], vars=v, same_threads={}, across={})
        for t in threads:
            a, b = dumps.get((t, 0)), dumps.get((t, 1))
            row["same_threads"][t] = compare_dumps(a, b) if a and b else None
        t0 = threads[0]
        for t in threads[1:]:
            a, b = dumps.get((t0, 0)), dumps.get((t, 0))
            row["across"]["%d vs %d" % (t0, t)] = compare_dumps(a, b) if a and b else None
        rows.append(row)

    def cell(c):
        if c is None:
            return "run failed"
        same, n, d = c
        return "bit-identical" if same else "DIFFERENT (%d lines, max |diff| %.3g)" % (n, d)

    h = ["case"] + ["%dt run 1 vs run 2" % t for t in threads] + ["threads %s" % k for k in rows[0]["across"]]
    md = ["| " + " | ".join(h) + " |", "|" + "---|" * len(h)]
    for row in rows:
        md.append("| " + " | ".join([row["case"]] + [cell(row["same_threads"][t]) for t in threads] +
                                     [cell(c) for c in row["across"].values()]) + " |")
    return rows, "\n".join(md)


MPI2 = ("mpirun", "-np", "2", "--bind-to", "none")


def run_pair_at_once(exe, case, v, workdir, timeout):
    """Two one-thread sable runs of the same deck started together: what two cores give two
    independent jobs that share only the hardware (memory bandwidth, L3, clock, other tenants)."""
    out = [None, None]

    def one(k):
        out[k] = run_engine("sable", exe, case, v, 1, os.path.join(workdir, "job%d" % k), timeout, "final.dump")
    jobs = [threading.Thread(target=one, args=(k,)) for k in (0, 1)]
    for j in jobs:
        j.start()
    for j in jobs:
        j.join()
    return out


def scaling_repeat(args, case, v, sable, liggghts, wd):
    """One repeat: sable 1t alone, two sable 1t at once, sable 2t, LIGGGHTS 1 and 2 MPI processes."""
    r = {"probe": core_probe(sable)}
    steps = [("sable 1t", lambda: run_engine("sable", sable, case, v, 1, wd + "/s1", args.timeout, "final.dump")),
             ("sable 1t x2 at once", lambda: run_pair_at_once(sable, case, v, wd + "/s1x2", args.timeout)),
             ("sable 2t", lambda: run_engine("sable", sable, case, v, 2, wd + "/s2", args.timeout, "final.dump"))]
    if liggghts:
        steps += [("LIGGGHTS 1p", lambda: run_engine("liggghts", liggghts, case, v, 1, wd + "/l1", args.timeout,
                                                     "final.dump")),
                  ("LIGGGHTS 2p", lambda: run_engine("liggghts", liggghts, case, v, 1, wd + "/l2", args.timeout,
                                                     "final.dump", launcher=MPI2))]
    for name, go in steps:
        log(f"[{case['name']}] {name} ...")
        res = go()
        for x in res if isinstance(res, list) else [res]:
            log(f"    {x['psps']:.3g} PS/s" if x["ok"] else f"    FAILED (exit {x['rc']}):\n" + x.get("tail", ""))
        r[name] = res
    return r


def ranks_repeat(args, case, v, sable, liggghts, wd):
    """One repeat on two cores: sable 1 rank x 2 threads, sable 2 MPI ranks x 1 thread, LIGGGHTS 2 MPI
    processes (no final dump: several sable ranks do not write dumps yet)."""
    v = dict(v, writedump=0)
    steps = [("sable 1r x 2t", lambda: run_engine("sable", sable, case, v, 2, wd + "/t2", args.timeout, "none")),
             ("sable 2r x 1t", lambda: run_engine("sable", sable, case, v, 1, wd + "/r2", args.timeout, "none",
                                                  launcher=MPI2))]
    if liggghts:
        steps.append(("LIGGGHTS 2p", lambda: run_engine("liggghts", liggghts, case, v, 1, wd + "/l2", args.timeout,
                                                        "none", launcher=MPI2)))
    r = {}
    for name, go in steps:
        log(f"[{case['name']}] {name} ...")
        x = go()
        log(f"    {x['psps']:.3g} PS/s, {x['cpu_s']:.1f} CPU-s" if x["ok"] else
            f"    FAILED (exit {x['rc']}):\n" + x.get("tail", ""))
        r[name] = x
    return r


def repeated(args, cases, sable, liggghts, tmp, one_repeat, table):
    """--repeats repeats of one_repeat per case (--scaling, --ranks), then their table."""
    rows = []
    for case in cases:
        v = dict(case["quick"] if args.quick else case["vars"])
        reps = [one_repeat(args, case, v, sable, liggghts, os.path.join(tmp, case["name"], "r%d" % k))
                for k in range(args.repeats)]
        rows.append(dict(case=case["name"], vars=v, runs=reps))
    return rows, table(rows)


def ranks_table(rows):
    """Medians over the repeats: PS/s of each configuration, the ratios within a repeat, the timed
    run's CPU seconds (all processes) of LIGGGHTS over sable's 2 ranks, sable's share of the loop
    in messages and its pair-time imbalance (max over mean rank)."""
    def ok(x):
        return x if x and x["ok"] else None

    def med(xs):
        xs = [x for x in xs if x is not None]
        return median_or_none(xs)
    h = ["case", "grains", "sable 1 rank x 2 threads, PS/s", "sable 2 ranks x 1 thread, PS/s", "LIGGGHTS 2 ranks, PS/s",
         "sable 2 ranks / 2 threads", "sable / LIGGGHTS (2 ranks each), PS/s", "LIGGGHTS / sable CPU-s, whole run",
         "sable comm, % of loop", "sable pair time max / mean rank", "sable grains per rank (min-max)"]
    md = ["| " + " | ".join(h) + " |", "|" + "---|" * len(h)]
    for row in rows:
        reps = row["runs"]
        t2 = [ok(r.get("sable 1r x 2t")) for r in reps]
        r2 = [ok(r.get("sable 2r x 1t")) for r in reps]
        l2 = [ok(r.get("LIGGGHTS 2p")) for r in reps]
        ratio = lambda a, b, key: med([x[key] / y[key] if x and y and y[key] else None for x, y in zip(a, b)])
        row["median"] = dict(
            sable_2t=med([x and x["psps"] for x in t2]), sable_2r=med([x and x["psps"] for x in r2]),
            liggghts_2p=med([x and x["psps"] for x in l2]), ranks_over_threads=ratio(r2, t2, "psps"),
            sable_over_liggghts=ratio(r2, l2, "psps"), cpu_liggghts_over_sable=ratio(l2, r2, "cpu_s"),
            comm_pct=med([x and x.get("comm_pct") for x in r2]),
            pair_imbalance=med([x["ranks"]["pair"]["max"] / x["ranks"]["pair"]["mean"]
                                if x and x.get("ranks", {}).get("pair", {}).get("mean") else None for x in r2]))
        g = next((x["ranks"].get("grains") for x in r2 if x and x.get("ranks")), None)
        cell = lambda v, f="%.3g": "-" if v is None else f % v
        m = row["median"]
        atoms = next((x["atoms"] for x in t2 + r2 if x), None)
        md.append("| " + " | ".join([row["case"], cell(atoms, "%d"), cell(m["sable_2t"]), cell(m["sable_2r"]),
                                    cell(m["liggghts_2p"]), cell(m["ranks_over_threads"], "%.2f"),
                                    cell(m["sable_over_liggghts"], "%.2f"), cell(m["cpu_liggghts_over_sable"], "%.2f"),
                                    cell(m["comm_pct"], "%.1f"), cell(m["pair_imbalance"], "%.2f"),
                                    "-" if not g else "%d-%d" % (g["min"], g["max"])]) + " |")
    return "\n".join(md)


def generated_by(argv, info):
    """The line that says how and where a report was made."""
    return (f"Generated by `python3 -m sable_tools.bench.bench {' '.join(argv)}` on {info['date']} "
            f"(sable {info.get('sable')}, commit {info.get('sable_commit')}, tree {info.get('sable_tree')}; "
            f"{info.get('cpu')}, {info.get('nproc')} cores).")


def write_ranks(prefix, rows, table, info, argv):
    text = "\n".join([
        "# Two cores: sable's threads against its MPI ranks, and LIGGGHTS on 2 ranks", "",
        generated_by(argv, info), "",
        "Each repeat runs the same deck, one after the other: sable as one process with 2 OpenMP "
        "threads; sable on 2 MPI ranks of one thread (`mpirun -np 2 --bind-to none`); LIGGGHTS on 2 MPI "
        "ranks. PS/s = grains x steps / loop time of the timed run; ratios within a repeat, medians over "
        "the repeats. CPU-s: user + system of the whole process tree (preparation included). sable's "
        "comm: the time in messages (exchange, borders, forward: `Rank balance` in its output), as a "
        "share of the timed loop; its imbalance: the slowest rank's pair time over the mean. The grid "
        "is the default (`processors * * *`: least subdomain surface).", "", table, ""])
    write_md_json(prefix, text, dict(info=info, rows=rows))


def scaling_ratios(rep):
    """Per repeat: sable 2t / 1t, two 1t jobs at once (summed PS/s) / one alone, LIGGGHTS 2p / 1p,
    sable 1t / LIGGGHTS 1p and sable 2t / LIGGGHTS 2p."""
    def psps(x):
        return x["psps"] if x and x["ok"] else None
    s1, s2 = psps(rep["sable 1t"]), psps(rep["sable 2t"])
    both = [psps(x) for x in rep["sable 1t x2 at once"]]
    l1, l2 = psps(rep.get("LIGGGHTS 1p")), psps(rep.get("LIGGGHTS 2p"))
    return dict(sable=s2 / s1 if s1 and s2 else None,
                two_jobs=sum(both) / s1 if s1 and None not in both else None,
                liggghts=l2 / l1 if l1 and l2 else None,
                one_core=s1 / l1 if s1 and l1 else None,
                two_cores=s2 / l2 if s2 and l2 else None)


def scaling_table(rows):
    keys = ("sable", "two_jobs", "liggghts", "one_core", "two_cores")
    for row in rows:
        row["ratios"] = [scaling_ratios(r) for r in row["runs"]]
        row["median"] = {k: median_or_none([q[k] for q in row["ratios"]]) for k in keys}

    def cell(k, row):
        m = row["median"][k]
        return "-" if m is None else "%.2f (%s)" % (m, ", ".join("%.2f" % q[k] for q in row["ratios"] if q[k]))
    h = ["case", "sable 2 / 1 threads", "two 1-thread sable jobs at once / one alone",
         "LIGGGHTS 2 / 1 MPI processes", "sable 1 thread / LIGGGHTS 1 process",
         "sable 2 threads / LIGGGHTS 2 processes", "core round trip, us (per repeat)"]
    md = ["| " + " | ".join(h) + " |", "|" + "---|" * len(h)]
    for row in rows:
        md.append("| " + " | ".join([row["case"]] + [cell(k, row) for k in keys] +
                                    [probe_cell([r.get("probe") for r in row["runs"]])]) + " |")
    return "\n".join(md)


def write_scaling(prefix, rows, table, info, argv):
    text = "\n".join([
        "# One to two cores: sable threads, two jobs at once, LIGGGHTS MPI", "",
        generated_by(argv, info), "",
        "Each repeat runs, one after the other: sable with 1 thread; two independent 1-thread sable "
        "runs of the same deck started together; sable with 2 threads; LIGGGHTS with 1 and with 2 MPI "
        "processes (`mpirun -np 2`). Ratios are of particle-steps/s of the timed run within one "
        "repeat; the median first, every repeat in brackets. Two jobs at once: their summed PS/s "
        "over the job alone, what two cores give two jobs that share only the hardware (memory "
        "bandwidth, L3, clock, the host's other tenants), each with the whole working set. A run "
        "split over two cores can gain more (each core's cache holds half the grains): LIGGGHTS' "
        "domains do. Core round trip: `sable_core_probe` before each repeat, the time a cache line takes "
        "to go to the other core and back.", "", table, ""])
    write_md_json(prefix, text, dict(info=info, rows=rows))


def write_md_json(prefix, text, data):
    with open(prefix + ".md", "w") as f:
        f.write(text)
    with open(prefix + ".json", "w") as f:
        json.dump(data, f, indent=1, default=str)


def merge_results(old, results):
    """--update: the cases of an earlier results JSON that this run did not measure (each marked
    with the date it was measured), then this run's, in CASES' order (unknown names last)."""
    merged = {k: v for k, v in old.get("results", {}).items() if k not in results}
    for v in merged.values():
        v.setdefault("measured", old.get("info", {}).get("date"))
    merged.update(results)
    order = [c["name"] for c in CASES]
    return {k: merged[k] for k in sorted(merged, key=lambda k: order.index(k) if k in order else 99)}


def main():
    ap = argparse.ArgumentParser(
        description="Benchmark sable against LIGGGHTS on the decks of input_scripts/bench/ "
                    "(cases: " + ", ".join("%s=%s" % (c["key"], c["name"]) for c in CASES) + ").",
        epilog="Examples:  bench.py --quick          (smoke test, seconds)\n"
               "           bench.py --cases a,c --repeats 3 --threads 1,2\n"
               "           bench.py --no-liggghts --liggghts-from input_scripts/bench/results.json\n"
               "           bench.py --determinism --cases a",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="a,b,c,d", help="comma list of case letters or names (default a,b,c,d)")
    ap.add_argument("--repeats", type=int, default=3, help="runs of each sable configuration (default 3)")
    ap.add_argument("--liggghts-repeats", type=int, default=None,
                    help="runs of LIGGGHTS (default: --repeats)")
    ap.add_argument("--threads", default="1,2", help="sable OMP_NUM_THREADS values (default 1,2)")
    ap.add_argument("--sable", default=None, help="sable binary (default: the first of build/, build-release/, build-bench/ that has one)")
    ap.add_argument("--liggghts", default="liggghts", help="LIGGGHTS binary (default liggghts)")
    ap.add_argument("--no-liggghts", action="store_true", help="do not run LIGGGHTS")
    ap.add_argument("--no-sable", action="store_true", help="do not run sable (LIGGGHTS baseline only)")
    ap.add_argument("--liggghts-from", metavar="JSON",
                    help="reuse LIGGGHTS runs from an earlier results JSON when deck and variables match")
    ap.add_argument("--quick", action="store_true", help="tiny sizes: a smoke test of the tooling (seconds)")
    ap.add_argument("--determinism", action="store_true",
                    help="run sable twice per thread count and compare the final dumps byte for byte")
    ap.add_argument("--scaling", action="store_true",
                    help="per repeat: sable 1t, two sable 1t jobs at once, sable 2t, "
                         "LIGGGHTS with 1 and 2 MPI processes; writes scaling[_quick].md/json")
    ap.add_argument("--ranks", action="store_true",
                    help="two cores: sable 1 rank x 2 threads, sable 2 MPI ranks, LIGGGHTS 2 MPI ranks (ranks.md)")
    ap.add_argument("--no-contacts", action="store_true", help="skip counting contacts in the final dumps")
    ap.add_argument("--timeout", type=float, default=0, help="seconds per run (default: none)")
    ap.add_argument("--out", default=None,
                    help="output prefix (default input_scripts/bench/results, results_quick with --quick, "
                         "determinism[_quick] with --determinism); writes PREFIX.md and PREFIX.json")
    ap.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                    help="override a deck variable for every selected case (repeatable), e.g. --set prep=4000")
    ap.add_argument("--update", action="store_true",
                    help="merge into the existing PREFIX.json: the cases run now replace theirs, the others stay")
    ap.add_argument("--keep", action="store_true", help="keep the run directories (logs, dumps)")
    args = ap.parse_args()
    if args.liggghts_repeats is None:
        args.liggghts_repeats = args.repeats
    print("usage: bench.py [--cases a,b,c,d] [--repeats 3] [--threads 1,2] [--sable build/sable] [--quick] "
          "[--determinism] (-h for all options)", flush=True)

    cases = select_cases(args.cases)
    for kv in args.set:
        if "=" not in kv:
            sys.exit("--set wants NAME=VALUE, got '%s'" % kv)
        k, val = kv.split("=", 1)
        for c in cases:
            c["quick" if args.quick else "vars"][k] = val
    threads = [int(t) for t in args.threads.split(",") if t.strip()]
    sable = None if args.no_sable else runner.find_sable(args.sable)
    if not args.no_sable and not sable:
        sys.exit("sable binary not found (%s); build it: cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && "
                 "cmake --build build -j" % (args.sable or "build/, build-release/, build-bench/"))
    liggghts = None
    if (args.scaling or args.ranks) and not shutil.which("mpirun"):
        sys.exit("--scaling and --ranks run under mpirun, which is missing (apt-get install openmpi-bin)")
    if not args.no_liggghts and not args.determinism:
        liggghts = shutil.which(args.liggghts)
        if not liggghts:
            sys.exit("LIGGGHTS binary '%s' not found (apt-get install liggghts), or pass --no-liggghts"
                     % args.liggghts)
    info = machine_info(sable, liggghts)
    tmp = tempfile.mkdtemp(prefix="sable-bench-")
    log(f"sable: {sable}  LIGGGHTS: {liggghts}  cases: {', '.join(c['name'] for c in cases)}  "
        f"threads: {threads}  run dirs: {tmp}  load: {info['loadavg_start'][0]:.2f}")
    try:
        if args.determinism:
            prefix = args.out or os.path.join(HERE, "determinism_quick" if args.quick else "determinism")
            rows, table = determinism(args, cases, threads, sable, tmp)
            info["loadavg_end"] = os.getloadavg()
            text = "\n".join([
                "# sable determinism check", "",
                f"Generated by `python3 -m sable_tools.bench.bench {' '.join(sys.argv[1:])}` on {info['date']} "
                f"(sable {sable}, commit {info.get('sable_commit')}, tree {info.get('sable_tree')}).", "",
                "Each deck runs twice per OMP_NUM_THREADS value; the final dumps (all atoms sorted by id, "
                "positions, velocities, spins at %.17g) are compared byte for byte.", "", table, ""])
            write_md_json(prefix, text, dict(info=info, rows=rows))
            print("\n" + table)
            print(f"\nwritten: {prefix}.md, {prefix}.json")
            return
        if args.ranks:
            prefix = args.out or os.path.join(HERE, "ranks_quick" if args.quick else "ranks")
            rows, table = repeated(args, cases, sable, liggghts, tmp, ranks_repeat, ranks_table)
            info["loadavg_end"] = os.getloadavg()
            write_ranks(prefix, rows, table, info, sys.argv[1:])
            print("\n" + table + f"\n\nwritten: {prefix}.md, {prefix}.json")
            return
        if args.scaling:
            prefix = args.out or os.path.join(HERE, "scaling_quick" if args.quick else "scaling")
            rows, table = repeated(args, cases, sable, liggghts, tmp, scaling_repeat, scaling_table)
            info["loadavg_end"] = os.getloadavg()
            write_scaling(prefix, rows, table, info, sys.argv[1:])
            print("\n" + table + f"\n\nwritten: {prefix}.md, {prefix}.json")
            return
        prefix = args.out or os.path.join(HERE, "results_quick" if args.quick else "results")
        results = bench(args, cases, threads, sable, liggghts, tmp)
        info["loadavg_end"] = os.getloadavg()
        if args.update and os.path.exists(prefix + ".json"):
            with open(prefix + ".json") as f:
                results = merge_results(json.load(f), results)
            info["merged_from"] = prefix + ".json"
        for res in results.values():
            for r in res["runs"]:
                if r["engine"] == "liggghts" and r.get("version"):
                    info["liggghts_version"] = r["version"]
        if args.update:  # show every thread count present in the merged runs
            threads = sorted({r["threads"] for v in results.values() for r in v["runs"] if r["engine"] == "sable"}
                             | set(threads))
        rows = summarize(results, threads)
        title = "sable vs LIGGGHTS benchmark" + (" (--quick smoke test: tiny sizes)" if args.quick else "")
        write_report(prefix + ".md", prefix + ".json", rows, results, threads, info, args, title)
        print("\n" + table_md(rows, threads, info, args))
        print(f"\nwritten: {prefix}.md, {prefix}.json")
        bad = sum(len(r["failures"]) for r in rows)
        if bad:
            print(f"{bad} run(s) failed; see the 'Failed runs' section of {prefix}.md")
            sys.exit(1)
    finally:
        if args.keep:
            log(f"run directories kept in {tmp}")
        else:
            shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
