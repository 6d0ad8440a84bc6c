"""Beam angles, LaserScan fields, mount mirroring and validation of laser profiles."""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np
import pytest

from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.sensor import GaussianNoise, ProfileError
from tests.helpers.model import profile

HUSKY_ROLL = 3.14159  # rad, as the Husky description writes "upside down"


def angular_gap(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Smallest absolute angle between directions a and b, whatever side of +-pi they lie."""
    return np.abs(np.angle(np.exp(1j * (np.asarray(a) - np.asarray(b)))))


def test_beams_are_evenly_spread_from_min_angle_to_max_angle_with_both_ends_sampled() -> None:
    angles = profile(samples=5, min_angle=-1.0, max_angle=1.0).beam_angles()

    assert len(angles) == 5
    assert angles[0] == -1.0
    assert angles[-1] == 1.0
    assert angles[1] == -0.5
    np.testing.assert_allclose(angles, [-1.0, -0.5, 0.0, 0.5, 1.0], atol=1e-15)


def test_every_beam_of_a_long_scan_lies_at_min_angle_plus_k_increments() -> None:
    scanner = profile(samples=720, min_angle=-2.0, max_angle=1.5)

    expected = [-2.0 + k * 3.5 / 719 for k in range(720)]

    np.testing.assert_allclose(scanner.beam_angles(), expected, rtol=0, atol=1e-12)
    assert scanner.angle_increment == pytest.approx(3.5 / 719)


def test_a_single_beam_scanner_looks_straight_ahead_with_zero_increment() -> None:
    scanner = profile(samples=1)
    meta = scanner.to_laserscan_meta()

    np.testing.assert_array_equal(scanner.beam_angles(), [0.0])
    assert scanner.beam_count == 1
    assert scanner.angle_increment == 0.0
    assert (meta.angle_min, meta.angle_max, meta.angle_increment) == (0.0, 0.0, 0.0)


def test_an_even_beam_count_over_a_symmetric_field_of_view_has_no_beam_straight_ahead() -> None:
    scanner = profile(samples=16, min_angle=-1.57, max_angle=1.57)
    angles = scanner.beam_angles()
    increment = 3.14 / 15

    assert 0.0 not in angles
    assert angles[7] == pytest.approx(-increment / 2)
    assert angles[8] == pytest.approx(increment / 2)
    assert np.min(np.abs(angles)) == pytest.approx(increment / 2)


def test_beam_count_is_samples_times_resolution_as_in_the_sdf_example() -> None:
    assert profile(samples=320, resolution=0.9).beam_count == 288
    assert len(profile(samples=320, resolution=0.9).beam_angles()) == 288


def test_a_resolution_giving_a_fractional_beam_count_is_rejected() -> None:
    with pytest.raises(ProfileError, match="not a whole number of beams") as refused:
        profile(samples=10, resolution=0.25)

    assert refused.value.field == "resolution"


def test_the_laserscan_header_matches_the_profile() -> None:
    scanner = profile(samples=720, min_angle=-1.57, max_angle=1.57, update_rate=50.0)
    meta = scanner.to_laserscan_meta()

    assert meta.angle_min == pytest.approx(-1.57)
    assert meta.angle_max == pytest.approx(1.57)
    assert meta.angle_increment == pytest.approx(3.14 / 719)
    assert meta.scan_time == pytest.approx(0.02)
    assert meta.time_increment == 0.0
    assert meta.range_min == 0.1
    assert meta.range_max == 10.0
    assert meta.angle_min + 719 * meta.angle_increment == pytest.approx(meta.angle_max)


@pytest.mark.parametrize("roll", [math.pi, HUSKY_ROLL])
def test_an_upside_down_scanner_mirrors_an_asymmetric_field_of_view(roll: float) -> None:
    scanner = profile(
        samples=7, min_angle=-1.0, max_angle=2.0, pose=Pose3D((0.337, 0.0, 0.3), (roll, 0.0, 0.0))
    )

    in_base = scanner.beam_angles_in_base()

    np.testing.assert_allclose(in_base, [1.0, 0.5, 0.0, -0.5, -1.0, -1.5, -2.0], atol=1e-5)
    assert np.all(np.diff(in_base) < 0)
    assert scanner.sector_in_base() == pytest.approx((-2.0, 3.0), abs=1e-5)


def test_a_scanner_turned_left_a_quarter_turn_scans_a_sector_shifted_by_a_quarter_turn() -> None:
    scanner = profile(
        samples=4, min_angle=-1.0, max_angle=2.0, pose=Pose3D(rpy=(0.0, 0.0, math.pi / 2))
    )

    in_base = scanner.beam_angles_in_base()

    # 2 + pi/2 lies past +pi and comes back as 2 + pi/2 - 2 pi.
    expected = [math.pi / 2 - 1.0, math.pi / 2, math.pi / 2 + 1.0, math.pi / 2 + 2.0 - 2 * math.pi]
    np.testing.assert_allclose(in_base, expected, atol=1e-12)
    assert scanner.sector_in_base() == pytest.approx((math.pi / 2 - 1.0, 3.0), abs=1e-12)


def test_a_rear_scanner_hung_upside_down_maps_laser_angle_theta_to_pi_minus_theta() -> None:
    scanner = profile(
        samples=7, min_angle=-1.0, max_angle=2.0, pose=Pose3D(rpy=(HUSKY_ROLL, 0.0, 3.14159))
    )
    laser = np.array([-1.0, -0.5, 0.0, 0.5, 1.0, 1.5, 2.0])

    in_base = scanner.beam_angles_in_base()

    assert np.all((in_base >= -math.pi) & (in_base < math.pi))
    assert np.max(angular_gap(in_base, math.pi - laser)) < 1e-5
    start, extent = scanner.sector_in_base()
    assert start == pytest.approx(math.pi - 2.0, abs=1e-5)
    assert extent == pytest.approx(3.0)


@pytest.mark.parametrize(
    ("overrides", "field", "message"),
    [
        ({"samples": 0}, "samples", "0 beams cannot scan"),
        ({"samples": -5}, "samples", "-5 beams cannot scan"),
        ({"min_angle": 1.0, "max_angle": 1.0}, "min_angle", "must be less than max_angle"),
        ({"min_angle": 1.0, "max_angle": -1.0}, "min_angle", "must be less than max_angle"),
        ({"min_angle": -3.2, "max_angle": 3.2}, "max_angle", "exceeds a full turn"),
        ({"min_angle": 0.0, "max_angle": 2 * math.pi + 2e-4}, "max_angle", "exceeds a full turn"),
        ({"range_min": -0.1}, "range.min", "negative"),
        ({"range_max": 0.1}, "range.max", "must be greater than range.min"),
        ({"range_max": 0.05}, "range.max", "must be greater than range.min"),
        ({"update_rate": 0.0}, "update_rate", "positive rate"),
        ({"update_rate": -50.0}, "update_rate", "positive rate"),
        ({"min_angle": math.nan}, "min_angle", "not a finite number"),
        ({"range_max": math.inf}, "range.max", "not a finite number"),
        ({"update_rate": math.inf}, "update_rate", "not a finite number"),
        ({"noise": GaussianNoise(stddev=math.nan)}, "noise", "not a finite number"),
        ({"pose": Pose3D((0.0, 0.0, math.inf))}, "pose", "not a finite number"),
        ({"noise": GaussianNoise(stddev=-0.01)}, "noise.stddev", "negative"),
        ({"pose": Pose3D(rpy=(0.0, 0.1, 0.0))}, "pose.rpy", "tilted"),
        ({"pose": Pose3D(rpy=(0.1, 0.0, 0.0))}, "pose.rpy", "tilted"),
    ],
)
def test_a_profile_no_scanner_can_have_is_rejected_naming_the_field(
    overrides: dict[str, Any], field: str, message: str
) -> None:
    with pytest.raises(ProfileError, match=re.escape(message)) as refused:
        profile(**overrides)

    assert refused.value.field == field
    assert refused.value.fix


@pytest.mark.parametrize(
    "overrides",
    [
        pytest.param({"min_angle": 0.0, "max_angle": 6.28319}, id="gazebo-full-turn"),
        pytest.param({"min_angle": -math.pi, "max_angle": math.pi}, id="exact-full-turn"),
        pytest.param({"pose": Pose3D(rpy=(HUSKY_ROLL, 0.0, 0.0))}, id="husky-upside-down"),
        pytest.param({"pose": Pose3D(rpy=(0.0, 0.0, 2.5))}, id="yawed"),
        pytest.param({"range_min": 0.0}, id="no-minimum-range"),
    ],
)
def test_realistic_profiles_from_gazebo_descriptions_are_accepted(
    overrides: dict[str, Any],
) -> None:
    assert profile(**overrides).beam_count == 720


def random_scanner(rng: np.random.Generator) -> Any:
    """A scanner with a random field of view (up to a full turn), beam count and mount."""
    low = float(rng.uniform(-math.pi, 0.0))
    width = float(rng.choice([rng.uniform(0.5, 2.0 * math.pi), 2.0 * math.pi]))
    roll = float(rng.choice([0.0, math.pi]))
    mount = Pose3D(
        (float(rng.uniform(-0.4, 0.4)), float(rng.uniform(-0.2, 0.2)), 0.3),
        (roll, 0.0, float(rng.uniform(-math.pi, math.pi))),
    )
    samples = int(rng.choice([1, 2, 16, 361, 1440]))
    return profile(samples=samples, min_angle=low, max_angle=low + width, pose=mount)


def test_the_beams_near_a_point_are_every_beam_that_passes_within_reach_of_it() -> None:
    rng = np.random.default_rng(3)
    for _ in range(40):
        scanner = random_scanner(rng)
        poses = np.column_stack([rng.uniform(-3, 3, (6, 2)), rng.uniform(-4, 4, 6)])
        point, reach = (float(rng.uniform(-3, 3)), float(rng.uniform(-3, 3))), 0.3
        origins, directions = scanner.rays(poses)
        offsets = np.asarray(point) - origins
        along = np.maximum(np.einsum("tnk,tnk->tn", offsets, directions), 0.0)
        gap = np.hypot(*(offsets - along[..., np.newaxis] * directions).transpose(2, 0, 1))

        scans, beams = scanner.beams_near(poses, point, reach)

        near = set(zip(*np.nonzero(gap <= reach), strict=True))
        listed = set(zip(scans.tolist(), beams.tolist(), strict=True))
        assert near <= listed
        assert all(gap[t, k] <= reach + 1e-9 for t, k in listed)
        np.testing.assert_allclose(
            scanner.beam_directions(poses, scans, beams), directions[scans, beams], atol=1e-12
        )
