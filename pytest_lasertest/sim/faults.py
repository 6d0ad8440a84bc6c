"""A controller's faults, and the checks on its answers that raise them.

A fault says what was called (its factory, `observe`, an optional method), at what simulated
time, what it raised or returned, where in the controller's code, and how to fix it; `Faulted`
carries it out of the drive (`guard.py` makes the calls and times them).
"""

from __future__ import annotations

import inspect
import math
import numbers
import reprlib
import traceback
from dataclasses import dataclass
from pathlib import Path

import numpy as np

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


def command_of(command: object, time: float) -> tuple[float, float]:
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


def raised_fault(call: str, time: float, error: BaseException) -> ControllerFault:
    if isinstance(error, SystemExit):
        problem = f"called sys.exit({error.code!r}), which would end the test run"
        fix = "raise an exception, or return (0.0, 0.0) to stand still, instead of exiting"
    else:
        problem = f"raised {_one_line(error)}"
        fix = "fix the controller where it raised (pytest --fulltrace shows the traceback)"
    return ControllerFault(call, time, problem, fix, fault_frames(error))


def fault_frames(error: BaseException) -> tuple[Frame, ...]:
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


def activity_of(value: object, time: float) -> tuple[tuple[float, str], ...]:
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


def positive_figure(value: object, name: str, unit: str, meaning: str) -> float | None:
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
