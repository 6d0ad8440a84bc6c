"""A nominal route through a world's walls: the waypoints a person would give for a goal.

When a pairs file gives only a goal in a world with walls, the route is planned: navfn's
cheapest 8-connected chain of cells (`move_base/navfn.py`) over the walls' map, every cell
nearer a wall than the robot's turning radius plus CLEARANCE blocked, then pulled taut into the
fewest straight legs that keep that far from every wall. The robot may then turn in place at
any waypoint, and the solver's swept footprints never touch a wall.
"""

from __future__ import annotations

import math

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, Point2D
from pytest_lasertest.model.walls import Walls
from pytest_lasertest.nav.move_base.cost_values import FREE, LETHAL
from pytest_lasertest.nav.move_base.navfn import NavfnSettings, plan_path

# How much further than its turning radius the route keeps the robot from every wall: its
# controller's path wanders about the straight line by a few centimetres.
CLEARANCE = 0.1  # m
# The grid the route is searched on, and how finely a leg is checked against the walls.
ROUTE_RESOLUTION = 0.05  # m
CHECK_STEP = 0.02  # m


def plan_route(start: Point2D, goal: Point2D, walls: Walls, radius: float) -> tuple[Point2D, ...]:
    """Waypoints from `start` to `goal` (last) that keep a robot of turning radius `radius` m
    CLEARANCE from every wall; empty when no such route exists."""
    keep = radius + CLEARANCE
    if _clear(np.array([[start.x, start.y], [goal.x, goal.y]]), walls, keep):
        return (goal,)
    low = np.minimum([start.x, start.y], [goal.x, goal.y])
    high = np.maximum([start.x, start.y], [goal.x, goal.y])
    corners = np.array([corner for box in walls.boxes for corner in box.corners()])
    low = np.minimum(low, corners.min(axis=0)) - keep - ROUTE_RESOLUTION
    high = np.maximum(high, corners.max(axis=0)) + keep + ROUTE_RESOLUTION
    width, height = (math.ceil(extent) for extent in (high - low) / ROUTE_RESOLUTION)
    ys, xs = np.mgrid[0:height, 0:width]
    centres = (np.column_stack([xs.ravel(), ys.ravel()]) + 0.5) * ROUTE_RESOLUTION + low
    blocked = walls.distances(centres) < keep
    costs = np.where(blocked, LETHAL, FREE).astype(np.uint8).reshape(height, width)
    ends = [_cell(point, low) for point in (start, goal)]
    settings = NavfnSettings(allow_unknown=False, default_tolerance=0.0)
    cells = plan_path(costs, ends[0], ends[1], settings, ROUTE_RESOLUTION)
    if cells is None:
        return ()
    points = (cells + 0.5) * ROUTE_RESOLUTION + low
    chain = np.vstack([[start.x, start.y], points[1:-1], [goal.x, goal.y]])
    return tuple(Point2D(float(x), float(y)) for x, y in _taut(chain, walls, keep)[1:])


def _cell(point: Point2D, low: FloatArray) -> tuple[int, int]:
    x, y = ((np.array([point.x, point.y]) - low) / ROUTE_RESOLUTION).astype(int)
    return int(x), int(y)


def _taut(chain: FloatArray, walls: Walls, keep: float) -> FloatArray:
    """The chain's points (K, 2) that few straight legs need: from each kept point, on to the
    last of the points after it whose legs from it all stay `keep` m from every wall."""
    kept = [0]
    while kept[-1] < len(chain) - 1:
        here = kept[-1]
        reach = here + 1
        while reach + 1 < len(chain) and _clear(chain[[here, reach + 1]], walls, keep):
            reach += 1
        kept.append(reach)
    taut: FloatArray = chain[kept]
    return taut


def _clear(ends: FloatArray, walls: Walls, keep: float) -> bool:
    """Whether the straight leg between two points (2, 2) stays `keep` m from every wall."""
    length = float(np.hypot(*(ends[1] - ends[0])))
    steps = max(math.ceil(length / CHECK_STEP), 1)
    shares = np.linspace(0.0, 1.0, steps + 1)[:, np.newaxis]
    points = ends[0] + shares * (ends[1] - ends[0])
    return bool(np.all(walls.distances(points) >= keep))
