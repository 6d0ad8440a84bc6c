"""Nav2's global costmap as the imitation rolls it: a window over the route, not the map's
extent (`Nav2` makes it at the first scan, centred where the robot starts), and the check that
each waypoint lies within the window NavFn can plan through."""

from __future__ import annotations

import dataclasses

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, Point2D
from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.nav.nav2.costmap import Nav2Costmap
from pytest_lasertest.nav.nav2.settings import CostmapConfig, Nav2Settings

Route = tuple[Point2D, ...]  # m, the waypoints in order


def make_global_costmap(
    s: Nav2Settings,
    footprint: FloatArray,
    start: tuple[float, float],
    route: Route,
    grid: OccupancyGrid | None,
) -> Nav2Costmap:
    """A window wide enough for every cell a run along the route can mark, clear or plan
    through, centred at `start` (m; it rolls with the robot), with the world's map `grid` in
    its static layer if it has one. `footprint` (V, 2) m."""
    config = s.global_
    settings = dataclasses.replace(config.costmap, size=global_window(config, start, route))
    static = config.static_layer if grid is not None else None
    if static is not None:
        # The map's own unknown cells, and the window beyond the map, are unknown until
        # scanned if the costmap tracks unknown space: its master, obstacle and static
        # layers all read the costmap's track_unknown_space.
        settings = dataclasses.replace(settings, track_unknown_space=static.track_unknown_space)
    costmap = Nav2Costmap(settings, footprint, config.source, s.marking)
    if static is not None and grid is not None:
        costmap.receive_map(grid, static)
    return costmap


def global_window(config: CostmapConfig, start: tuple[float, float], route: Route) -> float:
    """How wide the global costmap's window is (m): the configured width, or less where a run
    from `start` along `route` can mark, clear and plan through no more."""
    points = np.array([start, *((point.x, point.y) for point in route)])
    span = float(np.hypot(*(points[:, np.newaxis] - points[np.newaxis]).T).max())  # m
    reach = config.source.raytrace_max_range + config.costmap.inflation_radius + 1.0  # m
    return min(config.costmap.size, 2.0 * (span + reach))


def out_of_reach(settings: Nav2Settings, start: tuple[float, float], route: Route) -> int | None:
    """The index of the first waypoint the planner cannot reach from where the robot sets off
    for it: outside the rolling global costmap round that point (NavFn plans only within the
    costmap, and a goal off it fails as GoalOutsideMapBounds), by at least the goal tolerance
    and a cell; None if every one lies within."""
    half = global_window(settings.global_, start, route) / 2.0
    margin = settings.xy_goal_tolerance + settings.global_.costmap.resolution
    previous = start
    for index, point in enumerate(route):
        if max(abs(point.x - previous[0]), abs(point.y - previous[1])) >= half - margin:
            return index
        previous = (point.x, point.y)
    return None
