"""Nav2's MPPI optimizer: it drives along the plan within its limits, the same way under the same
seed, near the goal the goal pulls, and when every sample fails it says so."""

from __future__ import annotations

import numpy as np

from pytest_lasertest.nav.nav2.critics import (
    ConstraintCritic,
    GoalCritic,
    PathFollowCritic,
    PreferForwardCritic,
)
from pytest_lasertest.nav.nav2.mppi import CriticData, MppiSettings, Optimizer, _furthest_reached

SETTINGS = MppiSettings()
PATH = np.column_stack([np.arange(0.0, 5.0, 0.05), np.zeros(100)]).astype(np.float32)


def optimizer(seed: int) -> Optimizer:
    critics = [ConstraintCritic(SETTINGS), GoalCritic(), PreferForwardCritic(), PathFollowCritic()]
    return Optimizer(SETTINGS, critics, np.random.default_rng(seed))


def drive(mppi: Optimizer, cycles: int) -> list[tuple[float, float]]:
    """Commands of `cycles` cycles, the robot at rest at the path's start, driving them at once."""
    commands, speed = [], (0.0, 0.0)
    for _ in range(cycles):
        command = mppi.command((0.0, 0.0, 0.0), speed, PATH, (4.95, 0.0))
        assert command is not None
        commands.append(command)
        speed = command
    return commands


def test_the_robot_sets_off_along_a_straight_plan_within_its_limits() -> None:
    commands = np.array(drive(optimizer(1), 20))
    assert commands[-1, 0] > 0.3  # m/s, on its way toward 0.5
    assert np.all(commands[:, 0] <= SETTINGS.vx_max + 1e-6)
    assert np.all(np.abs(commands[:, 1]) <= SETTINGS.wz_max + 1e-6)
    assert np.all(np.abs(np.diff(commands[:, 0])) <= SETTINGS.ax_max * SETTINGS.model_dt + 1e-5)


def test_the_same_seed_gives_the_same_commands_and_another_seed_others() -> None:
    assert drive(optimizer(7), 5) == drive(optimizer(7), 5)
    assert drive(optimizer(7), 5) != drive(optimizer(8), 5)


def test_every_sample_failing_twice_in_a_row_gives_no_command_and_starts_afresh() -> None:
    def refuse(data: CriticData) -> None:
        data.fail = True

    mppi = Optimizer(SETTINGS, [refuse], np.random.default_rng(0))
    mppi.vx[:] = 0.4
    assert mppi.command((0.0, 0.0, 0.0), (0.4, 0.0), PATH, (4.95, 0.0)) is None
    assert not mppi.vx.any()


def test_near_the_goal_the_goal_critic_turns_the_robot_toward_it() -> None:
    mppi = Optimizer(SETTINGS, [GoalCritic()], np.random.default_rng(3))
    commands = [mppi.command((0.0, 0.0, 0.0), (0.0, 0.0), PATH, (0.5, 0.5)) for _ in range(15)]
    assert all(command is not None and command[1] > 0.0 for command in commands[5:])


def test_the_furthest_reached_point_is_the_sequential_scan_of_nav2() -> None:
    rng = np.random.default_rng(0)
    for _ in range(20):
        ends = rng.uniform(0.0, 5.0, (50, 2)).astype(np.float32)
        path = rng.uniform(0.0, 5.0, (30, 2)).astype(np.float32)
        furthest = 0
        for x, y in ends:  # findPathFurthestReachedPoint, as written
            squared = (path[furthest:, 0] - x) ** 2 + (path[furthest:, 1] - y) ** 2
            furthest = max(furthest, furthest + int(np.argmin(squared)))
        assert _furthest_reached(ends[:, 0], ends[:, 1], path) == furthest
