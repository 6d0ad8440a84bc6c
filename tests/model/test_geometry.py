"""Angles and mounts: wrapping an angle, and composing a mount's rotation as URDF does."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Pose3D, wrap_angle


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
