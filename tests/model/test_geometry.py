"""Angles and mounts: wrapping an angle, and composing a mount's rotation as URDF does."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Pose3D, crossing_edges, orientation, wrap_angle


def test_wrapping_an_angle_lands_in_minus_pi_inclusive_to_pi_exclusive() -> None:
    angles = np.array([math.pi, -math.pi, 1.5 * math.pi, -1.5 * math.pi, 0.25, 7.0])

    np.testing.assert_allclose(
        wrap_angle(angles),
        [-math.pi, -math.pi, -0.5 * math.pi, 0.5 * math.pi, 0.25, 7.0 - 2 * math.pi],
        atol=1e-12,
    )


def test_a_mount_rotation_is_a_proper_rotation_composed_as_urdf_does() -> None:
    rng = np.random.default_rng(7)
    for roll, pitch, yaw in rng.uniform(-math.pi, math.pi, size=(25, 3)):
        rx = np.array(
            [[1, 0, 0], [0, math.cos(roll), -math.sin(roll)], [0, math.sin(roll), math.cos(roll)]]
        )
        ry = np.array(
            [
                [math.cos(pitch), 0, math.sin(pitch)],
                [0, 1, 0],
                [-math.sin(pitch), 0, math.cos(pitch)],
            ]
        )
        rz = np.array(
            [[math.cos(yaw), -math.sin(yaw), 0], [math.sin(yaw), math.cos(yaw), 0], [0, 0, 1]]
        )

        rotation = Pose3D(rpy=(roll, pitch, yaw)).rotation()

        np.testing.assert_allclose(rotation @ rotation.T, np.eye(3), atol=1e-12)
        assert np.linalg.det(rotation) == pytest.approx(1.0)
        np.testing.assert_allclose(rotation, rz @ ry @ rx, atol=1e-12)


def test_orientation_is_positive_counter_clockwise_negative_clockwise_and_zero_on_a_line() -> None:
    assert orientation((0.0, 0.0), (1.0, 0.0), (1.0, 1.0)) == 1.0
    assert orientation((0.0, 0.0), (1.0, 1.0), (1.0, 0.0)) == -1.0
    assert orientation((1.0, 2.0), (3.0, 4.0), (5.0, 6.0)) == 0.0


STAR = [(math.cos(k * 4 * math.pi / 5), math.sin(k * 4 * math.pi / 5)) for k in range(5)]


@pytest.mark.parametrize(
    ("corners", "crossing"),
    [
        ([(1, 1), (1, -1), (-1, -1), (-1, 1)], None),
        ([(1, 1), (-1, -1), (1, -1), (-1, 1)], (0, 2)),
        (STAR, (0, 2)),
        ([(2, 0), (0, 0.5), (-2, 0), (0, 2)], None),  # an arrowhead: not convex, not crossing
        ([(1, 2), (3, 4), (5, 6)], None),  # on one line, as Nav2's footprint test reads one
        ([(0, 0), (2, 0), (2, 1), (1, 0), (0, 1)], None),  # a corner on an edge only touches
    ],
    ids=["square", "bow-tie", "star", "arrowhead", "on-one-line", "touching"],
)
def test_the_edges_of_an_outline_cross_only_where_they_pass_through_each_other(
    corners: list[tuple[float, float]], crossing: tuple[int, int] | None
) -> None:
    assert crossing_edges(corners) == crossing
