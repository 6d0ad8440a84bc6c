"""Where a laser sits on the robot: its link's pose composed down the description's frames.

URDF: the joint chain from the root link to the sensor's link (every joint at its zero
position), then the sensor's `<pose>`, expressed in `base_footprint` when the robot has one (the
ground-level frame ROS navigation works in), else in the root link. SDFormat: the link's `<pose>`
in its model (and each nested model's pose in its parent), then the sensor's `<pose>`; the
model frame is the base. SDF joint poses do not move links, so they are not read.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from pytest_lasertest.descriptions.laser_block import Locate
from pytest_lasertest.descriptions.xmlfile import XmlElement
from pytest_lasertest.model.geometry import Pose3D

FOOTPRINT = "base_footprint"
POSE_FIX = "write six numbers: x y z (m) roll pitch yaw (rad)"
MAX_POSE_NUMBER = 1e6  # m or rad, in any one <origin> or <pose>


@dataclass(frozen=True)
class Mount:
    """A sensor's pose in the robot's base frame, and that frame's name."""

    pose: Pose3D
    base: str


def urdf_mount(robot: XmlElement, link: str, sensor: XmlElement, locate: Locate) -> Mount:
    """The mount of a sensor on `link` of a URDF `<robot>`."""
    links = {element.get("name") for element in robot.all("link")}
    if link not in links:
        raise locate(sensor).error(
            f"the sensor hangs on link {link!r}, which this description does not define: is it "
            "a fragment that another file includes?",
            "point `urdf:` at the robot description that defines the link and its joints",
        )
    joints = _joints(robot, links, locate)
    up_from_link = _chain(link, joints, locate)
    base = FOOTPRINT if FOOTPRINT in links else _root(link, up_from_link)
    in_base = link_poses(robot, base, locate).get(link)
    if in_base is None:
        raise locate(sensor).error(
            f"no joint chain joins the sensor's link {link!r} to {base!r}",
            "join the laser's link to the robot with joints",
        )
    _check_fixed(link, up_from_link, _chain(base, joints, locate), locate)
    return Mount(in_base.then(sdf_pose(sensor.child("pose"), locate)), base)


def _check_fixed(
    link: str, up_from_link: list[_Joint], up_from_base: list[_Joint], locate: Locate
) -> None:
    """Refuse a joint between the base and the sensor's link that moves: the laser's pose
    would move with it (a laser turning about x on a continuous joint scans no level plane),
    and the gate reads the mount at the joint's zero."""
    shared = {id(joint) for joint in up_from_base}
    for joint in up_from_link:
        kind = joint.element.get("type")
        if id(joint) not in shared and kind != "fixed":
            raise locate(joint.element).error(
                f"the sensor's link {link!r} hangs on the {kind} joint "
                f"{joint.element.get('name')!r}: its pose moves with the joint, and the gate "
                "tests a scanner fixed to the robot",
                "mount the scanner on fixed joints; a turning or tilting scanner is no planar "
                "laser the gate imitates",
            )


def link_poses(robot: XmlElement, base: str, locate: Locate) -> dict[str, Pose3D]:
    """The pose in `base`'s frame of every link of a URDF `<robot>` that a joint chain joins to
    it, every joint at its zero position."""
    names = [element.get("name") for element in robot.all("link")]
    joints = _joints(robot, set(names), locate)
    up_from_base = _chain(base, joints, locate)
    root, in_root = _root(base, up_from_base), _in_root(up_from_base).inverse()
    poses = {}
    for link in (name for name in names if name is not None):  # in document order
        up_from_link = _chain(link, joints, locate)
        if _root(link, up_from_link) == root:
            poses[link] = in_root.then(_in_root(up_from_link))
    return poses


def spinning_links(robot: XmlElement, locate: Locate) -> set[str]:
    """The links a `continuous` joint turns without limit: a wheel's, say."""
    links = {element.get("name") for element in robot.all("link")}
    joints = _joints(robot, links, locate)
    return {link for link, joint in joints.items() if joint.element.get("type") == "continuous"}


@dataclass(frozen=True)
class _Joint:
    parent: str
    origin: Pose3D
    element: XmlElement


def _joints(robot: XmlElement, links: set[str | None], locate: Locate) -> dict[str, _Joint]:
    """Each child link's joint; SpecError at a joint that names a link the robot does not
    define, or gives a link a second parent (urdfdom refuses both; picking one would place
    the laser on a guess)."""
    joints: dict[str, _Joint] = {}
    for joint in robot.all("joint"):
        parent, child = (
            _link_of(joint, "parent", links, locate),
            _link_of(joint, "child", links, locate),
        )
        if child in joints:
            first = joints[child].element
            raise locate(joint).error(
                f"link {child!r} has two parent joints: {first.get('name')!r} (line "
                f"{locate(first).location.line}) and {joint.get('name')!r}",
                "a URDF is a tree: give every link one parent joint, and remove the other",
            )
        joints[child] = _Joint(parent, urdf_origin(joint, locate), joint)
    _check_one_root(robot, joints, locate)
    return joints


def _check_one_root(robot: XmlElement, joints: Mapping[str, _Joint], locate: Locate) -> None:
    """Refuse a second root link, one no joint joins to the rest (urdfdom's "Two root links
    found"): whatever hangs from it is no part of the robot the file describes."""
    roots = [link for link in robot.all("link") if link.get("name") not in joints]
    if len(roots) > 1:
        first, second = roots[0], roots[1]
        raise locate(second).error(
            f"link {second.get('name')!r} is a second root link: no joint joins it to "
            f'{first.get("name")!r} and the rest (urdfdom refuses it: "Two root links '
            'found")',
            f"join {second.get('name')!r} to the robot with a joint, or remove it",
        )


def _link_of(joint: XmlElement, end: str, links: set[str | None], locate: Locate) -> str:
    """The link a joint's <parent> or <child> names, which the robot must define."""
    element = joint.child(end)
    if element is None:
        raise locate(joint).error(
            f"joint {joint.get('name')!r} lacks <parent link> or <child link>",
            'give every joint <parent link="..."/> and <child link="..."/>',
        )
    link = element.get("link") or ""
    if link not in links:
        raise locate(joint).error(
            f"joint {joint.get('name')!r} names the {end} link {link!r}, which this "
            "description does not define",
            f'define <link name="{link}"/>, or correct the joint\'s <{end} link="...">; for a '
            "fragment that another file completes, give the scanner's full `pose:` next to "
            "`urdf:`",
        )
    return link


def urdf_origin(element: XmlElement, locate: Locate) -> Pose3D:
    """The `<origin xyz rpy>` of a URDF joint, collision or visual: where it sits in its
    parent's frame."""
    origin = element.child("origin")
    if origin is None:
        return Pose3D()
    xyz = _numbers(origin, origin.get("xyz") or "0 0 0", 3, locate)
    rpy = _numbers(origin, origin.get("rpy") or "0 0 0", 3, locate)
    return Pose3D(xyz=(xyz[0], xyz[1], xyz[2]), rpy=(rpy[0], rpy[1], rpy[2]))


def _chain(link: str, joints: Mapping[str, _Joint], locate: Locate) -> list[_Joint]:
    """The joints from `link` up to the root link, nearest first."""
    chain: list[_Joint] = []
    while link in joints:
        joint = joints[link]
        if any(seen is joint for seen in chain):
            raise locate(joint.element).error(
                f"the joints form a loop through link {link!r}",
                "a URDF is a tree: give every link one parent, and the root none",
            )
        chain.append(joint)
        link = joint.parent
    return chain


def _root(link: str, chain: list[_Joint]) -> str:
    """The root link of `link`, whose chain up is `chain`."""
    return chain[-1].parent if chain else link


def _in_root(chain: list[_Joint]) -> Pose3D:
    """The pose, in the root link's frame, of the link whose chain up is `chain`."""
    pose = Pose3D()
    for joint in reversed(chain):
        pose = pose.then(joint.origin)
    return pose


def sdf_mount(
    models: tuple[XmlElement, ...], link: XmlElement, sensor: XmlElement, locate: Locate
) -> Mount:
    """The mount of a sensor on `link`, in the outermost of the nested `models`."""
    pose = Pose3D()
    for model in models[1:]:
        pose = pose.then(sdf_pose(model.child("pose"), locate))
    for element in (link, sensor):
        pose = pose.then(sdf_pose(element.child("pose"), locate))
    return Mount(pose, models[0].get("name") or "model")


def sdf_pose(element: XmlElement | None, locate: Locate) -> Pose3D:
    """An SDF `<pose>`: x y z roll pitch yaw, relative to its parent's frame."""
    if element is None:
        return Pose3D()
    node = locate(element)
    if element.get("relative_to") not in (None, ""):
        raise node.error(
            f"a pose relative_to {element.get('relative_to')!r} is not read by the gate",
            "write the pose relative to its parent element (leave out relative_to)",
        )
    if element.get("rotation_format") not in (None, "euler_rpy"):
        raise node.error("a quaternion pose is not read by the gate", POSE_FIX)
    x, y, z, roll, pitch, yaw = _numbers(element, element.text, 6, locate)
    if element.get("degrees") == "true":
        roll, pitch, yaw = (math.radians(angle) for angle in (roll, pitch, yaw))
    return Pose3D(xyz=(x, y, z), rpy=(roll, pitch, yaw))


def _numbers(element: XmlElement, text: str, count: int, locate: Locate) -> tuple[float, ...]:
    words = text.split()
    try:
        numbers = tuple(float(word) for word in words)
    except ValueError:
        numbers = ()
    if len(numbers) != count or not all(math.isfinite(number) for number in numbers):
        raise locate(element).error(
            f"<{element.tag}> holds {text.strip()!r}, not {count} numbers",
            POSE_FIX if count == 6 else f"write {count} numbers separated by spaces",
        )
    if any(abs(number) > MAX_POSE_NUMBER for number in numbers):
        # Frames composed from such numbers cancel to rounding noise, not to a mount.
        raise locate(element).error(
            f"<{element.tag}> holds {text.strip()!r}: a number beyond {MAX_POSE_NUMBER:g} "
            "(m or rad), which no frame of a robot holds",
            "write the pose in m and rad, relative to the parent frame",
        )
    return numbers
