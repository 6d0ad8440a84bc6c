"""A regression's blame lines: the driver traits that alone make the candidate pass (`driver`),
and whether the pair's scan filter chain alone explains the failure (`filters`)."""

from __future__ import annotations

from pathlib import Path

from pytest_lasertest.model.geometry import Point2D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.protocol import Controller, LaserScan, Odometry
from pytest_lasertest.nav.reactive import ReactiveController
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.pairsfile.scan_filters import with_scan_filters, without_scan_filters
from pytest_lasertest.search.blame import (
    ChainTried,
    TraitTried,
    blame_chain,
    blame_text,
    chain_text,
)
from pytest_lasertest.search.drives import RunCache
from pytest_lasertest.search.plans import avoid_for
from pytest_lasertest.search.trials import Setting
from pytest_lasertest.sim.client import PhysicsClient
from tests.helpers.laser_filters import BLINDING, chain_of
from tests.helpers.paper import PAPER, scene

PAIR = next(pair for pair in PAPER.pairs if pair.name == "size")
REACTIVE = ControllerChoice("reactive", "the default", ReactiveController)


class Still:
    """A stack that never moves: stuck with its chain or without."""

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        return 0.0, 0.0


def still(robot: Robot, route: tuple[Point2D, ...]) -> Controller:
    return Still()


STILL = ControllerChoice("still", "tests/search/test_blame.py", still)


def test_the_traits_that_alone_make_the_candidate_pass_are_named_with_the_baselines_value() -> None:
    tried = (
        TraitTried("no_return", "inf", passes=True),
        TraitTried("latency", 0.003125, passes=False),
        TraitTried("stamp", "start", passes=True),
    )
    assert blame_text(tried) == (
        "passes with the baseline's no_return (inf), stamp (start): "
        "the failure comes from the driver"
    )


def test_when_no_trait_alone_makes_it_pass_the_line_says_so() -> None:
    tried = (TraitTried("no_return", "inf", False), TraitTried("latency", 0.0, False))
    assert blame_text(tried) == (
        "fails still with the baseline's no_return, latency, each alone: not one trait alone"
    )


def test_the_filters_line_says_when_the_chain_alone_explains_the_failure() -> None:
    assert chain_text(ChainTried("laser_filters.yaml", passes=True)) == (
        "passes without laser_filters.yaml's chain: the chain alone explains the failure "
        "(tune it for the candidate's scanner)"
    )
    assert chain_text(ChainTried("laser_filters.yaml", passes=False)) == (
        "fails without laser_filters.yaml's chain too: the chain alone does not explain it"
    )


def test_a_chain_that_blinds_the_stack_is_blamed_and_a_stack_that_never_moves_is_not(
    tmp_path: Path,
) -> None:
    # The size pair's first avoid placement: an obstacle both scanners read, which the bare
    # reactive stack drives around; behind a chain that drops every reading it cannot.
    chain = chain_of(tmp_path, BLINDING)
    placement = avoid_for(PAPER, scene(PAIR.name))[0].placement
    with PhysicsClient() as client:
        blinded = Setting(PAPER, PAIR, with_scan_filters(REACTIVE, chain), 1, client, RunCache())
        assert not blinded.drive(PAIR.candidate.profile, placement).passed
        assert blame_chain(blinded, placement.obstacle) == ChainTried("filters.yaml", passes=True)
        standing = Setting(PAPER, PAIR, with_scan_filters(STILL, chain), 1, client, RunCache())
        assert blame_chain(standing, placement.obstacle) == ChainTried("filters.yaml", passes=False)


def test_without_a_chain_nothing_is_tried() -> None:
    assert blame_chain(Setting(PAPER, PAIR, REACTIVE, 1, None, None), None) is None  # type: ignore[arg-type]


def test_taking_the_chain_out_gives_back_the_choice_it_was_put_in_front_of(
    tmp_path: Path,
) -> None:
    nav2 = ControllerChoice("nav2", "the default", ReactiveController, "Nav2 jazzy: NavFn, MPPI")
    assert without_scan_filters(with_scan_filters(nav2, chain_of(tmp_path, BLINDING))) == nav2
    assert without_scan_filters(nav2) is nav2
