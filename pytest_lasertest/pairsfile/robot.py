"""The `robot:` of a pairs file: a bundled robot by name, a robot.yaml path, or a robot written in
place: a robot file's fields, where `urdf:` may stand for `laser_mount:` and the description then
gives the mount:

    robot:
      urdf: robots/mybot.urdf.xacro     # with ref:, args:, packages:, sensor: as a scanner's
      body: {height: 0.3}               # optional: its description's collision shapes
      footprint: [[-0.3, -0.2], [0.3, -0.2], [0.3, 0.2], [-0.3, 0.2]]
      max_linear_velocity: 0.8
      ...                               # the robot file's other fields, but laser_mount
"""

from __future__ import annotations

import difflib
from pathlib import Path

from pytest_lasertest.inputs.node import Bounds, SpecNode, read_root
from pytest_lasertest.model.body import Body
from pytest_lasertest.model.geometry import Pose3D, crossing_edges, orientation
from pytest_lasertest.model.robot import MAX_CORNERS, MAX_FOOTPRINT_REACH, Robot, pad_footprint
from pytest_lasertest.model.scanner_limits import ProfileError, check_mount
from pytest_lasertest.pairsfile.body import BODY_FIX, described_body, read_body
from pytest_lasertest.pairsfile.bundled import ROBOT_FILE, bundled_robots
from pytest_lasertest.pairsfile.described import (
    DESCRIPTION_KEYS,
    is_described,
    read_described,
)
from pytest_lasertest.pairsfile.nav2_params import read_nav2
from pytest_lasertest.pairsfile.navigation import load_navigation_file

REQUIRED_KEYS = (
    "name",
    "body",
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
    "nav2",
    "nav2_version",
)
ROBOT_KEYS = REQUIRED_KEYS + OPTIONAL_KEYS
# A robot written in place: the robot file's keys, and its description's, which stand for
# `laser_mount` (the description then gives the mount and, unless `name` is written, the name).
IN_PLACE_KEYS = DESCRIPTION_KEYS + ROBOT_KEYS
# move_base's default controller_frequency is 20 Hz: a scan reaches the wheels one period later.
DEFAULT_REACTION_TIME = 0.05  # s
# Every bound is far beyond a real mobile robot's figure (the Husky's in brackets), so none is
# refused; beyond them a figure is a typo, and the messages say what it would cost.
# The physics steps every 20 ms: faster, the robot jumps further than a thin pole is wide.
SPEED = Bounds(
    0.0,
    20.0,
    "m/s",
    "the robot must move",
    "at 20 m/s it moves 0.4 m in one 20 ms physics step, past thin obstacles unseen",
    above_low=True,
)  # (1.0)
TURN_RATE = Bounds(
    0.0,
    20.0,
    "rad/s",
    "the robot must turn",
    "at 20 rad/s it turns 0.4 rad in one 20 ms physics step",
    above_low=True,
)  # (2.0)
# How hard it brakes sets how far ahead it must see an obstacle: near zero, that is the world.
ACCELERATION = Bounds(
    0.01,
    100.0,
    "m/s^2",
    "the robot would take minutes and metres to stop",
    "10 g is beyond any wheeled robot",
)  # (3.0)
ANGULAR_ACCELERATION = Bounds(
    0.01,
    1000.0,
    "rad/s^2",
    "the robot would take minutes to start turning",
    "no wheeled robot starts turning that fast",
)  # (6.0)
# The nominal pace times the path scan by scan: slower, a path of minutes holds millions of scans.
NOMINAL_SPEED = Bounds(
    0.01, 20.0, "m/s", "the path would take hours at this pace, scan by scan", SPEED.too_high
)  # (0.5)
NOMINAL_TURN_RATE = Bounds(
    0.01, 20.0, "rad/s", "each turn would take minutes, scan by scan", TURN_RATE.too_high
)  # (1.0)
REACTION_TIME = Bounds(
    0.0,
    10.0,
    "s",
    "no robot reacts before it reads a scan",
    "a robot that reacts 10 s late has driven past anything it saw",
)  # (0.2)
PADDING = Bounds(
    0.0, 1.0, "m", "costmap_2d pads a footprint outward", "padding is a few centimetres"
)  # (0.01)


def read_robot(node: SpecNode) -> Robot:
    """The robot a pairs file names, resolved against the bundled robots, then its directory; or
    the robot written in place around its description."""
    if isinstance(node.value, dict):
        return _read_in_place(node)
    return load_robot_file(resolve_robot(node))


def load_robot_file(path: Path) -> Robot:
    """A robot from its robot.yaml."""
    root = read_root(path, what="robot file", needs=", ".join(REQUIRED_KEYS))
    fields = root.mapping(ROBOT_KEYS, what="robot fields")
    _require(root, fields, REQUIRED_KEYS, "a robot file")
    return _robot(fields, fields["name"].text(), _mount(fields["laser_mount"]))


def _read_in_place(node: SpecNode) -> Robot:
    """A robot written in the pairs file: its laser mount read from its description, or
    written as a robot file writes it (as a repro pins a mount it read)."""
    fields = node.mapping(IN_PLACE_KEYS, what="robot fields")
    if not is_described(fields):
        if "laser_mount" not in fields:
            raise node.missing(
                "urdf",
                "write `urdf: FILE` (or `sdf: FILE`) to read the laser mount from the robot's "
                "description, or `laser_mount: {xyz: [...], rpy: [...]}`; or name a bundled "
                "robot or a robot.yaml",
            )
        _require(node, fields, REQUIRED_KEYS, "a robot written in place")
        return _robot(fields, fields["name"].text(), _mount(fields["laser_mount"]))
    if "laser_mount" in fields:
        raise fields["laser_mount"].error(
            "the laser mount of a robot written around its description is read from it",
            "drop laser_mount, or drop urdf: and write the mount yourself",
        )
    needed = tuple(key for key in REQUIRED_KEYS if key not in ("name", "laser_mount", "body"))
    _require(node, fields, needed, "a robot written in place")
    described = {key: fields.pop(key) for key in DESCRIPTION_KEYS if key in fields}
    file_node = described.get("urdf", described.get("sdf", node))
    # A profile's mount is checked as it is made (level scan plane): it serves as the robot's.
    laser = read_described(node, described)
    name = fields["name"].text() if "name" in fields else laser.label
    body = None if "body" in fields else described_body(node, file_node, laser)
    return _robot(fields, name, laser.profile.pose, body)


def _require(node: SpecNode, fields: dict[str, SpecNode], keys: tuple[str, ...], what: str) -> None:
    for key in keys:
        if key not in fields:
            fix = BODY_FIX if key == "body" else f"{what} needs {', '.join(keys)}"
            raise node.missing(key, fix)


def _robot(
    fields: dict[str, SpecNode], name: str, mount: Pose3D, body: Body | None = None
) -> Robot:
    """The robot the robot file's fields describe, named `name`, its laser at `mount`; without
    a `body` field, `body`."""
    top_speed = fields["max_linear_velocity"].number_in(SPEED)
    top_turn_rate = fields["max_angular_velocity"].number_in(TURN_RATE)
    padding = _optional(fields, "footprint_padding", PADDING, 0.0)
    footprint = _footprint(fields["footprint"])
    if body is None:
        body = read_body(fields["body"], footprint)
    robot = Robot(
        name=name,
        laser_mount=mount,
        footprint=pad_footprint(footprint, padding),
        max_linear_velocity=top_speed,
        max_linear_acceleration=fields["max_linear_acceleration"].number_in(ACCELERATION),
        max_angular_velocity=top_turn_rate,
        max_angular_acceleration=fields["max_angular_acceleration"].number_in(ANGULAR_ACCELERATION),
        nominal_speed=_nominal(fields, "nominal_speed", NOMINAL_SPEED, top_speed),
        nominal_turn_rate=_nominal(fields, "nominal_turn_rate", NOMINAL_TURN_RATE, top_turn_rate),
        reaction_time=_optional(fields, "reaction_time", REACTION_TIME, DEFAULT_REACTION_TIME),
        navigation=load_navigation_file(fields["navigation"]) if "navigation" in fields else (),
        body=body,
    )
    return read_nav2(fields, robot)


def _mount(node: SpecNode) -> Pose3D:
    mount = node.mapping(("xyz", "rpy"), what="mount pose fields")
    for key in ("xyz", "rpy"):
        if key not in mount:
            raise node.missing(key, f"write `{key}: [0.0, 0.0, 0.0]`")
    pose = Pose3D(xyz=mount["xyz"].triple("m"), rpy=mount["rpy"].triple("rad"))
    try:
        check_mount(pose)
    except ProfileError as error:
        raise mount[error.field.split(".")[-1]].error(error.problem, error.fix) from None
    return pose


def _optional(fields: dict[str, SpecNode], key: str, bounds: Bounds, default: float) -> float:
    return fields[key].number_in(bounds) if key in fields else default


def _nominal(fields: dict[str, SpecNode], key: str, bounds: Bounds, top: float) -> float:
    """A nominal pace, no faster than the robot's top one, which it is by default."""
    if key not in fields:
        return top
    pace = fields[key].number_in(bounds)
    if pace > top:
        limit = "max_linear_velocity" if key == "nominal_speed" else "max_angular_velocity"
        raise fields[key].error(
            f"{pace:g} {bounds.unit} is faster than the robot's {limit}, {top:g} {bounds.unit}",
            f"write a {key} of at most {top:g} {bounds.unit}, or leave it out to cruise at "
            "the top one",
        )
    return pace


def _footprint(node: SpecNode) -> tuple[tuple[float, float], ...]:
    """A convex polygon around the base origin (on its edge at least), as costmap_2d's
    `footprint` parameter."""
    example = (
        "write the corners as ROS does, "
        "e.g. [[-0.5, -0.33], [-0.5, 0.33], [0.5, 0.33], [0.5, -0.33]]"
    )
    corners = node.items(what="footprint corners [x, y]")
    if len(corners) > MAX_CORNERS:
        raise node.error(
            f"{len(corners)} corners are more than the {MAX_CORNERS} the gate accepts: "
            "costmaps test every edge at every cell they check",
            "write the robot's outline with fewer corners (a rectangle has 4)",
        )
    points = [_corner(corner) for corner in corners]
    if len(points) < 3:
        raise node.error(f"{len(points)} corners enclose no area", example)
    turns = [orientation(points[i - 2], points[i - 1], points[i]) for i in range(len(points))]
    if not (all(turn > 0 for turn in turns) or all(turn < 0 for turn in turns)):
        raise node.error("the corners do not form a convex polygon", example)
    # Turning one way at every corner, a star's outline goes round more than once.
    if crossing_edges(points) is not None:
        raise node.error(
            "the corners do not form a convex polygon: its edges cross each other",
            f"list the corners in order round the robot; {example}",
        )
    ordered = points if turns[0] > 0 else points[::-1]
    # On an edge is inside, as costmap_2d's own tests have it (footprint_tests.cpp's triangle).
    if any(orientation(ordered[i - 1], ordered[i], (0.0, 0.0)) < 0 for i in range(len(ordered))):
        raise node.error("the polygon does not contain the robot's origin", example)
    return tuple((x, y) for x, y in ordered)


def _corner(node: SpecNode) -> tuple[float, ...]:
    point = node.vector(2, "m")
    if max(abs(point[0]), abs(point[1])) > MAX_FOOTPRINT_REACH:
        raise node.error(
            f"the corner ({point[0]:g}, {point[1]:g}) m lies more than {MAX_FOOTPRINT_REACH:g} m "
            "from the robot's origin: no mobile robot is that large, and costmaps rasterise "
            "the footprint cell by cell",
            "write the corners in m around the base origin, e.g. [0.5, 0.33]",
        )
    return point


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
