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
import math
import numbers
import random
import reprlib
import traceback
import warnings
from dataclasses import dataclass
from pathlib import Path
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

FLOOR = 5.0  # s of wall-clock time a controller may take beyond the simulated time driven
COMMAND = "(forward speed m/s, turn rate rad/s)"
_HERE = Path(__file__).parent  # the simulator's own frames are left out of a fault's lines


@dataclass(frozen=True)
class Frame:
    """A line of the controller's code that a fault passed through."""

    path: str
    line: int
    function: str


@dataclass(frozen=True)
class ControllerFault:
    """How a controller broke the protocol in one drive."""

    call: str  # what was called: "the factory" or "observe"
    time: float  # s, the simulated time of the call
    problem: str  # what it raised or returned
    fix: str
    # The controller's own call, then the line that raised (or was interrupted), if different.
    frames: tuple[Frame, ...] = ()

    def describe(self) -> str:
        """`observe at t = 2.14 s returned None, ...`; the factory, without a time."""
        when = f" at t = {self.time:.2f} s" if self.call == "observe" else ""
        return f"{self.call}{when} {self.problem}"


class Faulted(BaseException):
    """A drive the controller broke. Not an `Exception`: nothing between the drive and the
    item (the search's Hypothesis, which would shrink an ordinary exception as a failure and
    drive it again many times) may take it for anything else."""

    def __init__(self, fault: ControllerFault) -> None:
        super().__init__(fault.describe())
        self.fault = fault


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
        return _positive(value, name, unit, meaning)

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        """The controller's command for this scan: two finite floats."""
        command = self._call("observe", time, self._observe, scan, odometry, time)
        return _command(command, time)

    def activity(self, time: float) -> tuple[tuple[float, str], ...]:
        """What the controller says it did, at the end of the drive at `time` s: (s, what)
        pairs, or none if it has no `activity`."""
        value = self._call("activity", time, getattr, self._controller, "activity", None)
        return _activity(value, time)

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
            raise Faulted(_raised(call, time, error)) from error
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
            _frames(stopped) if stopped is not None else (),
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


def _command(command: object, time: float) -> tuple[float, float]:
    """The command as two floats, exactly the numbers returned; a fault unless it is a tuple,
    list or array of two finite real numbers."""
    numbers = _two_numbers(command)
    if numbers is None:
        fix = f"return a tuple of two numbers {COMMAND}"
        if inspect.isgenerator(command):
            fix += ": observe must return its command, not yield it"
        problem = f"returned {shown(command)}, not {COMMAND}"
        raise Faulted(ControllerFault("observe", time, problem, fix))
    names = ("forward speed", "turn rate")
    bad = [name for name, value in zip(names, numbers, strict=True) if not math.isfinite(value)]
    if bad:
        raise Faulted(
            ControllerFault(
                "observe",
                time,
                f"returned {shown(command)}: {_not_finite(bad)}",
                "return finite numbers (to stand still, (0.0, 0.0)); a speed beyond the robot's "
                "limits is cut to them, but NaN and infinity are refused, as the Husky's "
                "diff_drive_controller ignores such a command",
            )
        )
    return numbers


def _not_finite(names: list[str]) -> str:
    """`the forward speed is not finite`, or both."""
    return f"the {' and the '.join(names)} {'is' if len(names) == 1 else 'are'} not finite"


def _two_numbers(command: object) -> tuple[float, float] | None:
    if isinstance(command, np.ndarray):
        if command.shape != (2,) or command.dtype.kind not in "iuf":
            return None
        return float(command[0]), float(command[1])
    if not isinstance(command, tuple | list) or len(command) != 2:
        return None
    first, second = command
    if not (_is_real(first) and _is_real(second)):
        return None
    return float(first), float(second)


def _is_real(value: object) -> bool:
    """An int, float or numpy integer or floating scalar; not a bool (True is no speed)."""
    return isinstance(value, int | float | np.integer | np.floating) and not isinstance(value, bool)


def _raised(call: str, time: float, error: BaseException) -> ControllerFault:
    if isinstance(error, SystemExit):
        problem = f"called sys.exit({error.code!r}), which would end the test run"
        fix = "raise an exception, or return (0.0, 0.0) to stand still, instead of exiting"
    else:
        problem = f"raised {_one_line(error)}"
        fix = "fix the controller where it raised (pytest --fulltrace shows the traceback)"
    return ControllerFault(call, time, problem, fix, _frames(error))


def _frames(error: BaseException) -> tuple[Frame, ...]:
    """The controller's own call and the line that raised, leaving out the simulator's frames."""
    stack = [
        Frame(summary.filename, summary.lineno or 0, summary.name)
        for summary in traceback.extract_tb(error.__traceback__)
        if Path(summary.filename).parent != _HERE
    ]
    if not stack:
        return ()
    return (stack[0],) if stack[0] == stack[-1] else (stack[0], stack[-1])


def _one_line(error: BaseException) -> str:
    """The exception's type and the first line of its message."""
    try:
        lines = str(error).strip().splitlines()
    except Exception:  # noqa: BLE001  (a message that cannot be written must not hide the error)
        lines = []
    return f"{type(error).__name__}: {lines[0]}" if lines else type(error).__name__


def shown(value: object) -> str:
    """A short repr of what the controller gave, whatever it is."""
    if inspect.isgenerator(value):
        return "a generator"
    short = reprlib.Repr()  # Python 3.11's takes its limits as attributes only
    short.maxstring = short.maxother = 40
    short.maxlist = short.maxtuple = 4
    try:
        return short.repr(value)
    except Exception:  # noqa: BLE001  (a repr that raises must not hide the fault)
        return f"a {type(value).__name__}"


def _global_rng_states() -> tuple[object, ...]:
    """The global random states a drive must leave alone: Python's and numpy's legacy one."""
    state = np.random.get_state(legacy=False)
    assert isinstance(state, dict)
    inner = state["state"]
    return (random.getstate(), inner["key"].tobytes(), inner["pos"], state["has_gauss"])


def _activity(value: object, time: float) -> tuple[tuple[float, str], ...]:
    """A controller's activity: none, or (finite time s, text) pairs."""
    if value is None:
        return ()
    pairs = list(value) if isinstance(value, list | tuple) else None
    if pairs is None or not all(_is_event(pair) for pair in pairs):
        raise Faulted(
            ControllerFault(
                "activity",
                time,
                f"is {shown(value)}, not a list of (time in s, text) pairs",
                "make activity a list of (time, what) pairs, e.g. [(12.5, 'Spin')], or leave "
                "it out",
            )
        )
    return tuple((float(when), str(what)) for when, what in pairs)


def _is_event(pair: object) -> bool:
    if not (isinstance(pair, tuple | list) and len(pair) == 2):
        return False
    when, what = pair
    number = isinstance(when, numbers.Real) and not isinstance(when, bool)
    return number and math.isfinite(float(when)) and isinstance(what, str)


def _positive(value: object, name: str, unit: str, meaning: str) -> float | None:
    """An optional figure of a controller's: none, or a positive finite number."""
    if value is None:
        return None
    figure = (
        float(value) if isinstance(value, numbers.Real) and not isinstance(value, bool) else 0.0
    )
    if not 0.0 < figure < math.inf:
        raise Faulted(
            ControllerFault(
                "the factory",
                0.0,
                f"returned a controller whose {name} is {shown(value)}, not a positive number "
                f"of {unit}",
                f"set {name} to {meaning}, or leave it out",
            )
        )
    return figure
