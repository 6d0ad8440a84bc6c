"""A robot written in place around its own description (`robot: {urdf: ..., ...}`): the laser
mount comes from the description, the values a description does not hold from the pairs file."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.model.body import Body
from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.pairsfile import PairsFile, load_pairs_file
from tests.helpers.git import commit_everything
from tests.helpers.runs import Case, assert_spec_error
from tests.helpers.texts import ROBOT, write

# Line numbers matter: the cases below break one line of it.
PAIRS = """\
robot:
  urdf: robot.urdf
  body: {height: 0.3}
  footprint: [[-0.3, -0.2], [0.3, -0.2], [0.3, 0.2], [-0.3, 0.2]]
  max_linear_velocity: 0.8
  max_linear_acceleration: 1.5
  max_angular_velocity: 1.2
  max_angular_acceleration: 3.0
world: {start: {x: 0, y: 0}, goal: {x: 6, y: 0}, time_limit: 30}
pairs:
  swap:
    baseline: {model: clearpath_lms1xx_gazebo}
    candidate: {model: clearpath_lms1xx_gazebo, samples: 180}
"""
# ROBOT's laser: base_link 0.1 m above base_footprint, the laser 0.3 m ahead and 0.2 m above it.
MOUNT = Pose3D(xyz=(0.3, 0.0, 0.3), rpy=(0.0, 0.0, 0.0))


def load(tmp_path: Path, pairs: str = PAIRS, robot: str = ROBOT) -> PairsFile:
    write(tmp_path, robot, "robot.urdf")
    return load_pairs_file(write(tmp_path, pairs))


def test_the_laser_mount_is_read_from_the_description_and_the_rest_from_the_pairs_file(
    tmp_path: Path,
) -> None:
    robot = load(tmp_path).robot
    assert robot.laser_mount.xyz == pytest.approx(MOUNT.xyz)
    assert robot.laser_mount.rpy == pytest.approx(MOUNT.rpy)
    assert robot.name == "front in robot.urdf"
    assert robot.max_linear_velocity == 0.8
    assert robot.body == Body("prism", robot.body.outline, 0.3)


def test_a_catalogue_scanner_without_a_pose_stands_where_the_description_mounts_the_laser(
    tmp_path: Path,
) -> None:
    spec = load(tmp_path)
    for pair in spec.pairs:
        assert pair.baseline.profile.pose.xyz == pytest.approx(MOUNT.xyz)
        assert pair.candidate.profile.pose.xyz == pytest.approx(MOUNT.xyz)


def test_a_moved_laser_in_the_description_moves_the_robots_mount(tmp_path: Path) -> None:
    moved = ROBOT.replace('<origin xyz="0.3 0 0.2" rpy="0 0 0"/>', '<origin xyz="0.1 0 0.4"/>')
    spec = load(tmp_path, robot=moved)
    assert spec.robot.laser_mount.xyz == pytest.approx((0.1, 0.0, 0.5))


def test_at_a_git_ref_the_mount_is_the_committed_descriptions(tmp_path: Path) -> None:
    load(tmp_path)  # writes robot.urdf and the pairs file
    commit_everything(tmp_path)
    moved = ROBOT.replace('<origin xyz="0.3 0 0.2" rpy="0 0 0"/>', '<origin xyz="0.1 0 0.4"/>')
    at_head = PAIRS.replace("  urdf: robot.urdf\n", "  urdf: robot.urdf\n  ref: HEAD\n")

    spec = load(tmp_path, at_head, robot=moved)

    assert spec.robot.laser_mount.xyz == pytest.approx(MOUNT.xyz)
    assert "at HEAD" in spec.robot.name


def test_a_robot_written_in_place_with_its_mount_needs_no_description(tmp_path: Path) -> None:
    written = PAIRS.replace(
        "  urdf: robot.urdf\n",
        "  name: R2\n  laser_mount: {xyz: [0.2, 0, 0.4], rpy: [0, 0, 0]}\n",
    )
    robot = load(tmp_path, written).robot
    assert (robot.name, robot.laser_mount.xyz) == ("R2", (0.2, 0.0, 0.4))
    assert robot.body.height == 0.3


def test_a_name_written_in_place_names_the_robot(tmp_path: Path) -> None:
    spec = load(tmp_path, PAIRS.replace("  urdf: robot.urdf\n", "  urdf: robot.urdf\n  name: R1\n"))
    assert spec.robot.name == "R1"


def wheel(name: str, y: float) -> str:
    """A wheel's link, a cylinder 0.2 m across turned onto its side, and the continuous joint
    that puts it `y` m left of base_link."""
    return f"""<link name="{name}">
    <collision>
      <origin rpy="1.5708 0 0"/>
      <geometry><cylinder radius="0.1" length="0.05"/></geometry>
    </collision>
  </link>
  <joint name="{name}_joint" type="continuous">
    <parent link="base_link"/>
    <child link="{name}"/>
    <origin xyz="0 {y:g} 0"/>
  </joint>"""


# ROBOT with collision geometry: a 0.2 m high chassis box whose top is 0.3 m up, wheels
# (cylinders turned onto their sides, 0.2 m across) and the laser's 5 cm box, topping out at
# 0.3 + 0.025 m.
COLLIDING = ROBOT.replace(
    '<link name="base_link"/>',
    """<link name="base_link">
    <collision>
      <origin xyz="0 0 0.1"/>
      <geometry><box size="0.6 0.4 0.2"/></geometry>
    </collision>
  </link>
  """
    + wheel("wheel", 0.22),
).replace(
    '<link name="laser"/>',
    """<link name="laser">
    <collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision>
  </link>""",
)
WITHOUT_BODY = PAIRS.replace("  body: {height: 0.3}\n", "")


def test_without_a_body_the_body_is_the_descriptions_collision_shapes_in_base_footprint(
    tmp_path: Path,
) -> None:
    robot = load(tmp_path, WITHOUT_BODY, COLLIDING).robot
    assert robot.body.kind == "description"
    assert [c.shape for c in robot.body.collisions] == ["box", "cylinder", "box"]
    # From the wheel's bottom on the ground to the top of the laser's box.
    assert robot.body.height == pytest.approx(0.325)
    # The chassis, the left wheel reaching past it and the laser's box past its front.
    extent = robot.body.extent()
    assert extent == pytest.approx(np.array([[-0.3, -0.2], [0.325, 0.245]]), abs=1e-6)


def test_a_wheel_on_its_side_reaches_up_by_its_radius_and_a_tall_one_by_half_its_length(
    tmp_path: Path,
) -> None:
    tall = COLLIDING.replace('<box size="0.6 0.4 0.2"/>', '<box size="0.6 0.4 0.01"/>').replace(
        '<box size="0.05 0.05 0.05"/>', '<box size="0.01 0.01 0.01"/>'
    )

    def top(description: str) -> float:
        return Body.top(load(tmp_path, WITHOUT_BODY, description).robot.body.collisions)

    # The laser's 1 cm box tops out at 0.305 m; the wheel's centre is 0.1 m up.
    assert top(tall) == pytest.approx(0.305)
    assert top(tall.replace('rpy="1.5708 0 0"', 'rpy="0 0 0"')) == pytest.approx(0.305)
    higher = tall.replace('length="0.05"', 'length="0.6"').replace('rpy="1.5708 0 0"', "")
    assert top(higher) == pytest.approx(0.4)


# COLLIDING with a second wheel, on the right: the pair a differential base rolls on.
ON_TWO_WHEELS = COLLIDING.replace(
    '<link name="laser">', wheel("right_wheel", -0.22) + '\n  <link name="laser">'
)


def test_cylinders_that_continuous_joints_turn_left_and_right_are_the_wheels_it_drives_on(
    tmp_path: Path,
) -> None:
    body = load(tmp_path, WITHOUT_BODY, ON_TWO_WHEELS).robot.body
    assert [c.shape for c in body.wheels] == ["cylinder", "cylinder"]
    assert body.track() == pytest.approx((0.1, 0.44))
    assert body.describe().endswith("driven through its 2 wheel joints (differential)")


def test_a_description_with_a_wheel_on_one_side_only_slides_and_says_so(tmp_path: Path) -> None:
    body = load(tmp_path, WITHOUT_BODY, COLLIDING).robot.body
    assert body.wheels == ()
    assert body.describe().endswith("moved at the commanded twist")


def test_a_continuous_joint_turning_a_standing_cylinder_is_no_wheel(tmp_path: Path) -> None:
    # A spinning scanner's drum, say: it turns about the vertical, not about an axle.
    standing = ON_TWO_WHEELS.replace('rpy="1.5708 0 0"', 'rpy="0 0 0"', 1)
    body = load(tmp_path, WITHOUT_BODY, standing).robot.body
    assert body.wheels == ()


def test_a_collision_mesh_gives_no_body_and_the_body_must_be_written(tmp_path: Path) -> None:
    meshed = COLLIDING.replace('<box size="0.6 0.4 0.2"/>', '<mesh filename="base.stl"/>')
    with pytest.raises(SpecError) as raised:
        load(tmp_path, WITHOUT_BODY, meshed)
    assert (raised.value.location.line, raised.value.field) == (1, "robot.body")
    assert "cannot be read (it holds a mesh" in raised.value.fix


def test_a_box_of_two_lengths_is_an_error_at_its_line_in_the_description(tmp_path: Path) -> None:
    broken = COLLIDING.replace('<box size="0.6 0.4 0.2"/>', '<box size="0.6 0.4"/>')
    with pytest.raises(SpecError) as raised:
        load(tmp_path, WITHOUT_BODY, broken)
    assert raised.value.location.path.name == "robot.urdf"
    assert (raised.value.location.line, raised.value.field) == (7, "<box>")
    assert '<box size="0.6 0.4"> is not 3 positive lengths' in raised.value.problem


def test_a_box_a_kilometre_long_is_an_error_at_its_line_in_the_description(
    tmp_path: Path,
) -> None:
    huge = COLLIDING.replace('<box size="0.6 0.4 0.2"/>', '<box size="1000 0.4 0.2"/>')
    with pytest.raises(SpecError) as raised:
        load(tmp_path, WITHOUT_BODY, huge)
    assert (raised.value.location.line, raised.value.field) == (7, "<box>")
    assert "is larger than the 5 m any part of a wheeled robot is" in raised.value.problem


CASES = {
    "a mount written beside the description": Case(
        "  body: {height: 0.3}\n",
        "  body: {height: 0.3}\n  laser_mount: {xyz: [0, 0, 0.3], rpy: [0, 0, 0]}\n",
        4,
        "robot.laser_mount",
        "the laser mount of a robot written around its description is read from it",
        "drop laser_mount",
    ),
    "no description": Case(
        "  urdf: robot.urdf\n",
        "",
        1,
        "robot.urdf",
        "missing",
        "to read the laser mount from the robot's description, or `laser_mount:",
    ),
    "no body": Case(
        "  body: {height: 0.3}\n",
        "",
        1,
        "robot.body",
        "missing",
        "write `body: husky`",
    ),
    "a description that does not exist": Case(
        "urdf: robot.urdf",
        "urdf: robots/mybot.urdf",
        1,  # of the file not found, as for a scanner's description; the problem names line 2
        "",
        "robots/mybot.urdf does not exist (read for robot.urdf at gate.lasertest.yaml:2)",
        "check the path",
    ),
    "a misspelt field": Case(
        "  max_linear_velocity: 0.8\n",
        "  max_linear_velocity: 0.8\n  max_linear_velocty: 0.8\n",
        6,
        "robot.max_linear_velocty",
        "unknown",
        "max_linear_velocity",
    ),
}


@pytest.mark.parametrize("case", CASES.values(), ids=CASES.keys())
def test_a_robot_written_in_place_that_cannot_be_read_is_one_error_at_its_line(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, case: Case
) -> None:
    monkeypatch.chdir(tmp_path)  # paths in messages are shown relative to the working directory
    assert case.old in PAIRS
    with pytest.raises(SpecError) as raised:
        load(tmp_path, PAIRS.replace(case.old, case.new, 1))
    # A description that is not there is reported at its own path, as a scanner's is.
    file = "mybot.urdf" if "mybot" in case.new else "gate.lasertest.yaml"
    assert_spec_error(raised.value, file, case)
