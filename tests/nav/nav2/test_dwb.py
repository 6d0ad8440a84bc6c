"""Nav2's DWB local planner: it sets off along the plan within its limits, slows before a wall and
gives up inside one, turns toward a plan behind it, stops translating at the goal, will not flip
its turn back and forth, and picks the trajectory DWB's own loop picks."""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from pytest_lasertest.nav.move_base.cost_values import INSCRIBED, LETHAL, UNKNOWN
from pytest_lasertest.nav.nav2.dwb import DwbController, local_plan
from pytest_lasertest.nav.nav2.dwb_critics import manhattan_distances
from pytest_lasertest.nav.nav2.dwb_settings import DwbSettings
from pytest_lasertest.nav.nav2.dwb_trajectories import roll_out, sample_twists
from pytest_lasertest.nav.nav2.mppi import CostGrid

SETTINGS = DwbSettings()
STRAIGHT = np.column_stack([np.arange(0.0, 1.7, 0.05), np.zeros(34)]).astype(np.float32)
CYCLE = 0.05  # s, the controller server's 20 Hz
Pose = tuple[float, float, float]
Twist = tuple[float, float]


def free_around(x: float, y: float, cells: int = 60) -> CostGrid:
    """A free local costmap of `cells` 5 cm cells a side centred on (x, y)."""
    half = cells * 0.05 / 2.0
    return CostGrid(np.zeros((cells, cells), np.uint8), (x - half, y - half), 0.05, False)


def wall_ahead(x_from: float) -> CostGrid:
    """A 3 m local costmap around the origin: lethal from `x_from` m on, inscribed 0.3 m before
    it, and an inflation gradient 0.5 m before that."""
    grid = free_around(0.0, 0.0)
    centres = (np.arange(60) + 0.5) * 0.05 - 1.5
    before = x_from - centres  # m from each column to the wall
    inflated = 252 * np.exp(-3.0 * (before - 0.3))
    column = np.where(
        before <= 0.0,
        LETHAL,
        np.where(before <= 0.3, INSCRIBED, np.where(before <= 0.8, inflated, 0)),
    )
    grid.costs[:] = column.astype(np.uint8)
    return grid


def drive(
    dwb: DwbController,
    pose: Pose,
    path: np.ndarray,
    goal: tuple[float, float],
    grid: CostGrid,
    cycles: int,
) -> tuple[list[Twist], Pose]:
    """The commands of `cycles` cycles, the robot driving each at once for a cycle; it stops
    at the first cycle without one."""
    commands: list[Twist] = []
    speed = (0.0, 0.0)
    for _ in range(cycles):
        command = dwb.command(pose, speed, path, goal, grid)
        if command is None:
            break
        commands.append(command)
        speed = command
        pose = (
            pose[0] + command[0] * math.cos(pose[2]) * CYCLE,
            pose[1] + command[0] * math.sin(pose[2]) * CYCLE,
            pose[2] + command[1] * CYCLE,
        )
    return commands, pose


def test_from_rest_every_velocity_within_the_limits_is_sampled_but_standing_still() -> None:
    vx, wz = sample_twists(SETTINGS, (0.0, 0.0))
    # Humble opens the window over sim_time, not one cycle: from rest all of it is reachable.
    assert len(vx) == 20 * 21 - 1  # 0 put in among the turn rates; (0, 0) left out
    assert np.isclose(vx.min(), 0.0)
    assert np.isclose(vx.max(), SETTINGS.max_vel_x)
    assert np.isclose(wz.min(), -1.0)
    assert np.isclose(wz.max(), 1.0)
    assert (wz == 0.0).sum() == 19  # once in each row but vx = 0's
    assert not ((vx == 0.0) & (wz == 0.0)).any()
    assert (wz[:20] < 0.0).sum() == 10  # vx outer, theta inner: the first row is vx = 0


def test_a_trajectory_speeds_up_from_the_robots_speed_within_the_acceleration_limit() -> None:
    vx, wz = np.array([0.26]), np.array([0.0])
    rollouts = roll_out(SETTINGS, (0.0, 0.0, 0.0), (0.0, 0.0), vx, wz)
    steps = np.diff(rollouts.x[0])[:-1]  # m a step, 9 steps of 1.7 / 9 s, and the repeat
    dt = SETTINGS.sim_time / 9
    assert len(steps) == 9
    assert np.allclose(steps[0], min(0.26, SETTINGS.acc_lim_x * dt) * dt)
    assert np.all(np.diff(steps / dt) <= SETTINGS.acc_lim_x * dt + 1e-12)
    assert np.allclose(rollouts.y, 0.0)
    assert np.allclose(rollouts.yaw, 0.0)


def test_the_robot_sets_off_along_a_straight_plan_within_max_vel_x() -> None:
    commands, pose = drive(
        DwbController(), (0.0, 0.0, 0.0), STRAIGHT, (5.0, 0.0), free_around(0.0, 0.0), 20
    )
    speeds = np.array(commands)
    assert len(speeds) == 20
    assert np.all(speeds[:, 0] <= SETTINGS.max_vel_x + 1e-12)  # 0.26, summed in 19 steps
    assert np.all(speeds[:, 0] > 0.2)
    assert np.all(speeds[:, 1] == 0.0)
    assert pose[0] > 0.2
    assert pose[1] == 0.0


def test_a_wall_across_the_plan_slows_the_robot_before_the_inscribed_band() -> None:
    commands, pose = drive(
        DwbController(), (0.0, 0.0, 0.0), STRAIGHT, (5.0, 0.0), wall_ahead(0.8), 60
    )
    speeds = np.array(commands)
    assert len(speeds) == 60
    assert speeds[0, 0] > 0.2
    assert speeds[-1, 0] < 0.1
    assert pose[0] < 0.8 - 0.3  # m: its centre kept out of the inscribed band


def test_with_every_trajectory_illegal_there_is_no_command() -> None:
    dwb = DwbController()
    assert dwb.command((0.0, 0.0, 0.0), (0.0, 0.0), STRAIGHT, (5.0, 0.0), wall_ahead(-1.0)) is None


def test_a_robot_facing_away_from_its_plan_turns_toward_it_then_drives() -> None:
    commands, pose = drive(
        DwbController(), (0.0, 0.0, math.pi), STRAIGHT, (5.0, 0.0), free_around(0.0, 0.0), 80
    )
    speeds = np.array(commands)
    assert np.all(speeds[:5, 0] == 0.0)
    assert np.all(np.abs(speeds[:5, 1]) == 1.0)
    assert abs(math.remainder(pose[2], 2.0 * math.pi)) < 0.3
    assert pose[0] > 0.1


def test_inside_xy_goal_tolerance_a_slow_robot_stops_translating() -> None:
    dwb, grid = DwbController(), free_around(1.5, 0.0)
    command = dwb.command((1.5, 0.0, 0.0), (0.2, 0.0), STRAIGHT, (1.65, 0.0), grid)
    assert command is not None
    # The goal's yaw is the robot's: the least turn sampled, no translation.
    assert command[0] == 0.0
    assert abs(command[1]) < 0.06


def test_inside_xy_goal_tolerance_a_fast_robot_must_slow_down_first() -> None:
    dwb, grid = DwbController(), free_around(1.5, 0.0)
    command = dwb.command((1.5, 0.0, 0.0), (0.26, 0.0), STRAIGHT, (1.65, 0.0), grid)
    assert command is not None
    assert 0.0 < command[0] < 0.26
    assert command[1] == 0.0


def test_after_the_turn_direction_flips_the_oscillation_critic_forbids_flipping_it_back() -> None:
    dwb, grid, goal = DwbController(), free_around(0.0, 0.0), (0.0, 5.0)
    left = np.column_stack([np.zeros(30), np.arange(0.0, 1.5, 0.05)]).astype(np.float32)
    right = left * np.float32(-1.0)
    turn = [dwb.command((0.0, 0.0, 0.0), (0.0, 0.0), plan, goal, grid) for plan in (left, right)]
    assert turn[0] is not None
    assert turn[0][1] > 0.0
    assert turn[1] is not None
    assert turn[1][1] < 0.0
    again = dwb.command((0.0, 0.0, 0.0), (0.0, 0.0), left, goal, grid)
    assert again is not None
    assert again[1] <= 0.0
    # Once the robot has turned more than oscillation_reset_angle, the flags are lifted.
    dwb.command((0.0, 0.0, -0.25), (0.0, 0.0), left, goal, grid)
    lifted = dwb.command((0.0, 0.0, -0.25), (0.0, 0.0), left, goal, grid)
    assert lifted is not None
    assert lifted[1] > 0.0


def test_the_same_inputs_give_the_same_command() -> None:
    grid = wall_ahead(0.8)
    first = DwbController().command((0.1, 0.05, 0.3), (0.1, 0.2), STRAIGHT, (5.0, 0.0), grid)
    second = DwbController().command((0.1, 0.05, 0.3), (0.1, 0.2), STRAIGHT, (5.0, 0.0), grid)
    assert first is not None
    assert first == second


def test_a_plan_with_no_point_near_the_robot_gives_no_command() -> None:
    far = STRAIGHT + np.float32(3.0)
    assert (
        DwbController().command((0.0, 0.0, 0.0), (0.0, 0.0), far, (5.0, 3.0), free_around(0.0, 0.0))
        is None
    )


def test_the_plan_is_cut_as_transform_global_plan_cuts_it() -> None:
    path = np.column_stack([np.arange(-2.02, 3.0, 0.05), np.zeros(101)])
    kept = local_plan(path, (0.0, 0.0, 0.0), free_around(0.0, 0.0), SETTINGS)
    # From the first point nearer than 1.5 m (half the costmap) to the first further than it.
    assert np.isclose(kept[0, 0], -1.47)
    assert np.isclose(kept[-1, 0], 1.48)
    # The start is searched for only within prune_distance (2 m) along the plan.
    assert not len(local_plan(path - [2.0, 0.0], (0.0, 0.0, 0.0), free_around(0.0, 0.0), SETTINGS))


# DWB as its C++ is written, trajectory by trajectory, from fresh critics: the reference the
# vectorised scoring must agree with.

EPSILON = 1e-5


class _Illegal(Exception):
    pass


def _project(start: float, acc: float, decel: float, dt: float, target: float) -> float:
    return min(target, start + acc * dt) if start < target else max(target, start + decel * dt)


class _OneD:
    """OneDVelocityIterator."""

    def __init__(self, current: float, low: float, high: float, limits: Twist, count: int) -> None:
        current = min(max(current, low), high)
        acc, decel = limits
        self.top = _project(current, acc, decel, SETTINGS.sim_time, high)
        self.bottom = _project(current, acc, decel, SETTINGS.sim_time, low)
        self.reset()
        span = self.top - self.bottom
        self.step = 1.0 if abs(span) < EPSILON else span / max(1, max(2, count) - 1)

    def reset(self) -> None:
        self.current, self.zero, self.zero_now = self.bottom, True, False

    def value(self) -> float:
        return 0.0 if self.zero_now else self.current

    def advance(self) -> None:
        ahead = self.current + self.step
        if self.zero and self.current < 0.0 and ahead > 0.0 and ahead <= self.top + EPSILON:
            self.zero_now, self.zero = True, False
        else:
            self.current += self.step
            self.zero_now = False

    def finished(self) -> bool:
        return self.current > self.top + EPSILON


def _twists(speed: Twist) -> list[Twist]:
    """XYThetaIterator (y yields 0 alone, so a finished theta moves x on)."""
    s = SETTINGS
    x = _OneD(speed[0], s.min_vel_x, s.max_vel_x, (s.acc_lim_x, s.decel_lim_x), s.vx_samples)
    limits = (s.acc_lim_theta, s.decel_lim_theta)
    theta = _OneD(speed[1], -s.max_vel_theta, s.max_vel_theta, limits, s.vtheta_samples)

    def valid() -> bool:
        square = x.value() * x.value() + 0.0 * 0.0
        return not (
            square > s.max_speed_xy**2 + EPSILON or (square == 0.0 and theta.value() == 0.0)
        )

    def iterate() -> None:
        while not x.finished():
            theta.advance()
            if theta.finished():
                theta.reset()
                x.advance()
            if valid():
                return

    twists = []
    if not valid():
        iterate()
    while not x.finished():
        twists.append((x.value(), theta.value()))
        iterate()
    return twists


def _trajectory(pose: Pose, speed: Twist, twist: Twist) -> list[Pose]:
    """StandardTrajectoryGenerator::generateTrajectory, include_last_point."""
    s = SETTINGS
    linear = abs(twist[0]) * s.sim_time / s.linear_granularity
    count = max(math.ceil(max(linear, abs(twist[1]) * s.sim_time / s.angular_granularity)), 1)
    dt = s.sim_time / count
    (x, y, yaw), (v, w) = pose, speed
    poses = [pose]
    for _ in range(count):
        v = _project(v, s.acc_lim_x, s.decel_lim_x, dt, twist[0])
        w = _project(w, s.acc_lim_theta, s.decel_lim_theta, dt, twist[1])
        x, y, yaw = x + v * math.cos(yaw) * dt, y + v * math.sin(yaw) * dt, yaw + w * dt
        poses.append((x, y, yaw))
    return [*poses, poses[-1]]


def _cell(grid: CostGrid, x: float, y: float) -> tuple[int, int]:
    """Costmap2D::worldToMap, off the grid an illegal trajectory."""
    height, width = grid.costs.shape
    if x < grid.origin[0] or y < grid.origin[1]:
        raise _Illegal
    column, row = (
        int((x - grid.origin[0]) / grid.resolution),
        int((y - grid.origin[1]) / grid.resolution),
    )
    if column >= width or row >= height:
        raise _Illegal
    return column, row


def _propagate(shape: tuple[int, int], sources: list[tuple[int, int]]) -> np.ndarray:
    """MapGridCritic's CostmapQueue: bins by Manhattan distance from the source, the lowest
    first, last in first out within one; a cell queued once; its value its distance from the
    source that queued it."""
    height, width = shape
    values, seen = np.full(shape, height * width + 1.0), np.zeros(shape, dtype=bool)
    bins: dict[int, list[tuple[int, int, int, int]]] = {}

    def enqueue(column: int, row: int, source: tuple[int, int]) -> None:
        if 0 <= column < width and 0 <= row < height and not seen[row, column]:
            seen[row, column] = True
            distance = abs(column - source[0]) + abs(row - source[1])
            bins.setdefault(distance, []).append((column, row, *source))

    for column, row in sources:
        values[row, column] = 0.0
        enqueue(column, row, (column, row))
    while any(bins.values()):
        column, row, *source = bins[min(key for key, cells in bins.items() if cells)].pop()
        values[row, column] = abs(column - source[0]) + abs(row - source[1])
        for next_column, next_row in (
            (column - 1, row),
            (column, row - 1),
            (column + 1, row),
            (column, row + 1),
        ):
            enqueue(next_column, next_row, (source[0], source[1]))
    return values


def _adjusted(plan: np.ndarray, resolution: float) -> list[tuple[float, float]]:
    """nav_2d_utils::adjustPlanResolution."""
    out, least = [(float(plan[0, 0]), float(plan[0, 1]))], resolution * resolution * 4.0
    last = out[0]
    for x, y in plan[1:].tolist():
        gap = (x - last[0]) * (x - last[0]) + (y - last[1]) * (y - last[1])
        if gap > least:
            steps = int((math.sqrt(gap) - math.sqrt(least)) / resolution) - 1
            for j in range(1, steps):
                out.append(
                    (last[0] + j * ((x - last[0]) / steps), last[1] + j * ((y - last[1]) / steps))
                )
        out.append((x, y))
        last = (x, y)
    return out


def _run(plan: list[tuple[float, float]], grid: CostGrid) -> list[tuple[int, int]]:
    """The first run of plan points on known cells."""
    cells: list[tuple[int, int]] = []
    for x, y in plan:
        try:
            column, row = _cell(grid, x, y)
            known = grid.costs[row, column] != UNKNOWN
        except _Illegal:
            known = False
        if known:
            cells.append((column, row))
        elif cells:
            break
    return cells


def _grids(
    pose: Pose, goal: tuple[float, float], plan: np.ndarray, grid: CostGrid
) -> list[np.ndarray]:
    """PathDist's, GoalDist's and GoalAlign's grids."""
    shape, resolution = grid.costs.shape, grid.resolution
    run = _run(_adjusted(plan, resolution), grid)
    bearing = math.atan2(goal[1] - pose[1], goal[0] - pose[0])
    moved = plan.copy()
    moved[-1] += 0.1 * np.array([math.cos(bearing), math.sin(bearing)])
    moved_run = _run(_adjusted(moved, resolution), grid)
    return [_propagate(shape, run), _propagate(shape, run[-1:]), _propagate(shape, moved_run[-1:])]


Critic = Callable[[list[Pose], Twist], float]


def _reference(
    pose: Pose, speed: Twist, path: np.ndarray, goal: tuple[float, float], grid: CostGrid
) -> Twist | None:
    """computeVelocityCommands with fresh critics: coreScoringAlgorithm's loop and
    scoreTrajectory's short circuit as written."""
    plan = local_plan(path.astype(np.float64), pose, grid, SETTINGS)
    if not len(plan):
        return None
    critics = _reference_critics(pose, speed, goal, plan, grid)
    best_total, best = -1.0, None
    for twist in _twists(speed):
        poses, total = _trajectory(pose, speed, twist), 0.0
        try:
            for critic, scale in critics:
                if scale == 0.0:
                    continue
                total += critic(poses, twist) * scale
                if best_total > 0.0 and total > best_total:
                    break
        except _Illegal:
            continue
        if best_total < 0.0 or total < best_total:
            best_total, best = total, twist
    return best


def _reference_critics(
    pose: Pose, speed: Twist, goal: tuple[float, float], plan: np.ndarray, grid: CostGrid
) -> list[tuple[Critic, float]]:
    """Humble's default critics in their order, with their getScale."""
    path_grid, goal_grid, front_grid = _grids(pose, goal, plan, grid)
    near_sq = (pose[0] - goal[0]) ** 2 + (pose[1] - goal[1]) ** 2
    half = grid.resolution * 0.5
    return [
        (_rotate_to_goal(pose, speed, near_sq), 32.0),
        (lambda poses, twist: 0.0, 1.0),  # a fresh Oscillation: nothing forbidden yet
        (_base_obstacle(grid), 0.02),
        (_map_grid(grid, front_grid, 0.1), half * 24.0),
        (_map_grid(grid, path_grid, 0.1), 0.0 if near_sq <= 0.1**2 else half * 32.0),
        (_map_grid(grid, path_grid, None), half * 32.0),
        (_map_grid(grid, goal_grid, None), half * 24.0),
    ]


def _rotate_to_goal(pose: Pose, speed: Twist, near_sq: float) -> Critic:
    in_window = near_sq <= 0.25**2
    rotating = in_window and speed[0] * speed[0] <= 0.25**2

    def critic(poses: list[Pose], twist: Twist) -> float:
        if not in_window:
            return 0.0
        turn = math.fmod(pose[2] - poses[-1][2], 2.0 * math.pi) + 2.0 * math.pi
        turn = math.fmod(turn, 2.0 * math.pi)
        turn = abs(turn - 2.0 * math.pi if turn > math.pi else turn)
        if not rotating:
            if twist[0] * twist[0] >= speed[0] * speed[0]:
                raise _Illegal
            return twist[0] * twist[0] * 5.0 + turn
        if abs(twist[0]) > 0.0:
            raise _Illegal
        return turn

    return critic


def _base_obstacle(grid: CostGrid) -> Critic:
    def critic(poses: list[Pose], twist: Twist) -> float:
        score = 0.0
        for x, y, _ in poses:
            column, row = _cell(grid, x, y)
            score = float(grid.costs[row, column])
            if score in (LETHAL, INSCRIBED, UNKNOWN):
                raise _Illegal
        return score

    return critic


def _map_grid(grid: CostGrid, values: np.ndarray, forward: float | None) -> Critic:
    """A MapGrid critic: every pose, failing on obstacle or unreachable cells, without a
    forward point; the last pose's forward point alone with one."""
    unreachable = grid.costs.size + 1.0

    def critic(poses: list[Pose], twist: Twist) -> float:
        score = 0.0
        for x, y, yaw in poses if forward is None else poses[-1:]:
            reach = forward or 0.0
            column, row = _cell(grid, x + reach * math.cos(yaw), y + reach * math.sin(yaw))
            score = float(values[row, column])
            if forward is None and score in (unreachable - 1.0, unreachable):
                raise _Illegal
        return score

    return critic


def _scenario(
    rng: np.random.Generator,
) -> tuple[Pose, Twist, np.ndarray, tuple[float, float], CostGrid]:
    """A robot with obstacles, now and then unknown cells, and a curving plan about it; now
    and then near its goal."""
    x, y = rng.uniform(-0.2, 0.2, 2).tolist()
    pose = (x, y, float(rng.uniform(-math.pi, math.pi)))
    speed = (float(rng.uniform(0.0, 0.3)), float(rng.uniform(-1.2, 1.2)))
    grid = free_around(x, y, cells=40)
    centres = grid.origin + (np.indices(grid.costs.shape)[::-1].transpose(1, 2, 0) + 0.5) * 0.05
    for _ in range(rng.integers(0, 4)):
        gap = np.hypot(*(centres - rng.uniform(-0.9, 0.9, 2)).transpose(2, 0, 1))
        gap -= rng.uniform(0.0, 0.1)  # m from a lethal disc
        inflated = np.where(gap <= 0.22, INSCRIBED, 252 * np.exp(-3.0 * (gap - 0.22)))
        cost = np.where(gap <= 0.0, LETHAL, np.where(gap <= 0.55, inflated, 0)).astype(np.uint8)
        grid.costs[:] = np.maximum(grid.costs, cost)
    if rng.random() < 0.3:
        row, column = rng.integers(0, 30, 2)
        grid.costs[row : row + 10, column : column + 10] = UNKNOWN
    path = _curve(pose, rng)
    return pose, speed, path, (float(path[-1, 0]), float(path[-1, 1])), grid


def _curve(pose: Pose, rng: np.random.Generator) -> np.ndarray:
    """A plan of 5 cm steps bending evenly from the robot, now and then short (its goal near),
    now and then with a gap for adjustPlanResolution to fill."""
    heading, bend = pose[2] + rng.uniform(-2.0, 2.0), rng.uniform(-1.5, 1.5)
    length = rng.uniform(0.15, 0.3) if rng.random() < 0.3 else 2.5
    angle = heading + bend * np.arange(0.0, length, 0.05)
    steps = np.column_stack([np.cos(angle), np.sin(angle)]) * 0.05
    path = np.array(pose[:2]) + np.cumsum(steps, axis=0)
    if rng.random() < 0.3 and len(path) > 12:
        path = np.delete(path, np.arange(5, 11), axis=0)
    return path.astype(np.float32)


def test_the_vectorised_scoring_picks_what_dwbs_trajectory_by_trajectory_loop_picks() -> None:
    rng = np.random.default_rng(4)
    found = []
    for _ in range(30):
        pose, speed, path, goal, grid = _scenario(rng)
        command = DwbController().command(pose, speed, path, goal, grid)
        assert command == _reference(pose, speed, path, goal, grid)
        found.append(command)
    assert any(command is None for command in found)
    assert sum(c is not None for c in found) > 15


def test_the_distance_grid_is_the_one_nav2s_costmap_queue_propagates() -> None:
    rng = np.random.default_rng(1)
    for count in (1, 2, 7, 30):
        columns, rows = rng.integers(0, 25, count), rng.integers(0, 20, count)
        expected = _propagate((20, 25), list(zip(columns.tolist(), rows.tolist(), strict=True)))
        assert np.array_equal(manhattan_distances((20, 25), rows, columns, 501.0), expected)
    assert np.all(manhattan_distances((20, 25), rows[:0], columns[:0], 501.0) == 501.0)
