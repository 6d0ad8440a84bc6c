"""Stored trajectories: a change meant to be exact (to the costmap's window, the local planner's
arrays, what is cast when) must leave every run bit for bit as it was.

Each digest hashes a run's times, poses and commands. A change that alters them on purpose (the
noise stream, a planner's rounding) must say so and show that the examples' outcomes stay the
same (docs/explanation/performance.md); then print the new digests with

    python -c "from tests.sim.test_digests import print_digests; print_digests()"

PyBullet and numpy's transcendental functions may round differently on another CPU or build:
the digests are this project's CI machine's.
"""

from __future__ import annotations

import pytest

from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.obstacles import Box, Cylinder
from pytest_lasertest.nav.move_base import MoveBase
from pytest_lasertest.nav.protocol import ControllerFactory
from pytest_lasertest.nav.reactive import ReactiveController
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.sim.client import PhysicsClient
from pytest_lasertest.sim.scenario import Scenario, run_scenario
from tests.helpers import EXAMPLES

PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
PAIRS = {pair.name: pair for pair in PAPER.pairs}
# Past a box and two poles, 7 m on or with a turn: the costmap marks, clears and rolls, DWA
# steers round, the 5 m scanner's phantom arc stands in the costmap, and the 16-beam robot
# drives into a pole.
STRAIGHT = (Point2D(7.0, 0.0),)
TURNING = (Point2D(3.0, 0.0), Point2D(3.0, 3.0))
OBSTACLES = (
    Box(1.6, -0.5, 0.3, 0.4, 0.3, 1.0),
    Cylinder(3.3, 1.2, 0.05, 1.0),
    Cylinder(2.6, 2.2, 0.025, 1.0),
)
RUNS: dict[str, tuple[str, str, ControllerFactory, tuple[Point2D, ...]]] = {
    "move_base, 720 beams": ("distance", "baseline", MoveBase, STRAIGHT),
    "move_base, the 5 m scanner": ("distance", "candidate", MoveBase, STRAIGHT),
    "move_base, 16 beams, turning": ("size", "candidate", MoveBase, TURNING),
    "reactive, the 5 m scanner, turning": ("distance", "candidate", ReactiveController, TURNING),
}
DIGESTS = {  # SHA-256 of each run's times, poses and commands
    "move_base, 720 beams": "ab9d517e4f6b9dbc2682a96e8db81e5f0f112e24f3bea6bd6b1c0d6bbb67a6fd",
    "move_base, the 5 m scanner": (
        "a6f1c678db005ec1f5ff71157f5643aa547e5a3a7e60842375f2488b286e9be1"
    ),
    "move_base, 16 beams, turning": (
        "8a6e171c52fbe828c48dd34f06a227c8af171dbb3a10e8b09193972cf4686b71"
    ),
    "reactive, the 5 m scanner, turning": (
        "66464601742eb14bbf44761f87e97eddada912c84916685614ab271bfe4c0e37"
    ),
}


def digest(name: str, client: PhysicsClient) -> str:
    pair, side, controller, route = RUNS[name]
    profile = getattr(PAIRS[pair], side).profile
    start = Pose2D(0.0, 0.0, 0.0)
    scenario = Scenario(PAPER.robot, profile, OBSTACLES, start, route, 20.0, seed=11)
    return run_scenario(scenario, controller, client).digest()


@pytest.mark.parametrize("name", list(RUNS))
def test_a_run_drives_the_trajectory_stored_for_it_bit_for_bit(name: str) -> None:
    with PhysicsClient() as client:
        assert digest(name, client) == DIGESTS[name]


def print_digests() -> None:
    with PhysicsClient() as client:
        for name in RUNS:
            print(f'    "{name}": "{digest(name, client)}",')
