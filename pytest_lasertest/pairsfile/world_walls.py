"""The walls of a pairs file's `world:`, from all its sources together: a `map:`, listed
`walls:` and the static models of an `sdf:` world. Each source is read by its own module; here
they are bounded together, at the line of the source that goes over: as many wall boxes as the
simulator steps, spread no wider than a map may be.
"""

from __future__ import annotations

import numpy as np

from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.obstacles import Box
from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.model.walls import MAP_MARGIN, Walls
from pytest_lasertest.pairsfile.maps import MAX_MAP_EXTENT, MAX_MAP_WALLS, read_map
from pytest_lasertest.pairsfile.sdf_world import read_sdf_walls
from pytest_lasertest.pairsfile.walls import read_walls

# The simulator steps every wall box and casts every scan against it, whichever source gives
# it: a map's bound holds for the world's walls together.
MAX_WORLD_WALLS = MAX_MAP_WALLS
# The sources of walls besides a map, in the order they are added to its boxes, each with the
# words for one of its walls and for several.
LISTED_SOURCES = (
    ("walls", read_walls, ("listed wall", "listed walls")),
    ("sdf", read_sdf_walls, ("static box of the SDF world", "static boxes of the SDF world")),
)


def read_world_walls(fields: dict[str, SpecNode], driven: tuple[tuple[float, float], ...]) -> Walls:
    """The walls of the world's map, those it lists and those of its SDF world, each source
    bounded together with those before it, at its own line; the map of listed and SDF walls
    covers them and the points `driven` (m), the start and waypoints."""
    grid = read_map(fields["map"]) if "map" in fields else None
    counts = [] if grid is None else [_map_count(grid)]
    listed: tuple[Box, ...] = ()
    for key, read, (one, several) in LISTED_SOURCES:
        if key in fields:
            boxes = read(fields[key])
            words = one if len(boxes) == 1 else several
            counts.append((len(boxes), f"the {len(boxes):,} {words}"))
            _check_wall_count(counts, fields[key])
            listed += boxes
            _check_walls_extent(grid, listed, driven, fields[key])
    if grid is not None:
        return Walls.mapped(grid, listed)
    return Walls.listed(listed, driven)


def _map_count(grid: OccupancyGrid) -> tuple[int, str]:
    count = grid.wall_box_count
    return count, f"the map's {count:,} wall boxes"


def _check_wall_count(counts: list[tuple[int, str]], node: SpecNode) -> None:
    """Refuse walls that, with those of the sources before them (`counts`, each with its
    words, this source's last), make more boxes than the simulator steps: each source's own
    bound lets a map's 5,000 boxes take 1,000 listed and SDF walls more."""
    total = sum(count for count, _ in counts)
    if total <= MAX_WORLD_WALLS:
        return
    *earlier, last = (what for _, what in counts)
    named = f"{', '.join(earlier)} and {last}" if earlier else last
    raise node.error(
        f"{named} make {total:,} wall boxes, more than the "
        f"{MAX_WORLD_WALLS:,} the simulator steps and casts every scan against",
        "clean the map of its speckle (isolated occupied cells), merge walls that meet in a "
        "line into one, or draw the listed walls into the map",
    )


def _check_walls_extent(
    grid: OccupancyGrid | None,
    walls: tuple[Box, ...],
    driven: tuple[tuple[float, float], ...],
    node: SpecNode,
) -> None:
    """Refuse walls spread wider than a map may be. Without a map they are drawn into one at
    MAP_RESOLUTION, its margin round them and the route, and walls kilometres apart would make
    one of billions of cells; with one, the world is held to the map's own bound (the route
    keeps to the map's known cells, `_check_on_map`)."""
    corners = np.array([corner for wall in walls for corner in wall.corners()]).reshape(-1, 2)
    if grid is None:
        width, height = _spread(np.vstack([corners, *driven]), MAP_MARGIN)
        what, bound, where = "the walls and the route", "the gate draws into a map", ""
    else:
        width, height = _spread(np.vstack([corners, *map_corners(grid)]), 0.0)
        what, bound, where = "the map and its walls", "a map may span", ", on the map"
    if max(width, height) > MAX_MAP_EXTENT:
        raise node.error(
            f"{what} spread over {width:g} x {height:g} m, wider than the {MAX_MAP_EXTENT:g} m "
            f"a side {bound}",
            f"keep the walls of the part the robot drives through{where}",
        )


def _spread(points: FloatArray, margin: float) -> tuple[float, float]:
    """How far the points, shape (P, 2), spread along x and along y (m), `margin` round them."""
    width, height = points.max(axis=0) - points.min(axis=0) + 2.0 * margin
    return float(width), float(height)


def map_corners(grid: OccupancyGrid) -> tuple[tuple[float, float], tuple[float, float]]:
    """The map's lower left and upper right corners (m)."""
    (low_x, low_y), side = grid.origin, grid.resolution
    return (low_x, low_y), (low_x + grid.width * side, low_y + grid.height * side)
