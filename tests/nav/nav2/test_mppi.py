"""Nav2's MPPI optimizer: it drives along the plan within its limits, the same way under the same
seed, near the goal the goal pulls, and when every sample fails it says so."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from pytest_lasertest.nav.nav2.critics import (
    ConstraintCritic,
    CostCritic,
    GoalCritic,
    PathAngleCritic,
    PathFollowCritic,
    PreferForwardCritic,
    _closest_along,
)
from pytest_lasertest.nav.nav2.mppi import (
    CostGrid,
    CriticData,
    MppiSettings,
    Optimizer,
    _furthest_reached,
)

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


def noise_of_cycles(settings: MppiSettings, cycles: int, fail_at: int = -1) -> list[np.ndarray]:
    """The noise (B, T) each cycle added to the sequence's vx; cycle `fail_at` fails once."""
    seen: list[np.ndarray] = []

    def record(data: CriticData) -> None:
        seen.append(data.cvx - mppi.vx)  # before predict bounded it: no limits bind here
        data.fail = len(seen) == fail_at + 1

    loose = dataclasses.replace(settings, ax_max=1e3, ax_min=-1e3, az_max=1e3)
    mppi = Optimizer(loose, [record], np.random.default_rng(0))
    for _ in range(cycles):
        mppi.command((0.0, 0.0, 0.0), (0.0, 0.0), PATH, (4.95, 0.0))
    return seen


def test_without_regenerate_noises_every_cycle_reads_one_draw_until_a_failure_resets_it() -> None:
    fixed = dataclasses.replace(SETTINGS, regenerate_noises=False, batch_size=50)
    first, second, failed, retried, after = noise_of_cycles(fixed, 4, fail_at=2)
    # Equal but for float32 rounding: each cycle adds the noise to a sequence of its own.
    assert np.allclose(first, second, atol=1e-6)
    assert np.allclose(first, failed, atol=1e-6)
    assert not np.allclose(failed, retried, atol=0.01)  # the fallback's reset drew afresh
    assert np.allclose(retried, after, atol=1e-6)
    assert 0.15 < float(np.std(first)) < 0.25  # vx_std 0.2 m/s


def test_with_regenerate_noises_every_cycle_reads_a_fresh_draw() -> None:
    first, second = noise_of_cycles(dataclasses.replace(SETTINGS, batch_size=50), 2)
    assert not np.allclose(first, second, atol=0.01)


def test_near_the_goal_the_goal_critic_turns_the_robot_toward_it() -> None:
    mppi = Optimizer(SETTINGS, [GoalCritic()], np.random.default_rng(3))
    commands = [mppi.command((0.0, 0.0, 0.0), (0.0, 0.0), PATH, (0.5, 0.5)) for _ in range(15)]
    assert all(command is not None and command[1] > 0.0 for command in commands[5:])


def test_the_furthest_reached_point_is_the_sequential_scan_of_nav2() -> None:
    rng = np.random.default_rng(0)
    for round_ in range(40):
        ends = rng.uniform(0.0, 5.0, (50, 2)).astype(np.float32)
        path = rng.uniform(0.0, 5.0, (30, 2)).astype(np.float32)
        if round_ % 2:  # on a 0.5 m grid, where many points lie equally near an end
            ends, path = np.round(ends * 2.0) / 2.0, np.round(path * 2.0) / 2.0
        furthest = 0
        for x, y in ends:  # findPathFurthestReachedPoint, as written
            squared = (path[furthest:, 0] - x) ** 2 + (path[furthest:, 1] - y) ** 2
            furthest = max(furthest, furthest + int(np.argmin(squared)))
        assert _furthest_reached(ends[:, 0], ends[:, 1], path) == furthest


def wall_ahead(x_from: float) -> CostGrid:
    """A local costmap 4 m square around the start: lethal from `x_from` m on, inscribed 0.3 m
    before it, and an inflation gradient 0.5 m before that."""
    resolution, cells = 0.05, 80
    centres = (np.arange(cells) + 0.5) * resolution - 2.0
    before = x_from - centres  # m from each column to the wall
    column = np.where(
        before <= 0.0,
        254,
        np.where(
            before <= 0.3, 253, np.where(before <= 0.8, 252 * np.exp(-3.0 * (before - 0.3)), 0)
        ),
    )
    costs = np.tile(column.astype(np.uint8), (cells, 1))
    return CostGrid(costs, (-2.0, -2.0), resolution, tracking_unknown=False)


def test_the_cost_critic_stops_the_robot_short_of_a_wall_across_its_plan() -> None:
    critics = [ConstraintCritic(SETTINGS), PreferForwardCritic(), PathFollowCritic(), CostCritic()]
    mppi = Optimizer(SETTINGS, critics, np.random.default_rng(5))
    pose, speed, grid = (0.0, 0.0, 0.0), (0.0, 0.0), wall_ahead(1.2)
    furthest = 0.0
    for _ in range(80):  # 4 s, the robot moved as commanded
        command = mppi.command(pose, speed, PATH, (4.95, 0.0), grid)
        assert command is not None
        speed = command
        pose = (
            pose[0] + command[0] * math.cos(pose[2]) * SETTINGS.model_dt,
            pose[1] + command[0] * math.sin(pose[2]) * SETTINGS.model_dt,
            pose[2] + command[1] * SETTINGS.model_dt,
        )
        furthest = max(furthest, pose[0])
    assert 0.2 < furthest < 0.9  # m: it set off, and stayed out of the inscribed band


def test_a_robot_whose_every_trajectory_collides_gets_no_command() -> None:
    mppi = Optimizer(SETTINGS, [CostCritic()], np.random.default_rng(0))
    in_the_wall = wall_ahead(-1.0)
    assert mppi.command((0.0, 0.0, 0.0), (0.0, 0.0), PATH, (4.95, 0.0), in_the_wall) is None


def test_the_path_point_to_align_to_is_nav2s_search_from_the_last_one_found() -> None:
    rng = np.random.default_rng(2)
    for _ in range(50):
        along = np.concatenate([[0.0], np.cumsum(rng.uniform(0.0, 0.1, 30))])
        travelled = np.cumsum(rng.uniform(0.0, 0.15, (5, 12)), axis=1)
        expected = np.zeros(travelled.shape, dtype=np.int64)
        for row in range(5):
            point = 0
            for column, distance in enumerate(travelled[row]):  # findClosestPathPt, as written
                before = along[point] if point else 0.0
                found = len(along) - 1
                for index in range(point + 1, len(along)):
                    if along[index] > distance:
                        found = index - 1 if distance - before < along[index] - distance else index
                        break
                    before = along[index]
                point = expected[row, column] = found
        found = np.maximum.accumulate(_closest_along(along, travelled), axis=1)
        assert np.array_equal(found, expected)


def test_a_robot_facing_away_from_its_plan_is_turned_toward_it_by_the_path_angle_critic() -> None:
    mppi = Optimizer(SETTINGS, [PathAngleCritic()], np.random.default_rng(4))
    facing_left = (0.0, 0.0, 1.5)  # rad; the plan runs along +x
    commands = [mppi.command(facing_left, (0.0, 0.0), PATH, (4.95, 0.0)) for _ in range(15)]
    assert all(command is not None and command[1] < 0.0 for command in commands[5:])
