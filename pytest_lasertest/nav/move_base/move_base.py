"""The default controller: ROS move_base with navfn, DWA and costmap_2d, as the Husky runs it.

Scan by scan it does what move_base's nodes do on their clocks:

- every 1 / `update_frequency` s the costmap takes the latest scan;
- every 1 / `controller_frequency` s move_base runs one cycle of its state machine:
  PLANNING (navfn plans from the robot to the goal on the inflated global costmap; a plan
  lets it control, none for `planner_patience` s makes it recover), CONTROLLING (DWA answers
  a velocity; none for `controller_patience` s makes it recover, sooner it plans again; no
  `oscillation_distance` of travel for `oscillation_timeout` s makes it recover) and CLEARING
  (the next recovery behaviour runs to its end, then it plans again; when none is left it
  gives up and stands);
- with `planner_frequency` above 0 it also plans again on that clock while controlling.

A route's waypoints are goals sent one after another, each reached within
`xy_goal_tolerance`.

Where this differs from ROS, on purpose: one obstacle grid serves as both costmaps. The global
costmap is it, inflated where the planner searches; the local costmap is its 10 m window
around the robot, where unknown reads as free as the local costmap has it. ROS's local costmap
would forget cells that left its window and came back into it; this one remembers them.

Given the world's map (`receive_map`), the global costmap's costs have a static layer under the
obstacle grid (`costmap.py`): navfn plans round walls no scan has seen, and no clearing ray
frees them. The local window reads the obstacle grid alone, as every local costmap of the
bundled robots' move_base configurations has no static layer (Husky costmap_local.yaml:
obstacles_laser and inflation; the Jackal's costmap_common_params.yaml plugins: obstacles_layer
and inflater_layer; the TurtleBot3's local_costmap_params.yaml: static_map false): DWA and the
recoveries' collision checks see a wall once the scanner does.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from enum import Enum

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, Point2D
from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.move_base.cost_values import LETHAL
from pytest_lasertest.nav.move_base.costmap import Costmap, CostmapSettings, InflationCost
from pytest_lasertest.nav.move_base.dwa import LocalPlanner, Surroundings
from pytest_lasertest.nav.move_base.navfn import windowed_plan
from pytest_lasertest.nav.move_base.publisher import published
from pytest_lasertest.nav.move_base.recovery import (
    BackUp,
    ClearCostmap,
    Pose,
    Recovery,
    RotateInPlace,
)
from pytest_lasertest.nav.move_base.settings import NavigationSettings, global_costmap_size
from pytest_lasertest.nav.move_base.static_layer import StaticLayerSettings
from pytest_lasertest.nav.protocol import LaserScan, Odometry

# base_local_planner's prunePlan drops the plan up to its first point this near the robot.
PRUNE_DISTANCE = 1.0  # m


class State(Enum):
    """move_base's states, and one for a run it is done with."""

    PLANNING = "planning"
    CONTROLLING = "controlling"
    CLEARING = "clearing"
    DONE = "done"  # the last goal reached, or given up


class Trigger(Enum):
    """What made move_base recover: each resets the recoveries once it stops happening."""

    PLANNING = "no plan"
    CONTROLLING = "no valid command"
    OSCILLATION = "oscillation"


class MoveBase:
    """move_base driving one robot along a route of goals."""

    def __init__(
        self,
        robot: Robot,
        route: tuple[Point2D, ...],
        settings: NavigationSettings | None = None,
    ) -> None:
        self.settings = settings or NavigationSettings.from_parameters(robot.navigation)
        self.route = route
        self.goal_index = 0
        self.goal_tolerance = self.settings.dwa.xy_goal_tolerance  # m: the goal oracle judges by it
        self.footprint = robot.footprint_array()  # (V, 2) m
        period = 1.0 / self.settings.move_base.controller_frequency  # s
        costmap = self.settings.costmap
        self.local_planner = LocalPlanner(
            self.settings.dwa,
            self.footprint,
            InflationCost.of(costmap, self.footprint),
            period,
            costmap.resolution,
            costmap.cells,
        )
        self.state = State.PLANNING
        self.plan: FloatArray = np.zeros((0, 2))  # m, the global plan, pruned as it is driven
        self.recovery_index = 0
        self.recovered: list[tuple[float, str]] = []  # (s, name): each recovery begun
        # Made at the first scan: the global costmap's window depends on where the robot is.
        self._costmap: Costmap | None = None
        self._map: OccupancyGrid | None = None  # the world's map, if it has one
        self.recoveries: list[Callable[[], Recovery]] = []
        self._recovery: Recovery | None = None
        self._trigger: Trigger | None = None  # what began the last recovery
        self._command = (0.0, 0.0)
        self._next_update = -math.inf  # s
        self._next_cycle = -math.inf  # s
        self._next_plan = math.inf  # s, when planner_frequency next replans
        self._valid_plan = self._valid_control = self._oscillation_reset = -math.inf  # s
        self._oscillation_pose: tuple[float, float] | None = None

    @property
    def costmap(self) -> Costmap:
        """The costmap, global and local in one (see the module docstring)."""
        if self._costmap is None:
            raise RuntimeError("move_base has no costmap before its first scan")
        return self._costmap

    def published_costmap(self) -> OccupancyGrid | None:
        """The global costmap as move_base publishes it on global_costmap/costmap
        (`publisher.py`); none before the first scan."""
        return None if self._costmap is None else published(self._costmap)

    def published_plan(self) -> FloatArray:
        """The global plan (N, 2) m, what is left of it ahead of the robot: navfn's plan, as
        move_base hands it to the local planner (and RViz shows it)."""
        return self.plan.copy()

    def receive_map(self, grid: OccupancyGrid) -> None:
        """The world's map, as map_server latches /map: the global costmap's static layer.

        Neither the Husky's navigation.yaml nor `settings.py` says whether the global costmap
        has one: the file is Clearpath's mapless configuration (move_base.launch with
        no_static_map loads costmap_global_laser.yaml: obstacles_laser and inflation), and with
        a map move_base.launch loads costmap_global_static.yaml instead (husky/husky
        noetic-devel dff7c81a, husky_navigation/config). Here, receiving a map is what switches
        the static layer on. It lies under the obstacle layer (static, obstacle, inflation), as
        the Jackal's map_nav_params/global_costmap_params.yaml and the TurtleBot3's
        global_costmap_params.yaml (static_map: true, which Costmap2DROS::loadOldParameters
        makes static_layer, obstacle_layer, inflation_layer) have it. Clearpath's
        costmap_global_static.yaml differs: it has a static and an inflation layer and no
        obstacle layer at all, in the map frame (rolling_window false, the map's size); the
        imitation keeps its rolling window and its obstacle layer, so the planner still sees
        what the scans mark.
        """
        self._map = grid
        if self._costmap is not None:
            self._costmap.receive_map(grid, self._static_layer())

    def _static_layer(self) -> StaticLayerSettings:
        """The static layer's parameters: ROS 1's defaults, with the global costmap's
        track_unknown_space, which Costmap2DROS copies onto the layer where a configuration
        sets it (the Husky's costmap_global_*.yaml set true). Where none does (the Jackal's,
        the TurtleBot3's) the layer's own default is true while the costmap's is false: the
        obstacle layer, not tracking unknown space either, then overwrites every cell the map
        leaves unknown with its own free or lethal one (updateWithMax), as if the layer had
        read it free."""
        return StaticLayerSettings(self.settings.global_costmap.track_unknown_space)

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        """The command of the latest cycle; the costmap and move_base each on their clock."""
        pose = (odometry.x, odometry.y, odometry.yaw)
        if self._costmap is None:
            self._start(pose, time)
        if time >= self._next_update:
            self._next_update = time + 1.0 / self.settings.costmap.update_frequency
            self.costmap.update(scan, pose)
        if self._recovery is not None:
            command = self._recovery.step(pose, time)
            if command is not None:
                return command
            self._end_recovery(time)
        if time >= self._next_cycle:
            self._next_cycle = time + 1.0 / self.settings.move_base.controller_frequency
            self._command = self._cycle(pose, (odometry.linear, odometry.angular), time)
        return self._command

    def _cycle(self, pose: Pose, velocity: tuple[float, float], time: float) -> tuple[float, float]:
        """One executeCycle of move_base."""
        if self.state is State.DONE:
            return 0.0, 0.0
        self._watch_oscillation(pose, time)
        replanning = self.state is State.CONTROLLING and time >= self._next_plan
        if self.state is State.PLANNING or replanning:
            self._replan(pose, time)
        if self.state is State.CONTROLLING:
            return self._control(pose, velocity, time)
        if self.state is State.CLEARING:
            return self._clear(pose, time)
        return 0.0, 0.0

    def _start(self, pose: Pose, time: float) -> None:
        """At the first scan: the global costmap around the robot, and the first goal."""
        points = np.array([pose[:2], *((point.x, point.y) for point in self.route)])
        self._costmap = Costmap(_global_settings(self.settings, points), self.footprint)
        if self._map is not None:
            self._costmap.receive_map(self._map, self._static_layer())
        self.recoveries = self._recoveries()
        self._new_goal(time)

    def _new_goal(self, time: float) -> None:
        """Take the next goal of the route, as a new move_base goal resets its state."""
        self.state = State.PLANNING
        self._valid_plan = self._valid_control = self._oscillation_reset = time
        self.recovery_index = 0

    def _replan(self, pose: Pose, time: float) -> None:
        """Run the planner; without a plan for planner_patience, recover."""
        frequency = self.settings.move_base.planner_frequency
        self._next_plan = time + 1.0 / frequency if frequency > 0.0 else math.inf
        plan = self._make_plan(pose)
        if plan is not None:
            self.plan = plan
            self.local_planner.oscillation.reset()
            self._valid_plan = time
            if self._trigger is Trigger.PLANNING:
                self.recovery_index = 0
            if self.state is State.PLANNING:
                self.state = State.CONTROLLING
        elif self.state is State.PLANNING and time > self._valid_plan + (
            self.settings.move_base.planner_patience
        ):
            self.state, self._trigger = State.CLEARING, Trigger.PLANNING

    def _control(
        self, pose: Pose, velocity: tuple[float, float], time: float
    ) -> tuple[float, float]:
        """DWA's command toward the goal; without one, plan again or recover."""
        goal = self.route[self.goal_index]
        if math.dist(pose[:2], (goal.x, goal.y)) <= self.settings.dwa.xy_goal_tolerance:
            return self._goal_reached(time)
        move_base = self.settings.move_base
        if move_base.oscillation_timeout > 0.0 and time > (
            self._oscillation_reset + move_base.oscillation_timeout
        ):
            self.state, self._trigger = State.CLEARING, Trigger.OSCILLATION
            return 0.0, 0.0
        command = self.local_planner.command(pose, velocity, self._surroundings(pose))
        if command is not None:
            self._valid_control = time
            if self._trigger is Trigger.CONTROLLING:
                self.recovery_index = 0
            return command
        if time > self._valid_control + move_base.controller_patience:
            self.state, self._trigger = State.CLEARING, Trigger.CONTROLLING
        else:
            self.state, self._valid_plan = State.PLANNING, time
        return 0.0, 0.0

    def _goal_reached(self, time: float) -> tuple[float, float]:
        if self.goal_index == len(self.route) - 1:
            self.state = State.DONE
        else:
            self.goal_index += 1
            self._new_goal(time)
        return 0.0, 0.0

    def _clear(self, pose: Pose, time: float) -> tuple[float, float]:
        """Start the next recovery behaviour, or give up when none is left."""
        if not self.settings.move_base.recovery_behavior_enabled or self.recovery_index >= len(
            self.recoveries
        ):
            self.state = State.DONE
            return 0.0, 0.0
        self._recovery = self.recoveries[self.recovery_index]()
        self.recovered.append((time, self._recovery.name))
        command = self._recovery.step(pose, time)
        if command is None:
            self._end_recovery(time)
            return 0.0, 0.0
        return command

    def _end_recovery(self, time: float) -> None:
        self._recovery = None
        self._oscillation_reset = time
        self.state = State.PLANNING
        self.recovery_index += 1
        # The next cycle keeps the controller's clock: at once if the behaviour outlasted the
        # period, as move_base's loop then runs late, else at the next tick.

    def _watch_oscillation(self, pose: Pose, time: float) -> None:
        """Reset the oscillation clock whenever the robot has moved far enough."""
        here = (pose[0], pose[1])
        if self._oscillation_pose is None or math.dist(here, self._oscillation_pose) >= (
            self.settings.move_base.oscillation_distance
        ):
            self._oscillation_pose, self._oscillation_reset = here, time
            if self._trigger is Trigger.OSCILLATION:
                self.recovery_index = 0

    def _make_plan(self, pose: Pose) -> FloatArray | None:
        """navfn's plan (K, 2) m from the robot to the goal, searched in the rectangle spanning
        both widened by planner_margin, or None."""
        goal = self.route[self.goal_index]
        margin = self.settings.move_base.planner_margin
        return windowed_plan(
            self.costmap, (pose[0], pose[1]), (goal.x, goal.y), self.settings.navfn, margin
        )

    def _surroundings(self, pose: Pose) -> Surroundings:
        """What DWA scores against: the plan, pruned behind the robot, from its first point in
        the local window to the last before it leaves it, and the lethal cells near the
        robot."""
        away = np.hypot(self.plan[:, 0] - pose[0], self.plan[:, 1] - pose[1])  # (K,) m
        near = away < PRUNE_DISTANCE
        if near.any():
            first = int(np.argmax(near))
            self.plan, away = self.plan[first:], away[first:]
        inside = away <= self.settings.costmap.size / 2.0
        local = self.plan[int(np.argmax(inside)) :] if inside.any() else self.plan[:0]
        leaves = ~inside[len(self.plan) - len(local) :]
        if leaves.any():
            local = local[: int(np.argmax(leaves))]
        goal = self.route[self.goal_index]
        return Surroundings(local, (goal.x, goal.y), self._lethal_near(pose))

    def _lethal_near(self, pose: Pose) -> FloatArray:
        """The centres (N, 2) m of the lethal cells DWA's rollouts and the recoveries can reach."""
        dwa = self.settings.dwa
        reach = dwa.max_vel_x * dwa.sim_time + 2.0 * self.local_planner.reach + 0.5  # m
        resolution, cells = self.costmap.settings.resolution, self.costmap.settings.cells
        x, y, _ = self.costmap.cell_of(np.array([[pose[0] - reach, pose[1] - reach]]))
        span = math.ceil(2.0 * reach / resolution) + 1
        x0, y0 = max(int(x[0]), 0), max(int(y[0]), 0)
        block = self.costmap.grid[y0 : min(y0 + span, cells), x0 : min(x0 + span, cells)]
        rows, columns = np.nonzero(block == LETHAL)
        return self.costmap.centres(columns + x0, rows + y0)

    def _recoveries(self) -> list[Callable[[], Recovery]]:
        """move_base's default recovery behaviours in order, with the back-up one after the
        first if it is enabled: each call starts a fresh run of one."""
        move_base, costmap = self.settings.move_base, self.costmap
        # move_base's aggressive reset keeps four circumscribed radii around the robot.
        aggressive = 4.0 * self.local_planner.reach  # m

        def rotate() -> Recovery:
            return RotateInPlace(self._is_clear)

        def back_up() -> Recovery:
            return BackUp(self._is_clear, move_base.back_up_distance, move_base.back_up_speed)

        recoveries: list[Callable[[], Recovery]] = [
            lambda: ClearCostmap("conservative_reset", costmap, move_base.conservative_reset_dist)
        ]
        if move_base.back_up_recovery:
            recoveries.append(back_up)
        if move_base.clearing_rotation_allowed:
            recoveries.append(rotate)
        recoveries.append(lambda: ClearCostmap("aggressive_reset", costmap, aggressive))
        if move_base.clearing_rotation_allowed:
            recoveries.append(rotate)
        return recoveries

    def _is_clear(self, poses: FloatArray) -> bool:
        """Whether the footprint at every pose (P, 3) is clear of the lethal cells."""
        middle = poses[len(poses) // 2]
        lethal = self._lethal_near((float(middle[0]), float(middle[1]), float(middle[2])))
        return self.local_planner.clear(poses, lethal)


def _global_settings(settings: NavigationSettings, points: FloatArray) -> CostmapSettings:
    """The global costmap: the local one's layers in a window of its own width, cut to what a
    run along `points` (P, 2) m can mark, clear and plan through; it keeps its rolling window's
    semantics, and saves moving 100 m of cells every time the robot moves one."""
    span = float(np.hypot(*(points[:, np.newaxis] - points[np.newaxis]).T).max())  # m
    return dataclasses.replace(
        settings.costmap,
        size=global_costmap_size(settings, span),
        track_unknown_space=settings.global_costmap.track_unknown_space,
    )
