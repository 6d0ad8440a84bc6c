"""What the corpus tests share: the corpus files by answer-key ID (F01...), the answer key's
tables, the `Description` a test reads, and helpers that build and compare profiles.

Both corpus test modules, test_corpus_urdf.py and test_corpus_sdf.py, import them from here; the
fixtures they use (the assembled packages, the descriptions built on them) are in this folder's
conftest.py.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass, replace
from pathlib import Path

import pytest

from pytest_lasertest.descriptions.lasers import DescriptionFile, Laser, read_lasers
from pytest_lasertest.descriptions.profile import ReadProfile, read_profile
from pytest_lasertest.descriptions.readers import WorkingTree
from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.sensor import GaussianNoise, LaserProfile
from tests.helpers import DATA

CORPUS = DATA / "corpus"
STUBS = DATA / "stubs"

HUSKY_NOETIC = CORPUS / "husky/noetic-devel/husky_description"
HUSKY_KINETIC = CORPUS / "husky/kinetic-devel/husky_description"
LMS1XX = CORPUS / "LMS1xx/noetic-devel"  # the lms1xx ROS package: the repository is the package
TURTLEBOT3 = CORPUS / "turtlebot3/noetic/turtlebot3_description"
JACKAL = CORPUS / "jackal/noetic-devel/jackal_description"
GAZEBO_PLUGINS = CORPUS / "gazebo_ros_pkgs/noetic-devel/gazebo_plugins"

F01 = HUSKY_NOETIC / "urdf/husky.urdf.xacro"
F02 = HUSKY_NOETIC / "urdf/accessories/sick_lms1xx_mount.urdf.xacro"
F03 = HUSKY_NOETIC / "urdf/accessories/hokuyo_ust10.urdf.xacro"
F04 = HUSKY_KINETIC / "urdf/husky.urdf.xacro"
F05 = HUSKY_KINETIC / "urdf/accessories/sick_lms1xx_mount.urdf.xacro"
F06 = LMS1XX / "urdf/sick_lms1xx.urdf.xacro"
F14 = TURTLEBOT3 / "urdf/turtlebot3_burger.gazebo.xacro"
F15 = TURTLEBOT3 / "urdf/turtlebot3_burger.urdf.xacro"
F16 = TURTLEBOT3 / "urdf/turtlebot3_waffle.gazebo.xacro"
F17 = CORPUS / "turtlebot3_simulations/main/turtlebot3_gazebo/models/turtlebot3_burger/model.sdf"
F18 = (
    CORPUS / "turtlebot3_simulations/noetic-devel/turtlebot3_gazebo/models/turtlebot3_burger"
    "/model.sdf"
)
F19 = JACKAL / "urdf/accessories/hokuyo_utm30.urdf.xacro"
F20 = GAZEBO_PLUGINS / "test/multi_robot_scenario/xacro/laser/hokuyo_gpu.xacro"
F21 = CORPUS / "sdformat/main/test/sdf/sensors.sdf"
F22 = CORPUS / "gz-sim/main/examples/worlds/export_occupancy_grid.sdf"

# The packages the husky accessories include unconditionally (flir_blackfly_mount, vlp16_mount),
# as stand-ins: none of them holds a 2D laser.
STUB_PACKAGES = {
    name: STUBS / name
    for name in ("velodyne_description", "fath_pivot_mount_description", "flir_camera_description")
}
# The answer key gives the husky mounts in base_link; the gate composes them into base_footprint,
# which husky.urdf.xacro puts wheel_vertical_offset - wheel_radius = 0.03282 - 0.1651 below it.
HUSKY_FOOTPRINT_DEPTH = 0.1651 - 0.03282  # m, 0.13228
ROLL_UPSIDE_DOWN = 3.14159  # husky.urdf.xacro's M_PI, not math.pi
# xacro's $(optenv VAR default) reads these; a developer's robot setup must not switch lasers on.
ROBOT_ENVIRONMENT = ("HUSKY_", "JACKAL_", "CPR_", "OUTDOORNAV_", "ROBOT_NAMESPACE", "GAZEBO_WORLD_")
EXACT = 1e-6  # m and rad: the mounts are sums of a few literals


# --- the answer key's tables -----------------------------------------------------------------

# F01: husky noetic-devel
HUSKY_LASERS = {
    # id: (xacro args, sensor, laser name, answer key's base_link xyz, rpy)
    "F01a-lms1xx-front-on-its-tower": (
        {"laser_enabled": "1"},
        None,
        "front_laser",
        (0.337, 0.0, 0.30795),
        (ROLL_UPSIDE_DOWN, 0.0, 0.0),
    ),
    "F01a-prime-lms1xx-front-without-tower": (
        {"laser_enabled": "1", "laser_tower": "0"},
        None,
        "front_laser",
        (0.3568, 0.0, 0.28785),
        (0.0, 0.0, 0.0),
    ),
    "F01b-lms1xx-rear": (
        {"laser_secondary_enabled": "1"},
        None,
        "rear_laser",
        # y: ~9e-8, because the mount turns by 3.14159, not pi
        (-0.1746, 0.0, 0.30795),
        (ROLL_UPSIDE_DOWN, 0.0, 3.14159),
    ),
    "F01c-ust10-front": (
        {"laser_ust10_front_enabled": "1"},
        None,
        "front_laser",
        (0.3018, 0.0, 0.29875),
        (0.0, 0.0, 0.0),
    ),
    "F01d-ust10-rear": (
        {"laser_ust10_rear_enabled": "1"},
        None,
        "rear_laser",
        (-0.1394, 0.0, 0.29875),
        (0.0, 0.0, 3.14159),
    ),
    "F01ab-sensor-picks-the-rear": (
        {"laser_enabled": "1", "laser_secondary_enabled": "1"},
        "rear_laser",
        "rear_laser",
        (-0.1746, 0.0, 0.30795),
        (ROLL_UPSIDE_DOWN, 0.0, 3.14159),
    ),
    "F01ab-sensor-picks-the-front": (
        {"laser_enabled": "1", "laser_secondary_enabled": "1"},
        "front_laser",
        "front_laser",
        (0.337, 0.0, 0.30795),
        (ROLL_UPSIDE_DOWN, 0.0, 0.0),
    ),
}

# F02: the LMS1xx mount called from a robot file of the user's own, which defines no M_PI
LMS1XX_MOUNT_CALL = (
    '  <xacro:include filename="$(find husky_description)/urdf/accessories/'
    'sick_lms1xx_mount.urdf.xacro"/>\n'
    '  <link name="base_link"/>\n'
    '  <xacro:sick_lms1xx_mount prefix="front" parent="base_link" topic="scan"'
    ' robot_namespace="/">\n'
    '    <origin xyz="0 0 0" rpy="0 0 0"/>\n'
    "  </xacro:sick_lms1xx_mount>"
)

# F21: sdformat's sensor test fixture
F21_ERRORS = {
    # sensor: (line, field, what the problem says)
    None: (
        1,
        "--sensor",
        "has 2 2D lasers: 'gpu_ray_sensor' (line 198), 'gpu_lidar_sensor' (line 202)",
    ),
    "gpu_ray_sensor": (
        198,
        "gpu_ray_sensor",
        "the gpu_ray sensor 'gpu_ray_sensor' has no <ray> or <lidar> block",
    ),
    "gpu_lidar_sensor": (202, "gpu_lidar_sensor", "the gpu_lidar sensor sets no <update_rate>"),
    # The line of the <vertical><samples>240</samples>.
    "ray_sensor": (
        334,
        "ray_sensor: <samples>",
        "the sensor 'ray_sensor' scans 240 vertical samples: it is a 3D lidar",
    ),
    "lidar_sensor": (
        365,
        "lidar_sensor: <samples>",
        "the sensor 'lidar_sensor' scans 240 vertical samples: it is a 3D lidar",
    ),
}


@dataclass(frozen=True)
class Description:
    """A top description file and the packages its `$(find)`s need."""

    path: Path
    packages: Mapping[str, Path]

    def read(self, *, sensor: str | None = None, **args: str) -> ReadProfile:
        """The laser the gate reads from it, with xacro args NAME=VALUE."""
        return read_profile(self.path, sensor=sensor, ref=None, args=args, packages=self.packages)

    def error(self, *, sensor: str | None = None, **args: str) -> SpecError:
        """The error reading it raises."""
        with pytest.raises(SpecError) as caught:
            self.read(sensor=sensor, **args)
        return caught.value


def husky_packages(husky_description: Path) -> dict[str, Path]:
    """The packages the husky's description needs: its own (`husky_description`), LMS1xx's,
    and the stand-ins."""
    return {"husky_description": husky_description, "lms1xx": LMS1XX, **STUB_PACKAGES}


def read(path: Path, **packages: Path) -> ReadProfile:
    """The laser of a corpus file (or a wrapper) that needs no xacro args."""
    return Description(path, packages).read()


def error_of(path: Path, packages: Mapping[str, Path], *, sensor: str | None = None) -> SpecError:
    return Description(path, packages).error(sensor=sensor)


def lasers(path: Path) -> tuple[Laser, ...]:
    return read_lasers(DescriptionFile(path, WorkingTree()))


def wrapper(directory: Path, body: str) -> Path:
    """A robot file of the user's own that includes a corpus macro file and calls its macro."""
    path = directory / "robot.urdf.xacro"
    path.write_text(
        '<?xml version="1.0"?>\n<robot name="mine" xmlns:xacro="http://ros.org/wiki/xacro">\n'
        f"{body}\n</robot>\n"
    )
    return path


def clearpath_laser(
    xyz: tuple[float, float, float], rpy: tuple[float, float, float]
) -> LaserProfile:
    """The ray block F06 (LMS1xx) and F03 (UST10) share: their macros' defaults."""
    return LaserProfile(
        samples=720,
        resolution=1,
        min_angle=-2.35619,
        max_angle=2.35619,
        range_min=0.1,
        range_max=30.0,
        range_resolution=0.01,
        update_rate=50,
        noise=GaussianNoise(mean=0.0, stddev=0.001),
        pose=Pose3D(xyz, rpy),
    )


def on_husky(
    in_base_link: tuple[float, float, float], rpy: tuple[float, float, float]
) -> LaserProfile:
    """A husky laser at the answer key's base_link mount, as the gate reads it (base_footprint)."""
    x, y, z = in_base_link
    return clearpath_laser((x, y, z + HUSKY_FOOTPRINT_DEPTH), rpy)


def lds_01(xyz: tuple[float, float, float], max_angle: float) -> LaserProfile:
    """The TurtleBot3 burger's LDS-01 as its Gazebo descriptions write it (F14-F18)."""
    return LaserProfile(
        samples=360,
        resolution=1,
        min_angle=0.0,
        max_angle=max_angle,
        range_min=0.12,
        range_max=3.5,
        range_resolution=0.015,
        update_rate=5,
        noise=GaussianNoise(mean=0.0, stddev=0.01),
        pose=Pose3D(xyz),
    )


def assert_profile(got: ReadProfile, expected: LaserProfile, base: str) -> None:
    """Every profile field equal (the files write them as literals), the mount within 1e-6, in
    the frame `base`."""
    level = Pose3D()
    assert replace(got.profile, pose=level) == replace(expected, pose=level)
    assert got.profile.pose.xyz == pytest.approx(expected.pose.xyz, abs=EXACT)
    assert got.profile.pose.rpy == pytest.approx(expected.pose.rpy, abs=EXACT)
    assert got.laser.mount().base == base


def assert_at(error: SpecError, path: Path, line: int) -> None:
    assert (error.location.path, error.location.line) == (path, line), str(error)


# --- the copies ------------------------------------------------------------------------------


def sha256sums() -> Iterator[tuple[str, str]]:
    for line in (CORPUS / "SHA256SUMS").read_text().splitlines():
        digest, name = line.split(maxsplit=1)
        yield digest, name
