"""MPPI's critics, each adding a cost per sampled trajectory (nav2_mppi_controller/src/critics
at jazzy f4108e5b; weights, powers and thresholds from Jazzy's nav2_params.yaml, else the
critic's own default).

Each is a frozen dataclass called with the cycle's `CriticData`; `power` raises the cost as
Nav2's `cost_power` does.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.geometry import IntArray
from pytest_lasertest.nav.move_base.cost_values import INSCRIBED, LETHAL, UNKNOWN
from pytest_lasertest.nav.nav2 import kernels
from pytest_lasertest.nav.nav2.mppi import F32, CostGrid, CriticData, MppiSettings


def _powered(cost: F32, weight: float, power: int) -> F32:
    weighted: F32 = (cost * np.float32(weight)).astype(np.float32)
    return weighted if power <= 1 else (weighted**power).astype(np.float32)


@dataclass(frozen=True)
class ConstraintCritic:
    """Speeds beyond the limits, summed over time (constraint_critic.cpp). Its limits are
    hypot(vx_max, vy_max) and -hypot(vx_min, vy_max), vy_max included even for a
    differential drive, as the critic reads them."""

    settings: MppiSettings
    weight: float = 4.0
    power: int = 1

    @property
    def max_vel_constraint(self) -> float:  # m/s, getMaxVelConstraint
        return math.hypot(self.settings.vx_max, self.settings.vy_max)

    @property
    def min_vel_constraint(self) -> float:  # m/s, getMinVelConstraint
        s = self.settings
        return math.copysign(math.hypot(s.vx_min, s.vy_max), s.vx_min if s.vx_min > 0 else -1)

    def __call__(self, data: CriticData) -> None:
        fastest, slowest = np.float32(self.max_vel_constraint), np.float32(self.min_vel_constraint)
        beyond = kernels.speed_beyond(data.time_major_speeds(), fastest, slowest)
        data.costs += _powered(beyond * np.float32(data.model_dt), self.weight, self.power)


@dataclass(frozen=True)
class GoalCritic:
    """Near the goal, each trajectory's mean distance to it (goal_critic.cpp)."""

    weight: float = 5.0
    power: int = 1
    threshold_to_consider: float = 1.4  # m

    def __call__(self, data: CriticData) -> None:
        if not data.within(self.threshold_to_consider):
            return
        goal = (np.float32(data.goal[0]), np.float32(data.goal[1]))
        distance = kernels.mean_distances(*data.time_major(), *goal)
        data.costs += _powered(distance, self.weight, self.power)


@dataclass(frozen=True)
class PreferForwardCritic:
    """Away from the goal, reversing, summed over time (prefer_forward_critic.cpp)."""

    weight: float = 5.0
    power: int = 1
    threshold_to_consider: float = 0.5  # m

    def __call__(self, data: CriticData) -> None:
        if data.within(self.threshold_to_consider):
            return
        reversing = kernels.speed_beyond(
            data.time_major_speeds(), np.float32(np.inf), np.float32(0)
        )
        data.costs += _powered(reversing * np.float32(data.model_dt), self.weight, self.power)


@dataclass(frozen=True)
class PathFollowCritic:
    """Away from the goal, each trajectory end's distance to the path point
    `offset_from_furthest` past the furthest the samples reach, moved on past points the
    costmap makes invalid (path_follow_critic.cpp)."""

    weight: float = 5.0
    power: int = 1
    threshold_to_consider: float = 1.4  # m
    offset_from_furthest: int = 5

    def __call__(self, data: CriticData) -> None:
        last = len(data.path) - 1
        if len(data.path) < 2 or data.within(self.threshold_to_consider):
            return
        index = data.ahead_of_furthest(self.offset_from_furthest)
        valid = data.path_points_valid()
        while index < last - 1 and not valid[index]:
            index += 1
        target_x, target_y = data.path[index]
        distance = np.hypot(data.x[:, -1] - target_x, data.y[:, -1] - target_y)
        data.costs += _powered(distance, self.weight, self.power)


@dataclass(frozen=True)
class CostCritic:
    """The costmap under every `trajectory_point_step`-th point of each trajectory
    (cost_critic.cpp, consider_footprint false): a trajectory that meets a lethal or inscribed
    cell (or an unknown one, unknown untracked) costs collision_cost; otherwise each point
    adds its cost, critical_cost from near_collision_cost up, and nothing near the goal but
    that; summed, times weight / 254 over the points. When every trajectory collides the
    cycle fails."""

    weight: float = 3.81
    power: int = 1
    critical_cost: float = 300.0
    near_collision_cost: int = 253
    collision_cost: float = 1_000_000.0
    near_goal_distance: float = 1.0  # m (Jazzy's params; the critic's own default is 0.5)
    trajectory_point_step: int = 2

    def __call__(self, data: CriticData) -> None:
        if data.costmap is None:
            return
        step = self.trajectory_point_step
        points = data.x.shape[1] // step
        grid, near_goal = data.costmap, data.within(self.near_goal_distance)
        sums, collided = kernels.cost_critic_sums(
            *data.time_major(),
            step,
            points,
            np.ascontiguousarray(grid.costs),
            np.float32(grid.origin[0]),
            np.float32(grid.origin[1]),
            np.float32(grid.resolution),
            grid.tracking_unknown,
            np.float32(self.near_collision_cost),
            self.critical_cost,
            near_goal,
        )
        repulsive = np.where(collided, self.collision_cost, sums)
        scale = self.weight / 254.0 / points
        data.costs += _powered(repulsive.astype(np.float32), scale, self.power)
        data.fail = bool(collided.all())


def _angle_between(a: F32 | float, b: F32 | float) -> F32:
    """|shortest_angular_distance(a, b)|: how far apart two headings are, 0..pi (rad)."""
    difference = np.asarray(b, dtype=np.float32) - np.asarray(a, dtype=np.float32)
    wrapped: F32 = np.abs(np.arctan2(np.sin(difference), np.cos(difference))).astype(np.float32)
    return wrapped


@dataclass(frozen=True)
class PathAngleCritic:
    """Away from the goal, when the path point `offset_from_furthest` past the furthest the
    samples reach lies more than max_angle_to_furthest off the robot's heading: each
    trajectory's final heading against the bearing from its end to that point
    (path_angle_critic.cpp; modes 0, forward preferred, and 1, either way)."""

    weight: float = 2.0
    power: int = 1
    threshold_to_consider: float = 0.5  # m
    offset_from_furthest: int = 4
    max_angle_to_furthest: float = 1.0  # rad
    mode: int = 0  # 0: FORWARD_PREFERENCE; 1: NO_DIRECTIONAL_PREFERENCE

    def __post_init__(self) -> None:
        if self.mode not in (0, 1):
            raise ValueError(f"PathAngleCritic mode {self.mode}: only modes 0 and 1 are imitated")

    def __call__(self, data: CriticData) -> None:
        if data.within(self.threshold_to_consider):
            return
        index = data.ahead_of_furthest(self.offset_from_furthest)
        target_x, target_y = (float(value) for value in data.path[index])
        x, y, yaw = data.pose
        bearing = math.atan2(target_y - y, target_x - x)
        off = float(_angle_between(bearing, yaw))
        if self.mode == 1:
            off = min(off, float(_angle_between(bearing, yaw + math.pi)))
        if off < self.max_angle_to_furthest:
            return
        bearings = np.arctan2(target_y - data.y[:, -1], target_x - data.x[:, -1])
        apart = _angle_between(data.yaw[:, -1], bearings)
        if self.mode == 1:
            bearings = np.where(apart < math.pi / 2.0, bearings, bearings + math.pi)
            apart = _angle_between(data.yaw[:, -1], bearings)
        data.costs += _powered(apart, self.weight, self.power)


@dataclass(frozen=True)
class PathAlignCritic:
    """Away from the goal, once the samples reach offset_from_furthest points along the path
    and few of those points are blocked: each trajectory's mean distance, over every
    trajectory_point_step-th point, to the path point as far along the path as the trajectory
    has come along itself (path_align_critic.cpp, use_path_orientations false)."""

    weight: float = 14.0
    power: int = 1
    threshold_to_consider: float = 0.5  # m
    offset_from_furthest: int = 20
    trajectory_point_step: int = 4
    max_path_occupancy_ratio: float = 0.05

    def __call__(self, data: CriticData) -> None:
        count = data.furthest_reached()
        if data.within(self.threshold_to_consider) or count < self.offset_from_furthest:
            return
        valid = data.path_points_valid()[:count]
        if self._blocked(valid):
            return
        path = np.ascontiguousarray(data.path[:count])
        along = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(path, axis=0).T))])
        step = self.trajectory_point_step
        summed, samples = kernels.path_align_gaps(*data.time_major(), step, along, path, valid)
        cost = np.where(samples > 0, summed / np.maximum(samples, 1), 0.0).astype(np.float32)
        data.costs += _powered(cost, self.weight, self.power)

    def _blocked(self, valid: npt.NDArray[np.bool_]) -> bool:
        """Whether, at some point along the counted path, more than the occupancy ratio of
        the points so far (and more than two) are blocked, as the critic counts them."""
        invalid = np.cumsum(~valid)
        ratio = invalid / float(len(valid))
        return bool(((ratio > self.max_path_occupancy_ratio) & (invalid > 2)).any())


def _closest_along(along: npt.NDArray[np.float64], travelled: npt.NDArray[np.float64]) -> IntArray:
    """findClosestPathPt from the start: the path point whose distance along the path is
    nearest each distance travelled (the later one on a tie), the last past the end."""
    after = np.searchsorted(along, travelled, side="right")
    last = len(along) - 1
    capped = np.minimum(after, last)
    before = np.maximum(after - 1, 0)
    nearer_before = (after <= last) & (travelled - along[before] < along[capped] - travelled)
    closest: IntArray = np.where(after > last, last, np.where(nearer_before, before, capped))
    return closest


def path_align_gaps_in_numpy(
    data: CriticData,
    step: int,
    along: npt.NDArray[np.float64],
    path: F32,
    valid: npt.NDArray[np.bool_],
) -> tuple[F32, IntArray]:
    """`kernels.path_align_gaps` in numpy, the reference it is tested against: the summed
    distances (B,) m from every step-th point but the first to the path point as far along,
    where that point is valid, and how many were counted (B,)."""
    x, y = data.x[:, ::step], data.y[:, ::step]
    travelled = np.cumsum(np.hypot(np.diff(x, axis=1), np.diff(y, axis=1)), axis=1)
    nearest = np.maximum.accumulate(_closest_along(along, travelled), axis=1)
    counted = valid[nearest]
    gaps = np.hypot(path[nearest, 0] - x[:, 1:], path[nearest, 1] - y[:, 1:])
    summed: F32 = np.where(counted, gaps, 0.0).sum(axis=1)
    samples: IntArray = counted.sum(axis=1)
    return summed, samples


def cost_critic_sums_in_numpy(
    critic: CostCritic, data: CriticData, grid: CostGrid
) -> tuple[F32, npt.NDArray[np.bool_]]:
    """`kernels.cost_critic_sums` in numpy, the reference it is tested against."""
    step = critic.trajectory_point_step
    points = data.x.shape[1] // step
    costs = grid.at(data.x[:, ::step][:, :points], data.y[:, ::step][:, :points])
    collides = (costs == LETHAL) | (costs == INSCRIBED)
    if not grid.tracking_unknown:
        collides |= costs == UNKNOWN
    ordinary = 0.0 if data.within(critic.near_goal_distance) else costs
    per_point = np.where(costs >= critic.near_collision_cost, critic.critical_cost, ordinary)
    sums: F32 = per_point.sum(axis=1)
    return sums, collides.any(axis=1)
