"""sable_tools.runner: screen text and exit status of a command, timeouts, logs, the commands it builds."""
import os

import pytest

from sable_tools import runner
from sable_tools.paths import repo_path


def test_execute_text_and_status(tmp_path):
    text, rc = runner.execute(["sh", "-c", "echo out; echo err >&2; exit 3"], tmp_path, 30)
    assert (text, rc) == ("out\nerr\n", 3)


def test_execute_timeout_keeps_the_screen(tmp_path):
    text, rc = runner.execute(["sh", "-c", "echo started; sleep 5"], tmp_path, 0.5)
    assert rc == -1 and text.startswith("started\n") and "timed out after 0.5 s" in text


def test_execute_missing_program(tmp_path):
    text, rc = runner.execute(runner.code_command("no_such_code_here", None), tmp_path, 30)
    assert rc != 0 and "no_such_code_here" in text


def test_run_logged(tmp_path):
    log = tmp_path / "log.txt"
    assert runner.run_logged(["sh", "-c", "echo $OMP_NUM_THREADS; exit 2"], tmp_path, log, runner.one_thread()) == 2
    assert log.read_text() == "1\n"
    assert runner.run_logged(["sleep", "5"], tmp_path, log, timeout=0.3) is None


def test_commands():
    assert runner.code_command("sable", "/x/sable") == ["/x/sable"]
    assert runner.export_yade("s", "d.in", ["-var", "a", "1"], "y.py") == ["s", "--export-yade", "d.in", "-var", "a",
                                                                         "1", "-o", "y.py"]
    assert runner.yade("y.py") == ["yade", "-j1", "-n", "-x", "y.py"]


def test_find_sable(tmp_path):
    exe = tmp_path / "sable"
    exe.write_text("#!/bin/sh\n")
    assert runner.find_sable(str(exe)) is None  # not executable
    exe.chmod(0o755)
    assert runner.find_sable(str(exe)) == str(exe)
    assert runner.find_sable(str(tmp_path / "missing")) is None


def test_built_falls_back_to_build():
    assert runner.built("no_such_program") == repo_path("build", "no_such_program")


def test_analyze_reports_its_failure():
    analyze = runner.built("sable-analyze")
    if not os.access(analyze, os.X_OK):
        pytest.skip("no build/sable-analyze")
    assert runner.analyze(["--help"]).returncode == 0
    r = runner.analyze(["no-such-subcommand"])
    assert r.returncode != 0 and r.stderr


def test_measured_status_times_and_screen(tmp_path):
    log = tmp_path / "screen.txt"
    # a second of CPU in the child alone (a busy loop), then exit 3
    m = runner.measured(["sh", "-c", "echo $OMP_NUM_THREADS; echo err >&2; "
                         "i=0; while [ $i -lt 200000 ]; do i=$((i+1)); done; exit 3"],
                        tmp_path, log, env=runner.one_thread())
    assert (m.rc, m.timed_out, m.text) == (3, False, "1\nerr\n")
    assert log.read_text() == m.text
    assert m.cpu > 0.05 and m.wall >= m.cpu * 0.5  # sh's own CPU time, not this process'
    assert m.cpu == pytest.approx(m.rusage.ru_utime + m.rusage.ru_stime, abs=1e-12)


def test_measured_timeout_kills(tmp_path):
    m = runner.measured(["sh", "-c", "echo started; exec sleep 5"], tmp_path, tmp_path / "log", timeout=0.3)
    assert m.timed_out and m.rc == -9 and m.text == "started\n"
    assert 0.3 <= m.wall < 3


def test_measured_watch_sees_the_running_pid(tmp_path):
    seen = []
    m = runner.measured(["sleep", "0.3"], tmp_path, tmp_path / "log", watch=seen.append, interval=0.01)
    assert m.rc == 0 and not m.timed_out
    assert len(seen) >= 5 and set(seen) == {seen[0]} and seen[0] != os.getpid()


def test_measured_missing_program(tmp_path):
    with pytest.raises(OSError):
        runner.measured(["no_such_code_here"], tmp_path, tmp_path / "log")
