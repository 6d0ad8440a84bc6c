"""The footprint's clearance from lethal cells: the compiled kernels skip only cells that cannot
be nearest, so the least over each rollout is the direct computation's to the bit, and which
points lie within reach of a cell is what numpy says."""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.nav.move_base.clearance import Edges, Poses, cell_within, least_gaps
from pytest_lasertest.nav.move_base.dwa import SQUARE_CELLS

RESOLUTION = 0.05  # m
SIDE = SQUARE_CELLS * RESOLUTION  # m, the squares DWA groups cells in
HUSKY = np.array([[-0.5, -0.33], [0.5, -0.33], [0.5, 0.33], [-0.5, 0.33]])  # m


def direct(edges: Edges, poses: Poses, lethal: FloatArray) -> FloatArray:
    """Every pose against every cell, by the operations clearance.py's docstring writes, then
    the least of each group."""
    x, y, yaw = (values[:, np.newaxis] for values in (poses.x, poses.y, poses.yaw))
    dx, dy = lethal[:, 0] - x, lethal[:, 1] - y  # (P, N) m
    forward, left = dx * np.cos(yaw) + dy * np.sin(yaw), dy * np.cos(yaw) - dx * np.sin(yaw)
    offsets = poses.scale[:, np.newaxis] * edges.offsets  # (P, V) m
    signed = np.full(forward.shape, -np.inf)
    for edge, (normal_x, normal_y) in enumerate(edges.normals):
        np.maximum(
            signed, normal_x * forward + normal_y * left - offsets[:, edge : edge + 1], out=signed
        )
    per_group: FloatArray = signed.min(axis=1).reshape(poses.groups, -1).min(axis=1)
    return per_group


def footprint(rng: np.random.Generator) -> FloatArray:
    """A convex footprint, counter-clockwise, around the base: 3 to 8 points on an ellipse."""
    count = int(rng.integers(3, 9))
    angles = np.sort(rng.uniform(0.0, 2.0 * np.pi, count))
    # Spread out, so that the base lies inside and no edge is degenerate.
    angles = np.linspace(0.0, 2.0 * np.pi, count, endpoint=False) + 0.3 * (angles - np.pi) / count
    radii = rng.uniform(0.1, 0.6, 2)
    return np.column_stack([radii[0] * np.cos(angles), radii[1] * np.sin(angles)])


def rollouts(rng: np.random.Generator, groups: int, steps: int) -> Poses:
    """Arcs from one pose, each ending at its own step and staying there, as DWA rolls out."""
    start = rng.uniform(-1.0, 1.0, 3)
    speed, turn = rng.uniform(0.0, 0.03, groups), rng.uniform(-0.1, 0.1, groups)
    ends = rng.integers(1, steps + 1, groups)
    taken = np.minimum(np.arange(steps), ends[:, np.newaxis] - 1)
    yaw = start[2] + turn[:, np.newaxis] * taken
    advance = speed[:, np.newaxis] * (taken > 0) * (np.arange(steps) < ends[:, np.newaxis])
    x = start[0] + np.cumsum(advance * np.cos(yaw), axis=1)
    y = start[1] + np.cumsum(advance * np.sin(yaw), axis=1)
    scale = np.repeat(rng.uniform(1.0, 1.2, groups), steps)
    return Poses(x.ravel(), y.ravel(), yaw.ravel(), scale, groups)


def cells(rng: np.random.Generator) -> FloatArray:
    """Lethal cell centres: walls of whole cells (solid blocks) and scattered marks."""
    grid = np.zeros((60, 60), dtype=bool)
    for _ in range(int(rng.integers(2, 6))):
        x, y = rng.integers(0, 60, 2)
        grid[y : y + rng.integers(3, 20), x : x + rng.integers(3, 20)] = True
    grid |= rng.random(grid.shape) < 0.01
    rows, columns = np.nonzero(grid)
    indices = np.column_stack([columns, rows]).astype(np.float64)
    centres: FloatArray = (indices + 0.5) * RESOLUTION - 1.5
    return centres


@pytest.mark.parametrize("seed", range(40))
def test_the_least_gap_of_each_rollout_is_the_direct_computations_to_the_bit(seed: int) -> None:
    rng = np.random.default_rng(seed)
    edges = Edges.of(footprint(rng))
    poses, lethal = rollouts(rng, int(rng.integers(1, 30)), int(rng.integers(1, 40))), cells(rng)
    assert np.array_equal(least_gaps(edges, poses, lethal, SIDE), direct(edges, poses, lethal))


def test_a_single_cell_and_no_cell_give_the_direct_least_and_inf() -> None:
    rng = np.random.default_rng(7)
    edges, poses = Edges.of(HUSKY), rollouts(rng, 12, 20)
    lethal = cells(rng)[:1]
    assert np.array_equal(least_gaps(edges, poses, lethal, SIDE), direct(edges, poses, lethal))
    assert np.array_equal(least_gaps(edges, poses, np.empty((0, 2)), SIDE), np.full(12, np.inf))


def test_a_cell_under_the_footprint_gives_a_negative_gap_and_one_beside_it_its_distance() -> None:
    edges = Edges.of(HUSKY)
    poses = Poses(np.zeros(2), np.zeros(2), np.zeros(2), np.ones(2), 1)
    wall = np.column_stack([np.full(100, 0.83), np.linspace(-2.5, 2.5, 100)])  # 0.33 m ahead
    assert least_gaps(edges, poses, wall, SIDE) == pytest.approx([0.33])
    under = np.vstack([wall, [[0.1, 0.1]]])
    assert least_gaps(edges, poses, under, SIDE)[0] == pytest.approx(-0.23)


@pytest.mark.parametrize("seed", range(20))
def test_which_points_lie_within_reach_of_a_cell_is_what_numpys_hypot_says(seed: int) -> None:
    rng = np.random.default_rng(seed)
    lethal, reach = cells(rng), float(rng.uniform(0.05, 0.5))
    points = rng.uniform(-1.6, 1.6, (60, 2))
    # On the edge of reach: straight across and on the diagonal.
    points[:10] = lethal[:10] + np.array([reach, 0.0])
    points[10:20] = lethal[10:20] + reach / np.sqrt(2.0)
    gaps = np.hypot(points[:, 0:1] - lethal[:, 0], points[:, 1:2] - lethal[:, 1])
    expected = (gaps <= reach).any(axis=1)
    assert 0 < expected.sum() < len(points)
    assert np.array_equal(cell_within(points, lethal, reach), expected)


def test_no_cell_is_within_reach_of_anything() -> None:
    points = np.zeros((3, 2))
    assert not cell_within(points, np.empty((0, 2)), 1.0).any()
