#!/usr/bin/env python3
"""Runs one good deck of tests/decks/ and judges what its header claims.

    check_deck.py --sable BIN DECK [--expect-fail TEXT]

The deck runs as `BIN -in DECK -log none -echo none` in the current directory; a nonzero
exit fails. A deck must say how it is judged, in its leading comment lines:

  # check: KEY OP VALUE [tol T | rel R]  (source: ...)
      KEY is a key of the deck's `RESULT key=value ...` output lines, OP one of
      = == < > <= >= !=, VALUE a number or an arithmetic expression over numbers
      and other RESULT keys (+ - * / **, abs sqrt exp sin cos pi). With `=`, tol is an
      absolute and rel a relative (to |VALUE|) tolerance, each a number or such an
      expression (a bound the deck computes, e.g. from its momentum); without either the
      values must be equal. Every check names the source of its value and
      tolerance (analytic, LIGGGHTS, YADE, ...). A missing key fails.
  # check-output: TEXT  (source: ...)
      the deck's output (screen) must contain TEXT.
  # check-file: FILE contains TEXT  (source: ...)
  # check-file: FILE matches REGEX  (source: ...)
      FILE, written by the run in its directory (removed before it), must contain
      TEXT (\n for a line break, \" for a quote; TEXT may be quoted "...") or a
      match of the Python regular expression REGEX (for numbers known to so many digits).
  a `fix ... halt ... error hard` in the deck (an in-deck check that stops the run).
  # judged-by: tests/unit/test_X.cpp
      that file must exist and name the deck.
  # smoke: WHY
      the deck only exercises commands; WHY says what and why nothing is judged.
  # runs-after: DECKNAME
      (for tests/CMakeLists.txt) run in DECKNAME's run directory after it.

With --ranks N the deck runs under `mpirun -np N` (oversubscribed, OpenMPI's root
variables set): it passes if it runs and its claims hold (an exact `=` within 1e-9
relative: the rank split's round-off), or if it stops at a located
line saying what does not run on N ranks yet (core/input/several_ranks.cpp); exit 77
(skipped) where mpirun or this build's MPI is missing.

A deck with none of the first four fails. --expect-fail TEXT inverts the
verdict for the checker's own controls (tests/decks/checker/): the run passes
only if the judgement fails with a message containing TEXT.
"""
import argparse
import ast
import math
import os
import re
import subprocess
import sys

from sable_tools.readers.screen import merged_keys  # PYTHONPATH: the repository (tests/CMakeLists.txt)

OPS = {
    "=": lambda a, b: a == b,
    "==": lambda a, b: a == b,
    "!=": lambda a, b: a != b,
    "<": lambda a, b: a < b,
    ">": lambda a, b: a > b,
    "<=": lambda a, b: a <= b,
    ">=": lambda a, b: a >= b,
}
# --ranks: an exact claim (`=` without tol or rel) holds on one rank; on several, each grain's
# forces are summed in another order and a pair across two subdomains is evaluated on both:
# round-off, which a deck's collisions amplify (1e-13 to 1e-12 measured, tests/mpi_ranks.py).
RANKS_REL = 1e-9
FUNCS = {"abs": abs, "sqrt": math.sqrt, "exp": math.exp, "sin": math.sin, "cos": math.cos}
CONSTS = {"pi": math.pi, "PI": math.pi}

CHECK_RE = re.compile(
    r"^#\s*check:\s*(?P<key>[A-Za-z_][\w.]*)\s*(?P<op>==|!=|<=|>=|=|<|>)\s*(?P<value>.+?)"
    r"(?:\s+(?P<kind>tol|rel)\s+(?P<tol>.+?))?\s*\(source:\s*(?P<source>.*\S)\s*\)\s*$")
OUTPUT_RE = re.compile(r"^#\s*check-output:\s*(?P<text>.+?)\s*\(source:\s*(?P<source>.*\S)\s*\)\s*$")
FILE_RE = re.compile(r"^#\s*check-file:\s*(?P<file>\S+)\s+(?P<how>contains|matches)\s+(?P<text>.+?)\s*\(source:\s*(?P<source>.*\S)\s*\)\s*$")
HALT_RE = re.compile(r"^\s*fix\s+\S+\s+\S+\s+halt\s+(?P<rest>.*)$")


class Fail(Exception):
    pass


def evaluate(expr, results):
    """Arithmetic over numbers and RESULT keys, nothing else (no names of Python's)."""
    def ev(node):
        if isinstance(node, ast.Expression):
            return ev(node.body)
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
            return float(node.value)
        if isinstance(node, ast.Name):
            if node.id in results:
                return number(node.id, results[node.id])
            if node.id in CONSTS:
                return CONSTS[node.id]
            raise Fail("check value '%s': '%s' is neither a RESULT key nor a constant" % (expr, node.id))
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            v = ev(node.operand)
            return -v if isinstance(node.op, ast.USub) else v
        if isinstance(node, ast.BinOp):
            a, b = ev(node.left), ev(node.right)
            ops = {ast.Add: lambda: a + b, ast.Sub: lambda: a - b, ast.Mult: lambda: a * b,
                   ast.Div: lambda: a / b, ast.Pow: lambda: a ** b}
            if type(node.op) in ops:
                return ops[type(node.op)]()
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in FUNCS
                and len(node.args) == 1 and not node.keywords):
            return FUNCS[node.func.id](ev(node.args[0]))
        raise Fail("check value '%s': only numbers, RESULT keys, + - * / ** and %s are allowed"
                   % (expr, ", ".join(FUNCS)))
    try:
        tree = ast.parse(expr.strip(), mode="eval")
    except SyntaxError:
        raise Fail("check value '%s' is not an expression" % expr)
    return ev(tree)


def unquote(text):
    text = text.strip()
    if len(text) >= 2 and text[0] == text[-1] == '"':
        text = text[1:-1]
    return text.replace("\\n", "\n").replace('\\"', '"')


def number(key, text):
    try:
        return float(text)
    except ValueError:
        raise Fail("RESULT %s=%s is not a number" % (key, text))


def header(deck_text):
    """The deck's leading comment block (blank lines allowed) and every comment line after it."""
    return [l.strip() for l in deck_text.splitlines() if l.strip().startswith("#")]


def halt_checks(deck_text):
    """The deck's `fix ... halt` lines that stop the run with an error (hard is halt's default)."""
    found = []
    joined = re.sub(r"&\s*\n", " ", deck_text)
    for line in joined.splitlines():
        m = HALT_RE.match(line.split("#", 1)[0])
        if not m:
            continue
        words = m.group("rest").split()
        if "error" in words:
            i = words.index("error")
            if i + 1 < len(words) and words[i + 1] != "hard":
                continue
        found.append(line.strip())
    return found


def results_of(output):
    try:
        return merged_keys(output, "RESULT")
    except ValueError as e:
        raise Fail(str(e))


def judge(args):
    deck = os.path.abspath(args.deck)
    name = os.path.splitext(os.path.basename(deck))[0]
    text = open(deck).read()
    comments = header(text)
    checks, judged_by, smoke, outputs, files = [], [], [], [], []
    for c in comments:
        if re.match(r"^#\s*check-output:", c):
            m = OUTPUT_RE.match(c)
            if not m:
                raise Fail("malformed check-output line (want '# check-output: TEXT (source: ...)'): %s" % c)
            outputs.append(m)
        elif re.match(r"^#\s*check-file:", c):
            m = FILE_RE.match(c)
            if not m:
                raise Fail("malformed check-file line (want '# check-file: FILE contains|matches TEXT (source: ...)'): %s" % c)
            files.append(m)
        elif re.match(r"^#\s*check:", c):
            m = CHECK_RE.match(c)
            if not m:
                raise Fail("malformed check line (want '# check: KEY OP VALUE [tol T | rel R] (source: ...)'): %s" % c)
            checks.append(m)
        elif re.match(r"^#\s*judged-by:", c):
            judged_by.append(c.split(":", 1)[1].strip())
        elif re.match(r"^#\s*smoke:", c):
            why = c.split(":", 1)[1].strip()
            if len(why) < 10:
                raise Fail("a '# smoke:' line must say what the deck exercises and why nothing is judged")
            smoke.append(why)
    halts = halt_checks(text)
    if not (checks or outputs or files or judged_by or smoke or halts):
        raise Fail("%s judges nothing: give it '# check:' lines, a fix halt ... error hard, "
                   "'# judged-by: FILE' or '# smoke: WHY' (tests/check_deck.py)" % name)
    root = os.path.dirname(os.path.dirname(os.path.dirname(deck)))
    for f in judged_by:
        path = os.path.join(root, f)
        if not os.path.isfile(path):
            raise Fail("judged-by file %s does not exist" % f)
        if name not in open(path, errors="replace").read():
            raise Fail("judged-by file %s does not name the deck %s" % (f, name))

    # A file left by an earlier run must not pass for this run's output.
    for m in files:
        if os.path.isfile(m.group("file")):
            os.remove(m.group("file"))
    cmd = [args.sable, "-in", deck, "-log", "none", "-echo", "none"]
    env = dict(os.environ, OMP_WAIT_POLICY="passive")
    if args.ranks:
        cmd = ["mpirun", "-np", str(args.ranks), "--oversubscribe", "--bind-to", "none"] + cmd
        # more ranks than cores: a waiting rank must give its core to the one it waits for
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1",
                   OMPI_MCA_mpi_yield_when_idle="1")
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env)
    out = p.stdout.decode(errors="replace")
    sys.stdout.write(out)
    if p.returncode != 0 and args.ranks:
        refused = re.search(r"^ERROR: (\S+\.in:\d+): .*on %d MPI ranks" % args.ranks, out, re.M)
        if refused:
            print("check_deck: %s stops on %d ranks at %s (not run there yet)" % (name, args.ranks, refused.group(1)))
            return
    if p.returncode != 0:
        raise Fail("%s exited with %d" % (" ".join(cmd), p.returncode))
    res = results_of(out)
    bad = []
    for m in checks:
        key, op, value, kind, tol, src = (m.group(g) for g in ("key", "op", "value", "kind", "tol", "source"))
        if key not in res:
            bad.append("check '%s': no RESULT %s=... in the output" % (m.group(0), key))
            continue
        got = number(key, res[key])
        want = evaluate(value, res)
        if kind:
            if op not in ("=", "=="):
                raise Fail("check '%s': tol/rel only go with '='" % m.group(0))
            t = evaluate(tol, res) * (abs(want) if kind == "rel" else 1.0)
            ok = abs(got - want) <= t
            verdict = "|%s - %.17g| = %.3g %s %.3g" % (res[key], want, abs(got - want), "<=" if ok else ">", t)
        elif args.ranks and op in ("=", "=="):
            # exact on one rank; the rank split sums forces in another order
            t = RANKS_REL * abs(want)
            ok = abs(got - want) <= t
            verdict = "|%s - %.17g| = %.3g %s %.3g (exact on one rank; %g relative on %d ranks)" % (
                res[key], want, abs(got - want), "<=" if ok else ">", t, RANKS_REL, args.ranks)
        else:
            ok = OPS[op](got, want)
            verdict = "%s %s %.17g" % (res[key], op, want)
        line = "%s: %s %s %s (source: %s): %s" % ("ok" if ok else "FAILED", key, op, value, src, verdict)
        print("check_deck: " + line)
        if not ok:
            bad.append(line)
    for m in outputs:
        text = unquote(m.group("text"))
        ok = text in out
        line = "%s: output contains '%s' (source: %s)" % ("ok" if ok else "FAILED", text, m.group("source"))
        print("check_deck: " + line)
        if not ok:
            bad.append(line)
    for m in files:
        how = m.group("how")
        text = unquote(m.group("text")) if how == "contains" else m.group("text")
        path = m.group("file")
        body = open(path, errors="replace").read() if os.path.isfile(path) else None
        ok = body is not None and (text in body if how == "contains" else re.search(text, body) is not None)
        line = "%s: %s %s '%s' (source: %s)" % ("ok" if ok else "FAILED", path,
                                               how if body is not None else "(missing) " + how,
                                               text.replace("\n", "\\n"), m.group("source"))
        print("check_deck: " + line)
        if not ok:
            bad.append(line)
    if bad:
        raise Fail("; ".join(bad))
    what = []
    if checks or outputs or files:
        what.append("%d checks" % (len(checks) + len(outputs) + len(files)))
    if halts:
        what.append("%d in-deck halt checks" % len(halts))
    if judged_by:
        what.append("judged by " + ", ".join(judged_by))
    if smoke:
        what.append("smoke: " + smoke[0])
    print("check_deck: %s passed (%s)" % (name, "; ".join(what)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sable", required=True)
    ap.add_argument("--expect-fail", metavar="TEXT")
    ap.add_argument("--ranks", type=int, default=0, help="run under mpirun -np RANKS")
    ap.add_argument("deck")
    args = ap.parse_args()
    if args.ranks:
        import shutil
        if not shutil.which("mpirun") or "Built with MPI" not in subprocess.run(
                [args.sable, "--help"], capture_output=True, text=True).stdout:
            print("check_deck: mpirun or this build's MPI is missing: skipped")
            return 77
    try:
        judge(args)
    except Fail as e:
        msg = str(e)
        if args.expect_fail is not None:
            if args.expect_fail in msg:
                print("check_deck: failed as expected: %s" % msg)
                return 0
            print("check_deck: failed, but not with '%s': %s" % (args.expect_fail, msg))
            return 1
        print("check_deck: FAILED: %s" % msg)
        return 1
    if args.expect_fail is not None:
        print("check_deck: passed, but should have failed with '%s'" % args.expect_fail)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
