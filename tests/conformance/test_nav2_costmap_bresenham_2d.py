"""nav2_costmap_2d's regression test of Bresenham's line (costmap_bresenham_2d.cpp), rebuilt on
the obstacle layer's ray tracing (`cleared`): rays from an off-centre cell to every edge cell
of a 60 x 60 window stay on it, and a ray to its own start cell visits that cell."""

from __future__ import annotations

import numpy as np

from pytest_lasertest.nav.nav2.obstacle_layer import ObservationSource, Window, cleared
from tests.helpers.upstream import NAVIGATION2_JAZZY, Source

BRESENHAM = Source(
    "Nav2 costmap: ray tracing",
    NAVIGATION2_JAZZY,
    "nav2_costmap_2d/test/regression/costmap_bresenham_2d.cpp",
)
# The upstream CostmapTest: 60 x 60 cells of 0.1 m from (0, 0).
WINDOW = Window(origin_x=0.0, origin_y=0.0, resolution=0.1, size_x=60, size_y=60)


def centre(cell_x: int, cell_y: int) -> tuple[float, float]:
    """A cell's centre (m)."""
    return ((cell_x + 0.5) * WINDOW.resolution, (cell_y + 0.5) * WINDOW.resolution)


@BRESENHAM.test("costmap_2d.bresenham2DBoundariesCheck", assertions=1)
def test_rays_to_every_edge_cell_visit_only_cells_of_the_window() -> None:
    # max_length 60 and min_length 6 cells, from the asymmetric start (2, 4).
    source = ObservationSource(raytrace_max_range=6.0, raytrace_min_range=0.6)
    edge = [(x, 0) for x in range(60)] + [(x, 59) for x in range(60)]
    edge += [(0, y) for y in range(60)] + [(59, y) for y in range(60)]
    ends = np.array([centre(x, y) for x, y in edge])
    cells = cleared(WINDOW, centre(2, 4), ends, source)
    assert len(cells) > 0
    assert ((cells >= 0) & (cells < WINDOW.size_x * WINDOW.size_y)).all()


@BRESENHAM.test("costmap_2d.bresenham2DSamePoint", assertions=1)
def test_a_ray_to_its_own_start_cell_visits_that_cell() -> None:
    source = ObservationSource(raytrace_max_range=6.0, raytrace_min_range=0.0)
    cells = cleared(WINDOW, centre(2, 4), np.array([centre(2, 4)]), source)
    assert 4 * WINDOW.size_x + 2 in cells
