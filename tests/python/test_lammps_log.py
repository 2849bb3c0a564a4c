"""sable's log read as LAMMPS log readers read one, by a small parser written here from LAMMPS'
documented markers (its manual's "Screen and logfile output", and the conventions of the
common readers): a run's thermo table opens after "Memory usage per processor" (LIGGGHTS,
older LAMMPS) or "Per MPI rank memory allocation" (newer LAMMPS), with a header line whose
first word is Step; rows of numbers follow, one per thermo output; "Loop time of T on P procs
for N steps with M atoms" closes it. Lines with other words inside a table (warnings, progress)
are skipped, as LAMMPS' own Python reader (lammps.formats.LogFile) skips them.
The same log is then read by sable_tools.readers.screen, which the studies use."""
import os
import re
import subprocess

from sable_tools.readers import screen
from scenes import falling_pair

RUN_START = ("Memory usage per processor", "Per MPI rank memory allocation")
LOOP = re.compile(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms$")
HEADER = re.compile(r"^\s*Step\s")
NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")

# Two grains falling: runs of 50 and 30 steps with a thermo row every 10 steps.
DECK = falling_pair("step atoms ke v_z1 vol", between='print "between the runs"')


def lammps_runs(text):
    """Each run's thermo table: dict(start=marker seen, columns, rows, skipped lines, loop=(T, P, N, M))."""
    runs, run, after_marker = [], None, False
    for line in text.splitlines():
        if line.startswith(RUN_START):
            after_marker = True
            continue
        if HEADER.match(line):
            run = dict(start=after_marker, columns=line.split(), rows=[], skipped=0, loop=None)
            after_marker = False
            continue
        after_marker = False
        if run is None:
            continue
        m = LOOP.match(line)
        if m:
            run["loop"] = (float(m.group(1)), int(m.group(2)), int(m.group(3)), int(m.group(4)))
            runs.append(run)
            run = None
            continue
        words = line.split()
        if len(words) == len(run["columns"]) and all(NUMBER.match(w) for w in words):
            run["rows"].append([float(w) for w in words])
        else:
            run["skipped"] += 1
    return runs


def run_deck(sable, tmp_path, *args):
    (tmp_path / "in.deck").write_text(DECK)
    p = subprocess.run([sable, "-in", "in.deck", *args], cwd=tmp_path, capture_output=True, text=True, timeout=120,
                       env={**os.environ, "OMP_NUM_THREADS": "1"})
    assert p.returncode == 0, p.stderr
    return p.stdout, (tmp_path / "log.sable").read_text()


def check_runs(runs, skipped_allowed):
    assert len(runs) == 2
    first_step = 0
    for run, steps in zip(runs, (50, 30)):
        assert run["start"], "the header must follow the run's memory line"
        assert run["columns"] == ["Step", "Atoms", "KinEng", "v_z1", "Volume"]
        assert run["loop"][1:] == (1, steps, 2)
        assert len(run["rows"]) == steps // 10 + 1  # the run's first step, then every 10 steps
        assert [r[0] for r in run["rows"]] == list(range(first_step, first_step + steps + 1, 10))
        assert all(r[1] == 2 and r[4] == 1.0 for r in run["rows"])  # two atoms, the unit box
        assert run["skipped"] == 0 or skipped_allowed
        first_step += steps
    # the grain falls: its height drops and the kinetic energy grows from the first row to the last
    rows = runs[0]["rows"] + runs[1]["rows"]
    assert rows[-1][3] < rows[0][3] and rows[-1][2] > rows[0][2] == 0.0


def test_log_parses_with_lammps_markers(sable, tmp_path):
    _, log = run_deck(sable, tmp_path)
    check_runs(lammps_runs(log), skipped_allowed=False)


def test_progress_lines_stay_off_the_logs_tables(sable, tmp_path):
    out, log = run_deck(sable, tmp_path, "-progress", "0")
    check_runs(lammps_runs(log), skipped_allowed=False)  # the log's tables hold rows only
    runs = lammps_runs(out)
    check_runs(runs, skipped_allowed=True)  # the screen's progress lines are lines with words
    assert [r["skipped"] for r in runs] == [49, 29]


def test_sables_reader_reads_the_same_log(sable, tmp_path):
    _, log = run_deck(sable, tmp_path)
    _, series = screen.parse_screen(log)
    assert set(series) == {"atoms", "ke", "z1", "vol"}  # LAMMPS' KinEng and Volume under their keywords
    assert series["atoms"][0] == list(range(0, 81, 10)) and series["atoms"][1] == [2.0] * 9
    loop = screen.sable_loop(log)
    assert (loop["steps"], loop["atoms"]) == (30, 2) and loop["builds"] >= 0 and loop["psps_printed"] > 0
    assert set(loop["split"]) == {"pair", "neigh", "integrate", "fixes", "output"}
    assert len(screen.loop_times(log)) == 2
