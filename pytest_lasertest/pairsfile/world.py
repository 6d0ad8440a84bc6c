"""The `world:` of a pairs file: where the robot starts, where it must go, how long it has, and
the walls it drives between (a `map:`, listed `walls:`, the static models of an `sdf:` world,
or any of them together).

With walls, the robot's footprint must stand clear of them at the start and along every leg of
the route; a world that gives only a goal has its route planned through the walls
(`nav/waypoints.py`).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from pytest_lasertest.inputs.node import Bounds, SpecNode
from pytest_lasertest.model.geometry import FULL_TURN, FloatArray, Point2D, Pose2D
from pytest_lasertest.model.obstacles import Box, polygon_clearance
from pytest_lasertest.model.occupancy import UNKNOWN, OccupancyGrid
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.model.route import Leg, NominalPath, nominal_path, place, swept_polygons
from pytest_lasertest.model.walls import NO_WALLS, Walls
from pytest_lasertest.nav.move_base.settings import (
    NavigationSettings,
    costmap_cells,
    global_costmap_size,
)
from pytest_lasertest.nav.waypoints import CLEARANCE, plan_route
from pytest_lasertest.pairsfile.world_walls import map_corners, read_world_walls

WORLD_KEYS = ("start", "goal", "route", "time_limit", "map", "walls", "sdf")
# Closer than this, two waypoints are one: the robot cannot tell them apart.
MIN_LEG = 1e-3  # m
# Every run simulates the time limit in 20 ms physics steps, each with a scan and a command: an
# hour is 180,000 steps, many minutes of computing per run, and a pair drives dozens of runs.
TIME_LIMIT = Bounds(
    1.0,
    3600.0,
    "s",
    "the robot cannot drive anywhere in less than a second",
    "every run simulates the whole time in 20 ms steps, and a pair drives dozens of runs",
)
# The solver plans along the route scan by scan; at its nominal pace the robot must finish it
# within the longest time limit.
MAX_NOMINAL_DURATION = TIME_LIMIT.high  # s
# Every check of a placement sweeps the robot's footprint along every leg and turn.
MAX_WAYPOINTS = 100
# Far from the origin a float holds positions to less than the millimetres the verifier needs.
COORDINATE = Bounds(
    -10_000.0,
    10_000.0,
    "m",
    "positions that far out lose the millimetres the verifier judges by",
    "positions that far out lose the millimetres the verifier judges by",
)
YAW = Bounds(
    -FULL_TURN,
    FULL_TURN,
    "rad",
    "write the heading within a turn of zero",
    "write the heading within a turn of zero",
)
# The simulator counts a robot within this of the goal as arrived (`sim/oracles.py`, Rules).
GOAL_TOLERANCE = 0.2  # m


@dataclass(frozen=True)
class World:
    """A start pose, a route ending at the goal, a time limit, and the walls."""

    start: Pose2D
    route: tuple[Point2D, ...]  # waypoints in order; the last is the goal
    time_limit: float  # s
    walls: Walls = NO_WALLS

    @property
    def goal(self) -> Point2D:
        """The last waypoint."""
        return self.route[-1]


def read_world(node: SpecNode, robot: Robot) -> World:
    """A World from `start`, one of `goal` or `route`, and `time_limit`, that `robot` can drive
    within its time limit."""
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
    waypoints = [fields["goal"]] if "goal" in fields else _waypoints(fields["route"])
    route = _route(start, waypoints)
    walls = read_world_walls(fields, ((start.x, start.y), *((point.x, point.y) for point in route)))
    route_node = fields.get("route", fields.get("goal", node))
    if "map" in fields and walls.grid is not None:
        ends = [(fields["start"], Point2D(start.x, start.y))]
        _check_on_map(walls.grid, ends + [(node, _point(node)) for node in waypoints])
    if walls:
        _check_ends(start, route, walls, robot, fields)
        if "goal" in fields:
            route = _planned(start, route[-1], walls, robot, fields["goal"])
    world = World(start, route, fields["time_limit"].number_in(TIME_LIMIT), walls)
    _check_legs(world, robot, route_node)
    _check_pace(world, robot, route_node)
    _check_global_costmap(world, robot, route_node)
    _check_time_limit(world, robot, fields["time_limit"])
    return world


def _check_ends(
    start: Pose2D,
    route: tuple[Point2D, ...],
    walls: Walls,
    robot: Robot,
    fields: dict[str, SpecNode],
) -> None:
    """Refuse a start pose whose footprint stands in a wall, and a last waypoint inside one."""
    footprint = place(robot.footprint_array(), np.array([start.x, start.y, start.yaw]))
    inside = [wall for wall in walls.near(start.x, start.y, 10.0) if _overlap(footprint, wall)]
    if inside:
        raise fields["start"].error(
            f"the robot's footprint at the start ({start.x:g}, {start.y:g}) stands in the wall "
            f"{_wall(inside[0])}",
            "move the start into free space, clear of every wall",
        )
    goal = route[-1]
    if walls.holding(np.array([[goal.x, goal.y]])):
        node = fields.get("goal", fields.get("route"))
        raise (node or fields["start"]).error(
            f"the goal ({goal.x:g}, {goal.y:g}) lies inside a wall",
            "move the goal into free space, clear of every wall",
        )


def _check_on_map(grid: OccupancyGrid, points: list[tuple[SpecNode, Point2D]]) -> None:
    """Refuse a start or waypoint the map does not know: off it, or on a cell it leaves
    unknown. The map is all Nav2's static layer and move_base's know of the world, and NavFn
    would not plan to a goal off it; a map of one cell, or of unknown space, would leave the
    route in open ground where the team meant walls."""
    for node, point in points:
        if grid.values_at(np.array([[point.x, point.y]]))[0] != UNKNOWN:
            continue
        (low_x, low_y), (high_x, high_y) = map_corners(grid)
        span = f"x {low_x:g} to {high_x:g} m, y {low_y:g} to {high_y:g} m"
        raise node.error(
            f"({point.x:g}, {point.y:g}) lies off the map or on a cell it leaves unknown (the "
            f"map spans {span}): Nav2's and move_base's planners would not plan there",
            "move it onto the map's free space, or give a map that covers the route",
        )


def _planned(
    start: Pose2D, goal: Point2D, walls: Walls, robot: Robot, node: SpecNode
) -> tuple[Point2D, ...]:
    """The route through the walls to the goal, planned; an error when there is none."""
    radius = float(np.max(np.hypot(*robot.footprint_array().T)))  # m
    route = plan_route(Point2D(start.x, start.y), goal, walls, radius)
    if not route:
        raise node.error(
            f"no route from the start to the goal ({goal.x:g}, {goal.y:g}) keeps the robot "
            f"(it turns within {radius:.2f} m) {CLEARANCE:g} m clear of every wall: the walls "
            "close the way, or leave no gap wide enough",
            "check the map or the walls for a gap that should be open, or move the goal",
        )
    return route


def _check_legs(world: World, robot: Robot, node: SpecNode) -> None:
    """Refuse a route whose swept footprint runs into a wall, naming the first leg that does."""
    if not world.walls:
        return
    path = nominal_path(world.start, world.route, robot.nominal_speed, robot.nominal_turn_rate)
    footprint = robot.footprint_array()
    for index, segment in enumerate(_segments_by_waypoint(path)):
        pieces = swept_polygons(path, footprint, segment[0], segment[1])
        hit = [wall for piece in pieces for wall in world.walls.boxes if _overlap(piece, wall)]
        if hit:
            point = world.route[index]
            raise node.error(
                f"the robot's footprint runs into the wall {_wall(hit[0])} on its way to "
                f"waypoint {index + 1} ({point.x:g}, {point.y:g})",
                "add waypoints around the wall, or give only the goal and let the gate plan "
                "the route through the walls",
            )


def _segments_by_waypoint(path: NominalPath) -> list[tuple[float, float]]:
    """For each waypoint, when the robot begins turning toward it and when it arrives (s)."""
    spans, begins = [], 0.0
    for segment in path.segments:
        if isinstance(segment, Leg):
            spans.append((begins, path.end_of(segment)))
            begins = path.end_of(segment)
    return spans


def _overlap(polygon: FloatArray, wall: Box) -> bool:
    return polygon_clearance(polygon, wall) < 0.0


def _wall(box: Box) -> str:
    """A wall as a reader finds it: its centre and sides."""
    return f"at ({box.x:g}, {box.y:g}), {box.length:g} x {box.width:g} m"


def _waypoints(node: SpecNode) -> list[SpecNode]:
    waypoints = node.items(what="waypoints")
    if not waypoints:
        raise node.error("the route is empty", "list at least one waypoint")
    if len(waypoints) > MAX_WAYPOINTS:
        raise node.error(
            f"the route has {len(waypoints)} waypoints, more than the {MAX_WAYPOINTS} the gate "
            "accepts: every check of a placement sweeps the robot along every leg and turn",
            f"keep the corners that matter, at most {MAX_WAYPOINTS}; the robot drives straight "
            "between them",
        )
    return waypoints


def _check_time_limit(world: World, robot: Robot, node: SpecNode) -> None:
    """Refuse a time limit in which the robot cannot reach the goal even at its top speed."""
    length = route_length(world)
    needed = max(length - GOAL_TOLERANCE, 0.0) / robot.max_linear_velocity  # s
    if world.time_limit >= needed:
        return
    nominal = nominal_path(world.start, world.route, robot.nominal_speed, robot.nominal_turn_rate)
    raise node.error(
        f"{world.time_limit:g} s is too short for the route: it is {length:.2f} m long, and "
        f"even at its top speed of {robot.max_linear_velocity:g} m/s, never slowing or "
        f"turning, the robot needs {needed:.2f} s to come within {GOAL_TOLERANCE:g} m of the "
        "goal; every run would fail, the baseline's as well as the candidate's",
        f"raise time_limit: at its nominal pace the route takes {nominal.duration:.1f} s, so "
        f"give it about twice that, e.g. {_round_up(2.0 * nominal.duration):g} s",
    )


def _check_pace(world: World, robot: Robot, node: SpecNode) -> None:
    """Refuse a route the robot takes longer than MAX_NOMINAL_DURATION to drive at its nominal
    pace: the solver would plan along it scan by scan."""
    nominal = nominal_path(world.start, world.route, robot.nominal_speed, robot.nominal_turn_rate)
    if nominal.duration <= MAX_NOMINAL_DURATION:
        return
    raise node.error(
        f"at its nominal speed of {robot.nominal_speed:g} m/s and turn rate of "
        f"{robot.nominal_turn_rate:g} rad/s the robot takes {nominal.duration:.0f} s along this "
        f"route, more than the {MAX_NOMINAL_DURATION:g} s the gate plans along, scan by scan",
        "shorten the route, or raise the robot file's nominal_speed and nominal_turn_rate",
    )


def _check_global_costmap(world: World, robot: Robot, node: SpecNode) -> None:
    """Refuse a route whose global costmap, at the robot's resolution, has too many cells."""
    settings = NavigationSettings.from_parameters(robot.navigation)
    corners = [(world.start.x, world.start.y), *((point.x, point.y) for point in world.route)]
    span = max(math.dist(a, b) for a in corners for b in corners)  # m
    size = global_costmap_size(settings, span)
    cells = costmap_cells(size, settings.costmap.resolution, "global")
    if cells is not None:
        problem, fix = cells
        raise node.error(
            f"along this route (its points up to {span:.0f} m apart) {problem}",
            f"{fix} (navigation: costmap.resolution, global_costmap.size), or shorten the route",
        )


def route_length(world: World) -> float:
    """How far the route runs from the start through every waypoint (m)."""
    corners = [(world.start.x, world.start.y), *((point.x, point.y) for point in world.route)]
    return sum(math.dist(a, b) for a, b in itertools.pairwise(corners))


def _round_up(seconds: float) -> float:
    """A time limit a person would write: whole tens of seconds, at least 10."""
    return max(10.0, math.ceil(seconds / 10.0) * 10.0)


def _pose(node: SpecNode) -> Pose2D:
    fields = node.mapping(("x", "y", "yaw"), what="pose fields (x, y, yaw)")
    x, y = _coordinates(node, fields)
    yaw = fields["yaw"].number_in(YAW) if "yaw" in fields else 0.0
    return Pose2D(x, y, yaw)


def _point(node: SpecNode) -> Point2D:
    fields = node.mapping(("x", "y"), what="point fields (x, y)")
    return Point2D(*_coordinates(node, fields))


def _coordinates(node: SpecNode, fields: dict[str, SpecNode]) -> tuple[float, float]:
    for key in ("x", "y"):
        if key not in fields:
            raise node.missing(key, f"write the {key} coordinate in m")
    return fields["x"].number_in(COORDINATE), fields["y"].number_in(COORDINATE)


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
