"""sable's command line as LAMMPS and LIGGGHTS users expect it (README, "Running a deck"):
--version and --help, the banner, -echo, -screen, -progress, a deck on standard input, and
the refusal to run as N copies under mpirun. Each test runs the binary of this build."""
import os
import re
import subprocess

import pytest

from sable_tools.paths import repo_path
from scenes import falling_pair

# Two grains falling for 50 + 30 steps: two runs, a thermo row every 10 steps.
DECK = falling_pair("step atoms ke v_z1", after='print "RESULT z=${z1}"')
VERSION_LINE = re.compile(r"^sable (\d+\.\d+\.\d+) \(commit (\S+)\)$")


def run(sable, args, cwd, stdin=None, env=None, input_text=None):
    return subprocess.run([sable] + args, cwd=cwd, input=input_text, stdin=stdin, capture_output=True, text=True,
                          env={**os.environ, "OMP_NUM_THREADS": "1", **(env or {})}, timeout=120)


def project_version():
    text = open(repo_path("CMakeLists.txt")).read()
    return re.search(r"project\(sable VERSION (\d+\.\d+\.\d+)", text).group(1)


@pytest.fixture
def deck(tmp_path):
    path = tmp_path / "in.deck"
    path.write_text(DECK)
    return str(path)


def test_version_prints_cmake_version_and_commit(sable, tmp_path):
    p = run(sable, ["--version"], tmp_path)
    assert p.returncode == 0 and p.stderr == ""
    m = VERSION_LINE.match(p.stdout.strip())
    assert m, p.stdout
    assert m.group(1) == project_version()
    # git describe --always --dirty: an abbreviated hash (a tag's describe has it after -g), or unknown without git
    assert m.group(2) == "unknown" or re.fullmatch(r"(.*-g)?[0-9a-f]{7,40}(-dirty)?", m.group(2)), m.group(2)
    assert not (tmp_path / "log.sable").exists()  # --version runs nothing


def test_changelog_has_the_version():  # (CITATION.cff's: test_version_stamp.py)
    assert "## [%s]" % project_version() in open(repo_path("CHANGELOG.md")).read()


@pytest.mark.parametrize("flag", ["-h", "--help"])
def test_help_goes_to_stdout_and_exits_0(sable, tmp_path, flag):
    p = run(sable, [flag], tmp_path)
    assert p.returncode == 0 and p.stderr == ""
    assert p.stdout.startswith("usage: sable")
    for option in ("-in", "-var", "-log", "-echo none|screen|log|both", "-screen none|FILE", "-progress",
                   "--export-yade", "--version", "OMP_NUM_THREADS"):
        assert option in p.stdout, option


def test_no_deck_on_a_terminal_prints_usage_and_exits_2(sable, tmp_path):
    try:
        parent, child = os.openpty()  # stdin a terminal: nothing piped, so nothing to run
    except OSError as e:  # a container without /dev/ptmx
        pytest.skip(f"no pseudo-terminal: {e}")
    try:
        p = run(sable, [], tmp_path, stdin=child)
    finally:
        os.close(parent)
        os.close(child)
    assert p.returncode == 2 and p.stderr.startswith("usage: sable") and p.stdout == ""


def test_unknown_option_names_it(sable, tmp_path):
    p = run(sable, ["-nope"], tmp_path)
    assert p.returncode == 1 and "unknown option '-nope'" in p.stderr


def test_banner_opens_screen_and_log(sable, tmp_path, deck):
    p = run(sable, ["-in", deck], tmp_path, env={"OMP_NUM_THREADS": "3"})
    assert p.returncode == 0, p.stderr
    version = run(sable, ["--version"], tmp_path).stdout.strip()
    for text in (p.stdout, (tmp_path / "log.sable").read_text()):
        first, second = text.splitlines()[:2]
        assert first == version
        assert second.strip() in ("OpenMP threads: 3 (set with OMP_NUM_THREADS; one process)",
                                  "threads: 1 (built without OpenMP)"), second


@pytest.mark.parametrize("mode, on_screen, in_log", [("none", False, False), ("screen", True, False),
                                                     ("log", False, True), ("both", True, True)])
def test_echo_modes(sable, tmp_path, deck, mode, on_screen, in_log):
    p = run(sable, ["-in", deck, "-echo", mode], tmp_path)
    assert p.returncode == 0, p.stderr
    log = (tmp_path / "log.sable").read_text()
    command = "variable z1 equal z[1]"
    assert (command in p.stdout.splitlines()) == on_screen
    assert (command in log.splitlines()) == in_log


def test_echo_refuses_other_modes(sable, tmp_path, deck):
    p = run(sable, ["-in", deck, "-echo", "all"], tmp_path)
    assert p.returncode == 1 and "-echo 'all': expected none, screen, log or both" in p.stderr


def test_screen_file_takes_the_screen_output(sable, tmp_path, deck):
    p = run(sable, ["-in", deck, "-screen", "screen.txt", "-log", "run.log"], tmp_path)
    assert p.returncode == 0, p.stderr
    assert p.stdout == ""
    screen = (tmp_path / "screen.txt").read_text()
    assert "RESULT z=" in screen and "Loop time of" in screen
    assert screen == (tmp_path / "run.log").read_text()  # both got every line (no echo, no progress)


def test_screen_none_is_silent_and_keeps_the_log(sable, tmp_path, deck):
    p = run(sable, ["-in", deck, "-screen", "none"], tmp_path)
    assert p.returncode == 0 and p.stdout == ""
    assert "RESULT z=" in (tmp_path / "log.sable").read_text()


def test_screen_file_gets_the_error_too(sable, tmp_path):
    p = run(sable, ["-screen", "screen.txt"], tmp_path, input_text="units si\nnot_a_command 1\n")
    assert p.returncode == 1
    assert "ERROR: stdin:2:" in p.stderr and "ERROR: stdin:2:" in (tmp_path / "screen.txt").read_text()


def test_screen_file_that_cannot_be_opened(sable, tmp_path, deck):
    p = run(sable, ["-in", deck, "-screen", str(tmp_path / "no_dir" / "s.txt")], tmp_path)
    assert p.returncode == 1 and "-screen" in p.stderr and "cannot open" in p.stderr


@pytest.mark.parametrize("args", [[], ["-in", "-"]])
def test_deck_on_standard_input(sable, tmp_path, args):
    p = run(sable, args, tmp_path, input_text=DECK)
    assert p.returncode == 0, p.stderr
    assert re.search(r"^RESULT z=0\.\d+", p.stdout, re.M), p.stdout


def test_empty_standard_input_is_an_error(sable, tmp_path):
    p = run(sable, [], tmp_path, input_text="")
    assert p.returncode == 1 and "standard input holds no deck" in p.stderr
    assert not (tmp_path / "log.sable").exists()


def test_progress_lines_screen_only_and_switchable(sable, tmp_path, deck):
    p = run(sable, ["-in", deck, "-progress", "0"], tmp_path)  # a progress line every step
    assert p.returncode == 0, p.stderr
    assert p.stdout.count("Progress: step ") == 49 + 29  # every step but each run's last
    assert "Progress" not in (tmp_path / "log.sable").read_text()
    p = run(sable, ["-in", deck, "-progress", "off"], tmp_path)
    assert p.returncode == 0 and "Progress" not in p.stdout
    p = run(sable, ["-in", deck, "-progress", "soon"], tmp_path)
    assert p.returncode == 1 and "-progress 'soon': expected on, off or a number of seconds >= 0" in p.stderr


@pytest.mark.parametrize("var", ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "MV2_COMM_WORLD_SIZE"])
def test_mpirun_without_mpi_is_refused(sable, tmp_path, deck, var):
    p = run(sable, ["-in", deck], tmp_path, env={var: "4"})
    assert p.returncode == 1
    # without MPI in the build, or with it (MPI then sees one process: no real launcher)
    assert "sable was built without MPI" in p.stderr or "sable's MPI sees one process" in p.stderr
    assert "%s=4" % var in p.stderr
    assert "OMP_NUM_THREADS" in p.stderr
    assert not (tmp_path / "log.sable").exists()  # refused before anything ran


def test_one_mpi_process_runs(sable, tmp_path, deck):
    p = run(sable, ["-in", deck], tmp_path, env={"OMPI_COMM_WORLD_SIZE": "1", "PMI_SIZE": "1"})
    assert p.returncode == 0 and "RESULT z=" in p.stdout
