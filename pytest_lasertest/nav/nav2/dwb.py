"""Nav2's DWB local planner (dwb_core, dwb_plugins, dwb_critics) as Humble's nav2_bringup runs
it, every candidate trajectory at once.

Read in ros-navigation/navigation2 at humble@3c3db59d6969d8ecee8e68468693d006397f4a0c, under
nav2_dwb_controller/: dwb_core/src/dwb_local_planner.cpp (computeVelocityCommands,
coreScoringAlgorithm, scoreTrajectory, transformGlobalPlan); the trajectories as
`dwb_trajectories.py` reads them, the critics as `dwb_critics.py` lists; the parameters in
`dwb_settings.py`. Our own numpy code, in float64 as DWB's doubles.

One cycle: the plan is cut to the part near the robot (transformGlobalPlan); the critics
prepare; every velocity the XYThetaIterator yields is rolled out for sim_time; each critic
scores each trajectory and may declare it illegal; the least total of scale x score among the
legal ones wins, the first in iteration order on a tie; the stateful critics are debriefed with
the command (zeros when none was legal, and then there is no command: NoLegalTrajectories).

- Velocities and trajectories: `dwb_trajectories`.
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

from collections.abc import Callable

import numpy as np

from pytest_lasertest.nav.nav2.dwb_critics import (
    F64,
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
from pytest_lasertest.nav.nav2.dwb_settings import MAP_GRID_CRITICS, DwbSettings
from pytest_lasertest.nav.nav2.dwb_trajectories import roll_out, sample_twists
from pytest_lasertest.nav.nav2.mppi import F32, CostGrid


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

    def reset(self) -> None:
        """nav2_core::Controller::reset, which the controller server calls whenever a
        FollowPath action ends: DWBLocalPlanner keeps the interface's default, nothing."""

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
