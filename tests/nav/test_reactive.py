"""The reference controller: it keeps a reading nearer than range_min as something at range_min."""

from __future__ import annotations

from pytest_lasertest.model.obstacles import Cylinder
from pytest_lasertest.nav.reactive import ReactiveController
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.sim.scenario import Scenario, run_scenario
from tests.helpers import EXAMPLES


def test_a_pole_the_lms111_passes_nearer_than_its_range_min_still_keeps_it_clear() -> None:
    # The Husky example's second leg, and a pole the LMS111 reads from afar; within 0.5 m of the
    # laser it reads -inf, which the controller keeps as something at range_min.
    husky = load_pairs_file(EXAMPLES / "husky.lasertest.yaml")
    lms111 = next(p for p in husky.pairs if p.name == "lms111_to_tim571_raised").baseline.profile
    pole = Cylinder(6.207, 3.410, 0.02535, 0.460)
    world = husky.world
    for seed in range(3):
        past_the_pole = Scenario(husky.robot, lms111, (pole,), world.start, world.route, 40.0, seed)
        run = run_scenario(past_the_pole, ReactiveController)
        assert run.passed, run.verdicts.failures()
