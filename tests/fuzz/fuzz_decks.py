#!/usr/bin/env python3
"""Deck-mutation fuzzer for sable (issue 24, item 4).

Seeds are the decks in tests/decks/*.in and input_scripts/compare/*.in. Each
mutant is a seed with a few random edits (numbers replaced by 0, -1, nan, inf,
1e300 or huge integers; words and lines dropped, duplicated, swapped or cut;
keywords swapped for others seen in the corpus; deck-given printf formats;
empty, reversed and huge loop variables; include recursion; deep parentheses;
self-referring variables). Runs are capped (`run N` -> `run min(N, cap)`) and
given a budget of CPU seconds (RLIMIT_CPU through prlimit, one OpenMP thread):
CPU time, unlike wall clock, does not depend on how loaded the machine is.
Each run is classified:

  crash   killed by a signal, or a sanitizer report on stderr
  hang    spent its CPU budget, not finishing runs; or used (almost) no CPU
          for the whole wall-clock backstop (blocked)
  endless spent its CPU budget, finishing run after run: the mutant loops
          over `run` without end (a `next` dropped), which is what the deck says
          (LAMMPS would run it for ever too); counted, not a failure
  noloc   failed without naming the deck file and line ("FILE:LINE:")
  error   failed with a located error (fine: bad input was refused)
  ok      ran to the end

CI mode (default): a fixed number of mutants from a fixed seed; exit 1 on any
crash, hang or noloc. --long: mutants until --minutes have passed, then a
report (--report FILE). --save-bad DIR writes each crasher as a regression deck.
Reproduce one mutant: --seed S --only K --keep DIR.
"""
import argparse
import concurrent.futures as cf
import glob
import math
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

from sable_tools.readers.screen import loop_times  # PYTHONPATH: the repository (tests/CMakeLists.txt)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SEED_GLOBS = ["tests/decks/*.in", "input_scripts/compare/*.in"]
LOCATED = re.compile(r"[\w./-]+:\d+[:)]")  # FILE:LINE: ... or (during 'run N' at FILE:LINE)
SANITIZER = re.compile(r"AddressSanitizer|LeakSanitizer|runtime error:|UndefinedBehaviorSanitizer")

BAD_NUMBERS = ["0", "-1", "nan", "inf", "-inf", "1e300", "-1e300", "1e-300", "9223372036854775807",
               "99999999999999999999", "2147483648", "-2147483649", "0.5", "1e9", "NaN", "1e"]
FORMATS = ["%d", "%s", "%n", "%f%f", "%10.3f%d", "%%", "%ld", "%.999f", "%*d", "%", "%lf", "%5$d", "%c",
           "%p", "%x", "%g", "%-12.4e", "%.3g abc", "abc", "%hhn", "%1000000d", "%.2f%%", "%e %e", "%Lf"]
NUMBER = re.compile(r"(?<![\w.$])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?![\w.])")


def load_seeds():
    seeds = []
    for g in SEED_GLOBS:
        for path in sorted(glob.glob(os.path.join(ROOT, g))):
            with open(path) as f:
                seeds.append((path, f.read().splitlines()))
    return seeds


def vocabulary(seeds):
    commands, words = set(), set()
    for _, lines in seeds:
        for l in lines:
            w = l.split("#")[0].split()
            if w:
                commands.add(w[0])
                words.update(x for x in w[1:] if re.match(r"^[a-z][a-z_/]*$", x))
    return sorted(commands), sorted(words)


def code_lines(lines):
    return [i for i, l in enumerate(lines) if l.split("#")[0].strip()]


class Mutator:
    def __init__(self, rng, commands, words):
        self.rng, self.commands, self.words = rng, commands, words

    def pick_line(self, lines):
        idx = code_lines(lines)
        return self.rng.choice(idx) if idx else None

    def m_number(self, lines):
        i = self.pick_line(lines)
        if i is None:
            return
        nums = list(NUMBER.finditer(lines[i]))
        if not nums:
            return
        m = self.rng.choice(nums)
        lines[i] = lines[i][:m.start()] + self.rng.choice(BAD_NUMBERS) + lines[i][m.end():]

    def _words(self, lines, f):
        i = self.pick_line(lines)
        if i is None:
            return
        w = lines[i].split()
        if len(w) > 1:
            f(w)
            lines[i] = " ".join(w)

    def m_drop_word(self, lines):
        self._words(lines, lambda w: w.pop(self.rng.randrange(1, len(w))))

    def m_dup_word(self, lines):
        def f(w):
            k = self.rng.randrange(1, len(w))
            w.insert(k, w[k])
        self._words(lines, f)

    def m_swap_words(self, lines):
        def f(w):
            a, b = self.rng.randrange(len(w)), self.rng.randrange(len(w))
            w[a], w[b] = w[b], w[a]
        self._words(lines, f)

    def m_neighbour_word(self, lines):
        def f(w):
            k = self.rng.randrange(len(w))
            w[k] = self.rng.choice(self.commands if k == 0 else self.words)
        self._words(lines, f)

    def m_drop_line(self, lines):
        i = self.pick_line(lines)
        if i is not None:
            del lines[i]

    def m_dup_line(self, lines):
        i = self.pick_line(lines)
        if i is not None:
            lines.insert(i, lines[i])

    def m_swap_lines(self, lines):
        idx = code_lines(lines)
        if len(idx) > 1:
            a, b = self.rng.sample(idx, 2)
            lines[a], lines[b] = lines[b], lines[a]

    def m_truncate(self, lines):
        i = self.pick_line(lines)
        if i is not None and len(lines[i]) > 1:
            lines[i] = lines[i][:self.rng.randrange(1, len(lines[i]))]

    def insert(self, lines, text):
        lines.insert(self.rng.randrange(len(lines) + 1), text)

    def m_format(self, lines):
        fmt = self.rng.choice(FORMATS)
        if self.rng.random() < 0.5:
            self.insert(lines, 'print "value $(2.5*3:%s)"' % fmt)
        else:
            self.insert(lines, "thermo_modify format float %s" % fmt)

    def m_loop(self, lines):
        self.insert(lines, self.rng.choice([
            "variable lp loop 0", "variable lp loop 5 1", "variable lp loop 1000000000",
            "variable lp loop -3 pad", "variable lp loop 3 -2 pad", "variable lp loop 9223372036854775807",
            "variable lp loop 1 1000000000 pad", "variable lp index", "variable lp loop -5"]))

    def m_include_self(self, lines):
        self.insert(lines, "include mutant.in")

    def m_parens(self, lines):
        n = self.rng.choice([200, 5000, 100000])
        expr = "(" * n + "1" + ")" * n
        self.insert(lines, self.rng.choice(['print "$(%s)"' % expr, "variable deep equal %s" % expr]))

    def m_selfref(self, lines):
        self.insert(lines, self.rng.choice([
            "variable sr equal v_sr+1\nprint \"${sr}\"",
            "variable sa atom v_sa*2\ncompute sc all reduce sum v_sa\nthermo_style custom step c_sc",
            "variable sa atom v_sb\nvariable sb atom v_sa\ndump sd all custom 1 sd.txt id v_sa",
            "variable se equal v_sf\nvariable sf equal v_se\nthermo_style custom step v_se"]))

    def m_unknown_name(self, lines):
        self.insert(lines, self.rng.choice([
            "thermo_style custom step atoms kee", "variable un equal c_nosuch+1\nthermo_style custom step v_un",
            "variable un equal stepz\nthermo_style custom step v_un", 'print "$(nosuch*2)"']))

    def mutate(self, lines, n):
        ops = [m for m in dir(self) if m.startswith("m_")]
        weights = {"m_number": 6, "m_drop_word": 2, "m_dup_word": 2, "m_swap_words": 2, "m_neighbour_word": 3,
                   "m_drop_line": 2, "m_dup_line": 2, "m_swap_lines": 2, "m_truncate": 2}
        for _ in range(n):
            op = self.rng.choices(ops, [weights.get(o, 1) for o in ops])[0]
            getattr(self, op)(lines)
        return op


def cap_runs(lines, cap):
    """Short runs: `run N` -> `run min(N, cap)`; a run given by a formula becomes `run cap`."""
    out = []
    for l in lines:
        m = re.match(r"^(\s*run\s+)(\S+)(.*)$", l)
        if m:
            try:
                v = float(m.group(2))
                if 0 <= v <= 1e15:
                    l = "%s%d%s" % (m.group(1), min(int(v), cap), m.group(3))
                elif v > 1e15:  # a mutated count (inf, 2^63): as long as the cap
                    l = "%s%d%s" % (m.group(1), cap, m.group(3))
            except ValueError:
                l = "%s%d%s" % (m.group(1), cap, m.group(3))
        out.append(l)
    return out


def make_mutant(seeds, commands, words, master_seed, k, cap):
    rng = random.Random("%d:%d" % (master_seed, k))
    path, lines = rng.choice(seeds)
    lines = cap_runs(list(lines), cap)
    op = Mutator(rng, commands, words).mutate(lines, rng.choice([1, 1, 1, 2, 3]))
    lines = cap_runs(lines, cap)  # a mutated `run N` is capped too (an uncapped `run 2^31 upto` is no hang of sable's)
    return path, "\n".join(lines) + "\n", op


BLOCKED_FACTOR = 30  # wall-clock seconds per CPU second of budget before a run counts as blocked
ENDLESS_RUNS = 20  # runs finished by a mutant that spent its CPU budget: it loops over them


def cpu_seconds(pid):
    """User + system CPU seconds of a live process (/proc/PID/stat), None if gone."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            fields = f.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return None


def finished_runs(log):
    """The `run`s a killed mutant finished (its log's timing blocks; one the log's buffer still
    held may be missing)."""
    try:
        with open(log, errors="replace") as f:
            return len(loop_times(f.read()))
    except OSError:
        return 0


def run_one(sable, seed_path, text, cpu_limit, keep=None):
    work = keep or tempfile.mkdtemp(prefix="sable_fuzz_")
    os.makedirs(work, exist_ok=True)
    try:
        for extra in glob.glob(os.path.join(os.path.dirname(seed_path), "*")):
            if not extra.endswith(".in") and os.path.isfile(extra):
                dst = os.path.join(work, os.path.basename(extra))
                if not os.path.exists(dst):
                    os.symlink(extra, dst)
        with open(os.path.join(work, "mutant.in"), "w") as f:
            f.write(text)
        env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive")
        env.setdefault("ASAN_OPTIONS", "detect_leaks=0")
        limit = max(1, int(math.ceil(cpu_limit)))
        cmd = ["prlimit", "--cpu=%d:%d" % (limit, limit + 5), "--core=0",
               sable, "-in", "mutant.in", "-log", "fuzz.log", "-screen", "none"]
        p = subprocess.Popen(cmd, cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env,
                             start_new_session=True)
        try:
            # Backstop for a blocked process only: it spends no CPU, so the CPU limit never fires.
            _, err = p.communicate(timeout=BLOCKED_FACTOR * limit)
        except subprocess.TimeoutExpired:
            cpu = cpu_seconds(p.pid)
            os.killpg(p.pid, signal.SIGKILL)
            p.communicate()
            return "hang", "blocked: %s CPU seconds in %d s of wall clock" % (cpu, BLOCKED_FACTOR * limit)
        if p.returncode in (-signal.SIGXCPU, -signal.SIGKILL):  # the CPU budget ran out (hard limit: SIGKILL)
            return ("endless" if finished_runs(os.path.join(work, "fuzz.log")) >= ENDLESS_RUNS else "hang"), ""
        err = err.decode(errors="replace")
        if p.returncode < 0 or SANITIZER.search(err):
            return "crash", err[-2000:]
        if p.returncode == 0:
            return "ok", ""
        at = err.find("ERROR:")
        return ("error" if at >= 0 and LOCATED.search(err[at:]) else "noloc"), err[-2000:]
    finally:
        if not keep:
            shutil.rmtree(work, ignore_errors=True)


BOX = ("units si\natom_style granular\nregion box block 0 1 0 1 0 1 units box\ncreate_box 1 box\n"
       "create_atoms 1 single 0.5 0.5 0.5 units box\nfix i all nve/sphere\ntimestep 1e-6\n")
CONTROLS = [  # (what, deck, expected class, CPU budget)
    ("a run that steps for ever", BOX + "run 2000000000\n", "hang", 2),
    ("a loop over `run` without end", BOX + "label a\nrun 10\njump SELF a\n", "endless", 2),
    ("a bad number", BOX + "timestep abc\n", "error", 20),
    ("a good deck", BOX + "run 10\n", "ok", 20),
]


def controls(sable):
    """The classifier's positive controls: each class is reached by a deck made for it."""
    bad = 0
    for what, text, want, budget in CONTROLS:
        kind, err = run_one(sable, os.path.join(ROOT, "tests", "decks", "control.in"), text, budget)
        print("%-32s -> %-8s (expected %s) %s" % (what, kind, want, short(err)))
        bad += kind != want
    return 1 if bad else 0


def short(err):
    lines = [l for l in err.splitlines() if l.strip()]
    return lines[-1][:300] if lines else ""


def save_bad(directory, k, kind, text, err):
    """A draft regression deck. tests/expect_error.cmake wants '# expect: FILE:LINE: TEXT': a
    noloc mutant's draft names where the error should point as FILE:?: (fill in by hand)."""
    os.makedirs(directory, exist_ok=True)
    base = "fuzz_%s_%d.in" % (kind, k)
    expect = ""
    if kind == "noloc":
        expect = "%s:?: %s" % (base, short(err).replace("ERROR: ", "")[:60])
    name = os.path.join(directory, base)
    with open(name, "w") as f:
        f.write("# expect: %s\n# found by tests/fuzz/fuzz_decks.py (%s)\n%s" % (expect, kind, text))
    return name


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sable", default=os.path.join(ROOT, "build", "sable"))
    ap.add_argument("--seed", type=int, default=24)
    ap.add_argument("--count", type=int, default=300)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--cpu-limit", type=float, default=20.0, help="CPU seconds before a run counts as a hang")
    ap.add_argument("--cap", type=int, default=20, help="largest `run N` kept")
    ap.add_argument("--long", action="store_true", help="run for --minutes and write --report")
    ap.add_argument("--minutes", type=float, default=60.0)
    ap.add_argument("--report", default="fuzz_report.txt")
    ap.add_argument("--save-bad", default=None, help="write crash/hang/noloc mutants here")
    ap.add_argument("--only", type=int, default=None, help="run only mutant K (to reproduce)")
    ap.add_argument("--keep", default=None, help="with --only: keep the run folder here")
    ap.add_argument("--print", action="store_true", help="with --only: print the mutant deck")
    ap.add_argument("--controls", action="store_true", help="positive controls of the classifier, then exit")
    args = ap.parse_args()
    args.sable = os.path.abspath(args.sable)
    if not os.access(args.sable, os.X_OK):
        sys.exit("no sable binary at %s" % args.sable)
    seeds = load_seeds()
    commands, words = vocabulary(seeds)

    if args.controls:
        return controls(args.sable)
    if args.only is not None:
        path, text, op = make_mutant(seeds, commands, words, args.seed, args.only, args.cap)
        if args.print:
            print(text)
        kind, err = run_one(args.sable, path, text, args.cpu_limit, args.keep)
        print("mutant %d of %s (%s): %s\n%s" % (args.only, os.path.relpath(path, ROOT), op, kind, err))
        return 0 if kind in ("ok", "error") else 1

    t0 = time.time()
    deadline = t0 + args.minutes * 60 if args.long else None
    counts, findings = {}, []

    def jobs():
        k = 0
        while (k < args.count) if deadline is None else (time.time() < deadline):
            yield k
            k += 1

    with cf.ThreadPoolExecutor(args.jobs) as ex:
        pending = {}
        it = jobs()
        def submit():
            k = next(it, None)
            if k is None:
                return False
            path, text, op = make_mutant(seeds, commands, words, args.seed, k, args.cap)
            pending[ex.submit(run_one, args.sable, path, text, args.cpu_limit)] = (k, path, text, op)
            return True
        for _ in range(args.jobs * 2):
            submit()
        while pending:
            done, _ = cf.wait(pending, return_when=cf.FIRST_COMPLETED)
            for fut in done:
                k, path, text, op = pending.pop(fut)
                kind, err = fut.result()
                counts[kind] = counts.get(kind, 0) + 1
                if kind in ("crash", "hang", "noloc"):
                    findings.append((k, kind, os.path.relpath(path, ROOT), op, short(err)))
                    print("%-6s mutant %d (%s, %s): %s" % (kind, k, os.path.relpath(path, ROOT), op, short(err)),
                          flush=True)
                    if args.save_bad:
                        save_bad(args.save_bad, k, kind, text, err)
                submit()
    total = sum(counts.values())
    summary = "fuzz seed %d: %d mutants in %.0f s: %s" % (
        args.seed, total, time.time() - t0, ", ".join("%s %d" % kv for kv in sorted(counts.items())))
    print(summary)
    if args.long:
        with open(args.report, "w") as f:
            f.write(summary + "\n\nreproduce one: tests/fuzz/fuzz_decks.py --seed %d --only K --print\n\n" % args.seed)
            for k, kind, path, op, msg in findings:
                f.write("%-6s %6d %-40s %-18s %s\n" % (kind, k, path, op, msg))
        print("report written to", args.report)
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
