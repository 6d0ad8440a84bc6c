"""Shared fixtures: pytester, and a valid pairs file to break one field at a time."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path
from typing import Any

import hypothesis  # noqa: F401  (see below)
import pytest

import pytest_lasertest.plugin.collect  # (see below)
import pytest_lasertest.solver.plan  # noqa: F401  (see below)
from pytest_lasertest.model.sensor import LaserProfile

# hypothesis, pytest_lasertest.plugin.collect and the solver (with z3) are imported only to stay
# loaded across pytester runs: in-process runs drop the modules they imported, numpy cannot be
# imported twice in one process, and Hypothesis's plugin would re-import hypothesis on every run.
pytest_plugins = ["pytester", "tests.corpus"]

REPO = Path(__file__).resolve().parents[1]
EXAMPLES = REPO / "examples"

# The paper's size pair on a 6 m run, one witness per direction: cheap to plan.
SIZE_PAIR = """\
robot: husky
world:
  start: {x: 0.0, y: 0.0, yaw: 0.0}
  goal: {x: 6.0, y: 0.0}
  time_limit: 60.0
settings:
  min_obstacle_size: 0.0507
  witnesses: 1
pairs:
  size:
    baseline: {model: clearpath_lms1xx_gazebo, samples: 32, range: {max: 10.0}}
    candidate: {model: clearpath_lms1xx_gazebo, samples: 16, range: {max: 10.0}}
"""

# Line numbers matter: tests that break a field assert the line it is on.
VALID_PAIRS = """\
robot: husky
world:
  start: {x: 0.0, y: 0.0, yaw: 0.0}
  goal: {x: 10.0, y: 0.0}
  time_limit: 60.0
settings:
  min_obstacle_size: 0.05
constraints:
  - "x > 1"
pairs:
  to_lms111:
    baseline:
      samples: 720
      min_angle: -1.57
      max_angle: 1.57
      range: {min: 0.1, max: 10.0}
      update_rate: 50
    candidate:
      model: sick_lms111
  same:
    baseline: {model: hokuyo_ust_10lx}
    candidate: {model: hokuyo_ust_10lx, noise: {stddev: 0.01}}
"""


@pytest.fixture
def pairs_file(pytester: pytest.Pytester) -> Path:
    """A valid pairs file, `gate.lasertest.yaml`, in the pytester directory."""
    path = pytester.path / "gate.lasertest.yaml"
    path.write_text(VALID_PAIRS)
    return path


def git(directory: Path, *args: str) -> str:
    """Run git with an argument list, without the user's configuration."""
    done = subprocess.run(
        ["git", "-c", "user.name=t", "-c", "user.email=t@t", "-C", str(directory), *args],
        check=True,
        capture_output=True,
        env={**os.environ, "GIT_CONFIG_GLOBAL": os.devnull, "GIT_CONFIG_NOSYSTEM": "1"},
    )
    return done.stdout.decode().strip()


def commit_everything(directory: Path) -> None:
    """Make `directory` a repository (branch main) whose one commit holds all its files."""
    git(directory, "-c", "init.defaultBranch=main", "init", "-q")
    git(directory, "add", "-A")
    git(directory, "commit", "-q", "-m", "everything")


def profile(**overrides: Any) -> LaserProfile:
    """The paper's scanner (720 beams over +-1.57 rad, 0.1-10 m, 50 Hz) with `overrides`."""
    fields: dict[str, Any] = {
        "samples": 720,
        "min_angle": -1.57,
        "max_angle": 1.57,
        "range_min": 0.1,
        "range_max": 10.0,
        "update_rate": 50.0,
    }
    fields.update(overrides)
    return LaserProfile(**fields)
