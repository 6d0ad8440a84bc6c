"""A pair's control run in a world with walls, as the gate's `PAIR[no-obstacle]` item drives it:
the Jackal of examples/worlds/doorway.lasertest.yaml, given only a goal in the next room, drives
through the 1.2 m doorway with either scanner (issue 25); under its Nav2 parameters it reaches a
goal in the open with one listed wall beside it (issue 46)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pytest_lasertest.pairsfile import Pair, PairsFile, load_pairs_file
from pytest_lasertest.pairsfile.controller import default_controller
from pytest_lasertest.search.drives import PairDrive, RunCache, drive_pair
from pytest_lasertest.sim.client import PhysicsClient
from pytest_lasertest.sim.scenario import Run
from tests.helpers import WORLDS
from tests.helpers.texts import WALL_BESIDE_THE_GOAL

DOORWAY = WORLDS / "doorway.lasertest.yaml"
# The wall between the rooms stands at x = 5 m (0.1 m thick); its doorway spans y 1.9-3.1 m.
WALL_X = 5.0  # m
DOORWAY_Y = (1.9, 3.1)  # m


@pytest.fixture(scope="module")
def doorway() -> PairsFile:
    return load_pairs_file(DOORWAY)


def control_run(spec: PairsFile, pair: Pair) -> PairDrive:
    with PhysicsClient() as client:
        return drive_pair(spec, pair, (), 1, default_controller(DOORWAY), client, RunCache())


def crossing(run: Run) -> float:
    """Where (y, m) the robot's base crossed the dividing wall's line."""
    beyond = np.flatnonzero(run.poses[:, 0] >= WALL_X)
    assert len(beyond), "the robot never reached the wall between the rooms"
    return float(run.poses[beyond[0], 1])


def test_both_robots_of_an_identical_pair_pass_through_the_doorway(doorway: PairsFile) -> None:
    pair = doorway.pairs[0]
    identical = dataclasses.replace(pair, candidate=pair.baseline)

    drive = control_run(doorway, identical)

    for run in (drive.baseline, drive.candidate):
        assert run.passed, run.verdicts.failures()
        assert DOORWAY_Y[0] < crossing(run) < DOORWAY_Y[1]


def test_the_doorway_examples_control_run_passes_with_the_old_and_the_new_scanner(
    doorway: PairsFile,
) -> None:
    drive = control_run(doorway, doorway.pairs[0])

    assert drive.baseline.passed, drive.baseline.verdicts.failures()
    assert drive.candidate.passed, drive.candidate.verdicts.failures()


def test_the_jackal_under_nav2_reaches_a_goal_with_one_wall_beside_it(
    pytester: pytest.Pytester,
) -> None:
    (pytester.path / "gate.lasertest.yaml").write_text(WALL_BESIDE_THE_GOAL)
    result = pytester.runpytest("-k", "no-obstacle", "--laser-seed=1")
    result.assert_outcomes(passed=1, deselected=result.parseoutcomes()["deselected"])
