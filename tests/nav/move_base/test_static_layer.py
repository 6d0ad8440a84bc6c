"""The global costmap's static layer: the world's map under the obstacle layer, as costmap_2d's
StaticLayer and LayeredCostmap combine them (static first, then the obstacle layer's
updateWithMax, then inflation), and move_base planning round a wall it has never seen."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pytest_lasertest.model.geometry import FloatArray, Point2D
from pytest_lasertest.model.obstacles import Box
from pytest_lasertest.model.occupancy import FREE as MAP_FREE
from pytest_lasertest.model.occupancy import OCCUPIED, OccupancyGrid, rasterised
from pytest_lasertest.model.occupancy import UNKNOWN as MAP_UNKNOWN
from pytest_lasertest.nav.move_base import MoveBase
from pytest_lasertest.nav.move_base.cost_values import FREE, INSCRIBED, LETHAL, UNKNOWN
from pytest_lasertest.nav.move_base.costmap import Costmap, CostmapSettings
from pytest_lasertest.nav.move_base.static_layer import StaticLayerSettings, with_max
from pytest_lasertest.nav.protocol import LaserScan, Odometry
from pytest_lasertest.pairsfile import load_pairs_file
from tests.helpers import EXAMPLES
from tests.helpers.costmap import cost_at, scan

FOOTPRINT = np.array([[-0.5, -0.3], [0.5, -0.3], [0.5, 0.3], [-0.5, 0.3]])
SETTINGS = CostmapSettings(size=12.0, obstacle_range=5.5, raytrace_range=6.0)
TRACKING = CostmapSettings(
    size=12.0, obstacle_range=5.5, raytrace_range=6.0, track_unknown_space=True
)
ROBOT = (0.0, 0.0, 0.0)
NOTHING = scan(math.inf)  # three beams, none returning: the window follows, nothing is seen
RESOLUTION = 0.05  # m, the maps' cells
Rectangle = tuple[float, float, float, float]  # x from, x to, y from, y to (m)


def a_map(
    *cells: tuple[Rectangle, int],
    low: tuple[float, float] = (-6.0, -6.0),
    high: tuple[float, float] = (6.0, 6.0),
) -> OccupancyGrid:
    """A free map from `low` to `high` (m) at RESOLUTION, each rectangle of `cells` set to its
    value."""
    width, height = (round((b - a) / RESOLUTION) for a, b in zip(low, high, strict=True))
    data = np.full((height, width), MAP_FREE, dtype=np.int8)
    for (x0, x1, y0, y1), value in cells:
        columns = slice(round((x0 - low[0]) / RESOLUTION), round((x1 - low[0]) / RESOLUTION))
        rows = slice(round((y0 - low[1]) / RESOLUTION), round((y1 - low[1]) / RESOLUTION))
        data[rows, columns] = value
    return OccupancyGrid(RESOLUTION, low, data)


# A wall two cells thick across the robot's way, 2 m ahead.
WALL = a_map(((2.0, 2.1, -0.5, 0.5), OCCUPIED))


def with_map(
    grid: OccupancyGrid, settings: CostmapSettings = SETTINGS, track: bool | None = None
) -> Costmap:
    """A costmap with `grid` as its static layer (tracking unknown space as the costmap does
    unless `track` says), its window centred on the robot by one scan of nothing."""
    costmap = Costmap(settings, FOOTPRINT)
    tracking = settings.track_unknown_space if track is None else track
    costmap.receive_map(grid, StaticLayerSettings(tracking))
    costmap.update(NOTHING, ROBOT)
    return costmap


def test_a_map_cell_marked_occupied_is_lethal_in_the_global_costmap_before_any_scan_sees_it() -> (
    None
):
    costmap = with_map(WALL)
    costs = costmap.costs()
    assert cost_at(costmap, 2.05, 0.0, costs) == LETHAL
    # The obstacle layer has seen nothing there; the wall is inflated as any lethal cell is.
    assert cost_at(costmap, 2.05, 0.0) == FREE
    assert cost_at(costmap, 1.85, 0.0, costs) == INSCRIBED
    assert 0 < cost_at(costmap, 1.6, 0.0, costs) < INSCRIBED
    assert cost_at(costmap, 2.05, 1.5, costs) == FREE


def test_a_scans_clearing_ray_through_a_wall_cell_does_not_free_it() -> None:
    costmap = with_map(WALL)
    costmap.grid[:] = LETHAL  # as if the obstacle layer had marked everything before
    costmap.update(scan(3.02), ROBOT)  # the ray to 3.02 m runs through the wall at 2 m
    costs = costmap.costs()
    # The obstacle layer's own cells are cleared all along the ray; the wall's cost stays.
    for x in (1.0, 2.05, 2.97):
        assert cost_at(costmap, x, 0.0) == FREE
    assert cost_at(costmap, 2.05, 0.0, costs) == LETHAL
    assert cost_at(costmap, 3.02, 0.0, costs) == LETHAL


def test_a_scan_marks_an_obstacle_on_a_map_cell_the_map_calls_free() -> None:
    costmap = with_map(WALL)
    costmap.update(scan(1.02), ROBOT)
    assert cost_at(costmap, 1.02, 0.0, costmap.costs()) == LETHAL


@pytest.mark.parametrize("track_unknown_space", [True, False], ids=["tracking", "not tracking"])
def test_unknown_map_cells_are_unknown_with_track_unknown_space_and_free_without(
    track_unknown_space: bool,
) -> None:
    # Unknown cells 1 to 1.5 m ahead; the map's free cells beside them are known free.
    grid = a_map(((1.0, 1.5, -0.25, 0.25), MAP_UNKNOWN))
    settings = TRACKING if track_unknown_space else SETTINGS
    costmap = with_map(grid, settings)
    unknown = UNKNOWN if track_unknown_space else FREE
    assert cost_at(costmap, 1.25, 0.0, costmap.costs()) == unknown
    assert cost_at(costmap, 1.25, 1.0, costmap.costs()) == FREE
    # A clearing ray frees it: the obstacle layer's free cell overwrites the unknown one.
    costmap.update(scan(3.02), ROBOT)
    assert cost_at(costmap, 1.25, 0.0, costmap.costs()) == FREE
    assert cost_at(costmap, 1.25, 0.2, costmap.costs()) == unknown  # beside the ray


def test_a_static_layer_that_tracks_unknown_space_in_a_costmap_that_does_not_leaves_them_free() -> (
    None
):
    # ROS 1's layer tracks unknown space unless told; the costmap's free obstacle layer
    # overwrites the unknown cells it writes, as updateWithMax does.
    grid = a_map(((1.0, 1.5, -0.25, 0.25), MAP_UNKNOWN))
    costmap = with_map(grid, SETTINGS, track=True)
    assert cost_at(costmap, 1.25, 0.0, costmap.costs()) == FREE


@pytest.mark.parametrize("track_unknown_space", [True, False], ids=["tracking", "not tracking"])
def test_cells_off_the_map_read_as_the_costmap_resets_them_until_a_scan_sees_them(
    track_unknown_space: bool,
) -> None:
    grid = a_map(low=(-1.0, -1.0), high=(1.0, 1.0))  # the window reaches 5 m past it
    costmap = with_map(grid, TRACKING if track_unknown_space else SETTINGS)
    unseen = UNKNOWN if track_unknown_space else FREE
    assert cost_at(costmap, 0.5, 0.5, costmap.costs()) == FREE  # on the map
    assert cost_at(costmap, 3.0, 2.0, costmap.costs()) == unseen
    costmap.update(scan(3.02), ROBOT)
    assert cost_at(costmap, 2.0, 0.0, costmap.costs()) == FREE
    assert cost_at(costmap, 3.02, 0.0, costmap.costs()) == LETHAL


def test_clearing_the_costmap_in_a_recovery_keeps_the_walls_of_the_map() -> None:
    costmap = with_map(WALL)
    costmap.update(scan(3.02), ROBOT)
    costmap.clear_outside(0.0, 0.0, 0.0)
    costs = costmap.costs()
    assert cost_at(costmap, 2.05, 0.0, costs) == LETHAL
    assert cost_at(costmap, 3.02, 0.0, costs) == FREE


def test_the_layers_combine_as_update_with_max_after_a_true_overwrite() -> None:
    values = np.array([FREE, 100, INSCRIBED, LETHAL, UNKNOWN], dtype=np.uint8)
    static, obstacle = np.meshgrid(values, values, indexing="ij")
    combined = with_max(static, obstacle)
    for s, o, c in zip(static.ravel(), obstacle.ravel(), combined.ravel(), strict=True):
        expected = s if o == UNKNOWN else (o if s == UNKNOWN else max(s, o))
        assert c == expected, (s, o)


@pytest.mark.parametrize(
    ("settings", "expected"),
    [
        # ROS 1's defaults: -1 unknown, from 100 lethal, the rest free.
        (StaticLayerSettings(), {0: FREE, 50: FREE, 99: FREE, 100: LETHAL, -1: UNKNOWN}),
        (StaticLayerSettings(track_unknown_space=False), {-1: FREE, 100: LETHAL}),
        # Any other negative value reads above 100 as a byte: lethal.
        (StaticLayerSettings(), {-2: LETHAL, -128: LETHAL}),
        # Scaled, truncated: 50 / 100 * 254 = 127.
        (StaticLayerSettings(trinary_costmap=False), {50: 127, 1: 2, 99: 251, 100: LETHAL}),
        (StaticLayerSettings(lethal_cost_threshold=65), {64: FREE, 65: LETHAL}),
        (StaticLayerSettings(unknown_cost_value=50), {50: UNKNOWN, -1: LETHAL}),
        # Nav2's releases imitated read 99 as ROS 1 does (inscribed_obstacle_cost_value came later).
        (StaticLayerSettings.nav2(True), {99: FREE, 98: FREE, 100: LETHAL, -1: UNKNOWN}),
    ],
)
def test_map_values_become_costs_as_interpret_value_turns_them(
    settings: StaticLayerSettings, expected: dict[int, int]
) -> None:
    table = settings.costs()
    for value, cost in expected.items():
        assert table[value & 0xFF] == cost, value


@pytest.mark.parametrize("seed", range(3))
def test_each_window_cell_reads_the_map_cell_under_its_centre_wherever_the_window_rolls(
    seed: int,
) -> None:
    # A coarser map than the costmap, its origin off the costmap's cells, smaller than the
    # window: every window cell is the map's cell under its centre, or unseen off the map.
    rng = np.random.default_rng(seed)
    data = rng.choice(np.array([MAP_FREE, 30, OCCUPIED, MAP_UNKNOWN], dtype=np.int8), (70, 90))
    grid = OccupancyGrid(0.1, (-4.03, -2.51), data)
    costmap = Costmap(TRACKING, FOOTPRINT)
    costmap.receive_map(grid, StaticLayerSettings())
    table = StaticLayerSettings().costs()
    for x, y in rng.uniform(-3.0, 3.0, (6, 2)):
        costmap.update(NOTHING, (float(x), float(y), 0.0))
        assert costmap.static is not None
        cells = costmap.settings.cells
        everywhere = range(cells)
        resolution = costmap.settings.resolution
        window = costmap.static.block(costmap.origin, resolution, everywhere, everywhere)
        columns, rows = np.meshgrid(np.arange(cells), np.arange(cells))
        centres = costmap.centres(columns.ravel(), rows.ravel())
        expected = table[grid.values_at(centres).view(np.uint8)].reshape(cells, cells)
        np.testing.assert_array_equal(window, expected)


def test_a_block_of_the_window_reads_what_the_whole_window_holds_there() -> None:
    costmap = with_map(WALL)
    costmap.update(NOTHING, (0.37, -0.21, 0.0))
    assert costmap.static is not None
    settings, everywhere = costmap.settings, range(costmap.settings.cells)
    whole = costmap.static.block(costmap.origin, settings.resolution, everywhere, everywhere)
    x, y, _ = costmap.cell_of(np.array([[1.0, 0.0]]))  # the row through the wall, from 1 m
    columns, rows = range(int(x[0]), int(x[0]) + 40), range(int(y[0]), int(y[0]) + 3)
    block = costmap.static.block(costmap.origin, settings.resolution, columns, rows)
    np.testing.assert_array_equal(
        block, whole[rows.start : rows.stop][:, columns.start : columns.stop]
    )
    assert (block == LETHAL).any()  # the wall crosses it
    assert (block != LETHAL).any()


def test_without_a_map_the_costs_combine_nothing_but_the_obstacle_layer() -> None:
    costmap = Costmap(SETTINGS, FOOTPRINT)
    costmap.update(scan(3.02), ROBOT)
    assert costmap.static is None
    assert np.shares_memory(costmap.combined(), costmap.grid)


# --- move_base ---

PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
TEN_METRES = next(pair for pair in PAPER.pairs if pair.name == "distance").baseline.profile
GOAL = Point2D(6.0, 0.0)
# 4 m of wall across the straight line to the goal, 3 m ahead, in a map drawn as a pairs file's
# walls are (1 m of free cells round it).
ACROSS = Box(3.0, 0.0, 0.0, 0.2, 4.0, 2.0)
ACROSS_MAP = rasterised((ACROSS,), RESOLUTION, 1.0)


def first_plan(robot_map: OccupancyGrid | None) -> FloatArray:
    """The Husky's move_base's plan (K, 2) m to GOAL after one scan in which it sees nothing
    (the 10 m scanner: every ray clears 6 m, none marks)."""
    move_base = MoveBase(PAPER.robot, (GOAL,))
    if robot_map is not None:
        move_base.receive_map(robot_map)
    nothing = np.full(TEN_METRES.beam_count, np.inf)
    meta = TEN_METRES.to_laserscan_meta()
    move_base.observe(LaserScan(0.0, nothing, meta, TEN_METRES.pose), Odometry(0, 0, 0, 0, 0), 0.0)
    return move_base.plan


def distance_to(box: Box, points: FloatArray) -> FloatArray:
    """How far each point (P, 2) lies outside the axis-aligned box (0 inside), (P,) m."""
    along = np.abs(points[:, 0] - box.x) - box.length / 2.0
    across = np.abs(points[:, 1] - box.y) - box.width / 2.0
    gap: FloatArray = np.hypot(np.maximum(along, 0.0), np.maximum(across, 0.0))
    return gap


def test_move_base_given_a_map_with_a_wall_across_its_way_plans_round_the_wall() -> None:
    plan = first_plan(ACROSS_MAP)
    assert len(plan)
    assert math.dist(plan[-1], (GOAL.x, GOAL.y)) < 0.1
    # It keeps out of the wall's inscribed cells (the Husky's inscribed radius is 0.34 m).
    assert distance_to(ACROSS, plan).min() > 0.34
    assert np.abs(plan[:, 1]).max() > ACROSS.width / 2.0


def test_move_base_without_the_map_plans_straight_through_the_wall_it_has_not_seen() -> None:
    plan = first_plan(None)
    assert np.abs(plan[:, 1]).max() < 0.1
    assert distance_to(ACROSS, plan).min() == 0.0
