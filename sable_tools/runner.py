"""Running sable, LIGGGHTS and YADE: where their binaries are, and one command's screen text."""
import os
import shutil
import subprocess

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
