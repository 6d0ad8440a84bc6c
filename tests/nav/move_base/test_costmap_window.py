"""The costmap beyond marking and clearing: unknown space, blocks of costs, flat rays, resets."""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
import pytest

from pytest_lasertest.nav.move_base.cost_values import FREE, INSCRIBED, LETHAL, UNKNOWN
from pytest_lasertest.nav.move_base.costmap import Costmap, CostmapSettings, lethal_distances
from tests.helpers.costmap import cost_at, scan

# Inscribed radius 0.32 m: not a whole number of 5 cm cells, so no distance ties with it.
FOOTPRINT = np.array([[-0.5, -0.32], [0.5, -0.32], [0.5, 0.32], [-0.5, 0.32]])
Mask = npt.NDArray[np.bool_]


def random_grid(costmap: Costmap, seed: int, lethal: float, unknown: float) -> None:
    rng = np.random.default_rng(seed)
    draw = rng.random(costmap.grid.shape)
    costmap.grid[:] = np.where(
        draw < lethal, LETHAL, np.where(draw < lethal + unknown, UNKNOWN, FREE)
    )


# --- track_unknown_space ---


def test_with_track_unknown_space_cells_start_unknown_and_a_scan_clears_only_its_rays() -> None:
    settings = CostmapSettings(size=12.0, obstacle_range=5.5, raytrace_range=6.0)
    tracking = Costmap(
        CostmapSettings(
            size=12.0, obstacle_range=5.5, raytrace_range=6.0, track_unknown_space=True
        ),
        FOOTPRINT,
    )
    assert (tracking.grid == UNKNOWN).all()
    assert (Costmap(settings, FOOTPRINT).grid == FREE).all()
    robot = (0.013, 0.012, 0.0)  # off the cell edges
    tracking.update(scan(3.02), robot)
    for x in (0.8, 1.5, 2.5, 2.97):  # along the ray, ahead of the footprint
        assert cost_at(tracking, x, 0.012) == FREE
    assert cost_at(tracking, 3.02, 0.012) == LETHAL
    assert cost_at(tracking, 3.3, 0.012) == UNKNOWN  # beyond the reading
    assert cost_at(tracking, 1.5, 0.3) == UNKNOWN  # beside the ray
    assert cost_at(tracking, -2.0, 0.012) == UNKNOWN  # behind the laser
    assert cost_at(tracking, 0.2, 0.2) == FREE  # under the footprint
    # Everything seen lies on the ray's row or under the footprint.
    rows, columns = np.nonzero(tracking.grid != UNKNOWN)
    centres_y = tracking.origin[1] + (rows + 0.5) * 0.05
    centres_x = tracking.origin[0] + (columns + 0.5) * 0.05
    on_ray = (np.abs(centres_y - 0.012) < 0.05) & (centres_x > 0.0) & (centres_x < 3.1)
    under = (np.abs(centres_x - 0.013) < 0.55) & (np.abs(centres_y - 0.012) < 0.37)
    assert (on_ray | under).all()


UNKNOWN_SETTINGS = CostmapSettings(
    size=4.0, inflation_radius=0.8, cost_scaling_factor=3.0, track_unknown_space=True
)
LONE = (40, 37)  # [y, x]: the one lethal cell in a window of unknown space


def lone_lethal_cell() -> tuple[Costmap, npt.NDArray[np.float64]]:
    """A window unknown but for a lethal cell and a free strip to its right, well within the
    inflation radius of it; and each cell's distance (m) to the lethal cell."""
    costmap = Costmap(UNKNOWN_SETTINGS, FOOTPRINT)
    costmap.grid[LONE] = LETHAL
    costmap.grid[:, 45:] = FREE
    rows, columns = np.mgrid[0:80, 0:80]
    distance: npt.NDArray[np.float64] = np.hypot(rows - LONE[0], columns - LONE[1]) * 0.05
    return costmap, distance


def test_an_unknown_cell_beyond_the_inscribed_radius_stays_unknown_in_costs() -> None:
    costmap, distance = lone_lethal_cell()
    costs = costmap.costs()
    unknown_beyond = (costmap.grid == UNKNOWN) & (distance > 0.32)
    assert (unknown_beyond & (distance < 0.8)).sum() > 100  # where a free cell would inflate
    assert (costs[unknown_beyond] == UNKNOWN).all()
    # A free cell as far away does inflate: 252 exp(-3 (d - 0.32)), 0 beyond the radius.
    free = costmap.grid == FREE
    falloff = np.where(distance <= 0.8, np.floor(252 * np.exp(-3.0 * (distance - 0.32))), FREE)
    assert (free & (distance < 0.8)).sum() > 50
    np.testing.assert_array_equal(costs[free], falloff[free])
    assert costs[LONE] == LETHAL


def test_an_unknown_cell_within_the_inscribed_radius_of_a_lethal_cell_costs_inscribed() -> None:
    costmap, distance = lone_lethal_cell()
    costs = costmap.costs()
    unknown_within = (costmap.grid == UNKNOWN) & (distance <= 0.32)
    assert unknown_within.sum() > 100
    assert (costs[unknown_within] == INSCRIBED).all()


# --- costs of a block ---

BLOCKS = [
    (slice(0, 30), slice(0, 30)),  # a corner
    (slice(100, 120), slice(90, None)),  # the opposite corner
    (slice(None), slice(50, 51)),  # one row
    (slice(7, 8), slice(None)),  # one column
    (slice(37, 83), slice(5, 118)),
    (slice(-15, None), slice(None, 12)),
    (slice(None), slice(None)),
]


@pytest.mark.parametrize(("columns", "rows"), BLOCKS)
def test_the_costs_of_a_block_are_the_whole_windows_costs_cut_to_that_block(
    columns: slice, rows: slice
) -> None:
    settings = CostmapSettings(size=6.0, inflation_radius=0.55, track_unknown_space=True)
    costmap = Costmap(settings, FOOTPRINT)
    random_grid(costmap, seed=11, lethal=0.01, unknown=0.3)
    whole = costmap.costs()
    block = costmap.costs(columns, rows)
    np.testing.assert_array_equal(block, whole[rows, columns])
    assert (whole == INSCRIBED).any()
    assert ((whole > FREE) & (whole < INSCRIBED)).any()


@pytest.mark.parametrize("seed", range(6))
def test_a_few_lethal_cells_inflate_as_the_whole_window_inflates_them(seed: int) -> None:
    """Inflation is computed around the lethal cells only; the costs equal those of inflating
    every cell of the window by its distance to the nearest lethal one."""
    rng = np.random.default_rng(seed)
    settings = CostmapSettings(size=6.0, inflation_radius=0.55)
    costmap = Costmap(settings, FOOTPRINT)
    for _ in range(int(rng.integers(1, 4))):  # a few small clusters, some at an edge
        x, y = rng.integers(0, settings.cells, 2)
        costmap.grid[y : y + 3, x : x + 2] = LETHAL
    reach = math.ceil(settings.inflation_radius / settings.resolution)
    distance = lethal_distances(costmap.grid == LETHAL, reach) * settings.resolution
    expected = np.maximum(costmap.grid, costmap.inflation(distance).astype(np.uint8))
    np.testing.assert_array_equal(costmap.costs(), expected)
    assert (costmap.costs() == FREE).any()


# --- clear_outside ---


def inside_square(costmap: Costmap, x: float, y: float, size: float) -> Mask:
    """Which cells [y, x] lie wholly inside the square `size` m wide around (x, y)."""
    resolution, cells = costmap.settings.resolution, costmap.settings.cells
    low_x = costmap.origin[0] + resolution * np.arange(cells)
    low_y = costmap.origin[1] + resolution * np.arange(cells)
    columns = (low_x > x - size / 2.0) & (low_x + resolution < x + size / 2.0)
    rows = (low_y > y - size / 2.0) & (low_y + resolution < y + size / 2.0)
    inside: Mask = rows[:, np.newaxis] & columns[np.newaxis, :]
    return inside


@pytest.mark.parametrize(
    ("x", "y", "size"),
    [
        (3.013, 2.987, 3.0),  # in the middle
        (0.413, 5.788, 2.0),  # over two edges of the window
        (3.013, 2.987, 0.07),  # narrower than two cells
        (3.013, 2.987, 20.0),  # wider than the window: everything kept
        (20.0, -20.0, 1.0),  # outside the window: everything forgotten
    ],
)
@pytest.mark.parametrize("track_unknown_space", [True, False], ids=["unknown", "free"])
def test_clear_outside_keeps_exactly_the_cells_strictly_inside_the_square(
    x: float, y: float, size: float, track_unknown_space: bool
) -> None:
    settings = CostmapSettings(size=6.0, track_unknown_space=track_unknown_space)
    costmap = Costmap(settings, FOOTPRINT)
    costmap.origin = (0.0, 0.0)
    random_grid(costmap, seed=4, lethal=0.3, unknown=0.3)
    before = costmap.grid.copy()
    costmap.clear_outside(x, y, size)
    inside = inside_square(costmap, x, y, size)
    np.testing.assert_array_equal(costmap.grid[inside], before[inside])
    assert (costmap.grid[~inside] == costmap.unseen).all()


def test_clear_outside_follows_the_window_where_it_has_rolled() -> None:
    costmap = Costmap(CostmapSettings(size=6.0, track_unknown_space=True), FOOTPRINT)
    costmap.update(scan(np.inf), (10.013, -4.987, 0.0))  # the window now centres on the robot
    assert costmap.origin != (0.0, 0.0)
    random_grid(costmap, seed=5, lethal=0.3, unknown=0.0)
    before = costmap.grid.copy()
    costmap.clear_outside(10.013, -4.987, 1.5)
    inside = inside_square(costmap, 10.013, -4.987, 1.5)
    assert inside.sum() == 29 * 29
    np.testing.assert_array_equal(costmap.grid[inside], before[inside])
    assert (costmap.grid[~inside] == UNKNOWN).all()
