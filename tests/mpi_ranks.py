#!/usr/bin/env python3
"""sable on several MPI ranks (issue 48; core/engine/comm.h, docs/parallel.md).

tests/mpi/bed.in (720 grains falling on a floor with friction, periodic in x and y) runs
on one process without mpirun (the reference), under `mpirun -np 1`, and on grids of 2,
3 and 4 ranks that cut it across its periodic faces and across its height. Checks:
- `mpirun -np 1` prints the same RESULT line as the run without mpirun, to the bit;
- every grid prints its `Px by Py by Pz MPI processor grid` line and the grain count at
  every step is 720 (no grain lost or doubled by a migration);
- each RESULT value (kinetic energy, top of the bed, the floor's force, centre of mass,
  its velocity) equals the one-rank value within 1e-9 relative after 1200 steps. The
  ranks sum each grain's forces in another order and evaluate a pair across a
  subdomain face from both sides, so the values differ by round-off, which the bed's
  collisions amplify: 1e-13 measured at 1200 steps (1e-3 by 3000 steps, when the bed
  has settled chaotically); the bound leaves room for the compiler and CPU;
- the final dump (write_dump ... modify sort id, gathered to rank 0) lists the same grains in
  the same order, each position within 1e-12 m of the one-rank value (1e-15 m measured);
- a mesh wall: tests/mpi/drum.in (400 grains falling in a rotating STL drum, tangential
  history on its triangles) on grids 2x1x1, 1x1x2 and 3x1x1: the drum's force and torque, the
  kinetic energy and the centre of mass within 1e-9 of one rank after 5000 steps (2e-12
  measured);
- insertion: tests/mpi/insert.in (insert/pack of 625 grains into a box holding a lattice of
  75) on grids 2x1x1, 1x1x2, 3x1x1 and 2x2x1 dumps, after one step, byte for byte the grains of
  one rank (ids, radii, positions, velocities drawn by the fix): the same grains whatever N;
- a restart written on 2 ranks (tests/decks/restart_write.in, check_deck.py --ranks 2) is read
  on 3 (restart_read.in, --ranks 3), whose run goes on to the uninterrupted one-rank run's
  values (its claims, within 1e-9 relative);
- balance shift: the bed on 1x1x2 with `balance 1.0 shift xyz 5 1.0` moves the z cut from 432/288
  grains to 360/360 (imbalance factor 1.2 to 1), keeps its 720 grains, and agrees with one rank
  within 1e-9;
- fix balance: the same bed on 1x1x2 with `fix bal all balance 100 1.02 shift xyz 5 1.02`
  moves the cut during the run (f_bal[3] > 0, the grains following at the next step's
  rebuild) and agrees with one rank within 1e-9;
- threads inside the ranks: a bed of 10240 grains (5120 per rank: the pair pass is threaded,
  ghosts' entries included) on 2 ranks of 2 threads gives the same bits as 2 ranks of one
  thread, and agrees with one process within 1e-9 after 1500 steps (2e-12 measured);
- a grain that leaves the box (an error on its rank alone, the others waiting in a collective)
  ends every rank with a non-zero status and the error naming the step and the grain, no hang;
- a deck using a style that does not run on several ranks yet (a VTK dump) stops with a
  non-zero status, its error printed once and naming its line.
Usage: mpi_ranks.py SABLE TESTS_DIR. Exit 77 (skipped) without mpirun, or when this
build of sable has no MPI (`sable --help` says which).
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

GRIDS = [(1, "1 1 1"), (2, "2 1 1"), (2, "1 1 2"), (3, "3 1 1"), (4, "2 2 1")]
REL = 1e-9
GRAINS = 720


def env(threads=1):
    # more ranks than cores: a waiting rank must give its core to the one it waits for
    e = {**os.environ, "OMP_NUM_THREADS": str(threads), "OMP_WAIT_POLICY": "passive", "OMPI_MCA_mpi_yield_when_idle": "1"}
    if os.geteuid() == 0:  # OpenMPI's mpirun refuses root without these (containers, CI)
        e.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    return e


def run(cmd, cwd, threads=1):
    return subprocess.run(cmd, cwd=cwd, env=env(threads), capture_output=True, text=True, timeout=300)


def mpirun(np, sable, args, cwd, threads=1):
    return run(["mpirun", "-np", str(np), "--oversubscribe", "--bind-to", "none", "-x", "OMP_NUM_THREADS", sable] + args,
               cwd, threads)


def result(text):
    m = re.search(r"^RESULT (.*)$", text, re.M)
    if not m:
        return None
    w = m.group(1).split()
    return {w[i]: float(w[i + 1]) for i in range(0, len(w), 2)}


def rel_diff(got, ref):
    """The largest relative difference of the RESULT values (a zero must stay zero)."""
    return max(abs(got[k] - v) / abs(v) if v != 0 else (0.0 if got[k] == 0 else float("inf")) for k, v in ref.items())


def dump_rows(path):
    """The rows of a text dump's last snapshot: (id, [values...])."""
    with open(path) as f:
        lines = f.read().splitlines()
    at = max(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    return [(int(l.split()[0]), [float(x) for x in l.split()[1:]]) for l in lines[at + 1:] if l.strip()]


def atoms_per_step(text):
    """The thermo table's Atoms column (step, atoms, ...), one row per step."""
    rows = re.findall(r"^\s+(\d+)\s+(\d+)\s+\S+", text, re.M)
    return [(int(s), int(n)) for s, n in rows]


def main():
    sable, tests = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    deck = os.path.join(tests, "mpi", "bed.in")
    if shutil.which("mpirun") is None:
        print("mpirun not found (Debian: openmpi-bin): skipped")
        return 77
    if "Built with MPI" not in subprocess.run([sable, "--help"], capture_output=True, text=True).stdout:
        print("this sable was built without MPI (SABLE_MPI off or no libopenmpi-dev): skipped")
        return 77
    failures = []
    with tempfile.TemporaryDirectory() as cwd:
        p = run([sable, "-in", deck, "-log", "none", "-var", "dump", "one.dump"], cwd)
        ref = result(p.stdout)
        ref_dump = dump_rows(os.path.join(cwd, "one.dump")) if p.returncode == 0 else []
        if p.returncode != 0 or ref is None:
            print(p.stdout[-3000:], p.stderr[-3000:])
            print("FAILED: the one-process reference run")
            return 1
        print("one process: " + " ".join("%s %.17g" % kv for kv in ref.items()))
        for np, grid in GRIDS:
            px, py, pz = grid.split()
            args = ["-in", deck, "-log", "none", "-var", "every", "1", "-var", "px", px, "-var", "py", py, "-var", "pz", pz,
                    "-var", "dump", "ranks.dump"]
            p = mpirun(np, sable, args, cwd)
            name = "np %d grid %s" % (np, grid)
            got = result(p.stdout)
            if p.returncode != 0 or got is None:
                failures.append("%s failed (exit %d):\n%s%s" % (name, p.returncode, p.stdout[-2000:], p.stderr[-2000:]))
                continue
            if "  %s by %s by %s MPI processor grid" % (px, py, pz) not in p.stdout:
                failures.append("%s printed no grid line" % name)
            counts = atoms_per_step(p.stdout)
            bad = [(s, n) for s, n in counts if n != GRAINS]
            if len(counts) < 1201 or bad:
                failures.append("%s: %d thermo rows, grain count off at %s" % (name, len(counts), bad[:5]))
            worst = rel_diff(got, ref)
            print("%s: %s; largest relative difference %.2g" % (name, " ".join("%s %.17g" % kv for kv in got.items()), worst))
            rows = dump_rows(os.path.join(cwd, "ranks.dump"))
            if [r[0] for r in rows] != [r[0] for r in ref_dump]:
                failures.append("%s: the dump's grains differ from one rank's (%d rows against %d)" %
                                (name, len(rows), len(ref_dump)))
            else:
                dx = max(abs(a - b) for (_, u), (_, w) in zip(rows, ref_dump) for a, b in zip(u[2:5], w[2:5]))
                print("%s: dump of %d grains, positions within %.2g m of one rank's" % (name, len(rows), dx))
                if dx > 1e-12:
                    failures.append("%s: a dumped position is %.3g m from one rank's (> 1e-12 m)" % (name, dx))
            if grid == "1 1 1" and got != ref:
                failures.append("mpirun -np 1 differs from the run without mpirun: %s against %s" % (got, ref))
            if worst > REL:
                failures.append("%s: relative difference %.3g > %g" % (name, worst, REL))
        p = mpirun(2, sable, ["-in", deck, "-log", "none", "-var", "balance", "1", "-var", "px", "1", "-var", "py", "1",
                              "-var", "pz", "2", "-var", "dump", "bal.dump"], cwd)
        got = result(p.stdout)
        moved = re.search(r"initial/final imbalance factor = ([0-9.]+) ([0-9.]+)", p.stdout)
        print("balance shift on 1x1x2: %s" % (moved.group(0) if moved else "no balance line"))
        if p.returncode != 0 or got is None or not moved or float(moved.group(2)) != 1.0 or float(moved.group(1)) <= 1.1:
            failures.append("balance shift: expected the imbalance 1.2 to go to 1:\n" + p.stdout[-2000:] + p.stderr[-1000:])
        else:
            worst = rel_diff(got, ref)
            if worst > REL:
                failures.append("balance shift: relative difference %.3g > %g" % (worst, REL))
        p = mpirun(2, sable, ["-in", deck, "-log", "none", "-var", "fixbal", "100", "-var", "px", "1", "-var", "py", "1",
                              "-var", "pz", "2", "-var", "dump", "fixbal.dump"], cwd)
        got = result(p.stdout)
        print("fix balance on 1x1x2: %s" % ("moves %g, largest relative difference %.2g" % (got["moves"], rel_diff(
            {k: v for k, v in got.items() if k != "moves"}, {k: v for k, v in ref.items() if k != "moves"})) if got else "failed"))
        if p.returncode != 0 or got is None or got["moves"] < 1 or rel_diff(
                {k: v for k, v in got.items() if k != "moves"}, {k: v for k, v in ref.items() if k != "moves"}) > REL:
            failures.append("fix balance: expected moves and agreement with one rank:\n" + p.stdout[-2000:] + p.stderr[-1000:])
        ins = ["-in", os.path.join(tests, "mpi", "insert.in"), "-log", "none"]
        p = run([sable] + ins + ["-var", "dump", "ins1.dump"], cwd)
        if p.returncode != 0:
            failures.append("insertion on one process failed:\n" + p.stdout[-2000:] + p.stderr[-2000:])
        else:
            ref_ins = open(os.path.join(cwd, "ins1.dump")).read()
            for np, grid in [(2, "2 1 1"), (2, "1 1 2"), (3, "3 1 1"), (4, "2 2 1")]:
                px, py, pz = grid.split()
                p = mpirun(np, sable, ins + ["-var", "dump", "insN.dump", "-var", "px", px, "-var", "py", py,
                                             "-var", "pz", pz], cwd)
                same = p.returncode == 0 and open(os.path.join(cwd, "insN.dump")).read() == ref_ins
                print("insertion, grid %s: %s" % (grid, "the same grains, byte for byte" if same else "DIFFERENT"))
                if not same:
                    failures.append("insertion on grid %s differs from one rank (exit %d):\n%s" %
                                    (grid, p.returncode, p.stdout[-1500:] + p.stderr[-1500:]))
        with tempfile.TemporaryDirectory() as rdir:
            check = [sys.executable, os.path.join(tests, "check_deck.py"), "--sable", sable]
            cenv = {**env(), "PYTHONPATH": os.path.dirname(tests)}
            verdicts = []
            for np, deck_name in ((2, "restart_write"), (3, "restart_read")):
                p = subprocess.run(check + ["--ranks", str(np), os.path.join(tests, "decks", deck_name + ".in")], cwd=rdir,
                                   env=cenv, capture_output=True, text=True, timeout=300)
                ok = p.returncode == 0 and ("check_deck: %s passed" % deck_name) in p.stdout
                verdicts.append(ok)
                print("%s on %d ranks: %s" % (deck_name, np, "passed" if ok else "FAILED"))
                if not ok:
                    failures.append("%s on %d ranks:\n%s%s" % (deck_name, np, p.stdout[-2500:], p.stderr[-1000:]))
        drum = ["-in", os.path.join(tests, "mpi", "drum.in"), "-log", "none", "-var", "stl",
                os.path.join(tests, "decks", "mesh_drum.stl")]
        p = run([sable] + drum, cwd)
        one = result(p.stdout)
        if p.returncode != 0 or one is None:
            failures.append("the drum on one process failed:\n" + p.stdout[-2000:] + p.stderr[-2000:])
        else:
            for np, grid in [(2, "2 1 1"), (2, "1 1 2"), (3, "3 1 1")]:
                px, py, pz = grid.split()
                p = mpirun(np, sable, drum + ["-var", "px", px, "-var", "py", py, "-var", "pz", pz], cwd)
                got = result(p.stdout)
                if p.returncode != 0 or got is None:
                    failures.append("the drum on grid %s failed:\n%s%s" % (grid, p.stdout[-2000:], p.stderr[-2000:]))
                    continue
                worst = max(abs(got[k] - v) / abs(v) for k, v in one.items() if v != 0)
                print("drum, grid %s: %s; largest relative difference %.2g" % (grid, got, worst))
                if got["fz"] == 0 or worst > REL:
                    failures.append("the drum on grid %s: relative difference %.3g > %g (or no wall force)" % (grid, worst, REL))
        big = ["-in", deck, "-log", "none", "-var", "nxy", "16", "-var", "nz", "10", "-var", "steps", "1500",
               "-var", "every", "500"]
        p = run([sable] + big, cwd)
        one = result(p.stdout)
        grid = ["-var", "px", "2", "-var", "py", "1", "-var", "pz", "1"]
        by_threads = {}
        for threads in (1, 2):
            p = mpirun(2, sable, big + grid, cwd, threads)
            by_threads[threads] = result(p.stdout)
            if p.returncode != 0 or by_threads[threads] is None:
                failures.append("10240 grains, np 2 x %d threads failed:\n%s%s" % (threads, p.stdout[-2000:], p.stderr[-2000:]))
        if one and by_threads.get(1) and by_threads.get(2):
            worst = max(abs(by_threads[1][k] - v) / abs(v) for k, v in one.items() if v != 0)
            print("10240 grains, np 2 x 1 thread: %s; x 2 threads %s; against one process %.2g" %
                  (by_threads[1], "the same bits" if by_threads[1] == by_threads[2] else by_threads[2], worst))
            if by_threads[1] != by_threads[2]:
                failures.append("10240 grains on 2 ranks: 2 threads differ from 1: %s against %s" % (by_threads[2], by_threads[1]))
            if worst > REL:
                failures.append("10240 grains on 2 ranks: relative difference %.3g > %g" % (worst, REL))
        p = mpirun(2, sable, ["-in", deck, "-log", "none", "-var", "kick", "5", "-var", "px", "1", "-var", "py", "1",
                              "-var", "pz", "2"], cwd)
        out = p.stdout + p.stderr
        lost = re.search(r"ERROR.*step (\d+): atom 720 left the box", out)
        print("np 2, grain 720 shot out of the box: exit %d, %s" % (p.returncode, lost.group(0) if lost else "no error line"))
        if p.returncode == 0 or not lost:
            failures.append("np 2, a grain leaving the box: expected a located error and a non-zero exit:\n" + out[-2000:])
        dumps = os.path.join(tests, "decks", "output_dumps.in")  # its dump custom/vtk does not run there yet
        p = mpirun(2, sable, ["-in", dumps, "-log", "none"], cwd)
        out = p.stdout + p.stderr
        said = len(re.findall(r"^ERROR", out, re.M))  # sable's lines (OpenMPI's abort adds ORTE_ERROR_LOG noise)
        print("np 2, a deck with a VTK dump: exit %d, %d error line(s)" % (p.returncode, said))
        if p.returncode == 0 or said != 1 or "output_dumps.in:" not in out or "runs on 2 MPI ranks" not in out:
            failures.append("np 2 with a VTK dump: expected one located refusal and a non-zero exit:\n" + out[-2000:])
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
