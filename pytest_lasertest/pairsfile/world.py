"""The `world:` of a pairs file: where the robot starts, where it must go, and how long it has."""

from __future__ import annotations

import math
from dataclasses import dataclass

from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.model.geometry import Point2D, Pose2D

WORLD_KEYS = ("start", "goal", "route", "time_limit")
# Closer than this, two waypoints are one: the robot cannot tell them apart.
MIN_LEG = 1e-3  # m


@dataclass(frozen=True)
class World:
    """An empty world with a start pose and a route ending at the goal."""

    start: Pose2D
    route: tuple[Point2D, ...]  # waypoints in order; the last is the goal
    time_limit: float  # s

    @property
    def goal(self) -> Point2D:
        """The last waypoint."""
        return self.route[-1]


def read_world(node: SpecNode) -> World:
    """A World from `start`, one of `goal` or `route`, and `time_limit`."""
    fields = node.mapping(WORLD_KEYS, what="world fields")
    if "start" not in fields:
        raise node.missing("start", "write `start: {x: 0.0, y: 0.0, yaw: 0.0}` (m, m, rad)")
    if "goal" in fields and "route" in fields:
        raise fields["route"].error(
            "both goal and route are given", "keep one: the goal is the route's last waypoint"
        )
    if "goal" not in fields and "route" not in fields:
        raise node.missing(
            "goal", "write `goal: {x: 10.0, y: 0.0}`, or a `route:` list of such waypoints"
        )
    if "time_limit" not in fields:
        raise node.missing("time_limit", "write the time the robot has to reach the goal, in s")
    start = _pose(fields["start"])
    waypoints = [fields["goal"]] if "goal" in fields else fields["route"].items(what="waypoints")
    if not waypoints:
        raise fields["route"].error("the route is empty", "list at least one waypoint")
    route = _route(start, waypoints)
    time_limit = fields["time_limit"]
    if time_limit.number("s") <= 0:
        raise time_limit.error(
            f"{time_limit.value} s leaves no time to drive", "write a positive time in s"
        )
    return World(start, route, time_limit.number("s"))


def _pose(node: SpecNode) -> Pose2D:
    fields = node.mapping(("x", "y", "yaw"), what="pose fields (x, y, yaw)")
    x, y = _coordinates(node, fields)
    yaw = fields["yaw"].number("rad") if "yaw" in fields else 0.0
    return Pose2D(x, y, yaw)


def _point(node: SpecNode) -> Point2D:
    fields = node.mapping(("x", "y"), what="point fields (x, y)")
    return Point2D(*_coordinates(node, fields))


def _coordinates(node: SpecNode, fields: dict[str, SpecNode]) -> tuple[float, float]:
    for key in ("x", "y"):
        if key not in fields:
            raise node.missing(key, f"write the {key} coordinate in m")
    return fields["x"].number("m"), fields["y"].number("m")


def _route(start: Pose2D, nodes: list[SpecNode]) -> tuple[Point2D, ...]:
    route: list[Point2D] = []
    previous = Point2D(start.x, start.y)
    for node in nodes:
        point = _point(node)
        if math.dist((point.x, point.y), (previous.x, previous.y)) < MIN_LEG:
            raise node.error(
                f"this waypoint ({point.x}, {point.y}) is where the robot already is",
                "remove it, or move it at least 1 mm away",
            )
        route.append(point)
        previous = point
    return tuple(route)
