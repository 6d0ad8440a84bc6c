"""The controller under test, held to its protocol: every call timed, every answer checked.

The controller is the user's code, and the one part of a drive that can hang, raise, or answer
something that is not a command. `Guard` makes it with its factory and calls its `observe`; it
turns each way of breaking the protocol into a `ControllerFault` (what was called, at what
simulated time, what it raised or returned, where, and how to fix it) raised as `Faulted`. It
never changes a drive that keeps the protocol: a command is read as exactly the two numbers
returned, and the timer only ever interrupts a controller that has overrun its time.

Time: a controller may take `FLOOR` seconds of wall-clock time plus the simulated time driven so
far (real time: a controller slower than that could not drive the real robot), counted over
its factory and every `observe` of the drive; the simulator's own time is not counted. On POSIX,
in the main thread (where pytest and pytest-xdist's workers run items), a real-time interval
timer (SIGALRM) interrupts a call that overruns, so even a controller that never returns fails
within seconds; elsewhere a call is judged when it returns.
"""

from __future__ import annotations

import inspect
import random
import warnings
from time import perf_counter
from typing import Any

import numpy as np

from pytest_lasertest.model.geometry import Point2D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.protocol import (
    Controller,
    ControllerFactory,
    LaserScan,
    OccupancyGrid,
    Odometry,
)
from pytest_lasertest.sim.alarm import Alarm, TimeUp
from pytest_lasertest.sim.faults import (
    COMMAND,
    ControllerFault,
    Faulted,
    activity_of,
    command_of,
    fault_frames,
    positive_figure,
    raised_fault,
    shown,
)

FLOOR = 5.0  # s of wall-clock time a controller may take beyond the simulated time driven


class ControllerWarning(UserWarning):
    """A controller that keeps the protocol but makes runs differ under one seed."""


class Guard:
    """One drive's controller, made, called and checked; a context manager around the drive,
    which restores the process's SIGALRM handler and timer on exit."""

    def __init__(self, factory: ControllerFactory) -> None:
        self.factory = factory
        self.name = qualified_name(factory)
        self._spent = 0.0  # s of wall-clock time inside the controller
        self._alarm = Alarm()
        self._observe: Any = None
        self._controller: object = None
        self._rng = _global_rng_states()
        self.goal_tolerance: float | None = None  # m, the controller's own, if it has one
        self.control_frequency: float | None = None  # Hz, its own clock's, if it has one
        self.stuck_window: float | None = None  # s, its own patience, if it has one

    def __enter__(self) -> Guard:
        self._alarm.install()
        return self

    def __exit__(self, kind: type[BaseException] | None, *rest: object) -> None:
        self._alarm.remove()
        if kind is None and _global_rng_states() != self._rng:
            self._warn_global_rng()

    def make(self, robot: Robot, route: tuple[Point2D, ...]) -> None:
        """Make the drive's controller; check that it has an `observe` to call."""
        controller: Controller = self._call("the factory", 0.0, self.factory, robot, route)
        observe = self._call("the factory", 0.0, getattr, controller, "observe", None)
        if not callable(observe):
            raise Faulted(
                ControllerFault(
                    "the factory",
                    0.0,
                    f"returned {shown(controller)}, which has no observe method",
                    f"return an object with observe(scan, odometry, time) answering {COMMAND}",
                )
            )
        _check_arity(observe)
        self._observe = observe
        self._controller = controller
        self.goal_tolerance = self._figure(
            "goal_tolerance",
            "metres",
            "the distance (m) at which its goal checker counts the goal reached",
        )
        self.control_frequency = self._figure(
            "control_frequency",
            "hertz",
            "the rate (Hz) its own clocks want to be called at between scans",
        )
        self.stuck_window = self._figure(
            "stuck_window",
            "seconds",
            "how long (s) it may make no progress while still trying, by its own logic",
        )

    def give_map(self, grid: OccupancyGrid) -> None:
        """Give the controller the world's map, if it has a `receive_map` to take it, before
        its first scan: map_server latches /map, and a node has it once it subscribes."""
        receive = self._call("the factory", 0.0, getattr, self._controller, "receive_map", None)
        if receive is not None:
            self._call("receive_map", 0.0, receive, grid)

    def ask(self, name: str, time: float) -> object:
        """What the controller's optional method `name` answers, called at `time` s without
        arguments; None if it has no such method. The caller judges the answer."""
        method = self._call(name, time, getattr, self._controller, name, None)
        return None if method is None else self._call(name, time, method)

    def _figure(self, name: str, unit: str, meaning: str) -> float | None:
        """The controller's optional figure `name`: none, or a positive finite number of
        `unit`; anything else fails the drive, named."""
        value = self._call("the factory", 0.0, getattr, self._controller, name, None)
        return positive_figure(value, name, unit, meaning)

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        """The controller's command for this scan: two finite floats."""
        command = self._call("observe", time, self._observe, scan, odometry, time)
        return command_of(command, time)

    def activity(self, time: float) -> tuple[tuple[float, str], ...]:
        """What the controller says it did, at the end of the drive at `time` s: (s, what)
        pairs, or none if it has no `activity`."""
        value = self._call("activity", time, getattr, self._controller, "activity", None)
        return activity_of(value, time)

    def _call(self, call: str, time: float, function: Any, *arguments: object) -> Any:
        """`function(*arguments)` within the controller's time; what it raises, a fault."""
        limit = FLOOR + time  # s
        started = perf_counter()
        try:
            try:
                self._alarm.arm(limit - self._spent)
                result = function(*arguments)
            finally:
                self._alarm.disarm()
                self._spent += perf_counter() - started
        except TimeUp as stopped:
            self._alarm.disarm()  # again: the interruption may have cut the first one short
            # The cause, with its traceback through the controller, is what --fulltrace shows.
            raise Faulted(self._overran(call, time, limit, stopped)) from stopped
        # The user's code: whatever it raises (even sys.exit) is the drive's fault, named.
        except (Exception, SystemExit) as error:
            raise Faulted(raised_fault(call, time, error)) from error
        # Judged on return as well: a call the timer could not interrupt (no SIGALRM here, or
        # stuck in C code) fails the drive once it is back.
        if self._spent > limit:
            raise Faulted(self._overran(call, time, limit, None))
        return result

    def _overran(
        self, call: str, time: float, limit: float, stopped: BaseException | None
    ) -> ControllerFault:
        taken = f"{self._spent:.1f} s of wall-clock time in this drive"
        allowed = f"{limit:.1f} s by then ({FLOOR:g} s plus the simulated time driven)"
        problem = (
            f"did not return in time: interrupted once the controller had taken {taken}, all "
            f"it may take {allowed}"
            if stopped is not None
            else f"returned too late: the controller had taken {taken}, more than the {allowed}"
        )
        return ControllerFault(
            call,
            time,
            problem,
            "find what blocks or slows it (a sleep, a lock, waiting for input, a loop that "
            "never ends): a controller slower than real time cannot drive the real robot",
            fault_frames(stopped) if stopped is not None else (),
        )

    def _warn_global_rng(self) -> None:
        code = getattr(getattr(self._observe, "__func__", self._observe), "__code__", None)
        warnings.warn_explicit(
            f"the controller {self.name} drew from (or reseeded) the global random state of "
            "`random` or `numpy.random` during a drive: its runs then depend on what ran "
            "before (pytest-randomly reseeds it for every test), so one --laser-seed no longer "
            "gives one result. Fix: give the controller a generator of its own, seeded in its "
            "factory: random.Random(0) or numpy.random.default_rng(0)",
            ControllerWarning,
            code.co_filename if code is not None else __file__,
            code.co_firstlineno if code is not None else 1,
            # Where `warnings.warn` keeps what it has shown: once per item under pytest, which
            # resets it for each; its summary then lists the items under the one message.
            registry=globals().setdefault("__warningregistry__", {}),
        )


def qualified_name(factory: object) -> str:
    """`module:qualname` of a factory, for messages."""
    module = getattr(factory, "__module__", None)
    name = getattr(factory, "__qualname__", None)
    return f"{module}:{name}" if module and name else shown(factory)


def _check_arity(observe: Any) -> None:
    """A fault if `observe` cannot be called with (scan, odometry, time)."""
    try:
        signature = inspect.signature(observe)
    except (TypeError, ValueError):
        return  # no signature to read (C code): its first call says what is wrong
    try:
        signature.bind(None, None, 0.0)
    except TypeError as error:
        raise Faulted(
            ControllerFault(
                "the factory",
                0.0,
                f"returned a controller whose observe cannot be called with (scan, odometry, "
                f"time): {error}",
                f"define observe(self, scan, odometry, time) answering {COMMAND}",
            )
        ) from None


def _global_rng_states() -> tuple[object, ...]:
    """The global random states a drive must leave alone: Python's and numpy's legacy one."""
    state = np.random.get_state(legacy=False)
    assert isinstance(state, dict)
    inner = state["state"]
    return (random.getstate(), inner["key"].tobytes(), inner["pos"], state["has_gauss"])
