"""A search's trials (`search/trials.py`): what the shrink budget bounds, driven in PyBullet with
a controller whose outcome is known."""

from __future__ import annotations

import pytest

from pytest_lasertest.model.geometry import Point2D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.protocol import Controller, LaserScan, Odometry
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.search.drives import RunCache
from pytest_lasertest.search.offsets import Offset, Untested
from pytest_lasertest.search.plans import avoid_for
from pytest_lasertest.search.trials import BUDGET_SPENT, Setting, TrialFailed, Trials
from pytest_lasertest.sim.client import PhysicsClient
from tests.helpers.paper import PAPER, scene


class Standing:
    """A controller that never moves: every robot is stuck, whatever its scanner."""

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        return 0.0, 0.0


def standing(robot: Robot, route: tuple[Point2D, ...]) -> Controller:
    return Standing()


PAIR = next(pair for pair in PAPER.pairs if pair.name == "size")
CHOICE = ControllerChoice("standing", "tests/search/test_trials.py", standing)


def searching(setting: Setting) -> Trials:
    """The trials of a search around the size pair's first avoid witness, with no shrink budget."""
    witness = avoid_for(PAPER, scene(PAIR.name))[0]
    return Trials(setting, scene(PAIR.name), witness.placement, (0.05, 1.0), "candidate", 0)


def test_without_a_shrink_budget_the_first_trial_is_still_driven_and_classified() -> None:
    with PhysicsClient() as client:
        trials = searching(Setting(PAPER, PAIR, CHOICE, 1, client, RunCache()))
        with pytest.raises(TrialFailed) as failed:
            trials(Offset())
        # The candidate, then the baseline to classify the failure: both stand still.
        assert trials.simulations == 2
        assert failed.value.result.classification == "pre-existing"
        # After the first failure a budget of 0 drives nothing more.
        with pytest.raises(Untested, match=BUDGET_SPENT):
            trials(Offset(x=0.01))
        assert trials.simulations == 2


def test_what_another_item_cached_still_counts_among_an_items_simulations() -> None:
    # Which items ran before in the process (xdist's distribution, a -k selection) must not
    # change how far an item's search goes: a second search of the same placement, its runs all
    # in the session's cache, counts them as the first did.
    with PhysicsClient() as client:
        setting = Setting(PAPER, PAIR, CHOICE, 1, client, RunCache())
        counts = []
        for _ in range(2):
            trials = searching(setting)
            with pytest.raises(TrialFailed):
                trials(Offset())
            with pytest.raises(Untested, match=BUDGET_SPENT):
                trials(Offset(x=0.01))
            counts.append(trials.simulations)
        assert counts == [2, 2]
