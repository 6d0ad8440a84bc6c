"""A world's walls: boxes standing on the ground that nobody placed to test anything, and the map
of them the navigation stack is given.

Walls are what a building has: they block the robot, hide what stands behind them from a
scanner, and no test obstacle may stand inside one. They come from a map (its occupied cells,
`occupancy.py`), or from boxes and segments a pairs file lists, which are then drawn into a map
at MAP_RESOLUTION, as a team would map them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.obstacles import (
    Box,
    Obstacle,
    box_holds,
    polygon_clearance,
    ray_distances,
)
from pytest_lasertest.model.occupancy import OccupancyGrid, drawn, rasterised

# Taller than any scanner is mounted: every scan plane meets a wall.
WALL_HEIGHT = 2.0  # m
# The resolution of the map drawn from listed walls: the common one of ROS maps (gmapping's and
# slam_toolbox's default).
MAP_RESOLUTION = 0.05  # m per cell
# How far the drawn map reaches past the walls, so that a costmap's edge is never a wall's.
MAP_MARGIN = 1.0  # m


@dataclass(frozen=True)
class Walls:
    """The walls of a world (none: an empty world), and the map of them a static layer reads."""

    boxes: tuple[Box, ...] = ()
    grid: OccupancyGrid | None = None  # what map_server publishes; None without walls

    def __bool__(self) -> bool:
        return bool(self.boxes)

    @classmethod
    def listed(
        cls, boxes: tuple[Box, ...], covering: tuple[tuple[float, float], ...] = ()
    ) -> Walls:
        """Walls a pairs file lists, with their map drawn at MAP_RESOLUTION over them and the
        points `covering` (m): the start and the waypoints, as a team maps where the robot
        drives (a goal off the map would be unknown space to the stacks)."""
        if not boxes:
            return cls()
        return cls(boxes, rasterised(boxes, MAP_RESOLUTION, MAP_MARGIN, covering))

    @classmethod
    def mapped(cls, grid: OccupancyGrid, listed: tuple[Box, ...] = ()) -> Walls:
        """The walls of a map, its occupied cells WALL_HEIGHT high, and any walls listed
        besides, drawn into the map a controller is given."""
        return cls(grid.wall_boxes(WALL_HEIGHT) + listed, drawn(grid, listed))

    def reach(self, origins: FloatArray, directions: FloatArray) -> FloatArray:
        """How far each ray, origins and unit directions shape (R, 2), runs before it meets a
        wall, shape (R,), m: inf where it meets none, 0 from inside one."""
        reach = np.full(len(origins), np.inf)
        for box in self.boxes:
            reach = np.minimum(reach, ray_distances(origins, directions, box))
        return reach

    def clearance(self, obstacle: Obstacle) -> float:
        """How far the obstacle stands from the nearest wall (m; negative: that deep inside
        one; inf without walls), in the obstacle's own clearance metric."""
        near = self.near(obstacle.x, obstacle.y, obstacle.bounding_radius + 1.0)
        return min(
            (polygon_clearance(np.array(box.corners()), obstacle) for box in near),
            default=math.inf,
        )

    def distances(self, points: FloatArray) -> FloatArray:
        """How far each point, shape (P, 2) m, lies from the nearest wall, (P,) m: 0 inside
        one, inf without walls."""
        nearest = np.full(len(points), np.inf)
        for box in self.boxes:
            cos, sin = math.cos(box.yaw), math.sin(box.yaw)
            offsets = points - (box.x, box.y)
            along = np.abs(offsets @ (cos, sin)) - box.length / 2.0
            across = np.abs(offsets @ (-sin, cos)) - box.width / 2.0
            gap = np.hypot(np.maximum(along, 0.0), np.maximum(across, 0.0))
            nearest = np.minimum(nearest, gap)
        return nearest

    def near(self, x: float, y: float, within: float) -> tuple[Box, ...]:
        """The walls whose footprint may come within `within` m of (x, y) m."""
        return tuple(
            box
            for box in self.boxes
            if math.hypot(box.x - x, box.y - y) - box.bounding_radius < within
        )

    def holding(self, points: FloatArray) -> list[Box]:
        """The walls that hold any of the points, shape (P, 2), m."""
        return [box for box in self.boxes if bool(np.any(box_holds(box, points)))]


# An empty world: the default wherever walls may be given.
NO_WALLS = Walls()
