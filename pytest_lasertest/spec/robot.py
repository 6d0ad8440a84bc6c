"""The `robot:` of a pairs file: a bundled robot by name, or a robot.yaml path."""

from __future__ import annotations

import difflib
from pathlib import Path

from pytest_lasertest.geometry import Pose3D
from pytest_lasertest.robot import Robot
from pytest_lasertest.spec.bundled import ROBOT_FILE, bundled_robots
from pytest_lasertest.spec.node import SpecNode, read_root

ROBOT_KEYS = ("name", "laser_mount", "max_linear_velocity")


def read_robot(node: SpecNode) -> Robot:
    """The robot a pairs file names, resolved against the bundled robots, then its directory."""
    return load_robot_file(resolve_robot(node))


def load_robot_file(path: Path) -> Robot:
    """A robot from its robot.yaml."""
    root = read_root(path, what="robot file", needs=", ".join(ROBOT_KEYS))
    fields = root.mapping(ROBOT_KEYS, what="robot fields")
    for key in ROBOT_KEYS:
        if key not in fields:
            raise root.missing(key, f"a robot file needs {', '.join(ROBOT_KEYS)}")
    mount = fields["laser_mount"].mapping(("xyz", "rpy"), what="mount pose fields")
    for key in ("xyz", "rpy"):
        if key not in mount:
            raise fields["laser_mount"].missing(key, f"write `{key}: [0.0, 0.0, 0.0]`")
    speed = fields["max_linear_velocity"]
    if speed.number("m/s") <= 0:
        raise speed.error(f"{speed.value} m/s cannot move the robot", "write its top speed in m/s")
    return Robot(
        name=fields["name"].text(),
        laser_mount=Pose3D(xyz=mount["xyz"].triple("m"), rpy=mount["rpy"].triple("rad")),
        max_linear_velocity=speed.number("m/s"),
    )


def resolve_robot(node: SpecNode) -> Path:
    """The robot.yaml that `robot:` names."""
    name = node.text()
    bundled = bundled_robots()
    if name in bundled:
        return bundled[name]
    path = node.location.path.parent / name
    if path.is_dir():
        path = path / ROBOT_FILE
    if path.is_file():
        return path
    close = difflib.get_close_matches(name, list(bundled), n=1, cutoff=0.5)
    hint = f"did you mean {close[0]!r}? " if close else ""
    raise node.error(
        f"{name!r} is neither a bundled robot nor a file or directory next to this file",
        f"{hint}bundled robots: {', '.join(bundled)}; or give a path to a {ROBOT_FILE}",
    )
