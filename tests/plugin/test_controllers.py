"""Custom controllers: `controller:` in a pairs file (a module next to it, or a name registered in
the `lasertest.controllers` entry-point group), and the `pytest_lasertest_make_controller` hook."""

from __future__ import annotations

from dataclasses import dataclass, field

import pytest

from pytest_lasertest.reports.drive import controller_line
from tests.helpers.runs import Case, assert_one_clean_error, controllers
from tests.helpers.texts import GOOD_PAIRS, SIZE_PAIR

# A controller that never moves: the control item fails with "goal not reached", which shows
# that it, and not the default, drove.
STAND_STILL = """\
class StandStill:
    def __init__(self, robot, route):
        pass

    def observe(self, scan, odometry, time):
        return 0.0, 0.0
"""
STILL_MODULE = f"""\
SPEED = 0.5


def make_with_settings(settings):
    return None


{STAND_STILL}"""
CONTROLLER_LINE = 5  # the line `controller:` is appended on, below GOOD_PAIRS
HOOK = "pytest_lasertest_make_controller"


@dataclass(frozen=True)
class BadController:
    """A `controller:` value, the modules beside the pairs file, and the error it must give."""

    value: str
    problem: str
    fix: str
    files: dict[str, str] = field(default_factory=lambda: {"still.py": STILL_MODULE})


BAD_CONTROLLERS = {
    "a number": BadController(
        "3",
        "expected `module:attribute` or the name of a registered controller, got 3",
        "write e.g. `controller: my_controller:make_controller`, "
        "or a registered name (move_base, nav2, reactive)",
    ),
    "a mapping": BadController(
        "{module: still}",
        "expected `module:attribute` or the name of a registered controller, got a mapping",
        "or a registered name (move_base, nav2, reactive)",
    ),
    "neither form": BadController(
        "reactiv",
        "'reactiv' is neither `module:attribute` nor a controller registered in the entry-point "
        "group lasertest.controllers",
        "did you mean 'reactive'? registered controllers: move_base, nav2, reactive; "
        "or name a factory",
    ),
    "a colon without a factory": BadController(
        "'still:'",
        "'still:' is not `module:attribute`",
        "e.g. `my_controller:make_controller`",
    ),
    "a misspelt module": BadController(
        "stil:StandStill",
        "no module 'stil': looked for stil.py and stil/__init__.py next to this file, then on "
        "sys.path",
        "did you mean 'still'? put stil.py next to the pairs file, or install the package",
    ),
    "a module that raises on import": BadController(
        "calibrated:make",
        "importing 'calibrated' raises RuntimeError: no calibration for this robot",
        "fix the module, or what it imports, until it imports cleanly",
        {"calibrated.py": 'raise RuntimeError("no calibration for this robot\\nsee the wiki")\n'},
    ),
    "a module whose own import is missing": BadController(
        "planner:make",
        "importing 'planner' raises ModuleNotFoundError: No module named 'not_installed_planner'",
        "fix the module, or what it imports",
        {"planner.py": "import not_installed_planner\n"},
    ),
    "a module with a syntax error": BadController(
        "typo:make",
        "importing 'typo' raises SyntaxError: ",
        "fix the module",
        {"typo.py": "def make(robot, route)\n    return None\n"},
    ),
    "a misspelt factory": BadController(
        "still:StandStil",
        "module 'still' (still.py) has no attribute 'StandStil'",
        "did you mean 'StandStill'? callables there: StandStill, make_with_settings",
    ),
    "a factory that is not callable": BadController(
        "still:SPEED",
        "still:SPEED is a float (0.5), not a callable",
        "name a callable that takes (robot, route) and returns an object with observe(",
    ),
    "a factory that takes other arguments": BadController(
        "still:make_with_settings",
        "still:make_with_settings cannot be called with (robot, route): too many positional",
        "name a callable that takes (robot, route)",
    ),
}


@pytest.mark.parametrize("case", BAD_CONTROLLERS.values(), ids=BAD_CONTROLLERS.keys())
def test_a_bad_controller_is_one_collection_error_naming_the_line_what_is_wrong_and_the_fix(
    pytester: pytest.Pytester, case: BadController
) -> None:
    for name, source in case.files.items():
        (pytester.path / name).write_text(source)
    (pytester.path / "gate.lasertest.yaml").write_text(f"{GOOD_PAIRS}controller: {case.value}\n")
    result = pytester.runpytest()
    error = Case("", "", CONTROLLER_LINE, "controller", case.problem, case.fix)
    assert_one_clean_error(result, CONTROLLER_LINE, "controller", error)


def run_control(pytester: pytest.Pytester, *arguments: str) -> pytest.RunResult:
    """The control items alone, recorded in JUnit XML as out.xml."""
    # The candidate policy fails a failure both robots share: a standing robot fails both.
    policy = "--laser-policy=candidate"
    return pytester.runpytest("-k", "no-obstacle", "--junitxml=out.xml", policy, *arguments)


@pytest.mark.parametrize(
    ("files", "value"),
    [
        ({"still.py": STILL_MODULE}, "still:StandStill"),
        ({"team/__init__.py": "", "team/still.py": STAND_STILL}, "team.still:StandStill"),
    ],
    ids=["module", "package"],
)
def test_a_controller_module_next_to_the_pairs_file_drives_both_robots(
    pytester: pytest.Pytester, files: dict[str, str], value: str
) -> None:
    pytester.mkdir("robots")
    for name, source in files.items():
        (pytester.path / "robots" / name).parent.mkdir(exist_ok=True)
        (pytester.path / "robots" / name).write_text(source)
    pairs = pytester.path / "robots" / "gate.lasertest.yaml"
    pairs.write_text(
        SIZE_PAIR.replace("time_limit: 60.0", f"time_limit: 12.0\ncontroller: {value}")
    )
    result = run_control(pytester)
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(
        [
            f"  controller {value} (from robots/gate.lasertest.yaml:6)",
            "  baseline   clearpath_lms1xx_gazebo: FAILED: *goal not reached*",
            "  candidate  clearpath_lms1xx_gazebo: FAILED: *goal not reached*",
        ]
    )
    assert controllers(pytester) == {"robots.gate.lasertest.yaml::size[no-obstacle]": value}


def test_every_xdist_worker_imports_the_controller_next_to_the_pairs_file(
    pytester: pytest.Pytester,
) -> None:
    (pytester.path / "still.py").write_text(STILL_MODULE)
    (pytester.path / "gate.lasertest.yaml").write_text(
        SIZE_PAIR.replace("time_limit: 60.0", "time_limit: 12.0\ncontroller: still:StandStill")
    )
    result = pytester.runpytest_subprocess(
        "-n", "2", "-m", "control or coverage", "--laser-policy=candidate"
    )
    result.assert_outcomes(failed=2)
    result.stdout.fnmatch_lines(["  controller still:StandStill (from gate.lasertest.yaml:6)"])


def test_a_conftest_hook_drives_the_pairs_files_below_it_and_none_returned_leaves_the_default(
    pytester: pytest.Pytester,
) -> None:
    # The top conftest answers None; the one in stood/ answers StandStill for its pairs file.
    pytester.makeconftest(f"def {HOOK}(config, spec):\n    return None\n")
    pytester.mkdir("stood")
    (pytester.path / "stood" / "conftest.py").write_text(
        f"{STAND_STILL}\n\ndef {HOOK}(config, spec):\n    return StandStill\n"
    )
    short = SIZE_PAIR.replace("time_limit: 60.0", "time_limit: 20.0")
    (pytester.path / "stood" / "gate.lasertest.yaml").write_text(short)
    (pytester.path / "gate.lasertest.yaml").write_text(short)
    result = run_control(pytester)
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(
        [f"  controller conftest:StandStill (from the {HOOK} hook)", "*goal not reached*"]
    )
    assert controllers(pytester) == {
        "gate.lasertest.yaml::size[no-obstacle]": "nav2",
        "stood.gate.lasertest.yaml::size[no-obstacle]": "conftest:StandStill",
    }


def test_the_pairs_file_s_controller_wins_over_the_hook(pytester: pytest.Pytester) -> None:
    pytester.makeconftest(f"{STAND_STILL}\n\ndef {HOOK}(config, spec):\n    return StandStill\n")
    (pytester.path / "gate.lasertest.yaml").write_text(
        SIZE_PAIR.replace("time_limit: 60.0", "time_limit: 20.0\ncontroller: reactive")
    )
    run_control(pytester).assert_outcomes(passed=1)
    assert controllers(pytester) == {"gate.lasertest.yaml::size[no-obstacle]": "reactive"}


def test_a_hook_that_returns_no_factory_is_a_collection_error(pytester: pytest.Pytester) -> None:
    pytester.makeconftest(f"def {HOOK}(config, spec):\n    return 0.5\n")
    (pytester.path / "gate.lasertest.yaml").write_text(GOOD_PAIRS)
    result = pytester.runpytest()
    error = Case(
        "",
        "",
        1,
        "controller",
        f"the {HOOK} hook (in a conftest.py or plugin) returned 0.5, not a controller factory",
        "return a callable that takes (robot, route) and returns a controller, or None",
    )
    assert_one_clean_error(result, 1, "controller", error)


def register(pytester: pytest.Pytester, name: str, target: str, module: str) -> None:
    """Install, on the run's sys.path, a distribution that registers `name` -> `target` in the
    `lasertest.controllers` entry-point group, with `module` as its code."""
    info = pytester.mkdir("team_controllers-1.0.dist-info")
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: team-controllers\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text(f"[lasertest.controllers]\n{name} = {target}\n")
    (pytester.path / f"{target.split(':')[0]}.py").write_text(module)
    pytester.syspathinsert()


def test_a_controller_another_package_registers_is_named_by_its_entry_point_name(
    pytester: pytest.Pytester,
) -> None:
    register(pytester, "stand_still", "team_still:StandStill", STAND_STILL)
    (pytester.path / "gate.lasertest.yaml").write_text(
        SIZE_PAIR.replace("time_limit: 60.0", "time_limit: 12.0\ncontroller: stand_still")
    )
    result = run_control(pytester)
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["  controller stand_still (from gate.lasertest.yaml:6)"])


def test_a_registered_controller_that_raises_on_import_is_a_collection_error(
    pytester: pytest.Pytester,
) -> None:
    register(pytester, "broken", "team_broken:make", "raise ImportError('needs ROS 2')\n")
    (pytester.path / "gate.lasertest.yaml").write_text(f"{GOOD_PAIRS}controller: broken\n")
    result = pytester.runpytest()
    error = Case(
        "",
        "",
        CONTROLLER_LINE,
        "controller",
        "the controller 'broken' (team_broken:make) raises on import: ImportError: needs ROS 2",
        "fix or reinstall the package that registers it (team-controllers)",
    )
    assert_one_clean_error(result, CONTROLLER_LINE, "controller", error)


def test_the_items_of_a_pairs_file_with_scan_filters_drive_behind_its_chain(
    pytester: pytest.Pytester,
) -> None:
    (pytester.path / "filters.yaml").write_text(
        "scan_filter_chain:\n- {name: range, type: laser_filters/LaserScanRangeFilter}\n"
    )
    pairs = GOOD_PAIRS + "controller: move_base\nnavigation: {scan_filters: filters.yaml}\n"
    (pytester.path / "gate.lasertest.yaml").write_text(pairs)
    items, _ = pytester.inline_genitems("gate.lasertest.yaml")
    driving = [item for item in items if hasattr(item, "controller")]
    assert driving  # the control item and the placement items
    for item in driving:
        controller = getattr(item, "controller")  # noqa: B009  (the item's own)
        assert controller.name == "move_base"
        assert controller.scan_filters is not None
        assert controller_line(controller).endswith(": scan filters: filters.yaml (1 filter)")
