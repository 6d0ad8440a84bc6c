"""The profile read from a description: the LMS1xx xacro's names for three fields, a laser hung
upside down, and an SDF model's laser mounted by its link and sensor poses."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from pytest_lasertest.descriptions.profile import read_profile
from pytest_lasertest.model.sensor import LaserProfile
from tests.helpers.texts import ROBOT


def read(tmp_path: Path, text: str) -> LaserProfile:
    """The profile of the one laser in a description with this text."""
    path = tmp_path / "robot.urdf"
    path.write_text(text)
    return read_profile(path, sensor=None, ref=None, args={}, packages={}).profile


def test_the_lms1xx_xacro_names_of_three_fields_are_read_as_gazebo_s(tmp_path: Path) -> None:
    aliased = (
        ROBOT.replace("<samples>32</samples>", "<sample_size>32</sample_size>")
        .replace("<min>0.1</min>", "<min_range>0.1</min_range>")
        .replace("<max>10.0</max>", "<max_range>10.0</max_range>")
    )
    assert read(tmp_path, aliased) == read(tmp_path, ROBOT)


def test_a_laser_hung_upside_down_mirrors_an_asymmetric_field_of_view(tmp_path: Path) -> None:
    asymmetric = ROBOT.replace("<min_angle>-1.57</min_angle>", "<min_angle>-0.5</min_angle>")
    upright = read(tmp_path, asymmetric.replace("<max_angle>1.57", "<max_angle>1.5"))
    hung = read(
        tmp_path,
        asymmetric.replace("<max_angle>1.57", "<max_angle>1.5").replace(
            '<origin xyz="0.3 0 0.2" rpy="0 0 0"/>', '<origin xyz="0.3 0 0.2" rpy="3.14159 0 0"/>'
        ),
    )
    # +theta in the laser frame is -theta in the base frame: [-0.5, 1.5] becomes [-1.5, 0.5].
    assert upright.sector_in_base() == pytest.approx((-0.5, 2.0))
    assert hung.sector_in_base() == pytest.approx((-1.5, 2.0), abs=1e-5)
    assert hung.pose.is_upside_down()


def test_an_sdf_model_s_laser_is_mounted_by_its_link_and_sensor_poses(tmp_path: Path) -> None:
    sdf = tmp_path / "model.sdf"
    sdf.write_text(
        '<sdf version="1.9"><model name="bot"><pose>5 5 0 0 0 1</pose>'
        "<link name='base'/><link name='lidar'><pose>0.1 0 0.2 0 0 1.5707963267948966</pose>"
        "<sensor name='scan' type='gpu_lidar'><pose>0.05 0 0.1 0 0 0</pose>"
        "<update_rate>10</update_rate><lidar><scan><horizontal><samples>90</samples>"
        "<min_angle>-1</min_angle><max_angle>1</max_angle></horizontal></scan>"
        "<range><min>0.1</min><max>8</max></range></lidar></sensor></link>"
        # A joint's pose does not move the link it names.
        "<joint name='j' type='fixed'><parent>base</parent><child>lidar</child>"
        "<pose>9 9 9 0 0 0</pose></joint></model></sdf>"
    )
    described = read_profile(sdf, sensor=None, ref=None, args={}, packages={})
    # The model's own pose places it in the world, not the laser on the robot.
    assert described.profile.pose.xyz == pytest.approx((0.1, 0.05, 0.3))
    assert described.profile.pose.rpy == pytest.approx((0.0, 0.0, math.pi / 2))
    assert described.laser.mount().base == "bot"
