"""The real, public SDF files of the corpus (F17, F18, F21, F22): each parses to the profile
its answer key gives, or fails with a message that says exactly why.

test_corpus_urdf.py explains the corpus (tests/data/corpus, its README.md and the answer key) and
tests the xacro/URDF files; corpus.py holds the paths, tables and helpers, and conftest.py the
fixtures.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.sensor import LaserProfile
from tests.descriptions.corpus import (
    EXACT,
    F17,
    F18,
    F21,
    F21_ERRORS,
    F22,
    assert_at,
    assert_profile,
    error_of,
    lasers,
    lds_01,
    read,
)

pytestmark = pytest.mark.usefixtures("no_robot_environment")


# --- F17, F18, F22: SDF models and worlds ----------------------------------------------------


@pytest.mark.parametrize(
    ("path", "kind", "link", "line", "update_rate"),
    [(F17, "gpu_lidar", "base_scan", 135, 5), (F18, "ray", "lidar", 94, 1800)],
    ids=["F17-main-lidar-crlf", "F18-noetic-ray"],
)
def test_the_turtlebot3_burger_sdf_places_its_lds_in_the_model_frame(
    path: Path, kind: str, link: str, line: int, update_rate: int
) -> None:
    # The link has no <pose>; the sensor's <pose> is the mount. The lidar_joint's pose does not
    # move the link, and the IMU's <update_rate>200 (F17) is not the scan rate.
    got = read(path)
    assert (got.laser.name, got.laser.link, got.laser.kind) == ("hls_lfcd_lds", link, kind)
    assert (got.laser.node.location.path, got.laser.node.location.line) == (path, line)
    expected = replace(lds_01((-0.032, 0.0, 0.171), 6.28), update_rate=update_rate)
    assert_profile(got, expected, "turtlebot3_burger")


def test_the_gz_sim_explorer_world_lidar_has_no_noise_and_ignores_the_plugin_resolution() -> None:
    got = read(F22)
    assert (got.laser.name, got.laser.link, got.laser.kind) == ("gpu_lidar", "link", "gpu_lidar")
    expected = LaserProfile(
        samples=640,
        resolution=1,  # not the FreeSpaceExplorer plugin's <resolution>0.25
        min_angle=0.0,
        max_angle=6.28,
        range_min=0.08,
        range_max=9.0,
        range_resolution=0.01,
        update_rate=10,
        noise=None,
        pose=Pose3D(),  # no sensor or link pose; the model's own pose is in the world
    )
    assert_profile(got, expected, "model_with_lidar")
    assert got.profile.noise is None


# --- F21: sdformat's sensor test fixture -----------------------------------------------------


def test_sdformats_fixture_with_an_unbound_prefix_still_yields_its_four_lasers() -> None:
    # F21 note: <my_namespace:custom_sensor> has no xmlns declaration; that is not an error.
    written = F21.read_bytes()
    assert b"<my_namespace:custom_sensor>" in written
    assert b"xmlns:my_namespace" not in written
    assert [(laser.name, laser.kind, laser.planar) for laser in lasers(F21)] == [
        ("gpu_ray_sensor", "gpu_ray", True),
        ("gpu_lidar_sensor", "gpu_lidar", True),
        ("ray_sensor", "ray", False),
        ("lidar_sensor", "lidar", False),
    ]


@pytest.mark.parametrize(
    ("sensor", "line", "field", "problem"),
    [(sensor, *expected) for sensor, expected in F21_ERRORS.items()],
    ids=[str(sensor) for sensor in F21_ERRORS],
)
def test_no_laser_of_sdformats_fixture_is_a_usable_2d_scanner_and_each_says_why(
    sensor: str | None, line: int, field: str, problem: str
) -> None:
    error = error_of(F21, {}, sensor=sensor)
    assert_at(error, F21, line)
    assert error.field == field
    assert problem in error.problem


def test_sdformats_gpu_lidar_with_a_legacy_ray_block_is_read_up_to_its_missing_rate() -> None:
    # F21 (b): libsdformat reads a <ray> child of a gpu_lidar as its <lidar>.
    (laser,) = [laser for laser in lasers(F21) if laser.name == "gpu_lidar_sensor"]
    fields = {key: node.value for key, node in laser.fields().items()}
    assert fields == {
        "samples": 640,
        "resolution": 1,
        "min_angle": -1.396263,
        "max_angle": 1.396263,
        "range.min": 0.08,
        "range.max": 10.0,
        "range.resolution": 0.01,
    }
    assert laser.mount().pose.xyz == pytest.approx((1.0, 2.0, 6.0), abs=EXACT)
    assert laser.mount().base == "model"


@pytest.mark.parametrize("name", ["ray_sensor", "lidar_sensor"])
def test_sdformats_3d_lidars_keep_their_horizontal_fields(name: str) -> None:
    # F21 (c), (d): resolution 0.9 and a noise mean of 0.98, unlike any other corpus laser.
    (laser,) = [laser for laser in lasers(F21) if laser.name == name]
    fields = {key: node.value for key, node in laser.fields().items()}
    assert fields["samples"] == 320
    assert fields["resolution"] == 0.9
    assert (fields["noise.mean"], fields["noise.stddev"]) == (0.98, 0.76)
    assert "update_rate" not in fields
