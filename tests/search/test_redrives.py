"""A regression survives the noise (`search/drives.py`): where the candidate alone fails, both
robots drive again under further, independent draws (fresh scan noise, each obstacle moved
within a centimetre), and the failure is a regression only if it holds under every one; else it
is marginal. Its report shows each draw (`reports/drive.redrive_lines`)."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from types import SimpleNamespace
from typing import Any

import pytest

from pytest_lasertest.model.obstacles import Box, Cylinder, Obstacle
from pytest_lasertest.model.policy import JITTER, REDRAWS
from pytest_lasertest.model.seeds import noise_seed
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.reports.drive import redrive_lines
from pytest_lasertest.search import drives
from pytest_lasertest.search.drives import RunCache, drive_pair
from pytest_lasertest.sim.oracles import Collision, Goal, Stuck, Verdicts
from pytest_lasertest.sim.scenario import Scenario
from tests.helpers import EXAMPLES

SPEC = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
PAIR = next(pair for pair in SPEC.pairs if pair.name == "size")
CHOICE = ControllerChoice("stand-in", "tests/search/test_redrives.py", lambda robot, route: None)
SEED = 5
# Whether a side passes under a draw: draw number -> (baseline passes, candidate passes).
Outcomes = dict[int, tuple[bool, bool]]


def stand_in(world: Scenario, passed: bool, clearance: float = 0.3) -> Any:
    """A run that passes, with `clearance` (m) to spare, or collides."""
    verdicts = Verdicts(
        Collision(None if passed else 12.0, clearance if passed else -0.001),
        Stuck(None, float("inf"), 0.1, 10.0),
        Goal(20.0 if passed else None, 0.1 if passed else 4.0, 0.2),
    )
    return SimpleNamespace(passed=passed, scenario=world, verdicts=verdicts)


def simulate(monkeypatch: pytest.MonkeyPatch, outcomes: Outcomes) -> list[Scenario]:
    """Answer every scenario with a stand-in run that passes as `outcomes` say for its draw."""
    draws = {noise_seed(SEED, draw): draw for draw in range(REDRAWS + 1)}
    simulated: list[Scenario] = []

    def run_scenario(world: Scenario, factory: Callable[..., Any], client: object) -> Any:
        simulated.append(world)
        baseline, candidate = outcomes[draws[world.seed]]
        is_candidate = world.profile == PAIR.candidate.profile
        return stand_in(world, candidate if is_candidate else baseline)

    monkeypatch.setattr(drives, "run_scenario", run_scenario)
    return simulated


def test_a_failure_of_the_candidate_alone_that_holds_under_every_draw_is_a_regression(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    simulated = simulate(monkeypatch, dict.fromkeys(range(REDRAWS + 1), (True, False)))
    drive = drive_pair(SPEC, PAIR, (), SEED, CHOICE, None, RunCache())  # type: ignore[arg-type]
    assert drive.classification == "regression"
    assert len(drive.redrives) == REDRAWS
    assert drive.simulations == len(simulated) == 2 * (REDRAWS + 1)
    # Each draw drives both robots with the same noise seed, none the run's own.
    assert [again.candidate.scenario.seed for again in drive.redrives] == [
        noise_seed(SEED, draw) for draw in range(1, REDRAWS + 1)
    ]


@pytest.mark.parametrize(
    ("undone", "redrives"),
    [((True, True), 1), ((False, False), 1)],
    ids=["the candidate passes under the first redraw", "the baseline fails under it"],
)
def test_a_failure_a_redraw_undoes_is_marginal_and_stops_redriving(
    monkeypatch: pytest.MonkeyPatch, undone: tuple[bool, bool], redrives: int
) -> None:
    outcomes = {0: (True, False), 1: undone, 2: (True, False)}
    simulate(monkeypatch, outcomes)
    drive = drive_pair(SPEC, PAIR, (), SEED, CHOICE, None, RunCache())  # type: ignore[arg-type]
    assert drive.classification == "marginal"
    assert len(drive.redrives) == redrives
    assert drive.fails("candidate")
    assert not drive.fails("regression")


@pytest.mark.parametrize(
    ("first", "expected"),
    [((True, True), "unchanged"), ((False, False), "pre-existing"), ((False, True), "improvement")],
)
def test_only_a_failure_of_the_candidate_alone_is_driven_again(
    monkeypatch: pytest.MonkeyPatch, first: tuple[bool, bool], expected: str
) -> None:
    simulated = simulate(monkeypatch, {0: first})
    drive = drive_pair(SPEC, PAIR, (), SEED, CHOICE, None, RunCache())  # type: ignore[arg-type]
    assert drive.classification == expected
    assert drive.redrives == ()
    assert len(simulated) == 2


def test_each_redraw_moves_every_obstacle_within_a_centimetre_for_both_robots_alike(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Without scan noise too: a stack that marks 5 cm cells hides 1 mm of noise, not a move.
    quiet = dataclasses.replace(
        PAIR,
        baseline=dataclasses.replace(
            PAIR.baseline, profile=dataclasses.replace(PAIR.baseline.profile, noise=None)
        ),
        candidate=dataclasses.replace(
            PAIR.candidate, profile=dataclasses.replace(PAIR.candidate.profile, noise=None)
        ),
    )
    obstacles: tuple[Obstacle, ...] = (
        Cylinder(4.0, 0.2, 0.05, 0.5),
        Box(6.0, -0.3, 0.0, 0.2, 0.1, 0.5),
    )

    def run_scenario(world: Scenario, factory: object, client: object) -> Any:
        return stand_in(world, world.profile != quiet.candidate.profile)

    monkeypatch.setattr(drives, "run_scenario", run_scenario)
    drive = drive_pair(SPEC, quiet, obstacles, SEED, CHOICE, None, RunCache())  # type: ignore[arg-type]
    assert drive.classification == "regression"
    assert len(drive.redrives) == REDRAWS
    moves = set()
    for again in drive.redrives:
        assert again.baseline.scenario.obstacles == again.candidate.scenario.obstacles
        for before, after in zip(obstacles, again.candidate.scenario.obstacles, strict=True):
            move = (after.x - before.x, after.y - before.y)
            assert max(abs(move[0]), abs(move[1])) <= JITTER + 1e-6
            assert (after.sides, after.height) == (before.sides, before.height)
            moves.add(move)
    assert len(moves) == len(obstacles) * REDRAWS  # every obstacle of every draw moves its own way


def test_a_baseline_that_passes_by_less_than_a_centimetre_makes_the_failure_marginal(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    simulated: list[Scenario] = []

    def run_scenario(world: Scenario, factory: object, client: object) -> Any:
        simulated.append(world)
        # The baseline grazes the obstacle with 4 mm to spare; the candidate touches it.
        return stand_in(world, world.profile != PAIR.candidate.profile, clearance=0.004)

    monkeypatch.setattr(drives, "run_scenario", run_scenario)
    drive = drive_pair(SPEC, PAIR, (), SEED, CHOICE, None, RunCache())  # type: ignore[arg-type]
    assert drive.classification == "marginal"
    # A near miss is marginal whatever further draws do: none is driven.
    assert len(simulated) == 2
    assert drives.near_misses(drive.baseline, drive.candidate) == [("collision", 0.004)]


def test_a_regressions_report_shows_each_draw_with_its_seed_move_and_both_margins(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    simulate(monkeypatch, dict.fromkeys(range(REDRAWS + 1), (True, False)))
    obstacle = (Cylinder(4.0, 0.2, 0.05, 0.5),)
    drive = drive_pair(SPEC, PAIR, obstacle, SEED, CHOICE, None, RunCache())  # type: ignore[arg-type]
    lines = redrive_lines(drive)
    assert lines[0] == (
        "  re-driven  under 2 further draws (fresh scan noise, each obstacle moved within 10 mm); "
        "the failure held under all of them:"
    )
    for number, (line, again) in enumerate(zip(lines[1:], drive.redrives, strict=True), start=1):
        assert again.draw is not None
        dx, dy = again.draw.shifts[0]
        assert line.startswith(
            f"    draw {number}   seed {noise_seed(SEED, number)}, obstacle moved "
            f"({dx * 1000:+.1f}, {dy * 1000:+.1f}) mm: baseline passed, margins collision 300.0"
        )
        assert "candidate FAILED (collision, goal), margins collision -1.0" in line


def test_a_marginal_failures_report_says_which_draw_undid_it(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    simulate(monkeypatch, {0: (True, False), 1: (True, True), 2: (True, False)})
    drive = drive_pair(SPEC, PAIR, (), SEED, CHOICE, None, RunCache())  # type: ignore[arg-type]
    lines = redrive_lines(drive)
    assert lines[0].endswith("the failure did not hold under all of them:")
    assert lines[0].startswith("  re-driven  under 1 further draw (")
    assert "baseline passed" in lines[1]
    assert "candidate passed" in lines[1]


def test_a_baseline_that_grazes_the_obstacle_makes_a_candidate_stuck_beside_it_marginal(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # A harmless swap under move_base: the baseline passed a pole with 2 mm to spare, and the
    # candidate, clear of it, was held beside it: a near miss of another oracle is one too.
    def run_scenario(world: Scenario, factory: object, client: object) -> Any:
        if world.profile != PAIR.candidate.profile:
            return stand_in(world, True, clearance=0.002)
        verdicts = Verdicts(
            Collision(None, 0.036), Stuck(29.76, 0.092, 0.1, 10.0), Goal(None, 2.46, 0.2)
        )
        return SimpleNamespace(passed=False, scenario=world, verdicts=verdicts)

    monkeypatch.setattr(drives, "run_scenario", run_scenario)
    drive = drive_pair(SPEC, PAIR, (), SEED, CHOICE, None, RunCache())  # type: ignore[arg-type]
    assert drive.classification == "marginal"
    assert drives.near_misses(drive.baseline, drive.candidate) == [("collision", 0.002)]
    assert redrive_lines(drive) == [
        "  near miss  draw 0: the baseline passed collision by only 2.0 mm (under 10 mm): it came "
        "that near failing too"
    ]


def test_a_candidate_that_passes_has_no_near_miss_to_show(monkeypatch: pytest.MonkeyPatch) -> None:
    simulate(monkeypatch, {0: (True, True)})
    drive = drive_pair(SPEC, PAIR, (), SEED, CHOICE, None, RunCache())  # type: ignore[arg-type]
    grazing = stand_in(drive.baseline.scenario, True, clearance=0.002)
    assert drives.near_misses(grazing, drive.candidate) == []
