"""Hostile controllers: a `controller:` that hangs, raises, answers NaN or something that is not
a command, exits, or draws from the global random state. Each is a short failure naming the
controller and what it did (or, where the factory shows it, a collection error at the
`controller:` line), never a traceback through pytest's insides, a hang or a silent pass."""

from __future__ import annotations

import signal
import time
from collections.abc import Iterator
from dataclasses import dataclass

import pytest

from tests.helpers.runs import Case, assert_one_clean_error, junit_cases
from tests.helpers.texts import SIZE_PAIR

CONTROLLER_LINE = 6  # where `gate` writes `controller:` into SIZE_PAIR
OBSERVE_LINE = 11  # the line of `observe`'s body in a module `controller_module` writes
# What a traceback through pytest, pluggy or the simulator would show.
NO_TRACEBACK = ("*Traceback*", "*/_pytest/*", "*/pluggy/*", "*pytest_lasertest/*.py*")


def controller_module(body: str, factory: str = "") -> str:
    """A module `Controller` whose observe runs `body` (on line OBSERVE_LINE), and `factory`."""
    return f"""\
import json
import math
import sys


class Controller:
    def __init__(self, robot, route):
        pass

    def observe(self, scan, odometry, time):
        {body}
{factory}"""


# These controllers stand still, or nearly: both robots fail, which the candidate policy fails.
STRICT = "--laser-policy=candidate"


def gate(pytester: pytest.Pytester, source: str, factory: str = "ctl:Controller") -> None:
    """`ctl.py` holding `source`, and a pairs file whose robots drive with `factory` from it."""
    (pytester.path / "ctl.py").write_text(source)
    (pytester.path / "gate.lasertest.yaml").write_text(
        SIZE_PAIR.replace("time_limit: 60.0", f"time_limit: 12.0\ncontroller: {factory}")
    )


def assert_no_traceback(result: pytest.RunResult) -> None:
    for pattern in NO_TRACEBACK:
        result.stdout.no_fnmatch_line(pattern)


@dataclass(frozen=True)
class Broken:
    """A controller that breaks the drive, and the lines its item's report must show."""

    body: str
    lines: tuple[str, ...]
    factory: str = ""
    name: str = "ctl:Controller"


AT_OBSERVE = f"  at         ctl.py:{OBSERVE_LINE} in observe"
NOT_A_COMMAND = "not (forward speed m/s, turn rate rad/s)"
BROKEN = {
    "observe raises": Broken(
        'return {}["speed"], 0.0',
        ("*observe at t = 0.00 s raised KeyError: 'speed'", AT_OBSERVE),
    ),
    "observe raises in a library it calls": Broken(
        'return json.loads("{"), 0.0',
        (
            "*observe at t = 0.00 s raised JSONDecodeError: Expecting property name*",
            AT_OBSERVE,
            "  inside     */json/decoder.py:* in raw_decode",
        ),
    ),
    "observe answers NaN": Broken(
        "return math.nan, 0.0",
        ("*observe at t = 0.00 s returned (nan, 0.0): the forward speed is not finite",),
    ),
    "observe answers infinity": Broken(
        "return 0.5, -math.inf",
        ("*observe at t = 0.00 s returned (0.5, -inf): the turn rate is not finite",),
    ),
    "observe answers None": Broken(
        "pass", (f"*observe at t = 0.00 s returned None, {NOT_A_COMMAND}",)
    ),
    "observe answers a string": Broken(
        'return "go"', (f"*observe at t = 0.00 s returned 'go', {NOT_A_COMMAND}",)
    ),
    "observe answers three numbers": Broken(
        "return 0.5, 0.0, 0.0",
        (f"*observe at t = 0.00 s returned (0.5, 0.0, 0.0), {NOT_A_COMMAND}",),
    ),
    "observe answers a bool": Broken(
        "return True, 0.0", (f"*observe at t = 0.00 s returned (True, 0.0), {NOT_A_COMMAND}",)
    ),
    "observe yields": Broken(
        "yield 0.5, 0.0",
        (
            f"*observe at t = 0.00 s returned a generator, {NOT_A_COMMAND}",
            "  fix        *observe must return its command, not yield it",
        ),
    ),
    "observe calls sys.exit": Broken(
        "sys.exit(3)",
        ("*observe at t = 0.00 s called sys.exit(3), which would end the test run", AT_OBSERVE),
    ),
    "the factory raises": Broken(
        "return 0.0, 0.0",
        ("*the factory raised RuntimeError: no map loaded", "  at         ctl.py:15 in make"),
        '\n\ndef make(robot, route):\n    raise RuntimeError("no map loaded")\n',
        "ctl:make",
    ),
    "the factory returns no controller": Broken(
        "return 0.0, 0.0",
        ("*the factory returned None, which has no observe method",),
        "\n\ndef make(robot, route):\n    return None\n",
        "ctl:make",
    ),
    "the factory's controller takes too few arguments": Broken(
        "return 0.0, 0.0",
        (
            "*the factory returned a controller whose observe cannot be called with (scan, "
            "odometry, time): too many positional arguments",
        ),
        "\n\nclass Short:\n    def observe(self, scan, odometry):\n        return 0.0, 0.0\n"
        "\n\ndef make(robot, route):\n    return Short()\n",
        "ctl:make",
    ),
}


@pytest.mark.parametrize("case", BROKEN.values(), ids=BROKEN.keys())
def test_a_controller_that_breaks_the_drive_fails_its_item_saying_what_it_did_and_where(
    pytester: pytest.Pytester, case: Broken
) -> None:
    gate(pytester, controller_module(case.body, case.factory), case.name)
    result = pytester.runpytest("-m", "control", STRICT)
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(
        [
            "the controller broke the drive: *",
            "  pair       size (gate.lasertest.yaml:*)",
            f"  controller {case.name} (from gate.lasertest.yaml:{CONTROLLER_LINE})",
            "  drive      the baseline robot (clearpath_lms1xx_gazebo), without any obstacle",
        ]
    )
    result.stdout.fnmatch_lines(list(case.lines))
    result.stdout.fnmatch_lines(["  fix        *", "  replay     pytest *"])
    assert_no_traceback(result)


def test_a_broken_controller_fails_every_item_of_its_pair_briefly_and_is_driven_once(
    pytester: pytest.Pytester,
) -> None:
    factory = (
        '\n\ndef make(robot, route):\n    open("made", "a").write("x")\n'
        "    return Controller(robot, route)\n"
    )
    gate(pytester, controller_module("return 1 / 0", factory), "ctl:make")
    result = pytester.runpytest("-m", "not coverage", "--laser-profile=dev")
    result.assert_outcomes(failed=4)  # no-obstacle, avoid-0 and one witness per direction
    headline = "the controller broke the drive: observe at t = 0.00 s raised ZeroDivisionError*"
    assert len([line for line in result.stdout.lines if line.startswith(headline[:-1])]) == 4
    assert_no_traceback(result)
    # The reports, before the summary (which CI=true prints untruncated): about a dozen lines each.
    reports = result.stdout.str().split("short test summary info")[0].splitlines()
    assert len(reports) < 70
    assert (pytester.path / "made").read_text() == "x"


def test_full_trace_shows_the_controller_s_traceback(pytester: pytest.Pytester) -> None:
    gate(pytester, controller_module("return 1 / 0"))
    result = pytester.runpytest("-m", "control", "--fulltrace")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines([f"ctl.py:{OBSERVE_LINE}: ZeroDivisionError"])


@pytest.fixture
def outer_timer() -> Iterator[list[int]]:
    """A SIGALRM handler and a 100 s timer of the test's own, as pytest-timeout sets them;
    restored afterwards. The list records the signals the handler was given."""
    rung: list[int] = []
    previous = signal.signal(signal.SIGALRM, lambda signum, frame: rung.append(signum))
    signal.setitimer(signal.ITIMER_REAL, 100.0)
    try:
        yield rung
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, previous)


def test_a_controller_that_never_returns_fails_its_item_within_seconds_leaving_timers_alone(
    pytester: pytest.Pytester, outer_timer: list[int]
) -> None:
    handler = signal.getsignal(signal.SIGALRM)
    gate(pytester, controller_module("__import__('time').sleep(3600)"))
    started = time.monotonic()
    result = pytester.runpytest("-m", "control", STRICT)
    assert time.monotonic() - started < 30.0
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(
        [
            "the controller broke the drive: observe at t = 0.00 s did not return in time: "
            "interrupted once the controller had taken 5.0 s of wall-clock time in this drive, "
            "all it may take 5.0 s by then (5 s plus the simulated time driven)",
            AT_OBSERVE,
            "  fix        find what blocks or slows it (a sleep, a lock, waiting for input, a "
            "loop that never ends): a controller slower than real time cannot drive the real "
            "robot",
        ]
    )
    assert_no_traceback(result)
    # The test's own handler is back, its timer still running toward its own deadline.
    assert signal.getsignal(signal.SIGALRM) is handler
    remaining, _ = signal.getitimer(signal.ITIMER_REAL)
    assert 60.0 < remaining < 100.0
    assert outer_timer == []


def test_a_controller_that_never_returns_fails_its_item_on_an_xdist_worker_too(
    pytester: pytest.Pytester,
) -> None:
    gate(pytester, controller_module("__import__('time').sleep(3600)"))
    result = pytester.runpytest_subprocess("-n", "1", "-m", "control")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["*observe at t = 0.00 s did not return in time*", AT_OBSERVE])


BAD_FACTORIES = {
    "a builtin": (
        "builtins:print",
        "builtins:print comes from Python's standard library (module 'builtins'), which makes "
        "no controller",
    ),
    "a standard-library function": (
        "os.path:join",
        "os.path:join comes from Python's standard library (module 'posixpath')",
    ),
    "a standard-library class": (
        "subprocess:Popen",
        "subprocess:Popen comes from Python's standard library (module 'subprocess')",
    ),
    "a class without observe": ("ctl:Empty", "ctl:Empty is a class without an observe method"),
    "a class whose observe takes too few arguments": (
        "ctl:Short",
        "ctl:Short.observe cannot be called with (scan, odometry, time): too many positional "
        "arguments",
    ),
    "a class whose observe is a number": (
        "ctl:Number",
        "ctl:Number.observe is a float (0.5), not a method",
    ),
}
ODD_CLASSES = """\
class Empty:
    def __init__(self, robot, route):
        pass


class Short(Empty):
    def observe(self, scan):
        return 0.0, 0.0


class Number(Empty):
    observe = 0.5
"""


@pytest.mark.parametrize(("factory", "problem"), BAD_FACTORIES.values(), ids=BAD_FACTORIES.keys())
def test_a_factory_that_cannot_make_a_controller_is_a_collection_error_at_its_line(
    pytester: pytest.Pytester, factory: str, problem: str
) -> None:
    gate(pytester, ODD_CLASSES, factory)
    result = pytester.runpytest()
    error = Case("", "", CONTROLLER_LINE, "controller", problem, "observe(")
    assert_one_clean_error(result, CONTROLLER_LINE, "controller", error)


HOOKED = {
    "print from the standard library": (
        "import builtins\nFACTORY = builtins.print",
        "the pytest_lasertest_make_controller hook's factory builtins:print comes from Python's "
        "standard library (module 'builtins'), which makes no controller",
    ),
    "a class whose observe takes too little": (
        f"{ODD_CLASSES}\nFACTORY = Short",
        "the pytest_lasertest_make_controller hook's factory conftest:Short.observe cannot be "
        "called with (scan, odometry, time): too many positional arguments",
    ),
}


@pytest.mark.parametrize(("source", "problem"), HOOKED.values(), ids=HOOKED.keys())
def test_a_factory_a_conftest_hook_returns_is_checked_as_a_controller_line_is(
    pytester: pytest.Pytester, source: str, problem: str
) -> None:
    hook = "\n\ndef pytest_lasertest_make_controller(config, spec):\n    return FACTORY\n"
    pytester.makeconftest(source + hook)
    (pytester.path / "gate.lasertest.yaml").write_text(SIZE_PAIR)
    result = pytester.runpytest()
    assert_one_clean_error(result, 1, "controller", Case("", "", 1, "controller", problem, ""))


UNUSUAL_BUT_VALID = """\
import functools


class Static:
    def __init__(self, robot, route):
        pass

    @staticmethod
    def observe(scan, odometry, time):
        return 0.0, 0.0


class Delegating:
    def __init__(self, robot, route):
        self.inner = Static(robot, route)

    def __getattr__(self, name):
        return getattr(self.inner, name)


def configured(gain, robot, route):
    return Static(robot, route)


partial = functools.partial(configured, 0.5)
"""


@pytest.mark.parametrize("factory", ["ctl:Static", "ctl:Delegating", "ctl:partial"])
def test_unusual_factories_that_can_make_a_controller_are_collected(
    pytester: pytest.Pytester, factory: str
) -> None:
    gate(pytester, UNUSUAL_BUT_VALID, factory)
    result = pytester.runpytest("-m", "control", STRICT)
    # It stands still: the goal is not reached, and nothing else goes wrong.
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["  baseline   *goal not reached*"])


def test_a_controller_drawing_from_the_global_random_state_is_warned_about_once_per_item(
    pytester: pytest.Pytester,
) -> None:
    gate(pytester, controller_module("return __import__('random').uniform(0, 1), 0.0"))
    result = pytester.runpytest("-m", "control", STRICT)
    result.stdout.fnmatch_lines(
        [
            "*warnings summary*",
            "gate.lasertest.yaml::size[[]no-obstacle[]]",
            # At the line observe is defined on.
            f"  */ctl.py:{OBSERVE_LINE - 1}: ControllerWarning: the controller ctl:Controller drew "
            "from "
            "(or reseeded) the global random state of `random` or `numpy.random` during a drive*"
            "Fix: give the controller a generator of its own, seeded in its factory: "
            "random.Random(0) or numpy.random.default_rng(0)",
        ]
    )
    result.stdout.fnmatch_lines(["*1 warning*"])


def test_a_controller_with_a_generator_of_its_own_is_not_warned_about(
    pytester: pytest.Pytester,
) -> None:
    gate(pytester, controller_module("return __import__('random').Random(0).uniform(0, 1), 0.0"))
    result = pytester.runpytest("-m", "control", STRICT)
    result.stdout.no_fnmatch_line("*ControllerWarning*")


COMMANDS = {
    "plain": "0.5, 0.2",
    "array": "numpy.array([0.5, 0.2])",
    "scalars": "numpy.float64(0.5), numpy.int64(0) + 0.2",
    "list": "[0.5, 0.2]",
}


def test_a_command_of_numpy_numbers_or_a_list_drives_exactly_as_the_same_floats(
    pytester: pytest.Pytester,
) -> None:
    for name, command in COMMANDS.items():
        source = "import numpy\n" + controller_module(f"return {command}")
        (pytester.path / f"{name}_ctl.py").write_text(source)
        (pytester.path / f"{name}.lasertest.yaml").write_text(
            SIZE_PAIR.replace(
                "time_limit: 60.0", f"time_limit: 12.0\ncontroller: {name}_ctl:Controller"
            )
        )
    # None reaches the goal, all drive; the candidate policy fails what both robots share.
    result = pytester.runpytest("-m", "control", "--junitxml=out.xml", "--laser-policy=candidate")
    result.assert_outcomes(failed=len(COMMANDS))
    cases = junit_cases(pytester.path / "out.xml")
    digests = {
        cases[f"{name}.lasertest.yaml::size[no-obstacle]"].properties[
            "lasertest.baseline.trajectory"
        ]
        for name in COMMANDS
    }
    assert len(digests) == 1


def test_a_controller_that_overwrites_its_scans_in_place_does_not_change_the_next_scan(
    pytester: pytest.Pytester,
) -> None:
    # In the empty world every reading is +inf: a scan that shared an array with the last one
    # (or with the scanner's own) would show the zeros written into it.
    body = (
        "assert not (scan.ranges == 0.0).any(), 'a scan shows the last one'\n"
        "        scan.ranges[:] = 0.0\n"
        "        return 0.0, 0.0"
    )
    gate(pytester, controller_module(body))
    result = pytester.runpytest("-m", "control", STRICT)
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["  baseline   *goal not reached*"])
    result.stdout.no_fnmatch_line("*the controller broke the drive*")
