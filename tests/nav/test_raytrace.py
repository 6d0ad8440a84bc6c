"""The kernels both stacks share: costmap_2d's Bresenham line, compiled, visits the numpy code's
cells, ray by ray; the pairwise sum adds a float32 row as numpy's sum does."""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.nav.kernels import pairwise_sum
from pytest_lasertest.nav.raytrace import bresenham, bresenham_in_numpy


@pytest.mark.parametrize("seed", range(6))
def test_the_compiled_line_visits_the_numpy_lines_cells_in_order(seed: int) -> None:
    rng = np.random.default_rng(seed)
    # Rays from one cell (a laser) or from a cell each (a footprint's edges), to ends in every
    # direction, along the axes and diagonals too, cut short of their ends or not.
    rays = 300
    shared = seed % 2 == 0
    start_x = 100 if shared else rng.integers(0, 200, rays)
    start_y = 90 if shared else rng.integers(0, 200, rays)
    end_x, end_y = rng.integers(0, 200, rays), rng.integers(0, 200, rays)
    end_x[:30], end_y[30:60] = start_x if shared else start_x[:30], 90 if shared else 0
    major = np.maximum(np.abs(end_x - start_x), np.abs(end_y - start_y))
    steps = np.minimum(major, rng.integers(0, 300, rays))
    cells = bresenham(start_x, start_y, end_x, end_y, steps, 200)
    assert np.array_equal(cells, bresenham_in_numpy(start_x, start_y, end_x, end_y, steps, 200))
    assert len(cells) == int(steps.sum()) + rays


def test_no_rays_visit_no_cells() -> None:
    nothing = np.zeros(0, dtype=np.int64)
    assert len(bresenham(5, 5, nothing, nothing, nothing, 200)) == 0


@pytest.mark.parametrize("count", [0, 1, 7, 8, 13, 127, 128, 129, 300, 2000, 5003])
def test_the_pairwise_sum_of_a_row_is_numpys_sum_to_the_bit(count: int) -> None:
    # Values of many magnitudes and both signs, where any other order of adding would show.
    rng = np.random.default_rng(count)
    row = (rng.normal(0.0, 1.0, count) * 10.0 ** rng.integers(-3, 4, count)).astype(np.float32)
    total = np.float32(0.0) + pairwise_sum(row, 0, count)
    assert np.float32(total).view(np.uint32) == row.sum().view(np.uint32)
