"""The `robot:` of a pairs file: a bundled robot by name, or a robot.yaml path."""

from __future__ import annotations

import difflib
from pathlib import Path

from pytest_lasertest.inputs.node import SpecNode, read_root
from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.robot import Robot, pad_footprint
from pytest_lasertest.pairsfile.bundled import ROBOT_FILE, bundled_robots
from pytest_lasertest.pairsfile.navigation import load_navigation_file

REQUIRED_KEYS = (
    "name",
    "laser_mount",
    "footprint",
    "max_linear_velocity",
    "max_linear_acceleration",
    "max_angular_velocity",
    "max_angular_acceleration",
)
OPTIONAL_KEYS = (
    "footprint_padding",
    "nominal_speed",
    "nominal_turn_rate",
    "reaction_time",
    "navigation",
)
ROBOT_KEYS = REQUIRED_KEYS + OPTIONAL_KEYS
# move_base's default controller_frequency is 20 Hz: a scan reaches the wheels one period later.
DEFAULT_REACTION_TIME = 0.05  # s


def read_robot(node: SpecNode) -> Robot:
    """The robot a pairs file names, resolved against the bundled robots, then its directory."""
    return load_robot_file(resolve_robot(node))


def load_robot_file(path: Path) -> Robot:
    """A robot from its robot.yaml."""
    root = read_root(path, what="robot file", needs=", ".join(REQUIRED_KEYS))
    fields = root.mapping(ROBOT_KEYS, what="robot fields")
    for key in REQUIRED_KEYS:
        if key not in fields:
            raise root.missing(key, f"a robot file needs {', '.join(REQUIRED_KEYS)}")
    top_speed = _positive(fields["max_linear_velocity"], "m/s", "its top speed")
    top_turn_rate = _positive(fields["max_angular_velocity"], "rad/s", "its top turn rate")
    padding = fields["footprint_padding"].number("m") if "footprint_padding" in fields else 0.0
    return Robot(
        name=fields["name"].text(),
        laser_mount=_mount(fields["laser_mount"]),
        footprint=pad_footprint(_footprint(fields["footprint"]), padding),
        max_linear_velocity=top_speed,
        max_linear_acceleration=_positive(
            fields["max_linear_acceleration"], "m/s^2", "how hard it brakes"
        ),
        max_angular_velocity=top_turn_rate,
        max_angular_acceleration=_positive(
            fields["max_angular_acceleration"], "rad/s^2", "how fast it starts turning"
        ),
        nominal_speed=_optional(fields, "nominal_speed", "m/s", "its cruising speed", top_speed),
        nominal_turn_rate=_optional(
            fields, "nominal_turn_rate", "rad/s", "how fast it turns in place", top_turn_rate
        ),
        reaction_time=_optional(
            fields, "reaction_time", "s", "its reaction time", DEFAULT_REACTION_TIME, zero=True
        ),
        navigation=load_navigation_file(fields["navigation"]) if "navigation" in fields else (),
    )


def _mount(node: SpecNode) -> Pose3D:
    mount = node.mapping(("xyz", "rpy"), what="mount pose fields")
    for key in ("xyz", "rpy"):
        if key not in mount:
            raise node.missing(key, f"write `{key}: [0.0, 0.0, 0.0]`")
    return Pose3D(xyz=mount["xyz"].triple("m"), rpy=mount["rpy"].triple("rad"))


def _positive(node: SpecNode, unit: str, what: str, *, zero: bool = False) -> float:
    value = node.number(unit)
    if value < 0 or (value == 0 and not zero):
        raise node.error(f"{node.value} {unit} cannot be {what}", f"write {what} in {unit}")
    return value


def _optional(
    fields: dict[str, SpecNode],
    key: str,
    unit: str,
    what: str,
    default: float,
    *,
    zero: bool = False,
) -> float:
    return _positive(fields[key], unit, what, zero=zero) if key in fields else default


def _footprint(node: SpecNode) -> tuple[tuple[float, float], ...]:
    """A convex polygon around the base origin, as costmap_2d's `footprint` parameter."""
    example = (
        "write the corners as ROS does, "
        "e.g. [[-0.5, -0.33], [-0.5, 0.33], [0.5, 0.33], [0.5, -0.33]]"
    )
    points = [point.vector(2, "m") for point in node.items(what="footprint corners [x, y]")]
    if len(points) < 3:
        raise node.error(f"{len(points)} corners enclose no area", example)
    turns = [_cross(points[i - 2], points[i - 1], points[i]) for i in range(len(points))]
    if not (all(turn > 0 for turn in turns) or all(turn < 0 for turn in turns)):
        raise node.error("the corners do not form a convex polygon", example)
    ordered = points if turns[0] > 0 else points[::-1]
    if any(_cross(ordered[i - 1], ordered[i], (0.0, 0.0)) <= 0 for i in range(len(ordered))):
        raise node.error("the polygon does not contain the robot's origin", example)
    return tuple((x, y) for x, y in ordered)


def _cross(a: tuple[float, ...], b: tuple[float, ...], c: tuple[float, ...]) -> float:
    return (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0])


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
