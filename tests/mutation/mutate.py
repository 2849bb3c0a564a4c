#!/usr/bin/env python3
"""Mutation check (issue 42, item 6): break the engine on purpose and list the tests that catch it.

Exports the committed HEAD into WORK/src, builds it in WORK/build (Release, as the test
command builds), runs the whole ctest suite once unmutated (the baseline), then for each
mutation below: applies it to WORK/src (each replacement must match exactly once), rebuilds
incrementally, runs the suite, and records the tests that pass in the baseline and fail with
the mutation. The mutation is reverted before the next one. Writes a Markdown report with the
commit it ran on; exits 1 if a mutation compiled and no test caught it.

    python3 tests/mutation/mutate.py [--work /tmp/sable_mutation] [--only NAME,NAME]
        [--report tests/mutation/report.md] [--exclude REGEX] [--jobs 2]

Each run costs one build (~12 min on 2 cores) plus, per mutation, an incremental build and one
suite (~15-20 min): run it in the background with its output in a file.
"""
import argparse
import datetime
import os
import shutil
import socket
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# name, what breaks, file, [(old, new), ...]
MUTATIONS = [
    ("tangential_sign", "the tangential spring force points along the shear displacement (sign flipped)",
     "contact_models/tangential/history.h",
     [("f.x = -kt * s0 * fac", "f.x = kt * s0 * fac"),
      ("f.y = -kt * s1 * fac", "f.y = kt * s1 * fac"),
      ("f.z = k3 ? -kt * s2 * fac", "f.z = k3 ? kt * s2 * fac")]),
    ("halt_threshold", "fix halt compares with ten times the deck's value",
     "fixes/fix_halt.cpp",
     [('value_ = a.num(7, "the value to compare with");', 'value_ = 10.0 * a.num(7, "the value to compare with");')]),
    ("wall_friction", "friction between unlike types is zero: a wall (primitive or mesh) of its own type "
                      "becomes frictionless (grain-grain friction of one type unchanged)",
     "contact_models/materials.cpp",
     [("    check_range(name, t);\n",
       "    check_range(name, t);\n"
       "    if (name == \"coefficientFriction\")\n"
       "      for (int i = 1; i <= ntypes_; ++i)\n"
       "        for (int j = 1; j <= ntypes_; ++j)\n"
       "          if (i != j) t[i * s + j] = 0.0;\n")]),
    ("restart_history", "write_restart stores zeros for the contact history (shear displacements lost)",
     "core/io/restart.cpp",
     [("p.put_vector(c.hist);", "p.put_vector(std::vector<double>(c.hist.size(), 0.0));")]),
    ("gravity_z_sign", "fix gravity's z component pulls the wrong way",
     "fixes/fix_gravity.cpp", [("f[3 * i + 2] += rmass[i] * a2;", "f[3 * i + 2] -= rmass[i] * a2;")]),
    ("hertz_damping_off", "Hertz's viscoelastic normal damping dropped (gamman = 0)",
     "contact_models/normal/hertz.h", [("n.gamman = gn_c[c.tp] * sm;", "n.gamman = 0.0 * gn_c[c.tp] * sm;")]),
]


def sh(cmd, cwd=None, log=None, check=True):
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if log:
        with open(log, "a") as f:
            f.write("$ " + " ".join(cmd) + "\n" + p.stdout)
    if check and p.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), p.stdout[-4000:]))
    return p


def export_head(src):
    """WORK/src becomes HEAD's tree; files whose content is unchanged keep their times, so that a
    second check (a later commit) rebuilds only what changed."""
    fresh = src + ".new"
    shutil.rmtree(fresh, ignore_errors=True)
    os.makedirs(fresh)
    archive = subprocess.run(["git", "archive", "HEAD"], cwd=ROOT, stdout=subprocess.PIPE, check=True).stdout
    subprocess.run(["tar", "-x", "-C", fresh], input=archive, check=True)
    os.makedirs(src, exist_ok=True)
    keep = set()
    for d, _, files in os.walk(fresh):
        for f in files:
            rel = os.path.relpath(os.path.join(d, f), fresh)
            keep.add(rel)
            dst = os.path.join(src, rel)
            new = open(os.path.join(d, f), "rb").read()
            if not os.path.isfile(dst) or open(dst, "rb").read() != new:
                os.makedirs(os.path.dirname(dst), exist_ok=True)
                shutil.copy2(os.path.join(d, f), dst)
                os.utime(dst)  # newer than the build's objects
    for d, _, files in os.walk(src):
        for f in files:
            if os.path.relpath(os.path.join(d, f), src) not in keep:
                os.remove(os.path.join(d, f))
    shutil.rmtree(fresh)


def apply(src, rel, reps):
    path = os.path.join(src, rel)
    text = open(path).read()
    orig = text
    for old, new in reps:
        n = text.count(old)
        if n != 1:
            sys.exit("%s: %r found %d times (expected 1): update tests/mutation/mutate.py" % (rel, old, n))
        text = text.replace(old, new)
    with open(path, "w") as f:
        f.write(text)
    return orig


def run_suite(build, tag, work, jobs, exclude, log):
    junit = os.path.join(work, "ctest_%s.xml" % tag)
    cmd = ["ctest", "--test-dir", build, "-j%d" % jobs, "--timeout", "900", "--output-junit", junit]
    if exclude:
        cmd += ["-E", exclude]
    t0 = time.time()
    sh(cmd, log=log, check=False)
    status = {}
    for tc in ET.parse(junit).getroot().iter("testcase"):
        st = tc.get("status")
        status[tc.get("name")] = "pass" if st == "run" and tc.find("failure") is None else st or "fail"
        if tc.find("failure") is not None:
            status[tc.get("name")] = "fail"
        if tc.find("skipped") is not None:
            status[tc.get("name")] = "skip"
    return status, time.time() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", default="/tmp/sable_mutation")
    ap.add_argument("--only", default=None, help="comma-separated mutation names")
    ap.add_argument("--report", default=os.path.join(ROOT, "tests", "mutation", "report.md"))
    ap.add_argument("--exclude", default=None, help="ctest -E REGEX for every suite run (stated in the report)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--list", action="store_true", help="list the mutations and exit")
    ap.add_argument("--build-only", action="store_true", help="export and build HEAD (and warm ccache), no suites")
    a = ap.parse_args()
    if a.list:
        for name, what, rel, _ in MUTATIONS:
            print("%-20s %-40s %s" % (name, rel, what))
        return 0
    chosen = MUTATIONS if not a.only else [m for m in MUTATIONS if m[0] in a.only.split(",")]
    if a.only and len(chosen) != len(a.only.split(",")):
        sys.exit("unknown mutation in --only %s (see --list)" % a.only)

    commit = sh(["git", "rev-parse", "HEAD"], cwd=ROOT).stdout.strip()
    dirty = sh(["git", "status", "--porcelain", "--untracked-files=no"], cwd=ROOT).stdout.strip()
    src, build = os.path.join(a.work, "src"), os.path.join(a.work, "build")
    log = os.path.join(a.work, "mutation.log")
    export_head(src)
    print("mutation check of %s%s in %s (log %s)" % (commit[:12], " (working tree has uncommitted changes: "
          "they are NOT tested)" if dirty else "", a.work, log), flush=True)

    t0 = time.time()
    # ccache (where installed) makes the rebuild after each revert a cache hit.
    launcher = ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"] if shutil.which("ccache") else []
    sh(["cmake", "-S", src, "-B", build, "-DCMAKE_BUILD_TYPE=Release"] + launcher, log=log)
    sh(["cmake", "--build", build, "-j%d" % a.jobs], log=log)
    print("baseline built in %.0f s" % (time.time() - t0), flush=True)
    if a.build_only:
        return 0
    base, tb = run_suite(build, "baseline", a.work, a.jobs, a.exclude, log)
    passing = {t for t, s in base.items() if s == "pass"}
    print("baseline: %d tests, %d pass, failing: %s (%.0f s)" % (
        len(base), len(passing), sorted(t for t, s in base.items() if s == "fail") or "none", tb), flush=True)

    rows = []
    for name, what, rel, reps in chosen:
        orig = apply(src, rel, reps)
        try:
            t1 = time.time()
            b = sh(["cmake", "--build", build, "-j%d" % a.jobs], log=log, check=False)
            if b.returncode != 0:
                rows.append((name, what, rel, reps, None, time.time() - t1))
                print("%s: does not compile (see %s)" % (name, log), flush=True)
                continue
            st, _ = run_suite(build, name, a.work, a.jobs, a.exclude, log)
            caught = sorted(t for t in passing if st.get(t) not in ("pass", "skip"))
            rows.append((name, what, rel, reps, caught, time.time() - t1))
            print("%s: caught by %d tests: %s" % (name, len(caught), ", ".join(caught[:12])), flush=True)
        finally:
            with open(os.path.join(src, rel), "w") as f:
                f.write(orig)
    sh(["cmake", "--build", build, "-j%d" % a.jobs], log=log, check=False)  # leave the build unmutated

    write_report(a, commit, dirty, base, passing, rows, time.time() - t0)
    bad = [r[0] for r in rows if r[4] is not None and not r[4]]
    if bad:
        print("NOT CAUGHT: %s" % ", ".join(bad))
        return 1
    return 0


def write_report(a, commit, dirty, base, passing, rows, seconds):
    out = ["# Mutation check", "",
           "Commit `%s`%s, %s, host %s, %d cores; `python3 tests/mutation/mutate.py%s%s`; %.0f min in all." % (
               commit, " (uncommitted changes not tested)" if dirty else "",
               datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"), socket.gethostname(),
               os.cpu_count(), " --only " + a.only if a.only else "", " --exclude '%s'" % a.exclude if a.exclude else "",
               seconds / 60),
           "",
           "Baseline: %d tests, %d pass%s." % (len(base), len(passing), "" if len(passing) == len(base) else
                                               ", not passing: " + ", ".join(sorted(set(base) - passing))),
           "A test catches a mutation when it passes unmutated and fails (or times out) mutated.", "",
           "| mutation | what breaks | file | caught by | tests |", "|---|---|---|---:|---|"]
    for name, what, rel, reps, caught, _ in rows:
        if caught is None:
            out.append("| %s | %s | `%s` | - | does not compile |" % (name, what, rel))
        else:
            shown = ", ".join("`%s`" % t for t in caught[:15]) + (" and %d more" % (len(caught) - 15)
                                                                  if len(caught) > 15 else "")
            out.append("| %s | %s | `%s` | %d | %s |" % (name, what, rel, len(caught), shown or "**NOT CAUGHT**"))
    out += ["", "The replacements:", ""]
    for name, _, rel, reps, _, _ in rows:
        for old, new in reps:
            out.append("- %s, `%s`: `%s` -> `%s`" % (name, rel, old.strip().replace("\n", " "),
                                                     new.strip().replace("\n", " ")))
    os.makedirs(os.path.dirname(os.path.abspath(a.report)), exist_ok=True)
    with open(a.report, "w") as f:
        f.write("\n".join(out) + "\n")
    print("wrote", a.report)


if __name__ == "__main__":
    sys.exit(main())
