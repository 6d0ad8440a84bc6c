"""The local costmap: costmap_2d's marking, clearing, rolling window, footprint and inflation."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from pytest_lasertest.nav.move_base.cost_values import FREE, INSCRIBED, LETHAL
from pytest_lasertest.nav.move_base.costmap import (
    Costmap,
    CostmapSettings,
    lethal_distances,
    ray_indices,
)
from tests.helpers.costmap import cost_at, scan

FOOTPRINT = np.array([[-0.5, -0.3], [0.5, -0.3], [0.5, 0.3], [-0.5, 0.3]])
SETTINGS = CostmapSettings(size=12.0, obstacle_range=5.5, raytrace_range=6.0)
ROBOT = (0.0, 0.0, 0.0)


def test_a_reading_nearer_than_obstacle_range_marks_its_cell_and_clears_the_way_to_it() -> None:
    costmap = Costmap(SETTINGS, FOOTPRINT)
    costmap.grid[:] = LETHAL  # as if everything had been seen before
    costmap.update(scan(3.02), ROBOT)
    assert cost_at(costmap, 3.02, 0.0) == LETHAL
    for x in (1.0, 2.0, 2.97):
        assert cost_at(costmap, x, 0.0) == FREE
    assert cost_at(costmap, 3.2, 0.0) == LETHAL  # beyond the reading: untouched


def test_the_phantom_arc_appears_exactly_when_range_max_less_epsilon_is_inside_obstacle_range() -> (
    None
):
    # +inf becomes range_max - 1e-4 = 4.9999 m; marking needs a distance below obstacle_range.
    for obstacle_range, marked in ((5.5, True), (5.00001, True), (4.9999, False), (4.5, False)):
        settings = CostmapSettings(
            size=12.0, obstacle_range=obstacle_range, raytrace_range=6.0, inf_is_valid=True
        )
        costmap = Costmap(settings, FOOTPRINT)
        costmap.update(scan(np.inf), ROBOT)
        assert (cost_at(costmap, 4.9999, 0.0) == LETHAL) is marked, obstacle_range
        assert (cost_at(costmap, 0.0, 4.9999) == LETHAL) is marked, obstacle_range


def test_without_inf_is_valid_no_return_marks_and_clears_nothing() -> None:
    costmap = Costmap(dataclasses.replace(SETTINGS, inf_is_valid=False), FOOTPRINT)
    costmap.grid[:] = LETHAL
    costmap.update(scan(np.inf), ROBOT)
    assert cost_at(costmap, 3.0, 0.0) == LETHAL


@pytest.mark.parametrize(
    ("reading", "kept"), [(0.05, False), (0.1, True), (4.99, True), (5.0, False)]
)
def test_only_readings_from_range_min_up_to_but_not_including_range_max_count(
    reading: float, kept: bool
) -> None:
    costmap = Costmap(SETTINGS, np.array([[-0.01, -0.01], [0.01, -0.01], [0.01, 0.01]]))
    costmap.update(scan(reading), ROBOT)
    assert (cost_at(costmap, reading, 0.0) == LETHAL) is kept


def test_clearing_stops_at_raytrace_range() -> None:
    costmap = Costmap(dataclasses.replace(SETTINGS, raytrace_range=2.0), FOOTPRINT)
    costmap.grid[:] = LETHAL
    costmap.update(scan(4.0), ROBOT)
    assert cost_at(costmap, 1.9, 0.0) == FREE
    assert cost_at(costmap, 2.2, 0.0) == LETHAL


def test_the_window_follows_the_robot_and_keeps_what_it_marked_where_it_was() -> None:
    costmap = Costmap(SETTINGS, FOOTPRINT)
    costmap.update(scan(3.02), ROBOT)
    first = costmap.origin
    costmap.update(scan(np.inf), (1.0, 0.5, 0.0))
    # Whole cells, the shift truncated: 19.25 cells in x, 9.25 in y.
    assert costmap.origin == pytest.approx((first[0] + 19 * 0.05, first[1] + 9 * 0.05))
    assert cost_at(costmap, 3.02, 0.0) == LETHAL


def test_a_cell_the_window_left_is_unseen_when_the_window_comes_back_over_it() -> None:
    costmap = Costmap(dataclasses.replace(SETTINGS, size=4.0), FOOTPRINT)
    costmap.update(scan(1.5), ROBOT)
    assert cost_at(costmap, 1.5, 0.0) == LETHAL
    # 1 m back, the window (2 m either side) leaves the marked cell behind: a slide of 20
    # cells over the buffer, which still holds the cell.
    costmap.update(scan(np.inf), (-1.0, 0.0, 0.0))
    costmap.update(scan(np.inf), ROBOT)
    assert cost_at(costmap, 1.5, 0.0) == FREE


class MovingCostmap(Costmap):
    """A window that moves its cells at every shift, as costmap_2d's updateOrigin does."""

    slack = 0


@pytest.mark.parametrize("seed", range(4))
def test_the_sliding_window_holds_the_cells_of_one_that_moves_its_cells_at_every_shift(
    seed: int,
) -> None:
    rng = np.random.default_rng(seed)
    sliding, moving = Costmap(SETTINGS, FOOTPRINT), MovingCostmap(SETTINGS, FOOTPRINT)
    pose = np.zeros(3)
    for _ in range(150):  # a walk of several metres each way: past the buffer's edge
        pose += (*rng.normal(0.0, 0.5, 2), rng.uniform(-1.0, 1.0))
        robot = (float(pose[0]), float(pose[1]), float(pose[2]))
        reading = scan(float(rng.uniform(0.6, 4.0)))
        sliding.update(reading, robot)
        moving.update(reading, robot)
        assert sliding.origin == moving.origin
        np.testing.assert_array_equal(sliding.grid, moving.grid)


def test_the_cells_under_the_footprint_are_freed() -> None:
    costmap = Costmap(SETTINGS, FOOTPRINT)
    costmap.grid[:] = LETHAL
    costmap.update(scan(np.inf), (2.0, 1.0, math.pi / 2))
    # Turned a quarter, the footprint spans 0.6 m in x and 1 m in y.
    assert cost_at(costmap, 2.25, 1.45) == FREE
    assert cost_at(costmap, 2.45, 1.0) == LETHAL


def test_inflation_costs_follow_costmap_2d_by_distance_from_the_nearest_lethal_cell() -> None:
    settings = dataclasses.replace(SETTINGS, inflation_radius=1.0, cost_scaling_factor=3.0)
    costmap = Costmap(settings, FOOTPRINT)
    costmap.update(scan(3.025), ROBOT)
    costs = costmap.costs()
    cell = 3.025  # the middle of the marked cell, and of those beside it along x
    inscribed = 0.3  # m, the footprint's half width
    assert cost_at(costmap, cell, 0.0, costs) == LETHAL
    assert cost_at(costmap, cell + 0.25, 0.0, costs) == INSCRIBED
    expected = int((INSCRIBED - 1) * math.exp(-3.0 * (0.6 - inscribed)))
    assert cost_at(costmap, cell + 0.6, 0.0, costs) == expected
    assert cost_at(costmap, cell + 1.1, 0.0, costs) == FREE


def test_the_distance_to_lethal_cells_is_the_exact_euclidean_one_within_reach() -> None:
    rng = np.random.default_rng(5)
    for _ in range(5):
        lethal = rng.random((40, 40)) < 0.01
        distance = lethal_distances(lethal, reach=8)
        ys, xs = np.nonzero(lethal)
        grid_y, grid_x = np.mgrid[0:40, 0:40]
        squared = np.full((40, 40), np.iinfo(np.int64).max)
        for y, x in zip(ys, xs, strict=True):
            squared = np.minimum(squared, (grid_x - x) ** 2 + (grid_y - y) ** 2)
        exact = np.sqrt(squared.astype(np.float64))  # the root of a whole number, to the bit
        within = exact <= 8
        assert np.array_equal(distance[within], exact[within])
        assert np.all(distance[~within] > 8)


@pytest.mark.parametrize("longest", [None, 9, 12, 25])
@pytest.mark.parametrize("start", [(0, 0), (30, 17), (59, 59), (5, 44), (3, 4)])
def test_the_ray_cells_are_those_of_costmap_2d_bresenham(
    start: tuple[int, int], longest: int | None
) -> None:
    cells = 60  # a window 60 cells wide: the rays' cells as flat indices x + y * 60
    rng = np.random.default_rng(start[0] * 100 + start[1])
    ends = rng.integers(0, cells, size=(150, 2))
    ends[:3] = [start, (start[0], 0), (0, start[1])]  # no ray, and the two axes
    index = ray_indices(*start, ends[:, 0], ends[:, 1], cells, longest)
    ys, xs = np.divmod(index, cells)
    expected = [cell for x, y in ends for cell in _reference(*start, x, y, longest)]
    assert list(zip(xs.tolist(), ys.tolist(), strict=True)) == expected


def _reference(x0: int, y0: int, x1: int, y1: int, longest: int | None) -> list[tuple[int, int]]:
    """costmap_2d's raytraceLine and bresenham2D, one cell at a time."""
    dx, dy = x1 - x0, y1 - y0
    step_x, step_y = (1 if dx > 0 else -1), (1 if dy > 0 else -1)
    length = math.hypot(dx, dy)
    scale = 1.0 if longest is None or length == 0.0 else min(1.0, longest / length)
    if abs(dx) >= abs(dy):
        major, minor, along, across = abs(dx), abs(dy), (step_x, 0), (0, step_y)
    else:
        major, minor, along, across = abs(dy), abs(dx), (0, step_y), (step_x, 0)
    error, x, y, cells = major // 2, x0, y0, []
    for _ in range(min(int(scale * major), major)):
        cells.append((x, y))
        x, y = x + along[0], y + along[1]
        error += minor
        if error >= major:
            x, y = x + across[0], y + across[1]
            error -= major
    cells.append((x, y))
    return cells


def test_the_freed_footprint_is_costmap_2d_convex_fill_cell_for_cell() -> None:
    rng = np.random.default_rng(4)
    blind = dataclasses.replace(SETTINGS, inf_is_valid=False)  # no ray clears anything
    for _ in range(40):
        costmap = Costmap(blind, FOOTPRINT)
        robot = (rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-math.pi, math.pi))
        costmap.update(scan(np.inf), robot)  # the window centres on the robot
        costmap.grid[:] = LETHAL
        costmap.update(scan(np.inf), robot)
        freed = set(zip(*np.nonzero(costmap.grid == FREE)[::-1], strict=True))
        assert freed == _convex_fill(costmap, robot)


def _convex_fill(costmap: Costmap, robot: tuple[float, float, float]) -> set[tuple[int, int]]:
    """costmap_2d's convexFillCells, one cell at a time: the outline's cells, edge by edge,
    then each column filled between its lowest and highest outline cell."""
    cos, sin = math.cos(robot[2]), math.sin(robot[2])
    corners = [
        costmap.cell_of(np.array([[robot[0] + cos * x - sin * y, robot[1] + sin * x + cos * y]]))
        for x, y in FOOTPRINT
    ]
    cells = [(int(x[0]), int(y[0])) for x, y, _ in corners]
    outline = [
        cell
        for (x0, y0), (x1, y1) in zip(cells, cells[1:] + cells[:1], strict=True)
        for cell in _reference(x0, y0, x1, y1, None)
    ]
    filled = set()
    for column in {x for x, _ in outline}:
        rows = [y for x, y in outline if x == column]
        filled |= {(column, row) for row in range(min(rows), max(rows) + 1)}
    return filled
