"""The sable binary for the tests that make their own outputs: $SABLE (ctest sets it; then a
missing binary fails), else build/sable, else those tests are skipped."""
import os

import pytest

from sable_tools.paths import repo_path


@pytest.fixture(scope="session")
def sable():
    given = os.environ.get("SABLE")
    path = given or repo_path("build", "sable")
    if not os.access(path, os.X_OK):
        if given:
            pytest.fail(f"SABLE={given} is not an executable")
        pytest.skip("no build/sable (set SABLE=PATH)")
    return path
