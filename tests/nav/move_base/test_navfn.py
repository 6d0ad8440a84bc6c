"""The global planner: navfn's costs, exact 8-connected potentials, and the plans down them."""

from __future__ import annotations

import heapq
import itertools
import math

import numpy as np
import numpy.typing as npt
import pytest

from pytest_lasertest.nav.move_base.cost_values import FREE, INSCRIBED, LETHAL, UNKNOWN
from pytest_lasertest.nav.move_base.navfn import (
    SCALE,
    UNREACHABLE,
    NavfnSettings,
    plan_path,
    potential,
)

Grid = npt.NDArray[np.uint8]
Cell = tuple[int, int]  # [x, y]
SETTINGS = NavfnSettings()
RESOLUTION = 0.05  # m per cell: the 0.1 m default tolerance reaches 2 cells
NEIGHBOURS = [(dx, dy) for dx in (-1, 0, 1) for dy in (-1, 0, 1) if dx or dy]


def entry_cost(code: int, settings: NavfnSettings) -> int | None:
    """navfn's cost of entering a cell of costmap cost `code`; None if it cannot be entered."""
    if code < INSCRIBED:
        return min(int(settings.neutral_cost + settings.cost_factor * code), INSCRIBED)
    if code == UNKNOWN and settings.allow_unknown:
        return INSCRIBED
    return None


def step_cost(costs: Grid, settings: NavfnSettings, a: Cell, b: Cell) -> int | None:
    """The potential gained stepping from cell `a` to its neighbour `b`; None if not allowed."""
    entered = entry_cost(int(costs[b[1], b[0]]), settings)
    if entered is None:
        return None
    if a[0] == b[0] or a[1] == b[1]:
        return entered * SCALE
    corners = (int(costs[a[1], b[0]]), int(costs[b[1], a[0]]))
    if any(entry_cost(code, settings) is None for code in corners):
        return None  # a diagonal step may not cut an obstacle's corner
    return round(entered * SCALE * math.sqrt(2))


def dijkstra(costs: Grid, start: Cell, settings: NavfnSettings) -> npt.NDArray[np.int64]:
    """The potential (R, C) by a plain priority-queue Dijkstra over the same steps."""
    rows, cols = costs.shape
    best = np.full((rows, cols), UNREACHABLE, dtype=np.int64)
    best[start[1], start[0]] = 0
    queue = [(0, start)]
    while queue:
        reached, cell = heapq.heappop(queue)
        if reached > best[cell[1], cell[0]]:
            continue
        for dx, dy in NEIGHBOURS:
            near = (cell[0] + dx, cell[1] + dy)
            if not (0 <= near[0] < cols and 0 <= near[1] < rows):
                continue
            step = step_cost(costs, settings, cell, near)
            if step is not None and reached + step < best[near[1], near[0]]:
                best[near[1], near[0]] = reached + step
                heapq.heappush(queue, (reached + step, near))
    return best


def path_cost(costs: Grid, path: npt.NDArray[np.intp], settings: NavfnSettings) -> int:
    cells: list[tuple[int, int]] = [(x, y) for x, y in path.tolist()]
    steps = [step_cost(costs, settings, a, b) for a, b in itertools.pairwise(cells)]
    assert None not in steps
    return sum(step for step in steps if step is not None)


def assert_chain(path: npt.NDArray[np.intp], start: Cell, end: Cell) -> None:
    """The path runs from start to end through 8-neighbours, each cell once."""
    assert path.shape[1] == 2
    assert tuple(path[0]) == start
    assert tuple(path[-1]) == end
    assert (np.abs(np.diff(path, axis=0)).max(axis=1) == 1).all()
    assert len({(x, y) for x, y in path.tolist()}) == len(path)


def random_costmap(rng: np.random.Generator, rows: int = 12, cols: int = 17) -> Grid:
    """Free, inflated, inscribed, lethal and unknown cells, mixed at random."""
    kind = rng.random((rows, cols))
    costs = rng.integers(1, INSCRIBED, (rows, cols))
    costs[kind < 0.45] = FREE
    costs[(kind >= 0.75) & (kind < 0.82)] = INSCRIBED
    costs[(kind >= 0.82) & (kind < 0.9)] = LETHAL
    costs[kind >= 0.9] = UNKNOWN
    return costs.astype(np.uint8)


def inflated(lethal: npt.NDArray[np.bool_]) -> Grid:
    """Costs as the inflation layer gives them: inscribed within 1 cell, decaying out to 4."""
    ys, xs = np.nonzero(lethal)
    xx, yy = np.meshgrid(np.arange(lethal.shape[1]), np.arange(lethal.shape[0]))
    distance = np.hypot(xx[..., None] - xs, yy[..., None] - ys).min(axis=-1)  # cells
    costs = np.where(distance <= 4, 252 * np.exp(1 - distance), 0).astype(np.uint8)
    costs[distance <= 1] = INSCRIBED
    costs[lethal] = LETHAL
    return costs


def corridor_grid(gap_row: int | None) -> Grid:
    """A lethal wall at x = 10 between start (2, 5) and goal (18, 5), with an unknown cell on
    the straight line and, in row `gap_row`, a free one."""
    costs = np.zeros((13, 21), dtype=np.uint8)
    costs[:, 10] = LETHAL
    costs[5, 10] = UNKNOWN
    if gap_row is not None:
        costs[gap_row, 10] = FREE
    return costs


def test_an_empty_grid_plans_a_straight_line() -> None:
    costs = np.zeros((20, 30), dtype=np.uint8)
    path = plan_path(costs, (2, 7), (25, 7), SETTINGS, RESOLUTION)
    assert path is not None
    assert path.tolist() == [[x, 7] for x in range(2, 26)]


def test_an_empty_grid_plans_a_diagonal_to_a_goal_at_45_degrees() -> None:
    costs = np.zeros((20, 30), dtype=np.uint8)
    path = plan_path(costs, (3, 2), (15, 14), SETTINGS, RESOLUTION)
    assert path is not None
    assert path.tolist() == [[3 + i, 2 + i] for i in range(13)]


@pytest.mark.parametrize("seed", range(30))
def test_the_potential_equals_a_brute_force_dijkstra_on_random_grids(seed: int) -> None:
    rng = np.random.default_rng(seed)
    costs = random_costmap(rng)
    settings = NavfnSettings(
        allow_unknown=bool(rng.random() < 0.5), cost_factor=float(rng.choice([0.8, 3.0]))
    )
    start = (int(rng.integers(costs.shape[1])), int(rng.integers(costs.shape[0])))
    assert (potential(costs, start, settings) == dijkstra(costs, start, settings)).all()


@pytest.mark.parametrize("seed", range(30))
def test_a_plan_to_a_reached_goal_costs_the_brute_force_potential_at_the_goal(seed: int) -> None:
    # The search stops once the goal is settled: the descent must still find a cheapest path.
    rng = np.random.default_rng(seed)
    costs = random_costmap(rng, rows=20, cols=25)
    costs[costs == UNKNOWN] = FREE  # fewer cells walled off, more goals reached
    start, goal = ((int(rng.integers(25)), int(rng.integers(20))) for _ in range(2))
    reached = dijkstra(costs, start, SETTINGS)[goal[1], goal[0]]
    path = plan_path(costs, start, goal, SETTINGS, RESOLUTION)
    if reached == UNREACHABLE:
        assert path is None or tuple(path[-1]) != goal
        return
    assert path is not None
    assert_chain(path, start, goal)
    assert path_cost(costs, path, SETTINGS) == reached


def test_the_potential_settles_along_a_winding_corridor() -> None:
    # A serpentine: every other column a wall, open alternately at the top and the bottom, so
    # the cheapest paths turn many times.
    costs = np.zeros((15, 31), dtype=np.uint8)
    for x in range(1, 31, 2):
        costs[:, x] = LETHAL
        costs[0 if x % 4 == 1 else 14, x] = FREE
    costs[4:11, 0] = 120
    assert (potential(costs, (0, 7), SETTINGS) == dijkstra(costs, (0, 7), SETTINGS)).all()


@pytest.mark.parametrize("shape", [(1, 9), (9, 1), (1, 1), (2, 2)])
def test_a_grid_one_or_two_cells_wide_plans_along_it(shape: tuple[int, int]) -> None:
    costs = np.zeros(shape, dtype=np.uint8)
    goal = (shape[1] - 1, shape[0] - 1)
    path = plan_path(costs, (0, 0), goal, SETTINGS, RESOLUTION)
    assert path is not None
    assert_chain(path, (0, 0), goal)
    assert len(path) == max(shape)


def test_the_path_goes_through_the_gap_in_a_wall_at_the_potential_s_cost() -> None:
    lethal = np.zeros((30, 40), dtype=bool)
    lethal[:20, 20] = True
    lethal[29:, 20] = True
    costs = inflated(lethal)
    start, goal = (5, 5), (35, 5)
    path = plan_path(costs, start, goal, SETTINGS, RESOLUTION)
    assert path is not None
    assert_chain(path, start, goal)
    assert (costs[path[:, 1], path[:, 0]] < INSCRIBED).all()
    crossing = path[path[:, 0] == 20, 1]
    assert crossing.size > 0
    assert ((crossing > 20) & (crossing < 28)).all()
    assert path_cost(costs, path, SETTINGS) == potential(costs, start, SETTINGS)[goal[1], goal[0]]


def test_a_goal_walled_off_completely_has_no_plan() -> None:
    costs = np.zeros((30, 30), dtype=np.uint8)
    costs[16:25, 16] = costs[16:25, 24] = LETHAL
    costs[16, 16:25] = costs[24, 16:25] = LETHAL
    # The goal's tolerance window (2 cells) lies inside the wall: nothing in it is reached.
    assert plan_path(costs, (3, 3), (20, 20), SETTINGS, RESOLUTION) is None


@pytest.mark.parametrize(
    ("code", "allow_unknown"), [(LETHAL, True), (INSCRIBED, True), (UNKNOWN, False)]
)
def test_a_start_on_a_cell_that_cannot_be_entered_still_plans_as_navfn_clears_the_robot_cell(
    code: int, allow_unknown: bool
) -> None:
    costs = np.zeros((10, 10), dtype=np.uint8)
    costs[4, 4] = code
    settings = NavfnSettings(allow_unknown=allow_unknown)
    path = plan_path(costs, (4, 4), (8, 8), settings, RESOLUTION)
    assert path is not None
    assert path[0].tolist() == [4, 4]
    assert path[-1].tolist() == [8, 8]


def test_a_diagonal_step_never_cuts_an_obstacle_corner() -> None:
    costs = np.zeros((5, 5), dtype=np.uint8)
    costs[0, 1] = costs[1, 0] = LETHAL
    assert plan_path(costs, (0, 0), (4, 4), SETTINGS, RESOLUTION) is None
    costs[0, 1] = FREE
    path = plan_path(costs, (0, 0), (4, 4), SETTINGS, RESOLUTION)
    assert path is not None
    assert path[:2].tolist() == [[0, 0], [1, 0]]


def test_unknown_cells_are_crossed_when_allowed_and_not_otherwise() -> None:
    costs = corridor_grid(gap_row=None)  # the unknown cell is the only way through
    path = plan_path(costs, (2, 5), (18, 5), SETTINGS, RESOLUTION)
    assert path is not None
    assert [10, 5] in path.tolist()
    assert plan_path(costs, (2, 5), (18, 5), NavfnSettings(allow_unknown=False), RESOLUTION) is None


def test_free_cells_are_preferred_to_a_shortcut_through_unknown_ones() -> None:
    # Through the unknown cell: 15 free steps and one at 253, 1003 in all. Round by the gap in
    # row 9: 8 free steps and 8 free diagonals, 965.7; by a gap in row 10, 6 and 10, 1007.1.
    detour = plan_path(corridor_grid(gap_row=9), (2, 5), (18, 5), SETTINGS, RESOLUTION)
    assert detour is not None
    assert [10, 9] in detour.tolist()
    assert [10, 5] not in detour.tolist()
    too_far = plan_path(corridor_grid(gap_row=10), (2, 5), (18, 5), SETTINGS, RESOLUTION)
    assert too_far is not None
    assert [10, 5] in too_far.tolist()


def test_a_lethal_goal_ends_the_path_at_the_nearest_reached_cell_within_tolerance() -> None:
    costs = np.zeros((25, 30), dtype=np.uint8)
    costs[9:12, 14:17] = LETHAL  # the goal (15, 10) and its 8 neighbours
    path = plan_path(costs, (2, 10), (15, 10), SETTINGS, RESOLUTION)
    assert path is not None
    # Four cells lie 2 cells off; NavfnROS keeps the first in [y, x] order.
    assert_chain(path, (2, 10), (15, 8))


def test_a_lethal_goal_with_nothing_reached_within_tolerance_has_no_plan() -> None:
    costs = np.zeros((25, 30), dtype=np.uint8)
    costs[8:13, 13:18] = LETHAL  # the goal (15, 10) and everything 2 cells about it
    assert plan_path(costs, (2, 10), (15, 10), SETTINGS, RESOLUTION) is None
    wider = NavfnSettings(default_tolerance=0.15)  # m: 3 cells, though 0.15 / 0.05 < 3 in floats
    path = plan_path(costs, (2, 10), (15, 10), wider, RESOLUTION)
    assert path is not None
    assert tuple(path[-1]) == (15, 7)


def test_the_same_input_gives_the_same_path() -> None:
    # Many paths tie on an open grid off the 45-degree lines; the planner always picks one.
    rng = np.random.default_rng(7)
    costs = random_costmap(rng, rows=40, cols=60)
    costs[costs >= INSCRIBED] = FREE
    costs[::3] = FREE
    first = plan_path(costs, (1, 2), (57, 31), SETTINGS, RESOLUTION)
    again = plan_path(costs.copy(), (1, 2), (57, 31), SETTINGS, RESOLUTION)
    assert first is not None
    assert again is not None
    assert np.array_equal(first, again)


@pytest.mark.parametrize(
    ("start", "goal"), [((-1, 0), (3, 3)), ((0, 0), (3, 10)), ((10, 0), (0, 0))]
)
def test_a_cell_outside_the_grid_is_an_error(start: Cell, goal: Cell) -> None:
    costs = np.zeros((10, 10), dtype=np.uint8)
    with pytest.raises(ValueError, match="outside the costmap of 10 x 10 cells"):
        plan_path(costs, start, goal, SETTINGS, RESOLUTION)


def test_a_costmap_that_is_not_uint8_is_an_error() -> None:
    with pytest.raises(ValueError, match="uint8"):
        plan_path(np.zeros((10, 10)), (0, 0), (3, 3), SETTINGS, RESOLUTION)
