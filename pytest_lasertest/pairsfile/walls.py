"""The `walls:` of a world: boxes and segments of wall a pairs file lists.

A box is written as an obstacle is, `{x: 4.0, y: 1.5, yaw: 0.0, length: 8.0, width: 0.2}`; a
segment as a line of wall with a thickness, `{from: {x: 0, y: 1}, to: {x: 8, y: 1},
thickness: 0.2}`. A segment's ends reach half its thickness past its points, so two segments
that share a point meet without a gap at the corner, as walls drawn in Gazebo's building editor
do. Either may give a `height`; walls are WALL_HEIGHT high otherwise, taller than any scanner.
"""

from __future__ import annotations

import math

from pytest_lasertest.inputs.node import Bounds, SpecNode
from pytest_lasertest.model.obstacles import Box
from pytest_lasertest.model.walls import WALL_HEIGHT

BOX_KEYS = ("x", "y", "yaw", "length", "width", "height")
SEGMENT_KEYS = ("from", "to", "thickness", "height")
# A flat lidar's cast and PyBullet's contacts stay exact for walls this thin; a wall thinner
# than a map cell would still be drawn as a whole cell.
THICKNESS = Bounds(
    0.01,
    10.0,
    "m",
    "a wall thinner than a centimetre is not one a robot meets",
    "a wall thicker than 10 m is a building: write its outline as walls",
)
EXTENT = Bounds(
    0.01,
    1000.0,
    "m",
    "a wall shorter than a centimetre is not one a robot meets",
    "a world wider than a kilometre holds more than one drive's route",
)
HEIGHT = Bounds(
    0.01,
    100.0,
    "m",
    "a wall lower than a centimetre stands below every scanner",
    "100 m is higher than any building a robot drives in",
)
# Within this of the origin a float keeps the millimetres the verifier judges by.
COORDINATE = Bounds(
    -10_000.0,
    10_000.0,
    "m",
    "positions that far out lose the millimetres the verifier judges by",
    "positions that far out lose the millimetres the verifier judges by",
)
MAX_WALLS = 500


def read_walls(node: SpecNode) -> tuple[Box, ...]:
    """The walls listed at `node`, each a box."""
    entries = node.items(what="walls")
    if len(entries) > MAX_WALLS:
        raise node.error(
            f"{len(entries)} walls are listed, more than the {MAX_WALLS} the simulator casts "
            "every scan against",
            "merge walls that meet in a line into one, or draw the building as a `map:`",
        )
    return tuple(_wall(entry) for entry in entries)


def _wall(node: SpecNode) -> Box:
    fields = node.entries(what="wall fields")
    if "from" in fields or "to" in fields:
        return _segment(node)
    return _box(node)


def _box(node: SpecNode) -> Box:
    fields = node.mapping(
        BOX_KEYS,
        what="box fields (x, y, yaw, length, width, height)",
        hints={"thickness": "a box has a length and a width; a segment has from, to, thickness"},
    )
    for key in ("x", "y", "length", "width"):
        if key not in fields:
            raise node.missing(
                key, "write a box as {x: 4.0, y: 1.5, yaw: 0.0, length: 8.0, width: 0.2} (m, rad)"
            )
    yaw = fields["yaw"].number("rad") if "yaw" in fields else 0.0
    return Box(
        fields["x"].number_in(COORDINATE),
        fields["y"].number_in(COORDINATE),
        yaw,
        fields["length"].number_in(EXTENT),
        fields["width"].number_in(THICKNESS),
        _height(fields),
    )


def _segment(node: SpecNode) -> Box:
    fields = node.mapping(
        SEGMENT_KEYS,
        what="segment fields (from, to, thickness, height)",
        hints={"width": "a segment's width is its `thickness`"},
    )
    for key in ("from", "to", "thickness"):
        if key not in fields:
            raise node.missing(
                key,
                "write a segment as {from: {x: 0.0, y: 1.0}, to: {x: 8.0, y: 1.0}, "
                "thickness: 0.2} (m)",
            )
    (x0, y0), (x1, y1) = _end(fields["from"]), _end(fields["to"])
    length = math.hypot(x1 - x0, y1 - y0)
    if length < EXTENT.low:
        raise fields["to"].error(
            f"the segment ends where it begins, at ({x0:g}, {y0:g})",
            "move `to` at least a centimetre from `from`, or write the wall as a box",
        )
    thickness = fields["thickness"].number_in(THICKNESS)
    return Box(
        (x0 + x1) / 2.0,
        (y0 + y1) / 2.0,
        math.atan2(y1 - y0, x1 - x0),
        length + thickness,
        thickness,
        _height(fields),
    )


def _end(node: SpecNode) -> tuple[float, float]:
    fields = node.mapping(("x", "y"), what="point fields (x, y)")
    for key in ("x", "y"):
        if key not in fields:
            raise node.missing(key, f"write the {key} coordinate in m")
    return fields["x"].number_in(COORDINATE), fields["y"].number_in(COORDINATE)


def _height(fields: dict[str, SpecNode]) -> float:
    return fields["height"].number_in(HEIGHT) if "height" in fields else WALL_HEIGHT
