"""Nav2 as nav2_bringup runs it (nav2_params.yaml and the default behaviour tree,
navigate_to_pose_w_replanning_and_recovery.xml, at jazzy f4108e5b), with the parameters of a
params file (`params.py`; Nav2's code defaults where it sets none).

Scan by scan, and between scans at its own clocks' rate (`control_frequency`), it does what
Nav2's servers do on their clocks:

- the local costmap (Jazzy's: a 3 m rolling window, 5 Hz) and the global costmap (1 Hz) take
  each new scan through Nav2's obstacle layer, marking by the release's rule;
- every second the tree's ComputePathToPose plans again with NavFn (tolerance 0.5 m, unknown
  space allowed), once more after clearing the global costmap if it finds no plan;
- the controller server (20 Hz) runs FollowPath, MPPI or DWB: MPPI on the part of the plan its
  path handler gives (`path_handler.py`), DWB on the plan from the point nearest the robot up
  to prune_distance along it; the goal checker ends each goal at
  xy_goal_tolerance; the progress checker (0.5 m in 10 s) or a controller with no valid command
  fails FollowPath, which runs once more after clearing the local costmap;
- a failure past those makes the tree recover with the next of its round robin (clear both
  costmaps, Spin 1.57 rad, Wait 5 s, BackUp 0.30 m at 0.15 m/s; a failing one hands on to the
  next), then navigate afresh; after 6 recoveries the navigation fails and the robot stands.

Every command passes the velocity smoother (`velocity_smoother.py`), then, each time the
smoother publishes, the collision monitor (`collision_monitor.py`). What it did that a report
should name is in `activity`. Where this differs on purpose: the global costmap is a window
over the route (as move_base's here), not the map's extent; without a map, with a static layer
it starts free, as an open field's map would make it, and without one it may track unknown
space (NavFn then keeps to the cells the scans have cleared, which rays that return nothing
never clear); given the world's map (`receive_map`), its static layer holds the map, under the
obstacle layer (`move_base/costmap.py`), and it tracks unknown space as configured; NavFn
searches a window 5 m around the robot and its goal; goals have no heading.
docs/explanation/navigation.md lists the rest.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, Point2D
from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.model.route import place
from pytest_lasertest.nav.move_base.cost_values import LETHAL
from pytest_lasertest.nav.move_base.navfn import windowed_plan
from pytest_lasertest.nav.move_base.publisher import published
from pytest_lasertest.nav.nav2.behaviors import BackUp, Spin, Wait
from pytest_lasertest.nav.nav2.collision_monitor import approach, scan_points
from pytest_lasertest.nav.nav2.costmap import Nav2Costmap
from pytest_lasertest.nav.nav2.critics import ConstraintCritic
from pytest_lasertest.nav.nav2.dwb import DwbController
from pytest_lasertest.nav.nav2.global_costmap import make_global_costmap
from pytest_lasertest.nav.nav2.mppi import F32, SAME_PERIOD, Critic, Optimizer
from pytest_lasertest.nav.nav2.params import configured
from pytest_lasertest.nav.nav2.path_handler import max_costmap_dist, transform_path
from pytest_lasertest.nav.nav2.settings import CostmapConfig, Nav2Settings
from pytest_lasertest.nav.nav2.velocity_smoother import VelocitySmoother
from pytest_lasertest.nav.protocol import LaserScan, Odometry

Pose = tuple[float, float, float]  # m, m, rad
# The default tree's RoundRobin of recoveries (navigate_to_pose_w_replanning_and_recovery.xml).
RECOVERIES = ("ClearingActions", "Spin", "Wait", "BackUp")


class Nav2:
    """Nav2 driving one robot along a route of goals."""

    def __init__(
        self,
        robot: Robot,
        route: tuple[Point2D, ...],
        settings: Nav2Settings | None = None,
        seed: int = 0,
    ) -> None:
        self.settings = s = settings or configured(robot.nav2, robot.nav2_release).settings
        self.route, self.goal_index = route, 0
        self.footprint = _footprint(s.local, robot)  # (V, 2) m
        self.controller = _follow_path(s, seed)
        self.local = Nav2Costmap(s.local.costmap, self.footprint, s.local.source, s.marking)
        self._global_footprint = _footprint(s.global_, robot)
        self.smoother = VelocitySmoother(s.smoother)
        self.goal_tolerance = s.xy_goal_tolerance  # m: the goal oracle judges by it
        self._global: Nav2Costmap | None = None  # made at the first scan, around the route
        self._map: OccupancyGrid | None = None  # the world's map, if it has one
        self.plan: FloatArray = np.zeros((0, 2))  # m
        self._handled: FloatArray = np.zeros((0, 2))  # m, the plan as MPPI's path handler keeps it
        self.failed: str | None = None  # why the navigation stopped, if it did
        self._command = (0.0, 0.0)
        self._next = dict.fromkeys(("local", "global", "plan", "cycle", "behavior"), -math.inf)
        self._progress: tuple[float, float, float] | None = None  # x, y (m) and time (s)
        # What the stack did, for the report: (s, what) for each recovery begun, each time the
        # collision monitor stopped the robot, and the navigation failing.
        self.activity: list[tuple[float, str]] = []
        self._held = False  # whether the collision monitor holds the robot
        self._allowed = (0.0, 0.0)  # the command the collision monitor last let through
        # The stamp of the last scan the collision monitor read, and its points (P, 2) m.
        self._seen: tuple[float, FloatArray] = (-math.inf, np.zeros((0, 2)))
        self._stamp = -math.inf  # s, the stamp of the last scan the costmaps were offered
        # The simulator calls between scans at this rate: the controller server's and the
        # smoother's clocks.
        self.control_frequency = max(s.controller_frequency, s.smoother.smoothing_frequency)
        # The stuck oracle waits as long as Nav2 keeps trying by its own logic before a
        # recovery has had its chance: the progress checker's allowance, then as long again
        # for a recovery (Spin's and BackUp's time_allowance is 10 s) and for navigating
        # again after it.
        self.stuck_window = 3.0 * s.movement_time_allowance  # s
        self._behavior: Spin | BackUp | Wait | None = None
        self._robin = 0  # the round robin's next action
        self._retries = 0  # the tree's RecoveryNode retries used
        self._tried = 0  # actions of the round robin failed in a row
        self._follow_retried = False  # FollowPath's RecoveryNode retry used

    def published_costmap(self) -> OccupancyGrid | None:
        """The global costmap as Nav2's global_costmap node publishes it on
        global_costmap/costmap (`publisher.py`); none before the first scan."""
        return None if self._global is None else published(self._global)

    def published_plan(self) -> FloatArray:
        """The global plan (N, 2) m the planner server last published on /plan."""
        return self.plan.copy()

    def receive_map(self, grid: OccupancyGrid) -> None:
        """The world's map, as map_server latches /map: the global costmap's static layer, if
        its plugins name one (Costmap2DROS's default plugins do; nav2_no_map_params.yaml's do
        not, and its costmap ignores the map).

        Only the global costmap takes it. Jazzy's nav2_params.yaml and ROBOTIS's TurtleBot3
        files give the local costmap no static layer, but Clearpath's a200 and j100 files
        (robots/husky/nav2.yaml, robots/jackal/nav2.yaml) do name static_layer in the local
        costmap's plugins too; the imitation's local costmap has none whatever the file says:
        MPPI, DWB and the behaviours' collision checks see a wall once the scanner does.
        """
        self._map = grid
        static = self.settings.global_.static_layer
        if self._global is not None and static is not None:
            # Given after the first scan, not as the simulator gives it: the costmap keeps
            # the unknown space it was made with.
            self._global.receive_map(grid, static)

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        """The command of the latest cycle, smoothed, as the collision monitor lets it through.
        The monitor acts on each command the smoother publishes (its cmd_vel_in callback), with
        the latest scan; between them the robot keeps the last it let through."""
        command = self._navigate(scan, odometry, time)
        if not self.smoother.due(time):
            return self._allowed
        smoothed = self.smoother.step(command, time)
        monitor = self.settings.collision_monitor
        if monitor is None:
            self._allowed = smoothed
            return smoothed
        if scan.stamp != self._seen[0]:  # between scans the monitor reads the last again
            self._seen = scan.stamp, scan_points(scan)
        self._allowed = approach(smoothed, self._seen[1], self.footprint, monitor)
        held = self._allowed == (0.0, 0.0) and smoothed != (0.0, 0.0)
        if held and not self._held:
            self.activity.append((time, "the collision monitor stopped the robot"))
        self._held = held
        return self._allowed

    def _navigate(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        """The command of the latest cycle; each server on its own clock, the behaviour tree
        choosing what runs."""
        pose = (odometry.x, odometry.y, odometry.yaw)
        s = self.settings
        if self._global is None:
            self._global = make_global_costmap(
                s, self._global_footprint, (pose[0], pose[1]), self.route, self._map
            )
        # A costmap takes a scan once, where the robot was when it was taken (tf at its
        # stamp); between scans only the controller's clocks run.
        fresh, self._stamp = scan.stamp != self._stamp, scan.stamp
        if fresh and self._due("local", time, 1.0 / s.local.costmap.update_frequency):
            self.local.update(scan, pose)
        if fresh and self._due("global", time, 1.0 / s.global_.costmap.update_frequency):
            self.global_costmap.update(scan, pose)
        if self._done():
            return 0.0, 0.0
        if self._behavior is not None:
            return self._recover(pose, time)
        if self._due("plan", time, s.replan_period) and not self._plan_with_recovery(pose, time):
            self.controller.reset()  # the tree halts FollowPath: its action ends
            return self._navigation_failed(pose, time)
        if self._due("cycle", time, 1.0 / s.controller_frequency):
            command = self._cycle(pose, (odometry.linear, odometry.angular), time)
            if command is None:
                return self._follow_failed(pose, time)
            self._command = command
        return self._command

    def _plan_with_recovery(self, pose: Pose, time: float) -> bool:
        """ComputePathToPose in its RecoveryNode: once more after clearing the global
        costmap entirely."""
        if self._replan(pose):
            return True
        self.global_costmap.clear_outside(pose[0], pose[1], 0.0)
        self.activity.append((time, "ClearGlobalCostmap-Context"))
        return self._replan(pose)

    def _follow_failed(self, pose: Pose, time: float) -> tuple[float, float]:
        """FollowPath in its RecoveryNode: once more after clearing the local costmap. Its
        action ended, the controller server resets the controller."""
        self.controller.reset()
        if self._follow_retried:
            return self._navigation_failed(pose, time)
        self._follow_retried = True
        self.local.clear_outside(pose[0], pose[1], 0.0)
        self.activity.append((time, "ClearLocalCostmap-Context"))
        self._progress = None
        self._command = (0.0, 0.0)
        return self._command

    def _navigation_failed(self, pose: Pose, time: float) -> tuple[float, float]:
        """The tree's RecoveryNode: the round robin's next recovery, or, after
        number_of_retries of them, the navigation fails."""
        self._command = (0.0, 0.0)
        if self._retries >= self.settings.number_of_retries:
            self.failed = f"navigation failed after {self._retries} recoveries"
            self.activity.append((time, self.failed))
            return self._command
        self._retries += 1
        self._tried = 0
        self._begin_recovery(pose, time)
        return self._recover(pose, time) if self._behavior is not None else self._command

    def _begin_recovery(self, pose: Pose, time: float) -> None:
        """Start the round robin's current action; clearing both costmaps ends at once."""
        name = RECOVERIES[self._robin]
        self.activity.append((time, name))
        if name == "ClearingActions":
            self.local.clear_outside(pose[0], pose[1], 0.0)
            self.global_costmap.clear_outside(pose[0], pose[1], 0.0)
            self._recovered()
        elif name == "Spin":
            self._behavior = Spin(1.57, self._collides, self.settings.behaviors)
        elif name == "Wait":
            self._behavior = Wait(5.0)
        else:
            self._behavior = BackUp(0.30, 0.15, self._collides, self.settings.behaviors)

    def _recover(self, pose: Pose, time: float) -> tuple[float, float]:
        """Step the running behaviour at the behaviour server's 10 Hz; when it ends, on to
        navigating again, or on failure to the round robin's next action (all failing fails
        the navigation)."""
        assert self._behavior is not None
        if not self._due("behavior", time, self.settings.behaviors.cycle_period):
            return self._command
        command = self._behavior.step(pose, time)
        if command is not None:
            self._command = command
            return command
        failed, self._behavior = self._behavior.failed, None
        self._command = (0.0, 0.0)
        if not failed:
            self._recovered()
            return self._command
        self._robin = (self._robin + 1) % len(RECOVERIES)
        self._tried += 1
        if self._tried == len(RECOVERIES):
            self.failed = "every recovery failed"
            self.activity.append((time, self.failed))
            return self._command
        self._begin_recovery(pose, time)
        return self._recover(pose, time) if self._behavior is not None else self._command

    def _recovered(self) -> None:
        """A recovery succeeded: the round robin moves on; navigation starts afresh, its
        controller cycle at once."""
        self._robin = (self._robin + 1) % len(RECOVERIES)
        self._afresh()
        self._next["cycle"] = -math.inf

    def _afresh(self) -> None:
        """Navigate afresh: FollowPath's retry and the progress checker start again, and the
        plan is made at once."""
        self._follow_retried = False
        self._progress = None
        self._next["plan"] = -math.inf

    def _collides(self, pose: Pose) -> bool:
        """Whether the footprint at `pose` is in collision for the behaviours' collision
        checker (CostmapTopicCollisionChecker::isCollisionFree on the local costmap,
        costmap_topic_collision_checker.cpp:58-98 at jazzy f4108e5b): a pose off the window, or
        a cost of lethal or more (unknown) on the footprint's outline."""
        _, _, inside = self.local.cell_of(np.array([pose[:2]]))
        if not inside[0]:
            return True
        return self.local.footprint_cost(place(self.footprint, np.array(pose))) >= LETHAL

    @property
    def global_costmap(self) -> Nav2Costmap:
        """The global costmap, once the first scan has made it."""
        if self._global is None:
            raise RuntimeError("Nav2 has no global costmap before its first scan")
        return self._global

    def _due(self, clock: str, time: float, period: float) -> bool:
        if time < self._next[clock]:
            return False
        self._next[clock] = time + period
        return True

    def _done(self) -> bool:
        return self.failed is not None or self.goal_index >= len(self.route)

    def _cycle(
        self, pose: Pose, speed: tuple[float, float], time: float
    ) -> tuple[float, float] | None:
        """One controller-server cycle: the goal checker, the progress checker, then MPPI."""
        goal = self.route[self.goal_index]
        if math.hypot(goal.x - pose[0], goal.y - pose[1]) <= self.settings.xy_goal_tolerance:
            self._next_goal()
            return 0.0, 0.0
        if not self._progressing(pose, time):
            return None  # FAILED_TO_MAKE_PROGRESS
        if not len(self.plan):
            return 0.0, 0.0
        path = (
            self._pruned(pose) if isinstance(self.controller, DwbController) else self._path(pose)
        )
        if not len(path):
            return None  # MPPI's InvalidPath: no pose of the plan on the local costmap
        # None: NO_VALID_CONTROL, every sample colliding.
        return self.controller.command(pose, speed, path, (goal.x, goal.y), self.local.cost_grid())

    def _next_goal(self) -> None:
        """The next waypoint, navigated to by a fresh run of the tree: its retries, round robin
        and checkers start again, as each NavigateToPose goal's do."""
        self.goal_index += 1
        self.controller.reset()  # FollowPath succeeded: its action ended
        self._retries = self._robin = 0
        self._afresh()

    def _progressing(self, pose: Pose, time: float) -> bool:
        """SimpleProgressChecker: moved required_movement_radius within the allowance."""
        s = self.settings
        if (
            self._progress is None
            or math.hypot(pose[0] - self._progress[0], pose[1] - self._progress[1])
            > s.required_movement_radius
        ):
            self._progress = (pose[0], pose[1], time)
            return True
        return time - self._progress[2] <= s.movement_time_allowance

    def _replan(self, pose: Pose) -> bool:
        """NavFn's plan from the robot to the goal on the global costmap; False, the old one
        kept, if none is found."""
        goal = self.route[self.goal_index]
        s = self.settings
        plan = windowed_plan(
            self.global_costmap, pose[:2], (goal.x, goal.y), s.navfn, s.planner_margin
        )
        if plan is None:
            return False
        self.plan = self._handled = plan  # the controller server's setPlan hands it on
        if isinstance(self.controller, DwbController):
            self.controller.set_plan()  # the controller server's setPlan, at each new path
        return True

    def _path(self, pose: Pose) -> F32:
        """MPPI's path handler's part of the plan for this cycle (`path_handler.py`), the plan
        it keeps pruned of the poses behind the robot."""
        s, local = self.settings, self.local
        search = s.max_robot_pose_search_dist
        if search is None:
            search = max_costmap_dist(local.settings.cells, local.settings.resolution)
        handled = transform_path(
            self._handled, pose, search, s.prune_distance, lambda p: local.cell_of(p)[2]
        )
        self._handled = handled.plan
        path: F32 = handled.path.astype(np.float32)
        return path

    def _pruned(self, pose: Pose) -> F32:
        """DWB's plan: from its point nearest the robot, up to prune_distance along it (DWB
        prunes it further itself, `dwb.local_plan`)."""
        away = np.hypot(self.plan[:, 0] - pose[0], self.plan[:, 1] - pose[1])
        path = self.plan[int(np.argmin(away)) :]
        steps = np.hypot(*np.diff(path, axis=0).T)
        along = np.concatenate([[0.0], np.cumsum(steps)])
        kept: F32 = path[along <= self.settings.prune_distance].astype(np.float32)
        return kept


def _follow_path(s: Nav2Settings, seed: int) -> Optimizer | DwbController:
    """FollowPath: MPPI with the settings' critics, or DWB if the params file names it."""
    if s.dwb is not None:
        return DwbController(s.dwb)
    critics: list[Critic] = [
        dataclasses.replace(critic, settings=s.mppi)
        if isinstance(critic, ConstraintCritic)
        else critic
        for critic in s.critics
    ]
    shift = abs(1.0 / s.controller_frequency - s.mppi.model_dt) < SAME_PERIOD
    return Optimizer(s.mppi, critics, np.random.default_rng(seed), shift)


def _footprint(config: CostmapConfig, robot: Robot) -> FloatArray:
    """The footprint a costmap plans for, (V, 2) m: its own, else the robot's."""
    if config.footprint is None:
        return robot.footprint_array()
    return np.array(config.footprint, dtype=float)
