"""The `navigation:` parameters of a pairs file and of a robot's navigation file."""

from __future__ import annotations

from pathlib import Path

import pytest

from pytest_lasertest.nav.move_base.settings import NavigationSettings
from pytest_lasertest.pairsfile.bundled import bundled_robots
from pytest_lasertest.pairsfile.pairs import load_pairs_file
from tests.helpers.runs import Case, assert_one_clean_error

# Line numbers matter: the cases below break one line of it.
NAV_PAIRS = """\
robot: husky
world: {start: {x: 0, y: 0}, goal: {x: 5, y: 0}, time_limit: 30}
navigation:
  move_base:
    controller_frequency: 10.0
    back_up_recovery: true
  dwa:
    vx_samples: 8
    max_vel_x: 0.4
pairs:
  longer: {baseline: {model: hokuyo_ust_10lx}, candidate: {model: hokuyo_ust_20lx}}
"""


CASES = {
    "an unknown section": Case(
        "  dwa:",
        "  dwaa:",
        7,
        "navigation.dwaa",
        "unknown key 'dwaa'",
        "did you mean 'dwa'?",
    ),
    "an unknown parameter": Case(
        "vx_samples: 8",
        "vx_sampels: 8",
        8,
        "navigation.dwa.vx_sampels",
        "unknown key 'vx_sampels'",
        "did you mean 'vx_samples'?",
    ),
    "a parameter of another section": Case(
        "vx_samples: 8",
        "controller_frequency: 8.0",
        8,
        "navigation.dwa.controller_frequency",
        "unknown key 'controller_frequency'",
        "known keys here: ",
    ),
    "a section that is not a mapping": Case(
        "  dwa:\n    vx_samples: 8\n    max_vel_x: 0.4\n",
        "  dwa: 8\n",
        7,
        "navigation.dwa",
        "expected a mapping of dwa parameters, got 8",
        "write `key: value` pairs",
    ),
    "a yes/no where a number belongs": Case(
        "controller_frequency: 10.0",
        "controller_frequency: true",
        5,
        "navigation.move_base.controller_frequency",
        "got true (a yes/no value)",
        "write a number",
    ),
    "a number where true or false belongs": Case(
        "back_up_recovery: true",
        "back_up_recovery: 1",
        6,
        "navigation.move_base.back_up_recovery",
        "back_up_recovery is true or false, not 1",
        "write true or false",
    ),
    "a fraction where a whole number belongs": Case(
        "vx_samples: 8",
        "vx_samples: 2.5",
        8,
        "navigation.dwa.vx_samples",
        "expected a whole number, got 2.5",
        "write an integer",
    ),
    "a negative speed": Case(
        "max_vel_x: 0.4",
        "max_vel_x: 0.4\n    max_rot_vel: -1.0",
        10,
        "navigation.dwa.max_rot_vel",
        "max_rot_vel cannot be negative (-1.0)",
        "write zero or more",
    ),
    "a zero controller_frequency": Case(
        "controller_frequency: 10.0",
        "controller_frequency: 0",
        5,
        "navigation.move_base.controller_frequency",
        "controller_frequency must be above zero, not 0",
        "write a positive controller_frequency",
    ),
    "no velocity samples": Case(
        "vx_samples: 8",
        "vx_samples: 0",
        8,
        "navigation.dwa.vx_samples",
        "vx_samples must be above zero, not 0",
        "write a positive vx_samples",
    ),
}


@pytest.mark.parametrize("case", CASES.values(), ids=CASES.keys())
def test_a_broken_navigation_section_is_one_collection_error_naming_line_field_and_fix(
    pytester: pytest.Pytester, case: Case
) -> None:
    assert case.old in NAV_PAIRS
    (pytester.path / "gate.lasertest.yaml").write_text(NAV_PAIRS.replace(case.old, case.new, 1))
    result = pytester.runpytest()
    assert_one_clean_error(result, case.line, case.field, case)


def test_a_valid_navigation_section_loads(tmp_path: Path) -> None:
    path = tmp_path / "gate.lasertest.yaml"
    path.write_text(NAV_PAIRS)
    navigation = load_pairs_file(path).robot.navigation
    assert navigation[-4:] == (
        ("move_base", "controller_frequency", 10.0),
        ("move_base", "back_up_recovery", True),
        ("dwa", "vx_samples", 8),
        ("dwa", "max_vel_x", 0.4),
    )


def test_a_negative_min_vel_x_is_accepted_so_that_dwa_may_reverse(tmp_path: Path) -> None:
    path = tmp_path / "gate.lasertest.yaml"
    path.write_text(NAV_PAIRS.replace("max_vel_x: 0.4", "min_vel_x: -0.1"))
    robot = load_pairs_file(path).robot
    assert robot.navigation[-1] == ("dwa", "min_vel_x", -0.1)
    assert NavigationSettings.from_parameters(robot.navigation).dwa.min_vel_x == -0.1


def test_a_pairs_file_override_wins_and_the_husky_keeps_its_other_values(
    tmp_path: Path,
) -> None:
    path = tmp_path / "gate.lasertest.yaml"
    path.write_text(
        NAV_PAIRS.replace(
            "  move_base:\n    controller_frequency: 10.0\n    back_up_recovery: true\n", ""
        ).replace("    vx_samples: 8\n", "")
    )
    navigation = load_pairs_file(path).robot.navigation
    assert navigation[-1] == ("dwa", "max_vel_x", 0.4)
    assert ("dwa", "max_vel_x", 0.5) in navigation[:-1]  # the Husky's own, overridden
    settings = NavigationSettings.from_parameters(navigation)
    assert settings.dwa.max_vel_x == 0.4
    # The Husky's navigation.yaml, not the ROS defaults (3 samples, 20 Hz, 0.55 m inflation).
    assert settings.dwa.vx_samples == 6
    assert settings.move_base.controller_frequency == 5.0
    assert settings.costmap.inflation_radius == 1.0
    assert settings.global_costmap.track_unknown_space is True
    # Untouched by either: the ROS default.
    assert settings.dwa.sim_time == 1.7


HUSKY_ROBOT = bundled_robots()["husky"].read_text()
NAVIGATION_LINE = next(
    number
    for number, text in enumerate(HUSKY_ROBOT.splitlines(), start=1)
    if text.startswith("navigation:")
)


def write_robot(pytester: pytest.Pytester, navigation_file: str | None) -> None:
    """The Husky's robot.yaml as robots/mybot/robot.yaml, its `navigation:` naming
    `navigation_file`, and a pairs file that uses it."""
    robot_dir = pytester.path / "robots" / "mybot"
    robot_dir.mkdir(parents=True)
    text = HUSKY_ROBOT.replace("navigation: navigation.yaml", f"navigation: {navigation_file}")
    (robot_dir / "robot.yaml").write_text(text)
    (pytester.path / "gate.lasertest.yaml").write_text(
        NAV_PAIRS.replace("robot: husky", "robot: robots/mybot")
    )


def test_a_robot_file_naming_a_missing_navigation_file_is_an_error_at_its_line(
    pytester: pytest.Pytester,
) -> None:
    assert "navigation: navigation.yaml" in HUSKY_ROBOT
    write_robot(pytester, "missing.yaml")
    result = pytester.runpytest()
    missing = Case(
        "",
        "",
        NAVIGATION_LINE,
        "navigation",
        "robots/mybot/missing.yaml does not exist",
        "give the path of a navigation YAML file relative to this robot file",
    )
    assert_one_clean_error(
        result, missing.line, missing.field, missing, file="robots/mybot/robot.yaml"
    )


def test_a_robot_navigation_file_with_a_bad_parameter_is_an_error_at_its_own_line(
    pytester: pytest.Pytester,
) -> None:
    write_robot(pytester, "nav.yaml")
    (pytester.path / "robots" / "mybot" / "nav.yaml").write_text(
        "# mine\nmove_base:\n  controller_frequency: 5.0\ndwa:\n  acc_lim_th: 3.2\n"
    )
    result = pytester.runpytest()
    renamed = Case(
        "",
        "",
        5,
        "dwa.acc_lim_th",
        "unknown key 'acc_lim_th'",
        "did you mean 'acc_lim_theta'?",
    )
    assert_one_clean_error(
        result, renamed.line, renamed.field, renamed, file="robots/mybot/nav.yaml"
    )
