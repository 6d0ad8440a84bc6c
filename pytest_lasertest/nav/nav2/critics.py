"""MPPI's critics, each adding a cost per sampled trajectory (nav2_mppi_controller/src/critics
at jazzy f4108e5b; weights, powers and thresholds from Jazzy's nav2_params.yaml, else the
critic's own default): being built.

Each is a frozen dataclass called with the cycle's `CriticData`; `power` raises the cost as
Nav2's `cost_power` does.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pytest_lasertest.nav.nav2.mppi import F32, CriticData, MppiSettings

INSCRIBED, LETHAL, NO_INFORMATION = 253, 254, 255


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

    def __call__(self, data: CriticData) -> None:
        s = self.settings
        fastest = math.hypot(s.vx_max, s.vy_max)
        slowest = math.copysign(math.hypot(s.vx_min, s.vy_max), s.vx_min if s.vx_min > 0 else -1)
        beyond = np.maximum(data.vx - fastest, 0.0) + np.maximum(slowest - data.vx, 0.0)
        data.costs += _powered(
            beyond.sum(axis=1) * np.float32(data.model_dt), self.weight, self.power
        )


@dataclass(frozen=True)
class GoalCritic:
    """Near the goal, each trajectory's mean distance to it (goal_critic.cpp)."""

    weight: float = 5.0
    power: int = 1
    threshold_to_consider: float = 1.4  # m

    def __call__(self, data: CriticData) -> None:
        if not data.within(self.threshold_to_consider):
            return
        distance = np.hypot(data.x - data.goal[0], data.y - data.goal[1]).mean(axis=1)
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
        backwards = np.maximum(-data.vx, 0.0).sum(axis=1) * np.float32(data.model_dt)
        data.costs += _powered(backwards, self.weight, self.power)


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
        index = min(data.furthest_reached() + self.offset_from_furthest, last)
        valid = data.path_valid
        while valid is not None and index < last - 1 and not valid[index]:
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
        costs = data.costmap.at(data.x[:, ::step][:, :points], data.y[:, ::step][:, :points])
        collides = (costs == LETHAL) | (costs == INSCRIBED)
        if not data.costmap.tracking_unknown:
            collides |= costs == NO_INFORMATION
        collided = collides.any(axis=1)
        ordinary = 0.0 if data.within(self.near_goal_distance) else costs
        per_point = np.where(costs >= self.near_collision_cost, self.critical_cost, ordinary)
        repulsive = np.where(collided, self.collision_cost, per_point.sum(axis=1))
        scale = self.weight / 254.0 / points
        data.costs += _powered(repulsive.astype(np.float32), scale, self.power)
        data.fail = bool(collided.all())
