"""Scenarios: a robot with one scanner, static obstacles, a route and a controller, run in
PyBullet to a trajectory and the oracles' verdicts.

One run is one fresh DIRECT client stepped at a fixed time step. The scanner scans at its
update rate; each scan goes through the scanner's driver (`model/driver.py`: its encodings,
beam order and range_max) and reaches the controller with the odometry at the driver's stamp,
at the first step from it (at once, for Gazebo's driver), and the command it answers is driven
through the wheels until the next scan. The same scenario gives the same trajectory, bit
for bit: PyBullet is deterministic for identical command sequences, and each scan's noise comes
from a generator of its own, seeded by the scenario's seed and the scan's index. The controller
is made and called through `Guard` (`guard.py`), which reads its commands exactly as returned
and turns a controller that raises, hangs or answers no command into `ControllerError`.

A scan is cast only if something reads its ranges (`CastOnRead`): move_base reads one scan in
twelve, at its costmap's update, as costmap_2d with observation_persistence 0 reads the latest
observation. So that skipping a scan changes nothing, its noise does not come from a stream the
scans share. The flat caster is deferred this way; PyBullet's cast meets the robot's own body
as it stands at the scan, so it is cast at once. A deferred cast runs within the controller's
call and counts toward its time: some 40 us a scan read.
"""

from __future__ import annotations

import collections
import dataclasses
import hashlib
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from pytest_lasertest.model.driver import publish
from pytest_lasertest.model.geometry import FloatArray, Point2D, Pose2D, Pose3D
from pytest_lasertest.model.obstacles import Obstacle
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.model.route import scan_count
from pytest_lasertest.model.sensor import LaserProfile, LaserScanMeta
from pytest_lasertest.model.walls import Walls
from pytest_lasertest.nav.protocol import ControllerFactory, LaserScan, Odometry
from pytest_lasertest.sim.client import PhysicsClient, PhysicsWorld
from pytest_lasertest.sim.drive import Drive, Twist, drive_step
from pytest_lasertest.sim.faults import ControllerFault, Faulted
from pytest_lasertest.sim.guard import Guard
from pytest_lasertest.sim.lidar import FlatLidar, noisy, ranges_from_fractions, scan_rays
from pytest_lasertest.sim.oracles import Referee, Rules, Verdicts
from pytest_lasertest.sim.recording import Recorder, Recording

# A physics step of one 50 Hz scan period: the Husky's drive reaches its commands within 3 % at
# 5-20 ms steps (tests/sim/test_drive.py), and the longest keeps the run cheapest.
TIME_STEP = 0.02  # s
Caster = Literal["flat", "pybullet"]


@dataclass(frozen=True)
class Scenario:
    """Everything a run depends on."""

    robot: Robot
    profile: LaserProfile
    obstacles: tuple[Obstacle, ...]
    start: Pose2D
    route: tuple[Point2D, ...]  # waypoints in order; the last is the goal
    time_limit: float  # s
    seed: int  # of the scan noise
    time_step: float = TIME_STEP  # s
    rules: Rules = field(default_factory=Rules)
    # Where the rays are cast: PyBullet's rayTestBatch, or the flat ray cast it equals on these
    # scenes of upright obstacles on level ground (tests/sim/test_lidar.py holds them equal).
    caster: Caster = "flat"
    # The world's walls: static bodies like the obstacles, and the map the controller is given.
    walls: Walls = field(default_factory=Walls)
    # Whether the run keeps what the robot published (`recording.py`): a failure's rosbag2 and
    # picture show it. Off in the search, where most runs are never looked at.
    record: bool = False

    @property
    def solids(self) -> tuple[Obstacle, ...]:
        """Everything standing in the world: the obstacles, then the walls."""
        return self.obstacles + self.walls.boxes


@dataclass(frozen=True, eq=False)
class Run:
    """What one run of a scenario did: one row per physics step."""

    scenario: Scenario
    times: FloatArray  # (T,) s, at the end of each step
    poses: FloatArray  # (T, 3) base_footprint [x, y, yaw], m, m, rad
    commands: FloatArray  # (T, 2) the command being driven [forward m/s, turn rad/s]
    # (T, 2) what drove the body: its wheel speeds [left, right] (rad/s), or the twist a
    # body without wheels moved at [forward m/s, turn rad/s]
    driven: FloatArray
    scans: int  # how many scans the controller was given
    verdicts: Verdicts
    # What the controller said it did, (s, what): a navigation stack's recoveries, say.
    activity: tuple[tuple[float, str], ...] = ()
    # With `Scenario.record`: the scans, and the controller's costmap and plan once a second
    # and when the run was decided (or ran out of time).
    recording: Recording | None = None

    @property
    def passed(self) -> bool:
        return self.verdicts.passed

    def digest(self) -> str:
        """A hash of the trajectory, equal for bit-identical runs."""
        digest = hashlib.sha256()
        for array in (self.times, self.poses, self.commands):
            digest.update(np.ascontiguousarray(array).tobytes())
        return digest.hexdigest()


class ControllerError(BaseException):
    """A run the controller broke (see `sim/guard.py`): what it did, and in which scenario.

    Not an `Exception`, as `Faulted` is not: it ends the run and whatever search drove it, and
    the item reports it."""

    def __init__(self, fault: ControllerFault, scenario: Scenario, controller: str) -> None:
        super().__init__(f"the controller {controller}: {fault.describe()}")
        self.fault = fault
        self.scenario = scenario
        self.controller = controller  # `module:qualname` of its factory


def run_scenario(
    scenario: Scenario, make_controller: ControllerFactory, client: PhysicsClient | None = None
) -> Run:
    """Run the scenario with a fresh controller from `make_controller` until it is decided or
    its time is up, in `client` (reset for it) or in a client of its own. A controller that
    breaks its protocol raises `ControllerError`."""
    guard = Guard(make_controller)
    try:
        with guard:
            guard.make(scenario.robot, scenario.route)
            if scenario.walls.grid is not None:
                guard.give_map(scenario.walls.grid)
            start, obstacles = scenario.start, scenario.solids
            body = scenario.robot.body
            with PhysicsWorld(start, obstacles, scenario.time_step, client, body) as world:
                return _Runner(scenario, world, guard).run()
    except Faulted as faulted:
        # What the controller raised, if it raised, is the cause: --fulltrace shows it.
        raise ControllerError(faulted.fault, scenario, guard.name) from faulted.__cause__


class _Runner:
    """One run in progress: the world, the scanner, the drive and the referee."""

    def __init__(self, scenario: Scenario, world: PhysicsWorld, controller: Guard) -> None:
        self.scenario = scenario
        self.world = world
        self.controller = controller
        self.drive = Drive(scenario.robot)
        start = Point2D(scenario.start.x, scenario.start.y)
        rules = scenario.rules
        if controller.goal_tolerance is not None:
            rules = dataclasses.replace(rules, goal_tolerance=controller.goal_tolerance)
        if controller.stuck_window is not None:
            window = max(rules.stuck_window, controller.stuck_window)
            rules = dataclasses.replace(rules, stuck_window=window)
        self.referee = Referee(rules, start, scenario.route, scenario.time_step)
        self.lidar = FlatLidar(scenario.profile, scenario.solids)
        self.meta = scenario.profile.to_laserscan_meta()
        self._latest: LaserScan | None = None  # the last scan given, for calls between scans
        # Scans measured and not yet delivered, oldest first: each arrives at its stamp.
        self._pending: collections.deque[LaserScan] = collections.deque()
        self._delay = scenario.profile.driver.delay(scenario.profile.scan_period)  # s
        self._next_tick = 0.0  # s, when the controller's own clock next wants a call
        self.recorder = Recorder(controller) if scenario.record else None

    def run(self) -> Run:
        scenario, world = self.scenario, self.world
        steps = round(scenario.time_limit / scenario.time_step)
        rows: list[tuple[float, ...]] = []
        command, scans, measured_scans = Twist(0.0, 0.0), 0, 0
        pose = world.base_pose()
        yaw = float(pose[2])
        for step in range(steps):
            time = step * scenario.time_step
            measured = Twist(*world.base_twist(yaw))
            ticks = self._tick_due(time)
            if self._scans_at(step) > measured_scans:
                self._pending.append(self._measure(measured_scans, time, pose))
                measured_scans += 1
            arrived = self._arrived(time)
            for scan in arrived:  # each scan whose stamp has come, oldest first
                self._latest = scan
                command = Twist(*self._call(scan, time, pose, measured))
                scans += 1
            if self.recorder is not None:
                self.recorder.step(time, arrived)
            if not arrived and ticks and self._latest is not None:
                command = Twist(*self._call(self._latest, time, pose, measured))
            driven = drive_step(world, self.drive, command, measured, yaw, scenario.time_step)
            time += scenario.time_step
            pose = world.base_pose()
            x, y, yaw = pose.tolist()
            rows.append((time, x, y, yaw, command.linear, command.angular, *driven))
            clearance, touching = world.proximity(pose, scenario.rules.clearance_horizon)
            if self.referee.update(time, x, y, clearance, touching):
                break
        table = np.array(rows).reshape(-1, 8)
        ended = float(table[-1, 0]) if len(table) else 0.0
        return Run(
            scenario,
            table[:, 0],
            table[:, 1:4],
            table[:, 4:6],
            table[:, 6:8],
            scans,
            self.referee.verdicts(),
            self.controller.activity(ended),
            self.recorder.finish(ended) if self.recorder is not None else None,
        )

    def _tick_due(self, time: float) -> bool:
        """Whether the controller's own clock (its control_frequency, if it has one) wants a
        call at `time` s; its ticks fall at whole periods from the start."""
        frequency = self.controller.control_frequency
        if frequency is None or time + 1e-9 < self._next_tick:
            return False
        # The first whole period after `time`, worked out, not stepped to: a clock of a GHz
        # would take a billion steps a second.
        self._next_tick = (math.floor((time + 1e-9) * frequency) + 1) / frequency
        return True

    def _arrived(self, time: float) -> list[LaserScan]:
        """The measured scans whose stamps have come by `time` s, taken off the queue."""
        arrived = []
        while self._pending and self._pending[0].stamp <= time + 1e-9:
            arrived.append(self._pending.popleft())
        return arrived

    def _scans_at(self, step: int) -> int:
        """How many scans the scanner has taken by the start of this step."""
        scenario = self.scenario
        return scan_count(scenario.profile.update_rate, step * scenario.time_step)

    def _measure(self, index: int, time: float, pose: FloatArray) -> LaserScan:
        """Scan number `index`, measured at `time` s from `pose`, as its driver publishes it:
        stamped (and delivered) its driver's delay later."""
        profile, seed = self.scenario.profile, self.scenario.seed
        driver, meta = profile.driver, self.meta
        # The scan is taken at `pose` (an array of this step's own), whenever it is read.

        def measure() -> FloatArray:
            if self.scenario.caster == "flat":
                ranges = self.lidar.ranges(pose)
            else:
                ranges = ranges_from_fractions(profile, self.world.cast(*scan_rays(profile, pose)))
            return noisy(profile, ranges, np.random.default_rng((seed, index)))

        def cast() -> FloatArray:
            return publish(driver, measure(), meta.range_min, meta.range_max)[0]

        stamp = time + self._delay
        if driver.range_max == "per_scan":  # the header depends on the ranges: cast them now
            ranges, range_max = publish(driver, measure(), meta.range_min, meta.range_max)
            meta = dataclasses.replace(meta, range_max=range_max)
            return CastOnRead(stamp, ranges, meta, profile.pose)
        deferred = cast if self.scenario.caster == "flat" else cast()
        return CastOnRead(stamp, deferred, meta, profile.pose)

    def _call(
        self, scan: LaserScan, time: float, pose: FloatArray, measured: Twist
    ) -> tuple[float, float]:
        """The controller's command at `time` s, the robot at `pose`, with `scan`: the one just
        taken, or, between scans, the last again (its stamp tells it apart)."""
        x, y, yaw = pose.tolist()
        odometry = Odometry(x, y, yaw, measured.linear, measured.angular)
        return self.controller.observe(scan, odometry, time)


class CastOnRead(LaserScan):
    """A LaserScan whose ranges are cast when first read, if given as a function that casts
    them (as `dataclasses.replace` gives them, an array is kept as it is)."""

    def __init__(
        self,
        stamp: float,
        ranges: FloatArray | Callable[[], FloatArray],
        meta: LaserScanMeta,
        mount: Pose3D,
    ) -> None:
        for name, value in (("stamp", stamp), ("meta", meta), ("mount", mount)):
            object.__setattr__(self, name, value)
        # Not an attribute until read: `__getattr__` is asked only for what is missing.
        object.__setattr__(self, "ranges" if isinstance(ranges, np.ndarray) else "_cast", ranges)

    def __getattr__(self, name: str) -> FloatArray:
        if name != "ranges" or "_cast" not in self.__dict__:
            raise AttributeError(name)
        ranges: FloatArray = self.__dict__.pop("_cast")()
        object.__setattr__(self, "ranges", ranges)
        return ranges
