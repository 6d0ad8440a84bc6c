"""nav2_mppi_controller's critic manager tests (critic_manager_test.cpp), rebuilt on what does its
work here: params.py loads the critics a params file lists, and `Optimizer` (mppi.py) scores
each cycle's samples with them.

Not applicable: the DummyCritic's initialisation (plugin lifecycle) and getFullName (plugin
namespaces).
"""

from __future__ import annotations

import numpy as np

from pytest_lasertest.nav.nav2.mppi import CriticData, MppiSettings, Optimizer
from tests.helpers.mppi import optimizer, path_along_x
from tests.helpers.upstream import NAVIGATION2_JAZZY, Source

CRITIC_MANAGER = Source(
    "Nav2 MPPI: critic manager",
    NAVIGATION2_JAZZY,
    "nav2_mppi_controller/test/critic_manager_test.cpp",
)


class Scored:
    """A critic that notes being asked to score."""

    def __init__(self) -> None:
        self.scored = False

    def __call__(self, data: CriticData) -> None:
        self.scored = True


@CRITIC_MANAGER.test("CriticManagerTests.BasicCriticOperations", assertions=2)
def test_the_critics_score_each_cycle() -> None:
    critic = Scored()
    mppi = Optimizer(MppiSettings(batch_size=100), [critic], np.random.default_rng(0))
    assert not critic.scored
    mppi.command((0.0, 0.0, 0.0), (0.0, 0.0), path_along_x([0.0, 5.0]), (5.0, 0.0))
    assert critic.scored


@CRITIC_MANAGER.test("CriticManagerTests.CriticLoadingTest", assertions=1)
def test_the_critics_listed_are_loaded() -> None:
    listed = ("ConstraintCritic", "PreferForwardCritic")
    assert len(optimizer({"FollowPath.critics": listed}).critics) == 2
