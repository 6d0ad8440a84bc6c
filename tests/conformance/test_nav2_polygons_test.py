"""nav2_collision_monitor's polygon tests (test/polygons_test.cpp), rebuilt on our collision
monitor (`collision_monitor.py`: `approach`, and the ray-crossing count `count_inside` that runs
in it, compiled in `kernels.py`) and on the
collision_monitor node's parameters as `params.configure` reads them (in a params file whose
collision_monitor sets the test's parameters, tests/helpers/nav2_params.py).

A collision time is read off `approach`'s answer: the command scaled by that time over
time_before_collision, as processApproach scales it; a negative time (no collision) is the
command let through unchanged.

Not applicable: the stop, slowdown and limit polygons' parameters, circles, polygons and
footprints taken from topics or other frames, publishing and visualize, static points strings,
sources_names (our monitor has one polygon, the footprint, and one scan), the sideways case of
testPolygonGetCollisionTime (a holonomic velocity).
"""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.model.robot import ParameterValue
from pytest_lasertest.nav.nav2.collision_monitor import CollisionMonitorSettings, approach
from pytest_lasertest.nav.nav2.kernels import count_inside
from pytest_lasertest.nav.nav2.node_parameters import ParameterProblem
from tests.helpers.nav2_params import nav2_settings
from tests.helpers.upstream import NAVIGATION2_JAZZY, Source

POLYGONS = Source(
    "Nav2 collision monitor", NAVIGATION2_JAZZY, "nav2_collision_monitor/test/polygons_test.cpp"
)
SQUARE = np.array([[0.5, 0.5], [0.5, -0.5], [-0.5, -0.5], [-0.5, 0.5]])  # m
# Concave, with edges along the x axis at y = -1, 0 and 1, where the ray crossings could err.
ARBITRARY = np.array(
    [[1.0, 1.0], [1.0, 0.0], [2.0, 0.0], [2.0, -1.0], [-1.0, -1.0], [-1.0, 1.0]]
)  # m
MIN_POINTS = 2
TIME_BEFORE_COLLISION = 1.0  # s
SIMULATION_TIME_STEP = 0.01  # s
EPSILON = float(np.finfo(np.float32).eps)  # upstream's tolerance
MONITOR = CollisionMonitorSettings(TIME_BEFORE_COLLISION, SIMULATION_TIME_STEP, MIN_POINTS)


def points(*xy: tuple[float, float]) -> np.ndarray:
    """Points (P, 2) m in the base frame."""
    return np.array(xy, dtype=float)


def collision_time(command: tuple[float, float], seen: np.ndarray) -> float:
    """getCollisionTime as `approach` answers it for the square footprint: the scale it puts on
    the command, times time_before_collision (s)."""
    allowed = approach(command, seen, SQUARE, MONITOR)
    axis = 0 if command[0] != 0.0 else 1  # the axis the command moves on
    return allowed[axis] / command[axis] * TIME_BEFORE_COLLISION


def inside(seen: np.ndarray, polygon: np.ndarray) -> int:
    """How many of the points (P, 2) m the polygon (V, 2) m holds, counted as the monitor counts
    them, in the robot's own frame."""
    return count_inside(seen, np.ascontiguousarray(polygon), 0.0, 0.0, 0.0)


def monitor(polygon: dict[str, ParameterValue]) -> CollisionMonitorSettings | None:
    """The monitor a params file makes whose collision_monitor has the one polygon TestPolygon,
    with these parameters, and one scan source."""
    parameters: dict[str, ParameterValue] = {
        "polygons": ("TestPolygon",),
        "observation_sources": ("source",),
        "source.type": "scan",
        **{f"TestPolygon.{name}": value for name, value in polygon.items()},
    }
    return nav2_settings({"collision_monitor": parameters}).collision_monitor


@POLYGONS.test("Tester.testPolygonGetPointsInside", assertions=2)
def test_points_outside_the_square_count_none_and_one_inside_counts_one() -> None:
    outside = points((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))
    assert inside(outside, SQUARE) == 0
    assert inside(np.vstack([outside, [[-0.1, 0.3]]]), SQUARE) == 1


@POLYGONS.test("Tester.testPolygonGetPointsInsideEdge", assertions=2)
def test_points_level_with_edges_along_the_ray_are_not_counted_inside() -> None:
    level = points((-2.0, -1.0), (-2.0, 0.0), (-2.0, 1.0), (3.0, -1.0), (3.0, 0.0), (3.0, 1.0))
    assert inside(level, ARBITRARY) == 0
    assert inside(np.vstack([level, [[0.0, 0.0]]]), ARBITRARY) == 1


@POLYGONS.test("Tester.testPolygonGetCollisionTime", assertions=5)
def test_the_collision_time_is_when_the_moving_footprint_first_holds_min_points() -> None:
    # 0.2 m ahead of the footprint's front at 0.5 m/s, and behind its back backwards: 0.4 s.
    ahead = collision_time((0.5, 0.0), points((0.7, -0.01), (0.7, 0.01)))
    assert ahead == pytest.approx(0.4, abs=SIMULATION_TIME_STEP)
    behind = collision_time((-0.5, 0.0), points((-0.7, -0.01), (-0.7, 0.01)))
    assert behind == pytest.approx(0.4, abs=SIMULATION_TIME_STEP)
    # Upstream expects 45 / 180 * M_PI, which C++'s integer division makes 0: the points lie
    # inside the footprint already, so turning reaches them at once.
    turning = collision_time((0.0, 1.0), points((0.49, -0.01), (0.49, 0.01)))
    assert turning == pytest.approx(0.0, abs=EPSILON)
    inside = collision_time((0.5, 0.0), points((0.1, -0.01), (0.1, 0.01)))
    assert inside == pytest.approx(0.0, abs=EPSILON)
    # 0.6 m ahead: the robot moves 0.5 m in the second simulated, no collision.
    far = points((1.1, -0.01), (1.1, 0.01))
    assert approach((0.5, 0.0), far, SQUARE, MONITOR) == (0.5, 0.0)


@POLYGONS.test("Tester.testPolygonGetApproachParameters", assertions=3)
def test_an_approach_polygon_reads_min_points_and_its_simulation_times() -> None:
    # The upstream setCommonParameters and a static square; our monitor reads three of them.
    read = monitor(
        {
            "type": "polygon",
            "action_type": "approach",
            "min_points": MIN_POINTS,
            "slowdown_ratio": 0.7,
            "linear_limit": 0.4,
            "angular_limit": 0.09,
            "time_before_collision": TIME_BEFORE_COLLISION,
            "simulation_time_step": SIMULATION_TIME_STEP,
            "visualize": True,
            "polygon_pub_topic": "polygon_pub",
            "points": "[[0.5, 0.5], [0.5, -0.5], [-0.5, -0.5], [-0.5, 0.5]]",
        }
    )
    assert read is not None
    assert read.min_points == MIN_POINTS
    assert read.time_before_collision == pytest.approx(TIME_BEFORE_COLLISION, abs=EPSILON)
    assert read.simulation_time_step == pytest.approx(SIMULATION_TIME_STEP, abs=EPSILON)


@POLYGONS.test("Tester.testPolygonIncorrectActionType", assertions=1)
def test_an_unknown_action_type_is_refused() -> None:
    with pytest.raises(ParameterProblem) as refused:
        monitor({"type": "polygon", "action_type": "incorrect_action_type"})
    assert refused.value.name == "TestPolygon.action_type"  # refused for that, not another


@POLYGONS.test("Tester.testPolygonUndeclaredActionType", assertions=1)
def test_a_polygon_without_an_action_type_is_refused() -> None:
    with pytest.raises(ParameterProblem) as refused:
        monitor({"type": "polygon"})
    assert refused.value.name == "TestPolygon.action_type"


@POLYGONS.test("Tester.testPolygonMaxPoints", assertions=1)
def test_the_deprecated_max_points_sets_min_points_one_above_it() -> None:
    # Upstream's polygon is a stop polygon, which our monitor refuses whatever max_points
    # says; max_points is read alike for every action type, so this one is an approach.
    read = monitor(
        {"type": "polygon", "action_type": "approach", "min_points": MIN_POINTS, "max_points": 5}
    )
    assert read is not None
    assert read.min_points == 5 + 1
