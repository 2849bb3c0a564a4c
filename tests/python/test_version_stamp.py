"""cmake/sable_version.cmake, which the build runs every time: it writes the version and the git
commit (git describe --always --dirty) into a small .cpp, rewrites it only when its text changes
(so an unchanged tree recompiles nothing and a new commit recompiles this file alone), and says
"unknown" where there is no git or no repository. Run here on a throwaway repository."""
import os
import re
import shutil
import subprocess

import pytest

from sable_tools.paths import repo_path

SCRIPT = repo_path("cmake", "sable_version.cmake")
pytestmark = pytest.mark.skipif(not (shutil.which("cmake") and shutil.which("git")), reason="needs cmake and git")


def stamp(src, out, git):
    subprocess.run(["cmake", "-DVERSION=1.2.3", f"-DSRC={src}", f"-DGIT={git}", f"-DOUT={out}", "-P", SCRIPT],
                   check=True, capture_output=True)
    return re.search(r'commit\(\) \{ return "([^"]*)"; \}', open(out).read()).group(1)


def git(repo, *args):
    env = {**os.environ, "GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@t", "GIT_COMMITTER_NAME": "t",
           "GIT_COMMITTER_EMAIL": "t@t"}
    return subprocess.run(["git", "-C", str(repo), *args], check=True, capture_output=True, text=True,
                          env=env).stdout.strip()


def test_commit_stamp_follows_the_tree_and_is_rewritten_only_on_change(tmp_path):
    repo, out = tmp_path / "repo", str(tmp_path / "sable_version.cpp")
    repo.mkdir()
    git(repo, "init", "-q")
    (repo / "a.txt").write_text("one\n")
    git(repo, "add", "a.txt")
    git(repo, "commit", "-q", "-m", "first")
    first = git(repo, "rev-parse", "--short", "HEAD")
    assert stamp(repo, out, shutil.which("git")) == first
    assert 'version() { return "1.2.3"; }' in open(out).read()
    os.utime(out, ns=(1_000_000_000, 1_000_000_000))  # an old file: a rewrite would change this
    assert stamp(repo, out, shutil.which("git")) == first
    assert os.stat(out).st_mtime_ns == 1_000_000_000
    (repo / "a.txt").write_text("two\n")
    assert stamp(repo, out, shutil.which("git")) == first + "-dirty"
    git(repo, "commit", "-q", "-am", "second")
    second = git(repo, "rev-parse", "--short", "HEAD")
    assert second != first and stamp(repo, out, shutil.which("git")) == second


def test_commit_unknown_without_git_or_repository(tmp_path):
    out = str(tmp_path / "v.cpp")
    assert stamp(tmp_path, out, "") == "unknown"  # git not found at configure time
    (tmp_path / "plain").mkdir()
    assert stamp(tmp_path / "plain", out, shutil.which("git")) == "unknown"  # a source tarball


def test_citation_is_cff_1_2_0_with_the_project_version():
    text = open(repo_path("CITATION.cff")).read()  # top-level "key: value" lines (no YAML parser needed)
    top = dict(re.findall(r'^([a-z-]+): *"?([^"\n]*)"?$', text, re.M))
    for key in ("cff-version", "message", "title"):  # CFF 1.2.0's required keys, with authors below
        assert top.get(key), key
    assert top["cff-version"] == "1.2.0" and top["license"] == "BSD-3-Clause"
    assert re.search(r'^authors:\n  - name: "the sable developers"$', text, re.M)
    cmake = open(repo_path("CMakeLists.txt")).read()
    assert top["version"] == re.search(r"project\(sable VERSION (\S+)", cmake).group(1)
    assert "Copyright (c) 2026, the sable developers" in open(repo_path("LICENSE")).read()
