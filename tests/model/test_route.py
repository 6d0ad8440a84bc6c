"""The nominal path: turn toward each waypoint, then drive straight to it, at a nominal pace."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.route import (
    Leg,
    NominalPath,
    Turn,
    nominal_path,
    place,
    scan_times,
    swept_polygons,
    timed_to,
)

FOOTPRINT = np.array([[-0.5, -0.3], [0.5, -0.3], [0.5, 0.3], [-0.5, 0.3]])


def test_a_goal_straight_ahead_is_one_leg_driven_at_the_nominal_speed() -> None:
    path = nominal_path(Pose2D(0, 0, 0), (Point2D(10, 0),), speed=0.5, turn_rate=1.0)
    assert [type(segment) for segment in path.segments] == [Leg]
    assert path.duration == pytest.approx(20.0)
    poses = path.poses_at(np.array([0.0, 4.0, 20.0, 25.0]))
    np.testing.assert_allclose(poses, [[0, 0, 0], [2, 0, 0], [10, 0, 0], [10, 0, 0]])


def test_a_route_that_turns_left_turns_in_place_at_the_corner_at_the_nominal_turn_rate() -> None:
    route = (Point2D(2, 0), Point2D(2, 2))
    path = nominal_path(Pose2D(0, 0, 0), route, speed=1.0, turn_rate=0.5)
    leg, turn, _ = path.segments
    assert isinstance(turn, Turn)
    assert turn.angle == pytest.approx(math.pi / 2)
    assert path.duration == pytest.approx(2.0 + math.pi + 2.0)
    halfway = path.poses_at(np.array([2.0 + math.pi / 2]))[0]
    np.testing.assert_allclose(halfway, [2.0, 0.0, math.pi / 4], atol=1e-12)
    assert path.polyline() == [(0, 0), (2, 0), pytest.approx((2, 2))]
    assert isinstance(leg, Leg)


def test_scans_are_taken_at_whole_multiples_of_the_scan_period_including_the_start() -> None:
    np.testing.assert_allclose(scan_times(50.0, 0.1), [0.0, 0.02, 0.04, 0.06, 0.08, 0.1])
    assert len(scan_times(10.0, 0.0)) == 1


def test_the_swept_polygons_hold_every_footprint_along_the_path() -> None:
    route = (Point2D(3, 0), Point2D(3, 3))
    path = nominal_path(Pose2D(0, 0, 0), route, speed=1.0, turn_rate=1.0)
    pieces = swept_polygons(path, FOOTPRINT, 0.0, path.duration)
    for pose in path.poses_at(np.linspace(0.0, path.duration, 200)):
        corners = place(FOOTPRINT, pose)
        assert any(_contains(piece, corners) for piece in pieces), pose


def test_only_the_stretch_asked_for_is_swept() -> None:
    path = nominal_path(Pose2D(0, 0, 0), (Point2D(10, 0),), speed=1.0, turn_rate=1.0)
    (piece,) = swept_polygons(path, FOOTPRINT, 2.0, 3.0)
    assert piece[:, 0].min() == pytest.approx(1.5)
    assert piece[:, 0].max() == pytest.approx(3.5)


def _contains(polygon: np.ndarray, points: np.ndarray) -> bool:
    edges = np.roll(polygon, -1, axis=0) - polygon
    for start, edge in zip(polygon, edges, strict=True):
        cross = edge[0] * (points[:, 1] - start[1]) - edge[1] * (points[:, 0] - start[0])
        if np.any(cross < -1e-9):
            return False
    return True


def _late_run(path: NominalPath, times: np.ndarray, late: float) -> np.ndarray:
    """The poses (T, 3) of a run that does what the path does, `late` s later."""
    return path.poses_at(np.maximum(times - late, 0.0))


def test_a_run_that_sets_off_late_times_the_path_by_when_it_crosses_each_leg() -> None:
    route = (Point2D(4, 0), Point2D(4, 4))
    path = nominal_path(Pose2D(0, 0, 0), route, speed=1.0, turn_rate=1.0)
    times = np.arange(0.0, 20.0, 0.02)
    timed = timed_to(path, times, _late_run(path, times, late=0.5))

    first, turn, second = timed.segments
    assert first.begins == pytest.approx(0.5, abs=0.02)
    assert second.begins == pytest.approx(path.segments[2].begins + 0.5, abs=0.02)
    assert turn.begins + abs(turn.angle) / path.turn_rate == pytest.approx(second.begins)
    # Where the legs and turns lie is the path's own.
    assert timed.polyline() == path.polyline()


def test_a_leg_the_run_never_reached_keeps_its_nominal_time_as_late_as_the_last() -> None:
    # Out and back: the way back begins where the way out began, so only a run that has got
    # to the far end may time it.
    route = (Point2D(4, 0), Point2D(0, 0))
    path = nominal_path(Pose2D(0, 0, 0), route, speed=1.0, turn_rate=1.0)
    times = np.arange(0.0, 3.0, 0.02)  # the run stops after 3 s, 2.5 m out
    out, _, back = timed_to(path, times, _late_run(path, times, late=0.5)).segments

    assert out.begins == pytest.approx(0.5, abs=0.02)
    assert back.begins == pytest.approx(path.segments[2].begins + 0.5, abs=0.02)
