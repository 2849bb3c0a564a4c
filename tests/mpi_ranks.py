#!/usr/bin/env python3
"""sable under mpirun (issue 48, the foundation: core/engine/comm.h).

`mpirun -np 2` must stop every rank with a non-zero status and the refusal printed once
(rank 0), before any file is written, within the time limit (no hang: the ranks end
with a collective MPI_Finalize). `mpirun -np 1` runs the deck and prints LAMMPS' grid
line. Usage: mpi_ranks.py SABLE DECK. Exit 77 (skipped) without mpirun, or when this
build of sable has no MPI (`sable --help` says which).
"""
import os
import shutil
import subprocess
import sys
import tempfile

REFUSAL = "cannot split the box across ranks yet"


def mpirun(np, sable, deck, cwd):
    env = {**os.environ, "OMP_NUM_THREADS": "1"}
    if os.geteuid() == 0:  # OpenMPI's mpirun refuses root without these (containers, CI)
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = ["mpirun", "-np", str(np), "--oversubscribe", sable, "-in", deck, "-log", "log.sable"]
    return subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=120)


def main():
    sable, deck = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    if shutil.which("mpirun") is None:
        print("mpirun not found (Debian: openmpi-bin): skipped")
        return 77
    if "Built with MPI" not in subprocess.run([sable, "--help"], capture_output=True, text=True).stdout:
        print("this sable was built without MPI (SABLE_MPI off or no libopenmpi-dev): skipped")
        return 77
    failures = []
    with tempfile.TemporaryDirectory() as cwd:
        p = mpirun(2, sable, deck, cwd)
        said = (p.stdout + p.stderr).count(REFUSAL)
        print("np 2: exit %d, refusal printed %d time(s)\n%s%s" % (p.returncode, said, p.stdout, p.stderr))
        if p.returncode == 0: failures.append("np 2 exited 0")
        if said != 1: failures.append("np 2 printed the refusal %d times, not once" % said)
        if os.path.exists(os.path.join(cwd, "log.sable")): failures.append("np 2 wrote a log")
    with tempfile.TemporaryDirectory() as cwd:
        p = mpirun(1, sable, deck, cwd)
        print("np 1: exit %d" % p.returncode)
        if p.returncode != 0: failures.append("np 1 failed:\n" + p.stdout[-2000:] + p.stderr[-2000:])
        elif "  1 by 1 by 1 MPI processor grid" not in p.stdout: failures.append("np 1 printed no grid line")
    for f in failures: print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
