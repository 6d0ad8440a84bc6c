"""The schema of `world:`: the start, the goal or route, the time limit, and the walls (a map,
listed walls, an SDF world)."""

from __future__ import annotations

from pytest_lasertest.inputs.node import Bounds
from pytest_lasertest.model.walls import WALL_HEIGHT
from pytest_lasertest.pairsfile import walls, world
from pytest_lasertest.pairsfile.schema.terms import (
    Schema,
    keyed,
    listing,
    mapping,
    number,
    one_of,
    real,
    text,
)


def world_schema() -> Schema:
    """`world:`: where the robot starts, where it must go, how long it has, and the walls."""
    terms = {
        "start": _pose(),
        "goal": _point("The goal, in the world frame; the route through walls is planned"),
        "route": listing(
            "Waypoints driven in order; the last is the goal.",
            _point("A waypoint, in the world frame"),
            least=1,
            most=world.MAX_WAYPOINTS,
        ),
        "time_limit": number(world.TIME_LIMIT, "The time the robot has to reach the goal"),
        "map": text("A map_server map YAML (with its PGM or PNG image), relative to this file"),
        "walls": listing(
            "Walls listed as boxes or segments.",
            one_of("A wall.", _box(), _segment()),
            most=walls.MAX_WALLS,
        ),
        "sdf": text("An SDF world whose static models are walls, relative to this file"),
    }
    return mapping(
        "Where the robot drives.",
        keyed(world.WORLD_KEYS, terms),
        ("start", "time_limit"),
        oneOf=[{"required": ["goal"]}, {"required": ["route"]}],
    )


def _pose() -> Schema:
    terms = {**_xy(world.COORDINATE), "yaw": number(world.YAW, "The heading; 0 when left out")}
    return mapping("Where the robot starts.", terms, ("x", "y"))


def _point(description: str) -> Schema:
    return mapping(f"{description}.", _xy(world.COORDINATE), ("x", "y"))


def _box() -> Schema:
    terms = {
        "x": number(walls.COORDINATE, "Its centre's x"),
        "y": number(walls.COORDINATE, "Its centre's y"),
        "yaw": real("Its heading; 0 when left out", "rad"),
        "length": number(walls.EXTENT, "Its side along its heading"),
        "width": number(walls.THICKNESS, "Its thickness"),
        "height": number(walls.HEIGHT, f"Its height; {WALL_HEIGHT:g} when left out"),
    }
    return mapping(
        "A box of wall, written as an obstacle is.",
        keyed(walls.BOX_KEYS, terms),
        ("x", "y", "length", "width"),
    )


def _segment() -> Schema:
    end = _xy(walls.COORDINATE)
    terms = {
        "from": mapping("One end.", end, ("x", "y")),
        "to": mapping("The other end.", end, ("x", "y")),
        "thickness": number(walls.THICKNESS, "Its thickness; it reaches half of it past its ends"),
        "height": number(walls.HEIGHT, f"Its height; {WALL_HEIGHT:g} when left out"),
    }
    return mapping(
        "A line of wall with a thickness.",
        keyed(walls.SEGMENT_KEYS, terms),
        ("from", "to", "thickness"),
    )


def _xy(bounds: Bounds) -> dict[str, Schema]:
    """A point's x and y in the world frame, within `bounds`."""
    return {axis: number(bounds, f"{axis} in the world frame") for axis in ("x", "y")}
