"""Bad pairs files become one collection error naming file, line and field, with a fix."""

from __future__ import annotations

import pytest

from tests.helpers.runs import Case, assert_one_clean_error
from tests.helpers.texts import GOOD_PAIRS, MY_ROBOT, VALID_PAIRS

CASES = {
    "malformed YAML": Case(
        "yaw: 0.0}",
        "yaw: 0.0",
        4,
        "",
        "this is not valid YAML: expected ',' or '}', but got ':' (while parsing a flow mapping "
        "that starts on line 3)",
        "check the indentation",
    ),
    "a tab in the indentation": Case(
        "  goal:", "\tgoal:", 4, "", "found character '\\t' that cannot start any token", "spaces"
    ),
    "a pair name of 5,000 characters": Case(
        "  to_lms111:",
        "  " + "to_lms111" * 556 + ":",
        11,
        "",
        "the key on this line is 5,004 characters long: YAML reads a key of at most 1,024",
        "give it a shorter name",
    ),
    "a misspelt key": Case(
        "samples: 720",
        "sampels: 720",
        13,
        "pairs.to_lms111.baseline.sampels",
        "unknown key 'sampels'",
        "did you mean 'samples'?",
    ),
    "a key from the LMS1xx xacro": Case(
        "samples: 720",
        "sample_size: 720",
        13,
        "pairs.to_lms111.baseline.sample_size",
        "unknown key 'sample_size'",
        "write `samples`",
    ),
    "a misspelt section": Case(
        "settings:", "setings:", 6, "setings", "unknown key 'setings'", "did you mean 'settings'?"
    ),
    "text where a number belongs": Case(
        "samples: 720",
        "samples: many",
        13,
        "pairs.to_lms111.baseline.samples",
        "expected a whole number, got the text 'many'",
        "write an integer",
    ),
    "a fraction of a sample": Case(
        "samples: 720",
        "samples: 720.5",
        13,
        "pairs.to_lms111.baseline.samples",
        "expected a whole number, got 720.5",
        "write an integer",
    ),
    "a list where a number belongs": Case(
        "update_rate: 50",
        "update_rate: [50]",
        17,
        "pairs.to_lms111.baseline.update_rate",
        "expected a number in Hz, got a list",
        "write a number in Hz",
    ),
    "a yes/no where a number belongs": Case(
        "update_rate: 50",
        "update_rate: yes",
        17,
        "pairs.to_lms111.baseline.update_rate",
        "expected a number in Hz, got true (a yes/no value)",
        "write a number in Hz",
    ),
    "NaN": Case(
        "max_angle: 1.57",
        "max_angle: .nan",
        15,
        "pairs.to_lms111.baseline.max_angle",
        "nan is not a finite number",
        "write a finite number in rad",
    ),
    "infinity": Case(
        "max: 10.0}",
        "max: .inf}",
        16,
        "pairs.to_lms111.baseline.range.max",
        "inf is not a finite number",
        "write a finite number in m",
    ),
    "min_angle not below max_angle": Case(
        "min_angle: -1.57",
        "min_angle: 1.57",
        14,
        "pairs.to_lms111.baseline.min_angle",
        "min_angle (1.57 rad) must be less than max_angle (1.57 rad)",
        "swap them or correct one",
    ),
    "no samples": Case(
        "samples: 720",
        "samples: 0",
        13,
        "pairs.to_lms111.baseline.samples",
        "0 beams cannot scan",
        "set samples to at least 1",
    ),
    "negative samples": Case(
        "samples: 720",
        "samples: -3",
        13,
        "pairs.to_lms111.baseline.samples",
        "-3 beams cannot scan",
        "set samples to at least 1",
    ),
    "range.min not below range.max": Case(
        "{min: 0.1, max: 10.0}",
        "{min: 10.0, max: 10.0}",
        16,
        "pairs.to_lms111.baseline.range.max",
        "range.max (10.0 m) must be greater than range.min (10.0 m)",
        "raise range.max or lower range.min",
    ),
    "a zero update rate": Case(
        "update_rate: 50",
        "update_rate: 0",
        17,
        "pairs.to_lms111.baseline.update_rate",
        "0.0 Hz: a scanner must publish scans at a positive rate",
        "set the scan rate in Hz",
    ),
    "a negative update rate": Case(
        "update_rate: 50",
        "update_rate: -5",
        17,
        "pairs.to_lms111.baseline.update_rate",
        "-5.0 Hz: a scanner must publish scans at a positive rate",
        "set the scan rate in Hz",
    ),
    "an unknown catalogue model": Case(
        "model: sick_lms111",
        "model: sick_lms11",
        19,
        "pairs.to_lms111.candidate.model",
        "unknown scanner model 'sick_lms11'",
        "did you mean 'sick_lms111'",
    ),
    "an override that clashes with the catalogue model": Case(
        "      model: sick_lms111",
        "      model: sick_lms111\n      range: {min: 25.0}",
        18,
        "pairs.to_lms111.candidate.range.max",
        "range.max (20.0 m) must be greater than range.min (25.0 m) (model 'sick_lms111' sets "
        "range.max at ",
        "raise range.max",
    ),
    "a robot file that does not exist": Case(
        "robot: husky",
        "robot: robots/mybot.yaml",
        1,
        "robot",
        "'robots/mybot.yaml' is neither a bundled robot nor a file or directory next to this file",
        "bundled robots: husky",
    ),
    "a misspelt bundled robot": Case(
        "robot: husky", "robot: huskey", 1, "robot", "'huskey' is neither", "did you mean 'husky'?"
    ),
    "duplicate pair names": Case(
        "  same:",
        "  to_lms111:",
        20,
        "pairs.to_lms111",
        "'to_lms111' appears twice here (first on line 11); YAML would silently keep only the last",
        "rename or remove one of them",
    ),
    "a pair name that breaks test ids": Case(
        "  same:",
        "  my pair:",
        20,
        "pairs.my pair",
        "the pair name 'my pair' cannot be part of a test id",
        "use letters, digits",
    ),
    "a pair name YAML reads as a number": Case(
        "  same:",
        "  1:",
        20,
        "pairs",
        "the key 1 is not text (YAML reads it as int)",
        "quote it: '1'",
    ),
    "a missing section": Case(
        "robot: husky\n", "", 1, "robot", "robot is missing", "a pairs file needs robot, world"
    ),
    "both goal and route": Case(
        "  goal: {x: 9.0, y: 0.0}",
        "  goal: {x: 9.0, y: 0.0}\n  route: [{x: 1, y: 1}]",
        5,
        "world.route",
        "both goal and route are given",
        "keep one",
    ),
    "no goal": Case(
        "  goal: {x: 9.0, y: 0.0}\n", "", 2, "world.goal", "goal is missing", "goal: {x: 10.0"
    ),
    "a goal where the robot starts": Case(
        "goal: {x: 9.0, y: 0.0}",
        "goal: {x: 0.0, y: 0.0}",
        4,
        "world.goal",
        "this waypoint (0.0, 0.0) is where the robot already is",
        "remove it",
    ),
    "no time to drive": Case(
        "time_limit: 60.0",
        "time_limit: 0",
        5,
        "world.time_limit",
        "0 s is below 1 s: the robot cannot drive anywhere in less than a second",
        "write a value from 1 to 3600 s",
    ),
    "a constraint that is code": Case(
        '"x > 1"',
        "\"__import__('os').system('true') == 0\"",
        9,
        "constraints[0]",
        "is not allowed",
        "the functions are abs, min, max",
    ),
    "a constraint on an unknown variable": Case(
        '"x > 1"', '"xx > 1"', 9, "constraints[0]", "unknown name `xx`", "did you mean `x`?"
    ),
    "noise other than gaussian": Case(
        "      update_rate: 50",
        "      update_rate: 50\n      noise: {type: uniform, stddev: 0.01}",
        18,
        "pairs.to_lms111.baseline.noise.type",
        "noise type 'uniform' is not modelled",
        "use `type: gaussian`",
    ),
    "a tilted scanner": Case(
        "      update_rate: 50",
        "      update_rate: 50\n      pose: {rpy: [0.0, 0.1, 0.0]}",
        18,
        "pairs.to_lms111.baseline.pose.rpy",
        "the scan plane is tilted by 0.100 rad; the gate models horizontal scans",
        "mount the scanner level",
    ),
    "a non-positive obstacle size": Case(
        "min_obstacle_size: 0.05",
        "min_obstacle_size: 0",
        7,
        "settings.min_obstacle_size",
        "0 m is no obstacle",
        "write a positive width in m",
    ),
    "a largest obstacle smaller than the smallest": Case(
        "min_obstacle_size: 0.05",
        "min_obstacle_size: 0.05\n  max_obstacle_size: 0.01",
        8,
        "settings.max_obstacle_size",
        "max_obstacle_size 0.01 m is below min_obstacle_size 0.05 m",
        "make max_obstacle_size at least as large",
    ),
    "an empty placements list": Case(
        "    candidate: {model: hokuyo_ust_10lx, noise: {stddev: 0.01}}\n",
        "    candidate: {model: hokuyo_ust_10lx, noise: {stddev: 0.01}}\n    placements: []\n",
        23,
        "pairs.same.placements",
        "the placements list is empty",
        "list at least one placement, or remove placements:",
    ),
    "a pinned obstacle of unknown shape": Case(
        "    candidate: {model: hokuyo_ust_10lx, noise: {stddev: 0.01}}\n",
        "    candidate: {model: hokuyo_ust_10lx, noise: {stddev: 0.01}}\n    placements:\n"
        "      - {obstacle: {shape: cone, x: 5, y: 0, radius: 0.1, height: 1}, seed: 0}\n",
        24,
        "pairs.same.placements[0].obstacle.shape",
        "unknown shape 'cone'",
        "write one of: box, cylinder",
    ),
    "no witnesses asked for": Case(
        "min_obstacle_size: 0.05",
        "min_obstacle_size: 0.05\n  witnesses: 0",
        8,
        "settings.witnesses",
        "0 witnesses per direction",
        "write a number from 1 to 20",
    ),
}


@pytest.mark.parametrize("case", CASES.values(), ids=CASES.keys())
def test_a_broken_pairs_file_is_one_collection_error_naming_line_field_and_fix(
    pytester: pytest.Pytester, case: Case
) -> None:
    assert case.old in VALID_PAIRS
    (pytester.path / "gate.lasertest.yaml").write_text(VALID_PAIRS.replace(case.old, case.new, 1))
    result = pytester.runpytest()
    assert_one_clean_error(result, case.line, case.field, case)


@pytest.mark.parametrize("text", ["", "# the pairs come later\n", "---\n"])
def test_an_empty_pairs_file_is_an_error_that_says_what_it_needs(
    pytester: pytest.Pytester, text: str
) -> None:
    (pytester.path / "gate.lasertest.yaml").write_text(text)
    result = pytester.runpytest()
    empty = Case("", "", 1, "", "the pairs file is empty", "it needs robot, world and pairs")
    assert_one_clean_error(result, 1, "", empty)


def test_a_pairs_file_that_is_a_list_says_it_needs_a_mapping(pytester: pytest.Pytester) -> None:
    (pytester.path / "gate.lasertest.yaml").write_text("- robot: husky\n")
    result = pytester.runpytest()
    listed = Case(
        "", "", 1, "", "expected a mapping of pairs-file sections, got a list", "key: value"
    )
    assert_one_clean_error(result, 1, "", listed)


def test_a_pairs_file_that_is_not_utf8_names_the_line_of_the_bad_byte(
    pytester: pytest.Pytester,
) -> None:
    (pytester.path / "gate.lasertest.yaml").write_bytes(b"robot: husky\nworld: caf\xe9\n")
    result = pytester.runpytest()
    binary = Case("", "", 2, "", "the file is not UTF-8 text", "save it as UTF-8")
    assert_one_clean_error(result, 2, "", binary)


@pytest.mark.parametrize("workers", [[], ["-n", "2"]], ids=["serial", "xdist"])
def test_a_broken_pairs_file_does_not_stop_the_other_files_from_running(
    pytester: pytest.Pytester, workers: list[str]
) -> None:
    (pytester.path / "broken.lasertest.yaml").write_text("robot: [husky\n")
    (pytester.path / "good.lasertest.yaml").write_text(GOOD_PAIRS)
    pytester.makepyfile(test_unit="def test_the_project_s_own_test(): pass")
    result = pytester.runpytest_subprocess(*workers, "-m", "not placement and not control")
    result.assert_outcomes(passed=2, errors=1)
    assert result.ret == pytest.ExitCode.TESTS_FAILED
    result.stdout.fnmatch_lines(["*ERROR collecting broken.lasertest.yaml*", "*1 error*"])
    result.stdout.no_fnmatch_line("*Interrupted*")


def test_collect_only_lists_the_good_files_and_the_broken_one(pytester: pytest.Pytester) -> None:
    (pytester.path / "broken.lasertest.yaml").write_text("robot: [husky\n")
    (pytester.path / "good.lasertest.yaml").write_text(GOOD_PAIRS)
    result = pytester.runpytest("--collect-only", "-q")
    result.stdout.fnmatch_lines(["good.lasertest.yaml::longer[[]coverage[]]", "*1 error*"])


def test_a_python_test_file_with_a_collection_error_still_interrupts_the_run(
    pytester: pytest.Pytester,
) -> None:
    pytester.makepyfile(test_broken="import does_not_exist")
    (pytester.path / "good.lasertest.yaml").write_text(GOOD_PAIRS)
    result = pytester.runpytest()
    result.stdout.fnmatch_lines(["*Interrupted: 1 error during collection*"])


def test_fulltrace_shows_where_in_the_plugin_the_error_was_raised(
    pytester: pytest.Pytester,
) -> None:
    (pytester.path / "gate.lasertest.yaml").write_text(
        VALID_PAIRS.replace("samples: 720", "samples: 0")
    )
    result = pytester.runpytest("--fulltrace")
    result.stdout.fnmatch_lines(["*pytest_lasertest/plugin/collect.py:*", "*CollectError*"])


def test_a_robot_directory_next_to_the_pairs_file_is_found_by_its_relative_path(
    pytester: pytest.Pytester,
) -> None:
    robot_dir = pytester.path / "robots" / "mybot"
    robot_dir.mkdir(parents=True)
    (robot_dir / "robot.yaml").write_text(MY_ROBOT)
    (pytester.path / "gate.lasertest.yaml").write_text(
        VALID_PAIRS.replace("robot: husky", "robot: robots/mybot")
    )
    result = pytester.runpytest("-m", "not placement and not control", "--laser-policy=candidate")
    result.assert_outcomes(passed=1, failed=1)


ROBOT_CASES = {
    "a footprint that is not convex": (
        "[[-0.3, -0.2], [0.3, -0.2], [0.3, 0.2], [-0.3, 0.2]]",
        "[[-0.3, -0.2], [0.3, -0.2], [0.0, 0.0], [0.3, 0.2], [-0.3, 0.2]]",
        3,
        "footprint",
        "the corners do not form a convex polygon",
    ),
    "a footprint that goes round twice (a star)": (
        "[[-0.3, -0.2], [0.3, -0.2], [0.3, 0.2], [-0.3, 0.2]]",
        "[[0.3, 0.0], [-0.24, 0.18], [0.09, -0.29], [0.09, 0.29], [-0.24, -0.18]]",
        3,
        "footprint",
        "the corners do not form a convex polygon: its edges cross each other",
    ),
    "a footprint beside the robot": (
        "[[-0.3, -0.2], [0.3, -0.2], [0.3, 0.2], [-0.3, 0.2]]",
        "[[1.0, 1.0], [2.0, 1.0], [2.0, 2.0]]",
        3,
        "footprint",
        "the polygon does not contain the robot's origin",
    ),
    "a footprint of two corners": (
        "[[-0.3, -0.2], [0.3, -0.2], [0.3, 0.2], [-0.3, 0.2]]",
        "[[-0.3, -0.2], [0.3, 0.2]]",
        3,
        "footprint",
        "2 corners enclose no area",
    ),
    "a robot that cannot brake": (
        "max_linear_acceleration: 1.5",
        "max_linear_acceleration: 0",
        5,
        "max_linear_acceleration",
        "0 m/s^2 is below 0.01 m/s^2: the robot would take minutes and metres to stop",
    ),
    "a robot that cannot start turning": (
        "max_angular_acceleration: 3.0",
        "max_angular_acceleration: 0",
        7,
        "max_angular_acceleration",
        "0 rad/s^2 is below 0.01 rad/s^2: the robot would take minutes to start turning",
    ),
    "a missing turn rate": (
        "max_angular_velocity: 1.2\n",
        "",
        1,
        "max_angular_velocity",
        "max_angular_velocity is missing",
    ),
}


@pytest.mark.parametrize("case", ROBOT_CASES.values(), ids=ROBOT_CASES.keys())
def test_a_broken_robot_file_is_a_collection_error_naming_its_line_and_field(
    pytester: pytest.Pytester, case: tuple[str, str, int, str, str]
) -> None:
    old, new, line, field, problem = case
    robot_dir = pytester.path / "robots" / "mybot"
    robot_dir.mkdir(parents=True)
    (robot_dir / "robot.yaml").write_text(MY_ROBOT.replace(old, new))
    (pytester.path / "gate.lasertest.yaml").write_text(
        VALID_PAIRS.replace("robot: husky", "robot: robots/mybot")
    )
    result = pytester.runpytest()
    result.assert_outcomes(errors=1)
    result.stdout.fnmatch_lines(
        [f"robots/mybot/robot.yaml:{line}: {field}: {problem}*", "  fix: *"]
    )
    result.stdout.no_fnmatch_line("*Traceback*")


def test_a_waypoint_beyond_nav2s_rolling_global_costmap_is_a_collection_error_at_the_route(
    pytester: pytest.Pytester,
) -> None:
    # The Husky's Clearpath parameters roll a 20 m global costmap with the robot: a goal 12 m
    # ahead lies off it, and Nav2's NavFn plans no path to a goal off its costmap.
    far = """\
robot: husky
controller: nav2
world:
  start: {x: 0.0, y: 0.0, yaw: 0.0}
  route:
    - {x: 5.0, y: 0.0}
    - {x: 17.0, y: 0.0}
  time_limit: 90.0
pairs:
  longer: {baseline: {model: hokuyo_ust_10lx}, candidate: {model: hokuyo_ust_20lx}}
"""
    (pytester.path / "gate.lasertest.yaml").write_text(far)
    result = pytester.runpytest("-p", "no:randomly")
    expected = Case(
        "",
        "",
        5,
        "world.route",
        "the waypoint (17, 0) lies 10 m or more from where the robot sets off for it, beyond "
        "the half of Nav2's rolling global costmap (20 m wide",
        "put waypoints closer together along the route",
    )
    assert_one_clean_error(result, 5, "world.route", expected)


def test_a_broken_scan_filters_file_is_one_collection_error_at_its_own_line(
    pytester: pytest.Pytester,
) -> None:
    # The chain is read at collection: its error names the params file, not the pairs file.
    (pytester.path / "filters.yaml").write_text(
        "scan_filter_chain:\n"
        "- name: range\n"
        "  type: laser_filters/LaserScanRangeFilter\n"
        "  params: {lower_treshold: 0.3}\n"
    )
    pairs = GOOD_PAIRS + "navigation: {scan_filters: filters.yaml}\n"
    (pytester.path / "gate.lasertest.yaml").write_text(pairs)
    result = pytester.runpytest()
    misspelt = Case(
        "",
        "",
        4,
        "scan_filter_chain[0].params.lower_treshold",
        "LaserScanRangeFilter reads no parameter 'lower_treshold': ROS 1 ignores it",
        "did you mean 'lower_threshold'?",
    )
    assert_one_clean_error(result, 4, misspelt.field, misspelt, file="filters.yaml")
