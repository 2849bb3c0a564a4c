"""Running sable, LIGGGHTS and YADE: where their binaries are, and one command's screen text."""
import os
import shutil
import subprocess
import time
from dataclasses import dataclass

from sable_tools.paths import REPO


BUILDS = ('build', 'build-release', 'build-bench')  # the build folders the READMEs name, build/ first


def built(name):
    """A program of this checkout's build (sable, sable-analyze): the first build folder that has
    it, else its place in build/ (whose absence the caller then reports)."""
    for d in BUILDS:
        p = os.path.join(REPO, d, name)
        if os.path.isfile(p) and os.access(p, os.X_OK):
            return p
    return os.path.join(REPO, BUILDS[0], name)


def find_sable(path=None):
    """The sable binary: path as given (or relative to the repository), else built('sable'); None if absent."""
    for p in ((path, os.path.join(REPO, path)) if path else (built('sable'),)):
        if os.path.isfile(p) and os.access(p, os.X_OK):
            return os.path.abspath(p)
    return None


def unbuffered(cmd):
    """cmd under stdbuf where there is one: LIGGGHTS loses its ERROR text when stdout is not a terminal."""
    return (['stdbuf', '-o0', '-e0'] if shutil.which('stdbuf') else []) + list(cmd)


def code_command(code, sable):
    """The command that starts a code on a deck: sable the binary given, LIGGGHTS from PATH
    (its bare name when absent: execute then reports that it could not start)."""
    if code == 'sable':
        return [sable]
    return unbuffered([shutil.which(code) or code])


def execute(cmd, cwd, timeout, env=None):
    """(screen text, exit status) of one command run in cwd; -1 when it timed out or did not start."""
    try:
        p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           text=True, errors='replace', timeout=timeout, env=env)
        return p.stdout, p.returncode
    except subprocess.TimeoutExpired as e:
        out = e.stdout.decode(errors='replace') if isinstance(e.stdout, bytes) else e.stdout or ''
        return out + f'\n(timed out after {timeout} s)', -1
    except OSError as e:
        return str(e), -1


def run_logged(cmd, cwd, log, env=None, timeout=None):
    """Runs cmd in cwd with its stdout and stderr into the file log; its exit status (None: timed out)."""
    with open(log, 'w') as f:
        try:
            return subprocess.run(cmd, cwd=cwd, stdout=f, stderr=subprocess.STDOUT, env=env, timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            return None


@dataclass(frozen=True)
class Measured:
    """One run of measured(): its exit status, times, resource usage and screen text."""
    rc: int           # exit status; -N: ended by signal N (a timed-out run: -9)
    wall: float       # s, from its start to its end (monotonic clock)
    cpu: float        # s, user + system of the process alone (os.wait4), whatever else runs
    timed_out: bool
    rusage: object    # os.wait4's resource usage (ru_maxrss, ...)
    text: str         # the screen, as written to the log


def measured(cmd, cwd, log, env=None, timeout=None, watch=None, interval=0.02):
    """Runs cmd in cwd with its stdout and stderr into the file log and waits for it with os.wait4,
    so that its CPU time and resource usage are its own (other threads may run other codes meanwhile).
    timeout (s; None or 0: none): then it is killed (rc -9, timed_out). watch(pid), if given, is
    called every `interval` s while it runs (the benchmark reads its peak memory from /proc so).
    A program that cannot start raises OSError, as subprocess does."""
    t0 = time.monotonic()
    timed_out = False
    with open(log, 'w') as f:
        p = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=f, stderr=subprocess.STDOUT)
        if not timeout and watch is None:
            _, status, ru = os.wait4(p.pid, 0)
        else:
            while True:
                if watch is not None:
                    watch(p.pid)
                pid, status, ru = os.wait4(p.pid, os.WNOHANG)
                if pid:
                    break
                if timeout and time.monotonic() - t0 > timeout:
                    p.kill()
                    _, status, ru = os.wait4(p.pid, 0)
                    timed_out = True
                    break
                time.sleep(interval)
    wall = time.monotonic() - t0
    p.returncode = os.waitstatus_to_exitcode(status)  # reaped here: Popen must not wait for it again
    with open(log, errors='replace') as f:
        text = f.read()
    return Measured(p.returncode, wall, ru.ru_utime + ru.ru_stime, timed_out, ru, text)


def one_thread():
    """The environment for a run on one core (OpenMP's threads: sable's, YADE's)."""
    return dict(os.environ, OMP_NUM_THREADS='1')


def export_yade(sable, deck, args, script):
    """The command that writes YADE's script of a deck (sable --export-yade)."""
    return [sable, '--export-yade', deck] + list(args) + ['-o', script]


def yade(script, exe='yade'):
    """The command that runs a YADE script: one thread, no GUI, exit at its end."""
    return [exe, '-j1', '-n', '-x', script]


def analyze(args, cwd=None, nice=False):
    """sable-analyze with these arguments (niced where a sweep shares the CPUs): the completed
    process, text output captured; the caller decides what a failure means for it."""
    cmd = (['nice', '-n', '10'] if nice else []) + [built('sable-analyze')] + [str(a) for a in args]
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
