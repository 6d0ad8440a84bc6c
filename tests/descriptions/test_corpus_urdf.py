"""Real, public robot descriptions: each one parses to the profile its answer key gives, or fails
with a message that says exactly why (a package the pairs file does not map, a macro nothing
calls, a Gazebo fragment, a 3D lidar, a sensor without an update rate). This module tests the
copies themselves and the xacro/URDF files (F01-F06, F14-F16, F19, F20); test_corpus_sdf.py tests
the SDF files (F17, F18, F21, F22).

The files are unmodified copies in tests/data/corpus (sources, commits and licences in its
README.md); the values are those of the corpus answer key (its sections 2 and 3), quoted below by
ID (F01...). Files a full xacro expansion needs but the corpus does not hold are stand-ins in
tests/data/stubs, assembled with the corpus files into one directory per ROS package.

F07-F13 (hildebrandt-carl/AutoLaserTestGen) are not here: that repository declares no licence, so
its files cannot be copied. The paper's parameter sets they carry (F07's macro variants, the
F11-F13 results) are covered by examples/paper.lasertest.yaml and its tests.

The paths, the answer key's tables and the helpers both modules use are in corpus.py, next to
this file, and their fixtures in its conftest.py.
"""

from __future__ import annotations

import hashlib
from dataclasses import replace
from pathlib import Path

import pytest

from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.sensor import GaussianNoise, LaserProfile
from pytest_lasertest.pairsfile.catalogue import load_catalogue
from tests.descriptions.corpus import (
    CORPUS,
    EXACT,
    F01,
    F02,
    F03,
    F04,
    F05,
    F06,
    F14,
    F15,
    F16,
    F17,
    F19,
    F20,
    GAZEBO_PLUGINS,
    HUSKY_LASERS,
    HUSKY_NOETIC,
    JACKAL,
    LMS1XX,
    LMS1XX_MOUNT_CALL,
    STUBS,
    TURTLEBOT3,
    Description,
    assert_at,
    assert_profile,
    clearpath_laser,
    error_of,
    lasers,
    lds_01,
    on_husky,
    read,
    sha256sums,
    wrapper,
)

pytestmark = pytest.mark.usefixtures("no_robot_environment")


# --- the copies ------------------------------------------------------------------------------


def test_the_corpus_copies_are_byte_for_byte_the_published_files() -> None:
    # Some files use CRLF on purpose (F17); git must not normalise them.
    assert (CORPUS / ".gitattributes").read_text().split() == ["*", "-text"]
    changed = [
        name
        for digest, name in sha256sums()
        if hashlib.sha256((CORPUS / name).read_bytes()).hexdigest() != digest
    ]
    assert changed == []
    assert b"\r\n" in F17.read_bytes()


def test_every_corpus_file_and_stub_has_a_licence_or_says_it_is_a_stand_in() -> None:
    listed = {name for _, name in sha256sums()}
    copied = {
        str(path.relative_to(CORPUS))
        for path in CORPUS.rglob("*")
        if path.is_file() and path.name not in ("README.md", "SHA256SUMS", ".gitattributes")
    }
    assert copied == listed
    readme = (CORPUS / "README.md").read_text()
    for name in listed:
        assert name in readme or name.endswith("LICENSE"), name
    for stub in STUBS.rglob("*.*"):
        assert stub.read_text().startswith("<!-- A stand-in written for"), stub


# --- F01: husky noetic-devel -----------------------------------------------------------------


@pytest.mark.parametrize(
    ("args", "sensor", "name", "in_base_link", "rpy"),
    HUSKY_LASERS.values(),
    ids=HUSKY_LASERS.keys(),
)
def test_a_husky_laser_its_xacro_arg_switches_on_reads_as_the_answer_key_says(
    husky: Description,
    args: dict[str, str],
    sensor: str | None,
    name: str,
    in_base_link: tuple[float, float, float],
    rpy: tuple[float, float, float],
) -> None:
    got = husky.read(sensor=sensor, **args)
    assert (got.laser.name, got.laser.link, got.laser.kind) == (name, name, "ray")
    assert_profile(got, on_husky(in_base_link, rpy), "base_footprint")


def test_the_husky_front_lms1xx_hangs_upside_down_above_base_footprint(
    husky: Description,
) -> None:
    on_tower = husky.read(laser_enabled="1").profile
    assert on_tower.pose.is_upside_down()
    assert on_tower.scan_height == pytest.approx(0.44023, abs=EXACT)
    # Without the tower the bracket is a virtual link and the scanner stands upright.
    assert not husky.read(laser_enabled="1", laser_tower="0").profile.pose.is_upside_down()


def test_the_husky_lasers_read_the_lms1xx_values_the_catalogue_model_copies(
    husky: Description,
) -> None:
    # pytest_lasertest/robots/lidars/clearpath_lms1xx_gazebo.yaml quotes F06's macro defaults.
    level = Pose3D()
    catalogued = load_catalogue().entries["clearpath_lms1xx_gazebo"].profile(level)
    assert replace(husky.read(laser_enabled="1").profile, pose=level) == catalogued


def test_husky_lasers_follow_the_environment_as_optenv_defaults_do(
    husky: Description, monkeypatch: pytest.MonkeyPatch
) -> None:
    # `laser_enabled` defaults to $(optenv HUSKY_LMS1XX_ENABLED 0): a Clearpath robot's setup.bash
    # switches the laser on without any xacro arg.
    monkeypatch.setenv("HUSKY_LMS1XX_ENABLED", "1")
    assert husky.read().laser.name == "front_laser"


def test_two_husky_lasers_need_the_sensor_named(husky: Description) -> None:
    error = husky.error(laser_enabled="1", laser_secondary_enabled="1")
    assert_at(error, husky.path, 1)
    assert error.field == "--sensor"
    assert "2 2D lasers" in error.problem
    assert "'front_laser'" in error.problem
    assert "'rear_laser'" in error.problem


def test_the_husky_with_default_args_has_no_laser_and_says_which_args_switch_one_on(
    husky: Description,
) -> None:
    error = husky.error()
    assert_at(error, husky.path, 1)
    assert error.problem.startswith("no laser")
    for arg, variable in (
        ("laser_enabled", "HUSKY_LMS1XX_ENABLED"),
        ("laser_secondary_enabled", "HUSKY_LMS1XX_SECONDARY_ENABLED"),
        ("laser_ust10_front_enabled", "HUSKY_UST10_ENABLED"),
        ("laser_ust10_rear_enabled", "HUSKY_UST10_SECONDARY_ENABLED"),
    ):
        assert f"{arg} (default '$(optenv {variable} 0)')" in error.problem


@pytest.mark.parametrize(
    ("path", "mapped", "line", "package"),
    [
        (F01, {}, 138, "husky_description"),
        (F04, {}, 44, "husky_description"),
        (F02, {}, 30, "lms1xx"),
        (F05, {}, 30, "lms1xx"),
        (F15, {}, 3, "turtlebot3_description"),
        # The corpus package alone: it lacks the accessories F01 includes (the stubs' files).
        (F01, {"husky_description": HUSKY_NOETIC}, 139, None),
    ],
    ids=["F01", "F04", "F02", "F05", "F15", "F01-corpus-package-alone"],
)
def test_a_description_names_the_package_or_include_it_lacks_at_the_line_that_needs_it(
    path: Path, mapped: dict[str, Path], line: int, package: str | None
) -> None:
    error = error_of(path, mapped)
    assert_at(error, path, line)
    if package is None:
        assert "intel_realsense.urdf.xacro, which does not exist" in error.problem
    else:
        assert f"the ROS package {package!r}" in error.problem
        assert f"packages: {{{package}: " in error.fix


def test_the_husky_names_lms1xx_in_the_accessory_that_includes_it(
    husky: Description,
) -> None:
    without = Description(
        husky.path, {name: path for name, path in husky.packages.items() if name != "lms1xx"}
    )
    error = without.error(laser_enabled="1")
    assert_at(error, husky.packages["husky_description"] / F02.relative_to(HUSKY_NOETIC), 30)
    assert "the ROS package 'lms1xx'" in error.problem


def test_a_husky_laser_is_reported_at_the_sensor_line_of_its_macro(
    husky: Description, packages: dict[str, Path]
) -> None:
    lms1xx = husky.read(laser_enabled="1").laser.node.location
    ust10 = husky.read(laser_ust10_front_enabled="1").laser.node.location
    assert (lms1xx.path, lms1xx.line) == (F06, 59)
    assert (ust10.path, ust10.line) == (
        packages["husky_noetic"] / F03.relative_to(HUSKY_NOETIC),
        19,
    )


def test_two_husky_lasers_of_one_name_are_reported_as_a_clash_not_as_missing(
    husky: Description,
) -> None:
    # Both front scanners create the link front_laser (F01 note): the description is broken.
    error = husky.error(sensor="front_laser", laser_enabled="1", laser_ust10_front_enabled="1")
    assert "front_laser" in error.problem
    assert "no laser sensor or link named" not in error.problem


# --- F02, F03, F05, F06, F19, F20: files that only define a macro -----------------------------


@pytest.mark.parametrize(
    ("path", "mapped", "macro", "where", "line"),
    [
        (F02, {"lms1xx": LMS1XX}, "sick_lms1xx_mount", F02, 32),
        (F03, {}, "hokuyo_ust10_mount", F03, 3),
        # F05's own macro holds no sensor (only the bracket): the uncalled laser is F06's.
        (F05, {"lms1xx": LMS1XX}, "sick_lms1xx", F06, 32),
        (F06, {}, "sick_lms1xx", F06, 32),
        (F19, {}, "hokuyo_utm30_mount", F19, 3),
        (F20, {}, "laser_gpu", F20, 5),
    ],
    ids=["F02", "F03", "F05", "F06", "F19", "F20"],
)
def test_a_file_that_only_defines_a_laser_macro_says_so_at_the_macro(
    path: Path, mapped: dict[str, Path], macro: str, where: Path, line: int
) -> None:
    error = error_of(path, mapped)
    assert_at(error, where, line)
    assert error.problem.startswith("no laser: the description only defines the xacro macro")
    assert f"{macro!r} (line {line})" in error.problem
    assert f"<xacro:{macro} .../>" in error.fix


def test_the_ust10_mount_passes_its_angles_through_to_the_sensor(tmp_path: Path) -> None:
    # F03 note: the inner macro's defaults are the outer macro's min_angle / max_angle.
    path = wrapper(
        tmp_path,
        '  <xacro:include filename="$(find husky_description)/urdf/accessories/'
        'hokuyo_ust10.urdf.xacro"/>\n'
        '  <link name="base_link"/>\n'
        '  <xacro:hokuyo_ust10_mount prefix="front" topic="scan" parent_link="base_link"'
        ' min_angle="-1.0" max_angle="1.0">\n'
        '    <origin xyz="0.1 0 0.2" rpy="0 0 0"/>\n'
        "  </xacro:hokuyo_ust10_mount>",
    )
    got = read(path, husky_description=HUSKY_NOETIC)
    expected = replace(clearpath_laser((0.1, 0.0, 0.2 + 0.0474), (0.0, 0.0, 0.0)), min_angle=-1.0)
    assert_profile(got, replace(expected, max_angle=1.0), "base_link")
    assert (got.laser.node.location.path, got.laser.node.location.line) == (F03, 19)


def test_the_utm30_mount_ignores_the_angles_it_is_given(tmp_path: Path) -> None:
    # F19 note: the inner macro's defaults are the literals +-2.2689, so -1.0 / 1.0 are dropped.
    # Jackal's accessories.urdf.xacro mounts it on front_mount, at (0.12, 0, 0.184) in base_link.
    path = wrapper(
        tmp_path,
        '  <xacro:include filename="$(find jackal_description)/urdf/accessories/'
        'hokuyo_utm30.urdf.xacro"/>\n'
        '  <link name="base_link"/>\n'
        '  <xacro:hokuyo_utm30_mount prefix="front" topic="front/scan" parent_link="base_link"'
        ' min_angle="-1.0" max_angle="1.0">\n'
        '    <origin xyz="0.12 0 0.184" rpy="0 0 0"/>\n'
        "  </xacro:hokuyo_utm30_mount>",
    )
    expected = replace(
        clearpath_laser((0.12, 0.0, 0.239), (0.0, 0.0, 0.0)),
        samples=1440,
        min_angle=-2.2689,
        max_angle=2.2689,
    )
    assert_profile(read(path, jackal_description=JACKAL), expected, "base_link")


def test_the_gpu_hokuyo_reads_max_angle_before_min_angle_and_skips_commented_values(
    tmp_path: Path,
) -> None:
    # F20 note: <max_angle> precedes <min_angle>, with commented-out +-3.14 beside them. The
    # call is the commented-out one in pioneer3dx.xacro. The sensor is not named after its link.
    path = wrapper(
        tmp_path,
        '  <xacro:include filename="$(find gazebo_plugins)/test/multi_robot_scenario/xacro/'
        'laser/hokuyo_gpu.xacro"/>\n'
        '  <link name="chassis"/>\n'
        '  <xacro:laser_gpu name="front_laser" parent="chassis" xyz="0.16 0 0.1" rpy="0 0 0"'
        ' meshes="package://p3dx/meshes"/>',
    )
    got = read(path, gazebo_plugins=GAZEBO_PLUGINS)
    assert (got.laser.name, got.laser.link, got.laser.kind) == (
        "head_hokuyo_sensor",
        "front_laser",
        "gpu_ray",
    )
    expected = LaserProfile(
        samples=683,
        resolution=1,
        min_angle=-2.0944,
        max_angle=2.0944,
        range_min=0.10,
        range_max=140.0,
        range_resolution=0.01,
        update_rate=30,
        noise=GaussianNoise(mean=0.0, stddev=0.01),
        pose=Pose3D((0.16, 0.0, 0.1)),
    )
    assert_profile(got, expected, "chassis")


def test_the_lms1xx_macro_called_with_its_defaults_reads_as_the_answer_key_says(
    tmp_path: Path,
) -> None:
    path = wrapper(
        tmp_path,
        '  <xacro:include filename="$(find lms1xx)/urdf/sick_lms1xx.urdf.xacro"/>\n'
        '  <link name="base_link"/>\n'
        "  <xacro:sick_lms1xx/>\n"
        '  <joint name="laser_joint" type="fixed">\n'
        '    <parent link="base_link"/><child link="laser"/>\n'
        '    <origin xyz="0.2 0 0.3" rpy="0 0 0"/>\n'
        "  </joint>",
    )
    got = read(path, lms1xx=LMS1XX)
    assert (got.laser.name, got.laser.link) == ("laser", "laser")  # F06: frame defaults to laser
    assert_profile(got, clearpath_laser((0.2, 0.0, 0.3), (0.0, 0.0, 0.0)), "base_link")


def test_the_lms1xx_mount_called_without_m_pi_names_m_pi(tmp_path: Path) -> None:
    # F02 row: standalone expansion fails, M_PI is only defined in F01/F04.
    path = wrapper(tmp_path, LMS1XX_MOUNT_CALL)
    error = error_of(path, {"lms1xx": LMS1XX, "husky_description": HUSKY_NOETIC})
    assert "M_PI" in error.problem
    assert error.problem.startswith("xacro cannot expand it")


def test_the_lms1xx_mount_called_without_m_pi_is_reported_where_m_pi_is_needed(
    tmp_path: Path,
) -> None:
    path = wrapper(tmp_path, LMS1XX_MOUNT_CALL)
    error = error_of(path, {"lms1xx": LMS1XX, "husky_description": HUSKY_NOETIC})
    assert (error.location.path, error.location.line) in {(F02, 41), (path, 5)}


# --- F04: husky kinetic-devel ----------------------------------------------------------------


def test_the_kinetic_husky_laser_calls_lack_the_xacro_prefix_newer_xacro_needs(
    husky_kinetic: Description,
) -> None:
    # F04 note: <sick_lms1xx_mount prefix="base"/> and <sick_lms1xx .../> expanded only in
    # xacro <= 1.13; from 1.14 they stay in the output as plain elements and no sensor remains.
    error = husky_kinetic.error(laser_enabled="true")
    assert_at(error, husky_kinetic.path, 142)
    assert error.problem.startswith("no laser")
    assert "<sick_lms1xx_mount> has no `xacro:` prefix" in error.problem
    assert "xacro 1.14" in error.problem
    assert "<sick_lms1xx_mount> (line 142), <sick_lms1xx> (line 144)" in error.fix


def test_the_kinetic_husky_with_default_args_has_no_laser(husky_kinetic: Description) -> None:
    error = husky_kinetic.error()
    assert_at(error, husky_kinetic.path, 1)
    assert error.problem.startswith("no laser")
    assert "laser_enabled (default 'false')" in error.problem


# --- F14, F15, F16: turtlebot3 noetic --------------------------------------------------------


@pytest.mark.parametrize(("path", "line"), [(F14, 104), (F16, 115)], ids=["F14", "F16"])
def test_a_turtlebot3_gazebo_fragment_says_its_link_is_defined_elsewhere(
    path: Path, line: int
) -> None:
    error = error_of(path, {})
    assert_at(error, path, line)
    assert error.field == "lds_lfcd_sensor"
    assert "link 'base_scan', which this description does not define" in error.problem
    assert "fragment" in error.problem


@pytest.mark.parametrize("path", [F14, F16], ids=["F14", "F16"])
def test_a_turtlebot3_gazebo_fragment_holds_one_laser_and_its_own_rate(path: Path) -> None:
    # The IMU (and, in F16, the depth camera realsense_R200) are not lasers; the plugins'
    # <updateRate> 30 and 0 (and the camera's 30.0) are not the scan rate.
    (laser,) = lasers(path)
    assert (laser.name, laser.link, laser.kind) == ("lds_lfcd_sensor", "base_scan", "ray")
    fields = {key: node.value for key, node in laser.fields().items()}
    assert fields["update_rate"] == 5
    assert fields["samples"] == 360


def test_the_depth_camera_of_the_waffle_is_not_taken_for_a_laser() -> None:
    assert [laser.name for laser in lasers(F16)] == ["lds_lfcd_sensor"]
    error = error_of(F16, {}, sensor="realsense_R200")
    assert "no laser sensor or link named 'realsense_R200'" in error.problem
    assert error.fix == "its lasers: 'lds_lfcd_sensor'"


def test_the_turtlebot3_burger_places_its_lds_above_base_footprint(
    turtlebot3_burger: Description, packages: dict[str, Path]
) -> None:
    got = turtlebot3_burger.read()
    assert (got.laser.name, got.laser.link, got.laser.kind) == (
        "lds_lfcd_sensor",
        "base_scan",
        "ray",
    )
    # scan_joint base_link -> base_scan (-0.032, 0, 0.172), base_joint 0.010 above base_footprint.
    assert_profile(got, lds_01((-0.032, 0.0, 0.182), 6.28319), "base_footprint")
    written = got.laser.node.location
    gazebo = packages["turtlebot3_description"] / F14.relative_to(TURTLEBOT3)
    assert (written.path, written.line) == (gazebo, 104)
