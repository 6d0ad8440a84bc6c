"""nav2_collision_monitor's node tests (test/collision_monitor_node_test.cpp), where they test an
approach polygon on the footprint, rebuilt on our `approach` with the points the node's source
would hand it; and the node's refusals to configure, rebuilt on `params.configure` (a params
file whose collision_monitor sets the test's parameters, tests/helpers/nav2_params.py).

testProcessApproachRotation reads a range sensor, which our monitor does not: the points are
made here as Range::getData makes them (the reading spread over the sensor's field of view),
and `approach` is given them. Of each command only x and the turn rate are compared: our
commands have no sideways part.

Not applicable: the stop, slowdown and limit polygons (testProcessStopSlowdownLimit,
testPolygonSource, testCeasePublishZeroVel, testPolygonNotEnabled, testSourceNotEnabled,
testSourceAssociatedToPolygon, the velocity polygon tests), approach on a circle
(testProcessApproach, also sideways; testCrossOver; testSourceTimeout and
testSourceTimeoutOverride, also source timeouts), and the node's services, topics, markers,
action states and lifecycle (testToggleService, testProcessNonActive, testCollisionPointsMarkers).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pytest_lasertest.model.robot import ParameterValue
from pytest_lasertest.nav.nav2.collision_monitor import CollisionMonitorSettings, approach
from pytest_lasertest.nav.nav2.node_parameters import ParameterProblem
from tests.helpers.nav2_params import nav2_settings
from tests.helpers.upstream import NAVIGATION2_JAZZY, Source

NODE = Source(
    "Nav2 collision monitor",
    NAVIGATION2_JAZZY,
    "nav2_collision_monitor/test/collision_monitor_node_test.cpp",
)
EPSILON = 1e-5  # upstream's tolerance
TIME_BEFORE_COLLISION = 1.0  # s
SIMULATION_TIME_STEP = 0.01  # s
MONITOR = CollisionMonitorSettings(TIME_BEFORE_COLLISION, SIMULATION_TIME_STEP, min_points=2)
# publishFootprint(1.0): a 2 m square about the base.
FOOTPRINT = np.array([[1.0, 1.0], [1.0, -1.0], [-1.0, -1.0], [-1.0, 1.0]])  # m
FIELD_OF_VIEW = math.pi / 10  # rad, publishRange's
OBSTACLES_ANGLE = math.pi / 200  # rad, addSource's for the range source
TURN = math.pi / 4  # rad/s, the command's


def range_points(reading: float) -> np.ndarray:
    """Range::getData's points (P, 2) m for a reading of `reading` m ahead: one every
    obstacles_angle across the field of view from its right edge, and one on its left edge."""
    half = FIELD_OF_VIEW / 2.0
    angles = np.append(np.arange(-half, half, OBSTACLES_ANGLE), half)
    return reading * np.column_stack([np.cos(angles), np.sin(angles)])


@NODE.test("Tester.testProcessApproachRotation", assertions=8)
def test_turning_toward_an_obstacle_slows_the_turn_so_it_is_reached_in_time() -> None:
    # 2 m and 2.5 m ahead lie beyond the square's corners (1.41 m) however it turns.
    for far in (2.0, 2.5):
        allowed = approach((0.0, TURN), range_points(far), FOOTPRINT, MONITOR)
        assert allowed[0] == pytest.approx(0.0, abs=EPSILON)
        assert allowed[1] == pytest.approx(TURN, abs=EPSILON)
    # 1.4 m ahead: the square's corner reaches the arc's right end after pi/5 rad of turning,
    # 0.8 s at pi/4 rad/s, so the turn is slowed to pi/5 rad/s.
    near = approach((0.0, TURN), range_points(1.4), FOOTPRINT, MONITOR)
    assert near[0] == pytest.approx(0.0, abs=EPSILON)
    step = TURN * SIMULATION_TIME_STEP / TIME_BEFORE_COLLISION  # rad/s, one step's worth
    assert near[1] == pytest.approx(math.pi / 5.0, abs=step)
    # 0.5 m ahead: inside the footprint already, so the robot stops.
    inside = approach((0.0, TURN), range_points(0.5), FOOTPRINT, MONITOR)
    assert inside[0] == pytest.approx(0.0, abs=EPSILON)
    assert inside[1] == pytest.approx(0.0, abs=EPSILON)


def configured(parameters: dict[str, ParameterValue]) -> CollisionMonitorSettings | None:
    """The monitor a params file with these collision_monitor parameters makes."""
    return nav2_settings({"collision_monitor": parameters}).collision_monitor


# addPolygon's and addSource's parameters for an approach polygon on a scan. Upstream's
# configuration tests below use a stop polygon, which our monitor refuses whatever else the
# file says; Nav2 checks what they test before or regardless of the action type
# (collision_monitor_node.cpp configureSources runs before configurePolygons, and a polygon's
# type is read before its action type), so ours use an approach polygon.
APPROACH: dict[str, ParameterValue] = {
    "Approach.enabled": True,
    "Approach.action_type": "approach",
    "Approach.min_points": 2,
    "Approach.time_before_collision": TIME_BEFORE_COLLISION,
    "Approach.simulation_time_step": SIMULATION_TIME_STEP,
    "Approach.footprint_topic": "footprint",
}
SCAN: dict[str, ParameterValue] = {"Scan.type": "scan", "Scan.topic": "Scan"}


@NODE.test("Tester.testIncorrectPolygonType", assertions=1)
def test_a_polygon_of_unknown_type_is_refused() -> None:
    with pytest.raises(ParameterProblem):
        configured(
            {
                "polygons": ("Approach",),
                "Approach.type": "unknown",
                "observation_sources": ("Scan",),
                **APPROACH,
                **SCAN,
            }
        )


@NODE.test("Tester.testIncorrectSourceType", assertions=1)
def test_a_source_of_unknown_type_is_refused() -> None:
    with pytest.raises(ParameterProblem):
        configured(
            {
                "polygons": ("Approach",),
                "Approach.type": "polygon",
                "observation_sources": ("UnknownSource",),
                "UnknownSource.type": "unknown",
                "UnknownSource.topic": "UnknownSource",
                **APPROACH,
            }
        )


@NODE.test("Tester.testPolygonsNotSet", assertions=1)
def test_a_monitor_without_polygons_is_refused() -> None:
    with pytest.raises(ParameterProblem, match="collision_monitor: polygons: is not set"):
        # As upstream: a stop polygon defined but not listed, which our reader never reads.
        configured(
            {
                "Stop.type": "polygon",
                "Stop.action_type": "stop",
                "Stop.points": "[[1.0, 1.0], [1.0, -1.0], [-1.0, -1.0], [-1.0, 1.0]]",
                **SCAN,
            }
        )


@NODE.test("Tester.testSourcesNotSet", assertions=1)
def test_a_monitor_without_observation_sources_is_refused() -> None:
    with pytest.raises(ParameterProblem, match="collision_monitor: observation_sources: is not"):
        configured({"polygons": ("Approach",), "Approach.type": "polygon", **APPROACH, **SCAN})
