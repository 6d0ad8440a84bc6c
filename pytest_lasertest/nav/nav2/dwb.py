"""Nav2's DWB local planner (dwb_core, dwb_plugins, dwb_critics) as Humble's nav2_bringup runs
it, every candidate trajectory at once.

Read in ros-navigation/navigation2 at humble@3c3db59d6969d8ecee8e68468693d006397f4a0c, under
nav2_dwb_controller/: dwb_core/src/dwb_local_planner.cpp (computeVelocityCommands,
coreScoringAlgorithm, scoreTrajectory, transformGlobalPlan), dwb_plugins/src/
standard_traj_generator.cpp, xy_theta_iterator.cpp, kinematic_parameters.cpp and
include/dwb_plugins/one_d_velocity_iterator.hpp; the critics as `dwb_critics.py` lists; the
defaults are nav2_bringup/params/nav2_params.yaml's FollowPath, and the sources' own where the
file sets none; a team's params file reads over DWB's own (`CODE_DEFAULTS`). Our own numpy
code, in float64 as DWB's doubles.

One cycle: the plan is cut to the part near the robot (transformGlobalPlan); the critics
prepare; every velocity the XYThetaIterator yields is rolled out for sim_time; each critic
scores each trajectory and may declare it illegal; the least total of scale x score among the
legal ones wins, the first in iteration order on a tie; the stateful critics are debriefed with
the command (zeros when none was legal, and then there is no command: NoLegalTrajectories).

- Velocities: vx from min_vel_x to max_vel_x (outer), theta from -max_vel_theta to max_vel_theta
  (inner), vx_samples and vtheta_samples evenly spaced, 0 put in where a range crosses it, (0, 0)
  and speeds above max_speed_xy left out. The window is the robot's speed plus or minus
  acc_lim x sim_time, not x 1 / controller_frequency: Humble's StandardTrajectoryGenerator passes
  sim_time to the iterator, so at these limits every velocity is reachable. A differential drive
  only: the y iterator yields 0 alone (min_vel_y = max_vel_y = 0), so vy_samples plays no part.
- Trajectories: ceil(max(|vx| sim_time / linear_granularity, |theta| sim_time /
  angular_granularity)) steps of equal time; each step's speed moves from the last toward the
  command by at most acc_lim (decel_lim) x dt; the pose moves along the heading of the step
  before; with include_last_point (its default) the last pose once more, as generateTrajectory
  appends it (standard_traj_generator.cpp:181-182).
- Scoring: scoreTrajectory's short circuit (stop adding once a total passes the best so far)
  changes which trajectory wins in no case, every score being non-negative; here every critic
  scores every trajectory, and the winner is the one DWB picks.

Where this differs from DWB on purpose:

- Goals have no heading here: RotateToGoal takes the robot's yaw of the cycle for the goal's
  (see `dwb_critics.RotateToGoal`).
- Nav2 resets the critics (RotateToGoal's latches, Oscillation's flags) in setPlan, at each new
  plan; the caller says so with `set_plan`, and a new goal does it by itself.
- The path is taken to be in the costmap's frame (no tf), already pruned of the points the robot
  has passed (transformGlobalPlan's erasing of them is the caller's); a path with no point left
  near the robot gives no command, as Nav2's "Resulting plan has 0 poses" fails the cycle.
- RotateToGoal's lookahead_time must be negative (the default): Humble's projectPose, which a
  non-negative one uses, reads past the trajectory's time offsets.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from pytest_lasertest.nav.nav2 import kernels
from pytest_lasertest.nav.nav2.dwb_critics import (
    F64,
    Bools,
    Frame,
    Oscillation,
    Pose,
    Rollouts,
    RotateToGoal,
    Scored,
    base_obstacle,
    goal_align,
    goal_dist,
    path_align,
    path_dist,
)
from pytest_lasertest.nav.nav2.mppi import F32, CostGrid

# one_d_velocity_iterator.hpp's and xy_theta_iterator.cpp's tolerance.
EPSILON = 1e-5
CRITICS = (
    "RotateToGoal",
    "Oscillation",
    "BaseObstacle",
    "GoalAlign",
    "PathAlign",
    "PathDist",
    "GoalDist",
)
# Their scale is multiplied by half the costmap's resolution (MapGridCritic::getScale).
MAP_GRID_CRITICS = frozenset({"GoalAlign", "PathAlign", "PathDist", "GoalDist"})


@dataclass(frozen=True)
class DwbSettings:
    """FollowPath's parameters, with Nav2's names; defaults from Humble's nav2_params.yaml, or
    the sources' where it sets none."""

    min_vel_x: float = 0.0  # m/s
    max_vel_x: float = 0.26  # m/s
    max_vel_theta: float = 1.0  # rad/s
    min_speed_xy: float = 0.0  # m/s
    max_speed_xy: float = 0.26  # m/s
    min_speed_theta: float = 0.0  # rad/s
    acc_lim_x: float = 2.5  # m/s^2
    acc_lim_theta: float = 3.2  # rad/s^2
    decel_lim_x: float = -2.5  # m/s^2
    decel_lim_theta: float = -3.2  # rad/s^2
    vx_samples: int = 20
    vtheta_samples: int = 20
    sim_time: float = 1.7  # s
    linear_granularity: float = 0.05  # m
    angular_granularity: float = 0.025  # rad
    xy_goal_tolerance: float = 0.25  # m
    trans_stopped_velocity: float = 0.25  # m/s
    short_circuit_trajectory_evaluation: bool = True  # changes no result: see the module
    prune_distance: float = 2.0  # m (source default)
    forward_prune_distance: float = 2.0  # m (source default)
    critics: tuple[str, ...] = CRITICS
    rotate_to_goal_scale: float = 32.0
    oscillation_scale: float = 1.0  # (source default)
    base_obstacle_scale: float = 0.02
    goal_align_scale: float = 24.0
    path_align_scale: float = 32.0
    path_dist_scale: float = 32.0
    goal_dist_scale: float = 24.0
    path_align_forward_point_distance: float = 0.1  # m
    goal_align_forward_point_distance: float = 0.1  # m
    slowing_factor: float = 5.0  # RotateToGoal's
    lookahead_time: float = -1.0  # s, RotateToGoal's: negative, the last pose
    oscillation_reset_dist: float = 0.05  # m (source default)
    oscillation_reset_angle: float = 0.2  # rad (source default)
    x_only_threshold: float = 0.05  # m/s, Oscillation's (source default)
    include_last_point: bool = True  # (source default, standard_traj_generator.cpp:76)

    def __post_init__(self) -> None:
        if self.lookahead_time >= 0.0:
            raise ValueError("only a negative lookahead_time (the last pose) is imitated")
        unknown = set(self.critics) - set(CRITICS)
        if unknown:
            raise ValueError(f"critics not imitated: {sorted(unknown)}")

    def scale(self, critic: str) -> float:
        """The critic's scale parameter."""
        return float(getattr(self, _snake(critic) + "_scale"))


def _snake(name: str) -> str:
    return "".join("_" + c.lower() if c.isupper() else c for c in name).lstrip("_")


def project_velocity(start: float, acc: float, decel: float, dt: float, target: float) -> float:
    """projectVelocity: from `start` toward `target` by at most acc dt up or decel dt down."""
    if start < target:
        return min(target, start + acc * dt)
    return max(target, start + decel * dt)


def velocity_samples(
    current: float, low: float, high: float, acc: float, decel: float, dt: float, count: int
) -> list[float]:
    """OneDVelocityIterator's values in order: from the least to the greatest velocity reachable
    within dt, in count - 1 equal increments (added one at a time, as Nav2 adds them), and 0
    once, where the values pass from negative to positive."""
    current = min(max(current, low), high)
    top = project_velocity(current, acc, decel, dt, high)
    value = project_velocity(current, acc, decel, dt, low)
    if abs(value - top) < EPSILON:
        return [value]
    increment = (top - value) / max(1, max(2, count) - 1)
    values, zero_due = [], True
    while value <= top + EPSILON:
        values.append(value)
        if zero_due and value < 0.0 < value + increment <= top + EPSILON:
            values.append(0.0)
            zero_due = False
        value += increment
    return values


def sample_twists(s: DwbSettings, speed: tuple[float, float]) -> tuple[F64, F64]:
    """XYThetaIterator's valid velocities (vx, theta), (K,) each, vx outer and theta inner."""
    vx = velocity_samples(
        speed[0], s.min_vel_x, s.max_vel_x, s.acc_lim_x, s.decel_lim_x, s.sim_time, s.vx_samples
    )
    wz = velocity_samples(
        speed[1],
        -s.max_vel_theta,
        s.max_vel_theta,
        s.acc_lim_theta,
        s.decel_lim_theta,
        s.sim_time,
        s.vtheta_samples,
    )
    x, theta = (grid.ravel() for grid in np.meshgrid(vx, wz, indexing="ij"))
    valid = _valid_speeds(s, x * x, theta)  # vy is 0: vx^2 is the speed squared
    return x[valid], theta[valid]


def _valid_speeds(s: DwbSettings, speed_sq: F64, theta: F64) -> Bools:
    """isValidSpeed: not above max_speed_xy, not below both minimum speeds, not standing."""
    valid = ~((s.max_speed_xy >= 0.0) & (speed_sq > s.max_speed_xy**2 + EPSILON))
    too_slow = (speed_sq + EPSILON < s.min_speed_xy**2) & (
        np.abs(theta) + EPSILON < s.min_speed_theta
    )
    valid &= ~(too_slow & (s.min_speed_xy >= 0.0) & (s.min_speed_theta >= 0.0))
    valid &= ~((speed_sq == 0.0) & (theta == 0.0))
    return valid


def rollout_poses(s: DwbSettings) -> int:
    """The most poses a cycle rolls out: every sampled twist, the longest steps of any."""
    longest = max(
        s.max_vel_x * s.sim_time / s.linear_granularity,
        s.max_vel_theta * s.sim_time / s.angular_granularity,
        abs(s.min_vel_x) * s.sim_time / s.linear_granularity,
    )
    return (s.vx_samples + 1) * (s.vtheta_samples + 1) * (math.ceil(longest) + 2)


def roll_out(s: DwbSettings, pose: Pose, speed: tuple[float, float], vx: F64, wz: F64) -> Rollouts:
    """generateTrajectory for every command (K,), N = 1 + the most steps poses each, one more
    with include_last_point (the last repeated), compiled (kernels.roll_out)."""
    limits = (s.sim_time, s.acc_lim_x, s.decel_lim_x, s.acc_lim_theta, s.decel_lim_theta)
    steps = _time_steps(s, vx, wz)
    start = (float(pose[0]), float(pose[1]), float(pose[2]))
    moving = (float(speed[0]), float(speed[1]))
    x, y, yaw = kernels.roll_out(start, moving, vx, wz, steps, limits, s.include_last_point)
    return Rollouts(vx, wz, x, y, yaw)


def _time_steps(s: DwbSettings, vx: F64, wz: F64) -> F64:
    """getTimeSteps: how many steps each command's trajectory takes, (K,)."""
    steps = np.ceil(
        np.maximum(
            np.abs(vx) * s.sim_time / s.linear_granularity,
            np.abs(wz) * s.sim_time / s.angular_granularity,
        )
    )
    found: F64 = np.maximum(steps, 1.0)  # getTimeSteps makes one step of none
    return found


def roll_out_in_numpy(
    s: DwbSettings, pose: Pose, speed: tuple[float, float], vx: F64, wz: F64
) -> Rollouts:
    """roll_out in numpy, the reference its kernel is tested against: time-major inside,
    (S, K), where a running sum adds whole rows; the critics read (K, N) views."""
    steps = _time_steps(s, vx, wz)
    dt = s.sim_time / steps  # (K,) s
    moving = np.arange(1.0, steps.max(initial=1.0) + 1.0)[:, np.newaxis] <= steps  # (S, K)
    linear = _ramp(speed[0], vx, s.acc_lim_x, s.decel_lim_x, dt, moving.shape)
    angular = _ramp(speed[1], wz, s.acc_lim_theta, s.decel_lim_theta, dt, moving.shape)
    yaw = _walk(pose[2], np.where(moving, angular * dt, 0.0))  # (N, K)
    # Each step moves along the heading of the pose before it; the cosine and sine only where
    # the trajectory still moves (about half the steps): past its end the step adds nothing.
    cos = np.cos(yaw[:-1], out=np.zeros(moving.shape), where=moving)
    sin = np.sin(yaw[:-1], out=np.zeros(moving.shape), where=moving)
    x = _walk(pose[0], linear * cos * dt)
    y = _walk(pose[1], linear * sin * dt)
    if s.include_last_point:
        x, y, yaw = (np.vstack((walked, walked[-1:])) for walked in (x, y, yaw))
    return Rollouts(vx, wz, x.T, y.T, yaw.T)


def _ramp(
    start: float, target: F64, acc: float, decel: float, dt: F64, shape: tuple[int, int]
) -> F64:
    """computeNewVelocity step after step, (S, K): the speed after each step, from `start`
    toward each target by acc dt (or decel dt) a step, added one step at a time as Nav2 adds
    them, the target capping it."""
    rising = start < target  # (K,)
    change = np.broadcast_to(np.where(rising, acc * dt, decel * dt), shape)
    speeds = _walk(start, change)[1:]
    capped: F64 = np.where(rising, np.minimum(speeds, target), np.maximum(speeds, target))
    return capped


def _walk(start: float, changes: F64) -> F64:
    """`start` and then its running sum with `changes` (S, K), row after row: (S + 1, K). Whole
    rows at a time are faster than numpy's cumsum along either axis."""
    walked = np.empty((len(changes) + 1, changes.shape[1]))
    walked[0] = start
    for row, change in enumerate(changes):
        np.add(walked[row], change, out=walked[row + 1])
    return walked


def local_plan(path: F64, pose: Pose, grid: CostGrid, s: DwbSettings) -> F64:
    """transformGlobalPlan with prune_plan and shorten_transformed_plan: from the first point
    (among those within prune_distance along the path) nearer the robot than the lesser of
    prune_distance and half the costmap, up to the first one after it further than the lesser
    of forward_prune_distance and half the costmap."""
    if not len(path):
        return path
    half = max(grid.costs.shape) * grid.resolution / 2.0
    along = np.cumsum(np.hypot(*np.diff(path, axis=0).T))  # m, to each point after the first
    past = np.flatnonzero(along > s.prune_distance)
    prune_point = int(past[0]) + 1 if len(past) else len(path)
    away = np.hypot(path[:, 0] - pose[0], path[:, 1] - pose[1])
    near = np.flatnonzero(away[:prune_point] < min(half, s.prune_distance))
    begin = int(near[0]) if len(near) else prune_point
    far = np.flatnonzero(away[begin:] > min(half, s.forward_prune_distance))
    end = begin + int(far[0]) if len(far) else len(path)
    kept: F64 = path[begin:end]
    return kept


# DWB's own defaults, for a params file that leaves a parameter out: the kinematic limits 0
# (kinematic_parameters.cpp:74-99), linear_granularity 0.5 (standard_traj_generator.cpp:68-70),
# every critic's scale 1.0 (trajectory_critic.hpp:105-110) and the align critics'
# forward_point_distance 0.325 (path_align.cpp:55-57, goal_align.cpp:55-57), at humble 3c3db59d
# as at jazzy f4108e5b; the rest as DwbSettings holds them (the code's own figures).
CODE_DEFAULTS = DwbSettings(
    max_vel_x=0.0,
    max_vel_theta=0.0,
    max_speed_xy=0.0,
    acc_lim_x=0.0,
    acc_lim_theta=0.0,
    decel_lim_x=0.0,
    decel_lim_theta=0.0,
    linear_granularity=0.5,
    rotate_to_goal_scale=1.0,
    base_obstacle_scale=1.0,
    goal_align_scale=1.0,
    path_align_scale=1.0,
    path_dist_scale=1.0,
    goal_dist_scale=1.0,
    path_align_forward_point_distance=0.325,
    goal_align_forward_point_distance=0.325,
)


class DwbController:
    """DWB for one robot: a command per call of `command`, critics' state kept between them."""

    def __init__(self, settings: DwbSettings | None = None) -> None:
        s = self.settings = settings or DwbSettings()
        self.rotate_to_goal = RotateToGoal(
            s.xy_goal_tolerance, s.trans_stopped_velocity, s.slowing_factor
        )
        self.oscillation = Oscillation(
            s.oscillation_reset_dist, s.oscillation_reset_angle, s.x_only_threshold
        )
        self._critics: dict[str, Callable[[Frame], Scored]] = {
            "RotateToGoal": self.rotate_to_goal.score,
            "Oscillation": self.oscillation.score,
            "BaseObstacle": base_obstacle,
            "GoalAlign": goal_align,
            "PathAlign": path_align,
            "PathDist": path_dist,
            "GoalDist": goal_dist,
        }
        self._goal: tuple[float, float] | None = None

    def set_plan(self) -> None:
        """A new plan: the critics start afresh, as DWBLocalPlanner::setPlan resets them."""
        self.rotate_to_goal.reset()
        self.oscillation.reset()

    def command(
        self,
        pose: Pose,
        speed: tuple[float, float],
        path: F32,
        goal: tuple[float, float],
        costs: CostGrid,
    ) -> tuple[float, float] | None:
        """The twist [vx, wz] (m/s, rad/s) to drive now, or None when the plan has no point
        near the robot or no trajectory is legal."""
        if goal != self._goal:
            self.set_plan()  # a new goal comes with a new plan
            self._goal = goal
        plan = local_plan(np.asarray(path, dtype=np.float64), pose, costs, self.settings)
        if not len(plan):
            return None
        self.rotate_to_goal.prepare(pose, speed, goal)
        self.oscillation.prepare(pose)
        vx, wz = sample_twists(self.settings, speed)
        rollouts = roll_out(self.settings, pose, speed, vx, wz)
        best = self._best(self._frame(pose, goal, plan, costs, rollouts))
        chosen = (0.0, 0.0) if best is None else (float(vx[best]), float(wz[best]))
        self.oscillation.debrief(chosen)
        return None if best is None else chosen

    def _frame(
        self, pose: Pose, goal: tuple[float, float], plan: F64, costs: CostGrid, rollouts: Rollouts
    ) -> Frame:
        s = self.settings
        reach = (s.path_align_forward_point_distance, s.goal_align_forward_point_distance)
        return Frame(pose, goal, plan, costs, rollouts, forward_point_distance=reach)

    def _best(self, frame: Frame) -> int | None:
        """The first legal trajectory of the least total, or None."""
        count = len(frame.rollouts.vx)
        total, legal = np.zeros(count), np.ones(count, dtype=bool)
        for critic in self.settings.critics:
            scale = self._scale(critic, frame)
            if scale == 0.0:
                continue  # scoreTrajectory skips it: it cannot make a trajectory illegal
            scored = self._critics[critic](frame)
            total += scored.raw * scale
            legal &= scored.legal
        if not legal.any():
            return None
        candidates = np.flatnonzero(legal)
        return int(candidates[np.argmin(total[candidates])])

    def _scale(self, critic: str, frame: Frame) -> float:
        """getScale: the scale, times half a cell for the MapGrid critics; PathAlign's is 0
        within its forward point distance of the goal."""
        s, pose, goal = self.settings, frame.pose, frame.goal
        if critic == "PathAlign":
            near = (pose[0] - goal[0]) ** 2 + (pose[1] - goal[1]) ** 2
            if near <= s.path_align_forward_point_distance**2:
                return 0.0
        if critic in MAP_GRID_CRITICS:
            return frame.grid.resolution * 0.5 * s.scale(critic)
        return s.scale(critic)
