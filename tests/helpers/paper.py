"""The paper's pairs file (examples/paper.lasertest.yaml, Table IV-b) as the solver and the
verifier see it: each pair's scene on the nominal path, and the solver's settings."""

from __future__ import annotations

from pytest_lasertest.model.route import nominal_path
from pytest_lasertest.model.verify import Scene
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.solver.search import SearchSettings
from tests.helpers import EXAMPLES

PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
# One witness per direction, no smaller than the pairs file allows.
SETTINGS = SearchSettings(witnesses=1, min_size=PAPER.settings.min_obstacle_size)


def scene(name: str) -> Scene:
    """The pair `name`'s two scanners on the Husky, along the world's nominal path."""
    pair = next(pair for pair in PAPER.pairs if pair.name == name)
    robot, world = PAPER.robot, PAPER.world
    path = nominal_path(world.start, world.route, robot.nominal_speed, robot.nominal_turn_rate)
    return Scene(pair.baseline.profile, pair.candidate.profile, robot, path)
