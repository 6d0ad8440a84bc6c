"""Shared fixtures: pytester, a valid pairs file to break one field at a time, and a repository
whose robot description a pairs file reads at HEAD.

The folders' own conftest.py files hold the fixtures only their tests use; the constants and
plain functions test modules share are in tests/helpers/.
"""

from __future__ import annotations

from pathlib import Path

import hypothesis  # noqa: F401  (see below)
import pytest
import xacro.substitution_args  # noqa: F401  (see below)

import pytest_lasertest.plugin.collect  # (see below)
import pytest_lasertest.solver.plan  # noqa: F401  (see below)

# hypothesis, pytest_lasertest.plugin.collect, the solver (with z3) and xacro are imported only to
# stay loaded across pytester runs: in-process runs drop the modules they imported, numpy cannot
# be imported twice in one process, Hypothesis's plugin would re-import hypothesis on every run,
# and a run that first imports xacro leaves its submodules half dropped, so that a later run's
# `$(find)` reaches a substitution_args module the expansion did not patch.
pytest_plugins = ["pytester"]

# The pairs files under data/ and docs/inputs/ are inputs the tests read (the worlds take minutes
# to drive; the docs show the errors of the broken ones), not items of this suite: the plugin
# would otherwise collect every `*.lasertest.yaml` it passes.
collect_ignore = ["data", "docs/inputs"]

# The helpers assert too (assert_one_clean_error, the corpus's assert_profile): rewrite their
# asserts as pytest does the tests', so that a failure shows the values. This must come before
# they are first imported.
pytest.register_assert_rewrite("tests.helpers", "tests.descriptions.corpus")

from tests.helpers.git import commit_everything  # noqa: E402
from tests.helpers.texts import PAIRS, ROBOT, VALID_PAIRS  # noqa: E402


def pytest_xdist_make_scheduler(config: pytest.Config, log: object) -> object | None:
    """Under `--dist loadgroup` (the README's test command), each documentation page's commands
    on one worker (tests/helpers/scheduling.py says why pytest-xdist alone no longer does)."""
    if config.getvalue("dist") != "loadgroup":
        return None
    from tests.helpers.scheduling import PageGroups

    return PageGroups(config, log)


@pytest.fixture(autouse=True)
def off_ci(monkeypatch: pytest.MonkeyPatch) -> None:
    """The suite runs as on a developer's machine wherever it runs: CI (which `.ci/run` sets)
    fixes each pairs file's seed and picks the ci profile, and the tests of that set it."""
    monkeypatch.delenv("CI", raising=False)


@pytest.fixture
def pairs_file(pytester: pytest.Pytester) -> Path:
    """A valid pairs file, `gate.lasertest.yaml`, in the pytester directory."""
    path = pytester.path / "gate.lasertest.yaml"
    path.write_text(VALID_PAIRS)
    return path


@pytest.fixture
def repository(pytester: pytest.Pytester) -> Path:
    """The pytester directory as a repository whose last commit holds ROBOT and PAIRS."""
    (pytester.path / "robot.urdf").write_text(ROBOT)
    (pytester.path / "gate.lasertest.yaml").write_text(PAIRS)
    commit_everything(pytester.path)
    return pytester.path
