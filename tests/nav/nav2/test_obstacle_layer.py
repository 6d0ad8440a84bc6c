"""Nav2's obstacle layer, release by release: navigation2 #6084 and #5476 reappear where the
release that had them is imitated, and not elsewhere."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pytest_lasertest.nav.nav2.obstacle_layer import (
    Marking,
    ObservationSource,
    Window,
    cleared,
    marked,
)

WINDOW = Window(origin_x=-2.0, origin_y=-2.0, resolution=0.05, size_x=80, size_y=80)
INF_AS = 0.80 - 1e-4  # m: +inf with inf_is_valid and range_max 0.80 (laserScanValidInfCallback)


def ring(sensor: tuple[float, float], radius: float, beams: int = 720) -> np.ndarray:
    """A scan's points (beams, 2) m, all `radius` from the sensor: an empty room's no-returns."""
    angles = np.linspace(-math.pi, math.pi, beams, endpoint=False)
    return np.column_stack(
        [sensor[0] + radius * np.cos(angles), sensor[1] + radius * np.sin(angles)]
    )


def sensor_positions(count: int = 40) -> list[tuple[float, float]]:
    """Where a laser mounted off the base's centre passes while the robot turns in place."""
    turns = np.linspace(0.0, 2.0 * math.pi, count, endpoint=False)
    return [(0.01 + 0.17 * math.cos(turn), 0.02 + 0.17 * math.sin(turn)) for turn in turns]


def test_no_returns_read_as_range_max_mark_phantom_cells_only_with_the_1_3_11_cell_rule() -> None:
    # navigation2 #6084: inf_is_valid, obstacle_max_range 0.70, range_max 0.80, 0.05 m cells.
    source = ObservationSource(obstacle_max_range=0.70)
    phantoms = {
        marking: sum(
            len(marked(WINDOW, sensor, ring(sensor, INF_AS), source, marking))
            for sensor in sensor_positions()
        )
        for marking in Marking
    }
    assert phantoms[Marking.CELLS] > 0
    assert phantoms[Marking.CELLS_PREFILTERED] == 0
    assert phantoms[Marking.EUCLIDEAN] == 0


def _after_update(marking: Marking, sensor: tuple[float, float], obstacle: np.ndarray) -> int:
    """The cost of the obstacle's cell, lethal before a scan that reads it, after that scan
    clears and then marks (254 lethal, 0 free)."""
    grid = np.full(WINDOW.size_x * WINDOW.size_y, 254, dtype=np.uint8)
    source = ObservationSource(obstacle_max_range=0.72, raytrace_max_range=0.72)
    grid[cleared(WINDOW, sensor, obstacle, source)] = 0
    grid[marked(WINDOW, sensor, obstacle, source, marking)] = 254
    x, y, _ = WINDOW.cells_of(obstacle[:, 0], obstacle[:, 1])
    return int(grid[x[0] + y[0] * WINDOW.size_x])


@pytest.mark.parametrize(
    ("marking", "kept"),
    [(Marking.EUCLIDEAN, False), (Marking.CELLS, True), (Marking.CELLS_PREFILTERED, False)],
)
def test_an_obstacle_backed_away_from_past_obstacle_max_range_stays_only_under_the_cell_rule(
    marking: Marking, kept: bool
) -> None:
    # navigation2 #5476: equal marking and clearing ranges; the robot has backed away until the
    # obstacle reads 0.74 m off, past 0.72 m yet 15 cells (ceil(0.72 / 0.05)) along the ray,
    # which clearing reaches. The release that fixed it (1.3.11) keeps it; 1.3.12's world
    # pre-filter loses it again, as its test testPointBeyondObstacleMaxRangeNotMarkedWhen-
    # SameMapCell asserts.
    sensor = (0.012, 0.01)
    obstacle = np.array([[sensor[0] + 0.74, sensor[1]]])
    assert (_after_update(marking, sensor, obstacle) == 254) is kept


def test_a_ray_frees_the_cells_to_its_end_from_raytrace_min_range_on() -> None:
    sensor = (0.01, 0.01)
    point = np.array([[0.51, 0.01]])  # 10 cells along x
    near = ObservationSource(raytrace_min_range=0.0)
    far = ObservationSource(raytrace_min_range=0.2)  # 4 cells
    from_sensor = cleared(WINDOW, sensor, point, near) - (40 + 40 * WINDOW.size_x)
    from_min_range = cleared(WINDOW, sensor, point, far) - (40 + 40 * WINDOW.size_x)
    assert from_sensor.tolist() == list(range(11))  # the end cell too, as bresenham2D does
    assert from_min_range.tolist() == list(range(4, 11))


def test_a_ray_shorter_than_raytrace_min_range_frees_nothing_and_a_long_one_stops() -> None:
    sensor = (0.01, 0.01)
    source = ObservationSource(raytrace_min_range=0.2, raytrace_max_range=0.3)  # 4 and 6 cells
    assert len(cleared(WINDOW, sensor, np.array([[0.16, 0.01]]), source)) == 0
    freed = cleared(WINDOW, sensor, np.array([[1.01, 0.01]]), source) - (40 + 40 * WINDOW.size_x)
    # raytraceLine scales the steps from the start at min range by max / whole length: 0.3.
    assert freed.tolist() == list(range(4, 4 + int(0.3 * 16) + 1))


def test_a_sensor_off_the_window_neither_marks_under_the_cell_rules_nor_clears() -> None:
    sensor = (-3.0, 0.0)
    points = np.array([[-1.5, 0.0]])
    source = ObservationSource()
    assert len(cleared(WINDOW, sensor, points, source)) == 0
    assert len(marked(WINDOW, sensor, points, source, Marking.CELLS)) == 0
    # The world rule never asks where the sensor is.
    assert len(marked(WINDOW, sensor, points, source, Marking.EUCLIDEAN)) == 1
