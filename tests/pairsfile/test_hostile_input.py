"""Hostile input to the pairs file and what the gate computes from it (issue 20): no crash, no
hang, no silent pass. A robot slower than its nominal speed is planned for; every size that
sizes an allocation or a loop has bounds that say why; YAML 1.1's surprises (text for 1.0e6,
octal for 0720, base 60 for 1:30) are named; impossible mounts, steps and infinities are
refused; a time limit no robot can meet is refused, and one the baseline fails too says so."""

from __future__ import annotations

import os
import threading
from pathlib import Path

import numpy as np
import pytest

from pytest_lasertest import cli
from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.obstacles import Cylinder
from pytest_lasertest.model.route import nominal_path, swept_polygons, timed_to
from pytest_lasertest.model.verify import Scene, stopping_clearance
from pytest_lasertest.nav.move_base.settings import LIMITS, NavigationSettings, parameter_types
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.search.drives import drive
from pytest_lasertest.search.plans import plan_for
from pytest_lasertest.solver.search import anchor_times
from pytest_lasertest.solver.user import formula_text
from tests.helpers import EXAMPLES
from tests.helpers.runs import Case, assert_one_clean_error
from tests.helpers.texts import MY_ROBOT

# Line numbers matter: each case breaks one line of it.
GATE = """\
robot: husky
world:
  start: {x: 0.0, y: 0.0, yaw: 0.0}
  goal: {x: 6.0, y: 0.0}
  time_limit: 60.0
settings:
  witnesses: 1
navigation:
  dwa: {max_vel_x: 0.5}
pairs:
  size:
    baseline: {model: clearpath_lms1xx_gazebo, samples: 32, range: {max: 10.0}}
    candidate:
      model: clearpath_lms1xx_gazebo
      samples: 16
      update_rate: 50
      range: {max: 10.0, resolution: 0.01}
      pose: {xyz: [0.337, 0.0, 0.44023]}
"""
# The paper's size pair on the 6 m route, driven by a robot whose DWA tops out at 0.3 m/s while
# the Husky's nominal speed is 0.5 m/s.
SLOW = (
    GATE.replace("dwa: {max_vel_x: 0.5}", "dwa: {max_vel_x: 0.3, max_trans_vel: 0.3}")
    + "controller: move_base\n"
)
# A controller of a team's own that crawls straight ahead at 0.2 m/s.
CRAWLER = """\
class Crawler:
    def __init__(self, robot, route):
        pass

    def observe(self, scan, odometry, time):
        return 0.2, 0.0
"""


def write(tmp_path: Path, text: str, name: str = "gate.lasertest.yaml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def refused(tmp_path: Path, text: str) -> SpecError:
    with pytest.raises(SpecError) as raised:
        load_pairs_file(write(tmp_path, text))
    return raised.value


# --- Case 1: a robot slower than its nominal speed ---------------------------------------------


def test_a_path_timed_to_a_run_that_sets_off_late_holds_the_robot_standing_at_the_start() -> None:
    path = nominal_path(Pose2D(0, 0, 0), (Point2D(10, 0),), speed=0.5, turn_rate=1.0)
    times = np.arange(0.02, 30.0, 0.02)
    # The run stands for 3 s, then drives at the nominal speed.
    late = timed_to(path, times, path.poses_at(np.maximum(times - 3.0, 0.0)))
    footprint = np.array([[-0.5, -0.3], [0.5, -0.3], [0.5, 0.3], [-0.5, 0.3]])
    standing = swept_polygons(late, footprint, 0.0, 1.0)
    assert len(standing) == 1
    assert standing[0][:, 0].min() == pytest.approx(-0.5)
    assert standing[0][:, 0].max() == pytest.approx(0.5)


def test_a_run_slower_than_the_nominal_speed_times_the_path_at_its_own_speed() -> None:
    path = nominal_path(Pose2D(0, 0, 0), (Point2D(10, 0),), speed=0.5, turn_rate=1.0)
    times = np.arange(0.02, 40.0, 0.02)
    slow = nominal_path(Pose2D(0, 0, 0), (Point2D(10, 0),), speed=0.3, turn_rate=1.0)
    timed = timed_to(path, times, slow.poses_at(times))
    assert timed.speed == pytest.approx(0.3, rel=1e-3)
    assert timed.segments[0].begins == pytest.approx(0.0, abs=0.05)
    assert timed.duration == pytest.approx(10.0 / 0.3, rel=1e-2)


def test_braking_from_the_start_of_a_path_that_waits_there_reads_a_clearance(
    tmp_path: Path,
) -> None:
    spec = load_pairs_file(write(tmp_path, GATE))
    path = nominal_path(spec.world.start, spec.world.route, 0.5, 1.0)
    times = np.arange(0.02, 30.0, 0.02)
    late = timed_to(path, times, path.poses_at(np.maximum(times - 2.0, 0.0)))
    pair = spec.pairs[0]
    scene = Scene(pair.baseline.profile, pair.candidate.profile, spec.robot, late)
    pole = Cylinder(x=4.0, y=0.0, radius=0.05, height=1.0)
    assert stopping_clearance(scene, pole, 0.0) == pytest.approx(4.0 - 0.05 - 0.51, abs=1e-6)


def test_lasertest_plan_places_witnesses_for_a_robot_whose_dwa_drives_slower_than_nominal(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert cli.main(["plan", str(write(tmp_path, SLOW))]) == 0
    out = capsys.readouterr().out
    assert "Traceback" not in out
    assert "  candidate-misses: sat" in out
    assert "    candidate-misses-0: " in out


def test_a_controller_that_crawls_at_a_constant_0_2_m_s_gets_a_plan_along_its_own_pace(
    tmp_path: Path,
) -> None:
    (tmp_path / "crawler.py").write_text(CRAWLER)
    spec = load_pairs_file(write(tmp_path, GATE + "controller: crawler:Crawler\n"))
    assert spec.controller is not None
    pair = spec.pairs[0]
    control = drive(spec, pair.baseline.profile, (), 0, spec.controller.factory)
    plan = plan_for(spec, pair, control)
    witnesses = plan.direction("candidate-misses").witnesses
    assert witnesses
    # The witness's anchor is timed at 0.2 m/s: where the crawler really is then.
    anchor = witnesses[0].placement.anchor
    assert float(np.interp(anchor, control.times, control.poses[:, 0])) == pytest.approx(
        0.2 * anchor, abs=0.1
    )


# --- Case 2: bounds on every size that sizes an allocation or a loop -------------------------

BOUNDS = {
    "10^26 samples": Case(
        "samples: 16",
        "samples: 100000000000000000000000000",
        15,
        "pairs.size.candidate.samples",
        "100000000000000000000000000 beams a scan is more than the 100,000 the gate accepts: "
        "the densest real 2D scanners give about 25,000",
        "at most 100,000",
    ),
    "a scan rate of 1 GHz": Case(
        "update_rate: 50",
        "update_rate: 1.0e+9",
        16,
        "pairs.size.candidate.update_rate",
        "1e+09 Hz is outside the 0.1-10000 Hz the gate accepts",
        "from 0.1 to 10000",
    ),
    "a scan every hour": Case(
        "update_rate: 50",
        "update_rate: 0.0003",
        16,
        "pairs.size.candidate.update_rate",
        "0.0003 Hz is outside the 0.1-10000 Hz the gate accepts: a scan every 10 s or less",
        "from 0.1 to 10000",
    ),
    "a range of a light year": Case(
        "range: {max: 10.0, resolution: 0.01}",
        "range: {max: 9.5e+15}",
        17,
        "pairs.size.candidate.range.max",
        "9.5e+15 m is more than the 1000 m the gate accepts",
        "at most 1000 m",
    ),
    "100000 DWA samples": Case(
        "dwa: {max_vel_x: 0.5}",
        "dwa: {vx_samples: 100000, vth_samples: 100000}",
        9,
        "navigation.dwa.vx_samples",
        "100000 is above 100, the most the gate accepts: every cycle rolls out",
        "write a value from 1 to 100",
    ),
    "DWA samples within their bounds but too many together": Case(
        "dwa: {max_vel_x: 0.5}",
        "dwa: {vx_samples: 100, vth_samples: 200}",
        9,
        "navigation.dwa.vth_samples",
        "DWA would roll out 690,234 poses every control cycle",
        "lower vx_samples, vth_samples or sim_time",
    ),
    "a DWA step of a micrometre": Case(
        "dwa: {max_vel_x: 0.5}",
        "dwa: {sim_granularity: 0.000001}",
        9,
        "navigation.dwa.sim_granularity",
        "1e-06 m is below 0.001 m: finer, every trajectory takes more steps",
        "from 0.001 to 10 m",
    ),
    "a costmap cell of 10 um": Case(
        "dwa: {max_vel_x: 0.5}",
        "costmap: {resolution: 0.00001}",
        9,
        "navigation.costmap.resolution",
        "1e-05 m is below 0.005 m: the costmap is size / resolution cells a side",
        "from 0.005 to 1 m",
    ),
    "a local costmap of 6000 cells a side": Case(
        "dwa: {max_vel_x: 0.5}",
        "costmap: {resolution: 0.005, size: 30.0}",
        9,
        "navigation.costmap.size",
        "the local costmap would be 30 m / 0.005 m = 6,000 cells a side, more than the 4000",
        "coarsen costmap.resolution to at least 0.0075 m",
    ),
    "a global costmap of 10000 cells a side along a 60 m route": Case(
        "goal: {x: 6.0, y: 0.0}\n  time_limit: 60.0",
        "goal: {x: 60.0, y: 0.0}\n  time_limit: 300.0\n  # a costmap cell of 1 cm",
        4,
        "world.goal",
        "along this route (its points up to 60 m apart) the global costmap would be 100 m / "
        "0.01 m = 10,000 cells a side",
        "coarsen costmap.resolution to at least 0.025 m",
    ),
    "a time limit of a million seconds": Case(
        "time_limit: 60.0",
        "time_limit: 1.0e+6",
        5,
        "world.time_limit",
        "1000000 s is above 3600 s, the most the gate accepts: every run simulates the whole "
        "time in 20 ms steps",
        "write a value from 1 to 3600 s",
    ),
    "a time limit written with 400 digits": Case(
        "time_limit: 60.0",
        "time_limit: 1" + "0" * 400,
        5,
        "world.time_limit",
        "1000... (401 digits) is too large for a number",
        "write a number in s",
    ),
    "a route of 101 waypoints": Case(
        "goal: {x: 6.0, y: 0.0}",
        "route: [" + ", ".join(f"{{x: {0.1 * (k + 1):.1f}, y: 0.0}}" for k in range(101)) + "]",
        4,
        "world.route",
        "the route has 101 waypoints, more than the 100 the gate accepts",
        "at most 100",
    ),
    "a goal 1e300 m away": Case(
        "goal: {x: 6.0, y: 0.0}",
        "goal: {x: 1.0e+300, y: 0.0}",
        4,
        "world.goal.x",
        "1e+300 m is above 10000 m, the most the gate accepts",
        "write a value from -10000 to 10000 m",
    ),
    "1800 Hz for an hour": Case(
        "time_limit: 60.0",
        "time_limit: 3600.0",
        13,
        "pairs.size.candidate",
        "at 1800 Hz over the 3600 s the gate judges this route (its time limit, or its nominal "
        "duration), the candidate scanner takes 6,480,000 scans, more than the 2,000,000",
        "lower the scanner's update_rate to at most 555.556 Hz",
    ),
    "obstacles of 1 mm": Case(
        "witnesses: 1",
        "witnesses: 1\n  min_obstacle_size: 0.001",
        8,
        "settings.min_obstacle_size",
        "0.001 m is below 0.01 m: the verifier confirms a reading only 5 mm inside an obstacle",
        "from 0.01 to 10 m",
    ),
    "obstacles of 1 km": Case(
        "witnesses: 1",
        "witnesses: 1\n  max_obstacle_size: 1000",
        8,
        "settings.max_obstacle_size",
        "1000 m is above 10 m, the most the gate accepts",
        "from 0.01 to 10 m",
    ),
    "a thousand witnesses": Case(
        "witnesses: 1",
        "witnesses: 1000",
        7,
        "settings.witnesses",
        "1000 witnesses per direction: each is a test item of its own",
        "from 1 to 20",
    ),
    "a solver rlimit of zero": Case(
        "witnesses: 1",
        "witnesses: 1\n  solver_rlimit: 0",
        8,
        "settings.solver_rlimit",
        "0 is below 1: Z3 stops every query at once",
        "from 1 to 5000000000",
    ),
    "a solver rlimit of 10 to the 12": Case(
        "witnesses: 1",
        "witnesses: 1\n  solver_rlimit: 1000000000000",
        8,
        "settings.solver_rlimit",
        "1000000000000 is above 5000000000, the most the gate accepts: at a thousand times",
        "from 1 to 5000000000",
    ),
    "a pinned pole 1 km wide": Case(
        "      pose: {xyz: [0.337, 0.0, 0.44023]}",
        "      pose: {xyz: [0.337, 0.0, 0.44023]}\n    placements:\n"
        "      - obstacle: {shape: cylinder, x: 3.0, y: 0.0, radius: 1000.0, height: 1.0}\n"
        "        seed: 1",
        20,
        "pairs.size.placements[0].obstacle.radius",
        "1000 m is above 5 m, the most the gate accepts: an obstacle that large is a wall",
        "write a value above 0 and at most 5 m",
    ),
    "1001 pinned placements": Case(
        "      pose: {xyz: [0.337, 0.0, 0.44023]}",
        "      pose: {xyz: [0.337, 0.0, 0.44023]}\n    placements:\n"
        + "".join(
            "      - {obstacle: {shape: cylinder, x: 3, y: 0, radius: 0.05, height: 1}, seed: 1}\n"
            for _ in range(1001)
        ),
        19,
        "pairs.size.placements",
        "1001 placements are more than the 1000 the gate accepts for a pair",
        "keep the recorded failures that matter",
    ),
}


@pytest.mark.parametrize("case", BOUNDS.values(), ids=BOUNDS.keys())
def test_a_size_beyond_its_bound_is_refused_at_its_line_with_the_reason_and_the_fix(
    tmp_path: Path, case: Case
) -> None:
    assert GATE.count(case.old) == 1
    text = GATE.replace(case.old, case.new)
    if "a costmap cell of 1 cm" in case.new:
        text = text.replace("dwa: {max_vel_x: 0.5}", "costmap: {resolution: 0.01}")
    if "1800 Hz" in case.problem:
        text = text.replace("update_rate: 50", "update_rate: 1800")
    error = refused(tmp_path, text)
    assert (error.location.line, error.field) == (case.line, case.field)
    assert case.problem in error.problem
    assert case.fix in error.fix


def test_10_to_the_26_samples_is_one_clean_collection_error_not_a_numpy_traceback(
    pytester: pytest.Pytester,
) -> None:
    case = BOUNDS["10^26 samples"]
    (pytester.path / "gate.lasertest.yaml").write_text(GATE.replace(case.old, case.new))
    result = pytester.runpytest()
    assert_one_clean_error(result, case.line, case.field, case)


def test_every_numeric_navigation_parameter_has_bounds_its_defaults_and_the_husky_keep() -> None:
    defaults = NavigationSettings()
    for section, names in parameter_types().items():
        for name, kind in names.items():
            if kind is bool:
                continue
            limit = LIMITS[section][name]
            assert limit.low <= getattr(getattr(defaults, section), name) <= limit.high, name


# A wheel's cylinder, and the turn and mark that make it one.
WHEEL = "cylinder: {radius: 0.1, length: 0.05}"
SIDEWAYS = "rpy: [-1.57, 0, 0], wheel: true"
ROBOT_CASES = {
    "a top speed of 1 km/s": (
        "max_linear_velocity: 0.8",
        "max_linear_velocity: 1000.0",
        4,
        "max_linear_velocity",
        "1000 m/s is above 20 m/s, the most the gate accepts: at 20 m/s it moves 0.4 m in one "
        "20 ms physics step",
    ),
    "an infinite top speed": (
        "max_linear_velocity: 0.8",
        "max_linear_velocity: .inf",
        4,
        "max_linear_velocity",
        "inf is not a finite number",
    ),
    "a turn rate that is not a number": (
        "max_angular_velocity: 1.2",
        "max_angular_velocity: .nan",
        6,
        "max_angular_velocity",
        "nan is not a finite number",
    ),
    "a cruise faster than the top speed": (
        "max_angular_acceleration: 3.0",
        "max_angular_acceleration: 3.0\nnominal_speed: 2.0",
        8,
        "nominal_speed",
        "2 m/s is faster than the robot's max_linear_velocity, 0.8 m/s",
    ),
    "a crawl of 1 um/s": (
        "max_angular_acceleration: 3.0",
        "max_angular_acceleration: 3.0\nnominal_speed: 0.000001",
        8,
        "nominal_speed",
        "1e-06 m/s is below 0.01 m/s: the path would take hours at this pace, scan by scan",
    ),
    "a footprint a kilometre wide": (
        "[0.3, 0.2], [-0.3, 0.2]]",
        "[0.3, 1000.0], [-0.3, 0.2]]",
        3,
        "footprint[2]",
        "the corner (0.3, 1000) m lies more than 20 m from the robot's origin",
    ),
    "a negative padding": (
        "max_angular_acceleration: 3.0",
        "max_angular_acceleration: 3.0\nfootprint_padding: -0.5",
        8,
        "footprint_padding",
        "-0.5 m is below 0 m: costmap_2d pads a footprint outward",
    ),
    "a laser 5 m below the ground": (
        "xyz: [0.2, 0, 0.3]",
        "xyz: [0.2, 0, -5.0]",
        2,
        "laser_mount.xyz",
        "the scanner is mounted 5 m below the ground (z = -5 m)",
    ),
    "no body, never a silent Husky": (
        "body: {height: 0.3}\n",
        "",
        1,
        "body",
        "body",
    ),
    "a body the simulator does not have": (
        "body: {height: 0.3}",
        "body: turtlebot3",
        8,
        "body",
        "'turtlebot3' is not a body the simulator has",
    ),
    "a flat body": (
        "body: {height: 0.3}",
        "body: {height: 0.0}",
        8,
        "body.height",
        "0 m is below 0.01 m: a body this flat is no robot",
    ),
    "a body without its height": (
        "body: {height: 0.3}",
        "body: {heigth: 0.3}",
        8,
        "body.heigth",
        "unknown key 'heigth'",
    ),
    "a body of a height and collisions": (
        "body: {height: 0.3}",
        "body: {height: 0.3, collisions: [{sphere: {radius: 0.1}, xyz: [0, 0, 0.1]}]}",
        8,
        "body",
        "a body is given by its height or by its collisions, not both",
    ),
    "a body of nothing": (
        "body: {height: 0.3}",
        "body: {}",
        8,
        "body.height",
        "height is missing",
    ),
    "a body of no collisions": (
        "body: {height: 0.3}",
        "body: {collisions: []}",
        8,
        "body.collisions",
        "0 collision shapes: a body has from 1 to 200",
    ),
    "a collision of two shapes": (
        "body: {height: 0.3}",
        "body: {collisions: [{sphere: {radius: 0.1}, box: {size: [1, 1, 1]}, xyz: [0, 0, 1]}]}",
        8,
        "body.collisions[0]",
        "a collision is one shape",
    ),
    "a cylinder of a negative radius": (
        "body: {height: 0.3}",
        "body: {collisions: [{cylinder: {radius: -0.1, length: 0.2}, xyz: [0, 0, 0.1]}]}",
        8,
        "body.collisions[0].cylinder.radius",
        "-0.1 m is not above 0 m: a shape has a size",
    ),
    "a box of two lengths": (
        "body: {height: 0.3}",
        "body: {collisions: [{box: {size: [0.6, 0.4]}, xyz: [0, 0, 0.1]}]}",
        8,
        "body.collisions[0].box.size",
        "expected 3 numbers in m, got 2",
    ),
    "a collision placed nowhere": (
        "body: {height: 0.3}",
        "body: {collisions: [{sphere: {radius: 0.1}}]}",
        8,
        "body.collisions[0].xyz",
        "xyz is missing",
    ),
    "a collision 100 m from the robot": (
        "body: {height: 0.3}",
        "body: {collisions: [{sphere: {radius: 0.1}, xyz: [100, 0, 0.1]}]}",
        8,
        "body.collisions[0].xyz",
        "[100.0, 0.0, 0.1] m lies more than 20 m from the robot's base",
    ),
    "a body of collisions a millimetre tall": (
        "body: {height: 0.3}",
        "body: {collisions: [{sphere: {radius: 0.0005}, xyz: [0, 0, 0.0005]}]}",
        8,
        "body",
        "0.001 m is below 0.01 m: a body this flat is no robot",
    ),
    "a box for a wheel": (
        "body: {height: 0.3}",
        "body: {collisions: [{box: {size: [0.1, 0.1, 0.1]}, xyz: [0, 0.2, 0.05], wheel: true}]}",
        8,
        "body.collisions[0].wheel",
        "this shape cannot be a wheel: a box does not roll: a wheel is a cylinder",
    ),
    "a wheel lying flat": (
        "body: {height: 0.3}",
        f"body: {{collisions: [{{{WHEEL}, xyz: [0, 0.2, 0.1], wheel: true}}]}}",
        8,
        "body.collisions[0].wheel",
        "its axis does not lie along the base's y axis (a wheel rolls forward)",
    ),
    "a wheel astride the base": (
        "body: {height: 0.3}",
        f"body: {{collisions: [{{{WHEEL}, xyz: [0, 0, 0.1], {SIDEWAYS}}}]}}",
        8,
        "body.collisions[0].wheel",
        "it straddles the base's x axis: a wheel drives the left or the right side",
    ),
    "wheels on one side": (
        "body: {height: 0.3}",
        f"body: {{collisions: [{{{WHEEL}, xyz: [0.2, 0.2, 0.1], {SIDEWAYS}}},"
        f" {{{WHEEL}, xyz: [-0.2, 0.2, 0.1], {SIDEWAYS}}}]}}",
        8,
        "body.collisions",
        "a body drives on wheels both left (y > 0) and right (y < 0) of its base",
    ),
    "a wheel off the ground": (
        "body: {height: 0.3}",
        "body: {collisions: [{box: {size: [0.5, 0.3, 0.2]}, xyz: [0, 0, 0.1]},"
        f" {{{WHEEL}, xyz: [0, 0.2, 0.2], {SIDEWAYS}}},"
        f" {{{WHEEL}, xyz: [0, -0.2, 0.1], {SIDEWAYS}}}]}}",
        8,
        "body.collisions",
        "the wheel at y = 0.2 m stops 0.100 m above the body's lowest point",
    ),
    "a wheel of yes": (
        "body: {height: 0.3}",
        f"body: {{collisions: [{{{WHEEL}, xyz: [0, 0.2, 0.1], wheel: yes please}}]}}",
        8,
        "body.collisions[0].wheel",
        "wheel is true or false, not the text 'yes please'",
    ),
}


def test_a_fifo_named_as_a_pairs_file_is_refused_before_it_is_read(tmp_path: Path) -> None:
    pairs = tmp_path / "gate.lasertest.yaml"
    os.mkfifo(pairs)
    # Should the reader block on the FIFO, a writer comes after 30 s and the test fails.
    watchdog = threading.Timer(30.0, lambda: os.close(os.open(pairs, os.O_WRONLY)))
    watchdog.start()
    try:
        with pytest.raises(SpecError) as raised:
            load_pairs_file(pairs)
    finally:
        watchdog.cancel()
    assert raised.value.location.path == pairs
    assert "is a FIFO (named pipe), which would wait for a writer for ever" in raised.value.problem
    assert raised.value.fix == "name the YAML file itself, saved on disk"


@pytest.mark.parametrize("case", ROBOT_CASES.values(), ids=ROBOT_CASES.keys())
def test_a_robot_file_beyond_any_real_robot_is_refused_at_its_line(
    tmp_path: Path, case: tuple[str, str, int, str, str]
) -> None:
    old, new, line, field, problem = case
    assert MY_ROBOT.count(old) == 1
    robot = tmp_path / "robot.yaml"
    robot.write_text(MY_ROBOT.replace(old, new))
    with pytest.raises(SpecError) as raised:
        load_pairs_file(write(tmp_path, GATE.replace("robot: husky", "robot: robot.yaml")))
    error = raised.value
    assert (error.location.path, error.location.line, error.field) == (robot, line, field)
    assert problem in error.problem


@pytest.mark.parametrize(
    ("text", "problem"),
    [
        ("x > 1.0e+300", "1e+300 is outside what the solver tells apart"),
        ("size >= 0.0000001", "1e-07 is outside what the solver tells apart"),
    ],
)
def test_a_constraint_number_beyond_what_the_solver_tells_apart_is_refused(
    tmp_path: Path, text: str, problem: str
) -> None:
    error = refused(tmp_path, GATE.replace("settings:", f'constraints: ["{text}"]\nsettings:'))
    assert error.field == "constraints[0]"
    assert problem in error.problem


def test_a_constraint_on_a_micrometre_reaches_the_solver_as_written(tmp_path: Path) -> None:
    spec = load_pairs_file(
        write(tmp_path, GATE.replace("settings:", 'constraints: ["size >= 0.000001"]\nsettings:'))
    )
    assert formula_text(spec.constraints[0].formula, 0.0) == "(>= S 0.000001)"


def test_more_than_100_constraints_are_refused(tmp_path: Path) -> None:
    items = "".join(f'\n  - "x > {k}"' for k in range(101))
    error = refused(tmp_path, GATE.replace("settings:", f"constraints:{items}\nsettings:"))
    assert "101 constraints are more than the 100 the gate accepts" in error.problem


def test_a_yaml_file_of_more_than_a_megabyte_is_refused_before_it_is_parsed(
    tmp_path: Path,
) -> None:
    error = refused(tmp_path, GATE + "# " + "x" * 1_000_000 + "\n")
    assert "more than the 1,000,000 any file the gate reads as YAML needs" in error.problem


def test_lists_nested_a_thousand_deep_are_refused_not_a_recursion_error(tmp_path: Path) -> None:
    error = refused(tmp_path, GATE + "extra: " + "[" * 1000 + "]" * 1000 + "\n")
    assert error.location.line == 19
    assert "nested more than 50 deep" in error.problem


def test_a_route_of_more_than_an_hour_at_the_nominal_pace_is_refused(tmp_path: Path) -> None:
    text = GATE.replace("goal: {x: 6.0, y: 0.0}", "goal: {x: 2000.0, y: 0.0}")
    error = refused(tmp_path, text.replace("time_limit: 60.0", "time_limit: 3600.0"))
    assert (error.location.line, error.field) == (4, "world.goal")
    assert (
        "at its nominal speed of 0.5 m/s and turn rate of 1 rad/s the robot takes 4000 s along "
        "this route, more than the 3600 s the gate plans along, scan by scan"
    ) in error.problem


def test_a_route_of_a_kilometre_is_searched_at_no_more_than_100_anchors(tmp_path: Path) -> None:
    spec = load_pairs_file(write(tmp_path, GATE))
    path = nominal_path(Pose2D(0, 0, 0), (Point2D(1000.0, 0.0),), speed=0.5, turn_rate=1.0)
    pair = spec.pairs[0]
    scene = Scene(pair.baseline.profile, pair.candidate.profile, spec.robot, path)
    anchors = anchor_times(scene, "candidate-misses", 0.5)
    assert 90 <= len(anchors) <= 100
    assert anchors[-1] > 0.9 * path.duration


def test_every_example_pairs_file_and_robot_keeps_within_the_bounds() -> None:
    for path in sorted(EXAMPLES.rglob("*.lasertest.yaml")):
        assert load_pairs_file(path).pairs, path


# --- Case 3: messages that said too little, and values accepted without comment --------------

YAML_CASES = {
    "1.0e6, text in YAML 1.1": Case(
        "time_limit: 60.0",
        "time_limit: 1.0e6",
        5,
        "world.time_limit",
        "'1.0e6' was read as text: YAML 1.1 (PyYAML's) reads a number with an exponent only "
        "with a dot and a signed exponent",
        "write 1.0e+6",
    ),
    "a scan rate of 5e1 Hz, text in YAML 1.1": Case(
        "update_rate: 50",
        "update_rate: 5e1",
        16,
        "pairs.size.candidate.update_rate",
        "'5e1' was read as text",
        "write 5.0e+1",
    ),
    "1.0e3 samples": Case(
        "samples: 16",
        "samples: 1.0e3",
        15,
        "pairs.size.candidate.samples",
        "'1.0e3' was read as text",
        "write 1000",
    ),
    "0720 samples, octal in YAML 1.1": Case(
        "samples: 16",
        "samples: 0720",
        15,
        "pairs.size.candidate.samples",
        "YAML 1.1 reads 0720, with its leading zero, as the octal number 464",
        "write it without the leading zero: 720",
    ),
    "0790 samples, text in YAML 1.1": Case(
        "samples: 16",
        "samples: 0790",
        15,
        "pairs.size.candidate.samples",
        "'0790' was read as text: YAML 1.1 takes an integer with a leading zero for octal",
        "write it without the leading zero: 790",
    ),
    "1:30, base 60 in YAML 1.1": Case(
        "time_limit: 60.0",
        "time_limit: 1:30",
        5,
        "world.time_limit",
        "YAML 1.1 reads 1:30 as the base-60 (sexagesimal) number 90",
        "(90 if that is it)",
    ),
    "a mount 5 m below the ground": Case(
        "pose: {xyz: [0.337, 0.0, 0.44023]}",
        "pose: {xyz: [0.337, 0.0, -5.0]}",
        18,
        "pairs.size.candidate.pose.xyz",
        "the scanner is mounted 5 m below the ground (z = -5 m): the base frame "
        "(base_footprint) lies on the ground",
        "write the scanner's height above the ground as z",
    ),
    "a reading step of 100 m": Case(
        "resolution: 0.01",
        "resolution: 100.0",
        17,
        "pairs.size.candidate.range.resolution",
        "a reading step of 100 m is no finer than the whole range (0.1-10 m)",
        "or leave it out",
    ),
    "noise as wide as the range": Case(
        "update_rate: 50",
        "update_rate: 50\n      noise: {stddev: 20.0}",
        17,
        "pairs.size.candidate.noise.stddev",
        "20 m is as wide as the whole range (0.1-10 m): the readings would be noise",
        "a few mm to a few cm",
    ),
    "an infinite DWA speed": Case(
        "dwa: {max_vel_x: 0.5}",
        "dwa: {max_vel_x: .inf}",
        9,
        "navigation.dwa.max_vel_x",
        "inf is not a finite number",
        "the gate takes no .inf or .nan",
    ),
    "a least speed above the most": Case(
        "dwa: {max_vel_x: 0.5}",
        "dwa: {min_trans_vel: 0.6}",
        9,
        "navigation.dwa.min_trans_vel",
        "min_trans_vel (0.6) is above max_trans_vel (0.5): DWA would sample no velocity it may "
        "drive, and the robot would never move",
        "make min_trans_vel at most max_trans_vel",
    ),
    "a time limit no robot can meet": Case(
        "time_limit: 60.0",
        "time_limit: 3.0",
        5,
        "world.time_limit",
        "3 s is too short for the route: it is 6.00 m long, and even at its top speed of 1 m/s, "
        "never slowing or turning, the robot needs 5.80 s to come within 0.2 m of the goal; "
        "every run would fail, the baseline's as well as the candidate's",
        "raise time_limit: at its nominal pace the route takes 12.0 s, so give it about twice "
        "that, e.g. 30 s",
    ),
}


@pytest.mark.parametrize("case", YAML_CASES.values(), ids=YAML_CASES.keys())
def test_a_value_read_as_something_else_or_impossible_is_named_with_the_fix(
    tmp_path: Path, case: Case
) -> None:
    assert GATE.count(case.old) == 1
    error = refused(tmp_path, GATE.replace(case.old, case.new))
    assert (error.location.line, error.field) == (case.line, case.field)
    assert case.problem in error.problem
    assert case.fix in error.fix


def test_a_control_run_the_baseline_fails_too_blames_the_world_not_the_scanner_change(
    pytester: pytest.Pytester,
) -> None:
    # 6 s is enough at the Husky's top speed (1 m/s) but not at move_base's 0.5 m/s.
    (pytester.path / "gate.lasertest.yaml").write_text(
        GATE.replace("time_limit: 60.0", "time_limit: 6.0")
    )
    result = pytester.runpytest("-k", "no-obstacle", "--laser-policy=candidate")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(
        [
            "the baseline fails without any obstacle too: the world, its time limit or the "
            "controller is at fault, not the scanner change",
            "  fix        the baseline robot was still on its way when world.time_limit (6 s) ran "
            "out, * m from the goal: raise time_limit",
        ]
    )
    result.stdout.no_fnmatch_line("*the change breaks the robot everywhere*")


def test_a_placement_item_of_a_slow_robot_drives_its_witness_instead_of_raising(
    pytester: pytest.Pytester,
) -> None:
    (pytester.path / "gate.lasertest.yaml").write_text(SLOW)
    result = pytester.runpytest(
        *("-k", "candidate-misses-0", "--laser-profile=dev", "--laser-seed=1"),
        "--laser-policy=candidate",
    )
    result.stdout.no_fnmatch_line("*min() arg is an empty sequence*")
    result.stdout.no_fnmatch_line("*Traceback*")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["the candidate fails (collision*", "  oracle     collision: *"])
