"""DWB's critics as Humble's nav2_bringup lists them, each scoring every trajectory at once.

Read in ros-navigation/navigation2 at humble@3c3db59d6969d8ecee8e68468693d006397f4a0c, under
nav2_dwb_controller/: dwb_critics/src/rotate_to_goal.cpp, oscillation.cpp, base_obstacle.cpp,
map_grid.cpp, path_dist.cpp, goal_dist.cpp, path_align.cpp, goal_align.cpp, alignment_util.cpp;
costmap_queue/src/costmap_queue.cpp and include/costmap_queue/map_based_queue.hpp (the
propagation); nav_2d_utils/src/path_ops.cpp (adjustPlanResolution); and
nav2_costmap_2d/src/costmap_2d.cpp (worldToMap). Our own numpy code, with its distance transform
and its reading of the cells under every pose compiled (kernels.py); `dwb.py` runs the critics.

Each critic gives, for K trajectories, a raw score and which are legal (DWB's
IllegalTrajectoryException):

- RotateToGoal: nothing until the robot has come within xy_goal_tolerance of the goal (latched);
  then, while the robot moves faster than trans_stopped_velocity, only slower commands are legal,
  scored slowing_factor speed^2 plus the rotation; once it is that slow (latched), only commands
  without translation are legal, scored by the rotation: |the last pose's yaw - the goal's yaw|.
- Oscillation: once the command's sign flips in x (or in theta, while |x| <= x_only_threshold),
  the other sign is illegal until the robot has moved oscillation_reset_dist or turned
  oscillation_reset_angle from where the flip happened.
- BaseObstacle: the cost of the cell under each pose (the robot's centre: this critic ignores
  the footprint; ObstacleFootprint is the one that reads it, and the default list does not use
  it). A pose off the grid or on a lethal, inscribed or no-information cell is illegal; the score
  is the last pose's cost (sum_scores false).
- PathDist, GoalDist: a grid of Manhattan distances, in cells, to the plan's cells (to the local
  goal's cell), read under every pose (stop_on_failure): off the grid or unreachable is illegal;
  the score is the last pose's (aggregation_type last).
- PathAlign, GoalAlign: the same grids, read only at the point forward_point_distance ahead of
  the last pose (stop_on_failure false): that point off the grid is illegal. GoalAlign's grid
  starts from the local goal moved forward_point_distance further along the bearing from the
  robot to the goal.

The MapGrid critics' breadth-first queue (MapGridQueue::validCellToQueue) accepts every cell, so in
Humble the distances cross obstacles and unknown space alike, despite its header's comment; unknown
cells only keep plan points from being sources. The queue pops cells by Manhattan distance from
their source and gives each the distance from the source that reached it first, which on an
unobstructed 4-connected grid is the Manhattan distance to the nearest source: here a separable L1
distance transform (compiled, kernels.l1_distances) gives the same grid. No Humble critic marks
obstacle cells (setAsObstacle is never called), so "unreachable" (cells + 1) is the only failing
value, found everywhere when no source cell was found (prepare failed; DWB only warns).
"""

from __future__ import annotations

import functools
import itertools
import math
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from pytest_lasertest.nav.move_base.cost_values import INSCRIBED, LETHAL, UNKNOWN
from pytest_lasertest.nav.nav2.kernels import cells_under, l1_distances, read_every_pose
from pytest_lasertest.nav.nav2.mppi import CostGrid

F64 = npt.NDArray[np.float64]
Bools = npt.NDArray[np.bool_]
Ints = npt.NDArray[np.int64]
Pose = tuple[float, float, float]  # m, m, rad
# The costs a pose may not stand on: BaseObstacleCritic's lethal, inscribed and no information.
UNDRIVABLE = np.array([LETHAL, INSCRIBED, UNKNOWN], dtype=np.float64)


@dataclass(frozen=True)
class Scored:
    """One critic's verdict on K trajectories."""

    raw: F64  # (K,) the score before the critic's scale
    legal: Bools  # (K,)


@dataclass(frozen=True)
class Rollouts:
    """The sampled commands and the poses each one's trajectory passes through: K trajectories
    of N poses, the start first, a shorter one's last pose repeated to N (every critic reads the
    last pose, or asks whether any pose fails, which a repeat changes in neither)."""

    vx: F64  # (K,) m/s
    wz: F64  # (K,) rad/s
    x: F64  # (K, N) m
    y: F64  # (K, N) m
    yaw: F64  # (K, N) rad


@dataclass(frozen=True)
class Cells:
    """worldToMap of points: their cells (0 where off the grid) and whether they are on it."""

    column: Ints
    row: Ints
    on: Bools


def world_to_map(grid: CostGrid, x: F64, y: F64) -> Cells:
    """Costmap2D::worldToMap in float64 for points of any shape: below the origin is off; the
    cell is the truncated quotient, which must fall inside the grid."""
    height, width = grid.costs.shape
    column = (x - grid.origin[0]) / grid.resolution
    row = (y - grid.origin[1]) / grid.resolution
    on = (x >= grid.origin[0]) & (y >= grid.origin[1]) & (column < width) & (row < height)
    # Cast only inside the grid: a point far off it would overflow the integer.
    return Cells(
        np.where(on, column, 0.0).astype(np.int64), np.where(on, row, 0.0).astype(np.int64), on
    )


@dataclass(frozen=True)
class Frame:
    """What the critics read in one cycle; the distance grids are made when first read."""

    pose: Pose
    goal: tuple[float, float]  # m
    plan: F64  # (P, 2) m, the transformed plan
    grid: CostGrid
    rollouts: Rollouts
    forward_point_distance: tuple[float, float]  # m, PathAlign's and GoalAlign's

    @functools.cached_property
    def cells(self) -> Ints:
        """The flat cell (row x width + column) under every pose of every trajectory, -1 off
        the grid, (K, N)."""
        height, width = self.grid.costs.shape
        x, y = (np.ascontiguousarray(axis) for axis in (self.rollouts.x, self.rollouts.y))
        origin, resolution = self.grid.origin, self.grid.resolution
        found: Ints = cells_under(x, y, origin[0], origin[1], resolution, height, width)
        return found

    @functools.cached_property
    def unreachable(self) -> float:
        """MapGridCritic's unreachable_score: the cell count plus one."""
        return float(self.grid.costs.size + 1)

    @functools.cached_property
    def path_distances(self) -> F64:
        """PathDistCritic::prepare: the first run of plan points on known cells is the source."""
        rows, columns = _first_known_run(adjust_plan_resolution(self.plan, self.grid), self.grid)
        return manhattan_distances(self.grid.costs.shape, rows, columns, self.unreachable)

    @functools.cached_property
    def goal_distances(self) -> F64:
        """GoalDistCritic::prepare: the last point of that run is the source."""
        return self._from_local_goal(self.plan)

    @functools.cached_property
    def goal_front_distances(self) -> F64:
        """GoalAlignCritic::prepare: the plan's last point moved forward_point_distance on along
        the bearing from the robot to the goal, then as GoalDist."""
        bearing = math.atan2(self.goal[1] - self.pose[1], self.goal[0] - self.pose[0])
        target = self.plan.copy()
        target[-1] += self.forward_point_distance[1] * np.array(
            [math.cos(bearing), math.sin(bearing)]
        )
        return self._from_local_goal(target)

    def _from_local_goal(self, plan: F64) -> F64:
        rows, columns = _first_known_run(adjust_plan_resolution(plan, self.grid), self.grid)
        return manhattan_distances(self.grid.costs.shape, rows[-1:], columns[-1:], self.unreachable)


def adjust_plan_resolution(plan: F64, grid: CostGrid) -> F64:
    """nav_2d_utils::adjustPlanResolution: points added in each gap of the plan (P, 2) wider
    than two cells, as Nav2 spaces them (steps = int((gap - 2 cells) / cell) - 1, points
    1 .. steps - 1 of gap / steps apart)."""
    resolution = grid.resolution
    least_sq = resolution * resolution * 4.0
    gaps = np.diff(plan, axis=0)
    if not (gaps[:, 0] * gaps[:, 0] + gaps[:, 1] * gaps[:, 1] > least_sq).any():
        return plan  # a plan of cell centres, as NavFn's, has no gap to fill
    points = [plan[:1]]
    for last, point in itertools.pairwise(plan):
        dx, dy = float(point[0] - last[0]), float(point[1] - last[1])
        gap_sq = dx * dx + dy * dy
        steps = int((math.sqrt(gap_sq) - math.sqrt(least_sq)) / resolution) - 1
        if gap_sq > least_sq and steps > 1:
            between = np.arange(1, steps)[:, np.newaxis]
            points.append(last + between * ((point - last) / steps))
        points.append(point[np.newaxis])
    adjusted: F64 = np.concatenate(points)
    return adjusted


def _first_known_run(plan: F64, grid: CostGrid) -> tuple[Ints, Ints]:
    """The cells (rows, columns) of the first unbroken run of plan points on the grid and not
    on a no-information cell: PathDist's sources; the run's last is GoalDist's local goal."""
    cells = world_to_map(grid, plan[:, 0], plan[:, 1])
    known = cells.on & (grid.costs[cells.row, cells.column] != UNKNOWN)
    found = np.flatnonzero(known)
    if not len(found):
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    gaps = np.flatnonzero(~known[found[0] :])
    run = slice(found[0], found[0] + gaps[0] if len(gaps) else len(plan))
    return cells.row[run], cells.column[run]


def manhattan_distances(
    shape: tuple[int, int], rows: Ints, columns: Ints, unreachable: float
) -> F64:
    """The Manhattan distance (cells) from every cell of a grid (H, W) to the nearest source
    cell, `unreachable` everywhere without a source (compiled: kernels.l1_distances)."""
    if not len(rows):
        return np.full(shape, unreachable)
    return l1_distances(shape[0], shape[1], rows.astype(np.int64), columns.astype(np.int64))


def base_obstacle(frame: Frame) -> Scored:
    """BaseObstacleCritic: every pose's cell must be on the grid and drivable; the last one's
    cost is the score."""
    costs = frame.grid.costs.ravel().astype(np.float64)
    return Scored(*read_every_pose(frame.cells, costs, UNDRIVABLE))


def path_dist(frame: Frame) -> Scored:
    """PathDistCritic: the plan distance under every pose, the last one's the score."""
    return _under_every_pose(frame, frame.path_distances)


def goal_dist(frame: Frame) -> Scored:
    """GoalDistCritic: the local goal distance under every pose, the last one's the score."""
    return _under_every_pose(frame, frame.goal_distances)


def path_align(frame: Frame) -> Scored:
    """PathAlignCritic: the plan distance at the last pose's forward point."""
    return _ahead_of_last_pose(frame, frame.path_distances, frame.forward_point_distance[0])


def goal_align(frame: Frame) -> Scored:
    """GoalAlignCritic: the moved local goal's distance at the last pose's forward point."""
    return _ahead_of_last_pose(frame, frame.goal_front_distances, frame.forward_point_distance[1])


def _under_every_pose(frame: Frame, distances: F64) -> Scored:
    """MapGridCritic with stop_on_failure and aggregation last."""
    failing = np.array([frame.unreachable])
    return Scored(*read_every_pose(frame.cells, distances.ravel(), failing))


def _ahead_of_last_pose(frame: Frame, distances: F64, reach: float) -> Scored:
    """MapGridCritic without stop_on_failure, aggregation last, at getForwardPose's point."""
    rollouts = frame.rollouts
    yaw = rollouts.yaw[:, -1]
    x = rollouts.x[:, -1] + reach * np.cos(yaw)
    y = rollouts.y[:, -1] + reach * np.sin(yaw)
    cells = world_to_map(frame.grid, x, y)
    return Scored(distances[cells.row, cells.column], cells.on)


@dataclass
class RotateToGoal:
    """RotateToGoalCritic, whose window and rotating phase, once entered, last until reset (a
    new plan). Nav2's goals have a heading, our routes' goals none: the goal's yaw is taken to
    be the robot's yaw of the cycle, so that near the goal the critic only asks the robot to
    slow down and stop translating, and prefers the least turn. DWB never samples (0, 0), so
    the least turn is the gentlest sampled (vtheta's step, 0.053 rad/s at the defaults). Nav2's
    goal checker would end the goal there, its heading already met; ours ends it at the same
    0.25 m."""

    xy_goal_tolerance: float  # m
    trans_stopped_velocity: float  # m/s
    slowing_factor: float
    in_window: bool = False
    rotating: bool = False
    speed_sq: float = 0.0  # (m/s)^2, the robot's speed this cycle
    goal_yaw: float = 0.0  # rad

    def prepare(self, pose: Pose, speed: tuple[float, float], goal: tuple[float, float]) -> None:
        distance_sq = (pose[0] - goal[0]) ** 2 + (pose[1] - goal[1]) ** 2
        self.in_window = self.in_window or distance_sq <= self.xy_goal_tolerance**2
        self.speed_sq = speed[0] * speed[0]
        stopped = self.speed_sq <= self.trans_stopped_velocity**2
        self.rotating = self.rotating or (self.in_window and stopped)
        self.goal_yaw = pose[2]

    def score(self, frame: Frame) -> Scored:
        vx = frame.rollouts.vx
        if not self.in_window:
            return Scored(np.zeros(len(vx)), np.ones(len(vx), dtype=bool))
        turn = np.abs(_shortest_angular_distance(frame.rollouts.yaw[:, -1], self.goal_yaw))
        if not self.rotating:
            speed_sq = vx * vx
            return Scored(speed_sq * self.slowing_factor + turn, speed_sq < self.speed_sq)
        return Scored(turn, np.abs(vx) <= 0.0)

    def reset(self) -> None:
        self.in_window = self.rotating = False


def _shortest_angular_distance(start: F64, end: float) -> F64:
    """angles::shortest_angular_distance: end - start, normalised into (-pi, pi]."""
    turn = np.fmod(np.fmod(end - start, 2.0 * math.pi) + 2.0 * math.pi, 2.0 * math.pi)
    found: F64 = np.where(turn > math.pi, turn - 2.0 * math.pi, turn)
    return found


@dataclass
class Trend:
    """OscillationCritic's CommandTrend for one dimension: the last sign commanded, and which
    signs a flip has forbidden (a flip to negative forbids positive, and the other way)."""

    sign: int = 0
    positive_only: bool = False
    negative_only: bool = False

    def update(self, velocity: float) -> bool:
        """Record the command; True if it flipped the sign."""
        sign = (velocity > 0.0) - (velocity < 0.0)
        flipped = sign != 0 and self.sign == -sign
        if flipped:
            self.positive_only |= sign > 0
            self.negative_only |= sign < 0
        if sign:
            self.sign = sign
        return flipped

    @property
    def flipped(self) -> bool:
        return self.positive_only or self.negative_only

    def oscillating(self, velocities: F64) -> Bools:
        found: Bools = (self.positive_only & (velocities < 0.0)) | (
            self.negative_only & (velocities > 0.0)
        )
        return found


@dataclass
class Oscillation:
    """OscillationCritic with its reset by distance and angle (oscillation_reset_time is -1 by
    default: no reset by time). A differential drive never commands y: its trend stays still."""

    reset_distance: float  # m
    reset_angle: float  # rad
    x_only_threshold: float  # m/s
    x: Trend = field(default_factory=Trend)
    theta: Trend = field(default_factory=Trend)
    pose: Pose = (0.0, 0.0, 0.0)
    flipped_at: Pose = (0.0, 0.0, 0.0)

    def prepare(self, pose: Pose) -> None:
        self.pose = pose

    def score(self, frame: Frame) -> Scored:
        rollouts = frame.rollouts
        legal = ~(self.x.oscillating(rollouts.vx) | self.theta.oscillating(rollouts.wz))
        return Scored(np.zeros(len(legal)), legal)

    def debrief(self, command: tuple[float, float]) -> None:
        """After the cycle: note the command (zeros when none was legal); lift the flags once
        the robot has moved far enough from where the last flip happened."""
        flipped = self.x.update(command[0])
        if self.x_only_threshold < 0.0 or abs(command[0]) <= self.x_only_threshold:
            flipped |= self.theta.update(command[1])
        if flipped:
            self.flipped_at = self.pose
        if (self.x.flipped or self.theta.flipped) and self._moved():
            self.reset()

    def _moved(self) -> bool:
        distance_sq = (self.pose[0] - self.flipped_at[0]) ** 2 + (
            self.pose[1] - self.flipped_at[1]
        ) ** 2
        # Nav2 compares the raw yaw difference, not normalised.
        turned = abs(self.pose[2] - self.flipped_at[2])
        return (self.reset_distance >= 0.0 and distance_sq > self.reset_distance**2) or (
            self.reset_angle >= 0.0 and turned > self.reset_angle
        )

    def reset(self) -> None:
        self.x, self.theta = Trend(), Trend()
