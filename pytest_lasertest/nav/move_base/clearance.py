"""How near a footprint comes to lethal cells: the least signed distance over each group of poses
(a rollout's steps), exact, computed only where it can be least.

The signed distance from a convex footprint at a pose to a point is the largest of its edge
lines' (normal . point - offset): <= 0 inside, and outside at most the Euclidean distance (less
by a corner). DWA needs only its least over a rollout's steps and the cells near them. With
walls in the map that is thousands of cells at thousands of poses; kernels.py skips,
compiled, the cells that cannot be nearest. A cell it measures is measured by these operations,
in this order, so the least is the same to the bit as measuring every cell at every pose:

    dx, dy = cell_x - x, cell_y - y                   (the cell from the base, odom axes)
    forward, left = dx * cos + dy * sin, dy * cos - dx * sin
    signed = max over edges of normal_x * forward + normal_y * left - scale * offset
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.nav.move_base.kernels import any_within, least_per_group

# m: covers the rounding of the bounds, so a square kept in doubt changes no least.
ROUNDING = 1e-9


@dataclass(frozen=True)
class Edges:
    """A convex footprint's edges, counter-clockwise: signed distance = normal . point - offset."""

    normals: FloatArray  # (V, 2) unit outward normals
    offsets: FloatArray  # (V,) m

    @classmethod
    def of(cls, footprint: FloatArray) -> Edges:
        """The edges of a footprint (V, 2) m, its vertices counter-clockwise."""
        edges = np.roll(footprint, -1, axis=0) - footprint
        normals = np.column_stack([edges[:, 1], -edges[:, 0]])
        normals /= np.hypot(normals[:, 0], normals[:, 1])[:, np.newaxis]
        return cls(normals, (normals * footprint).sum(axis=1))


@dataclass(frozen=True)
class Poses:
    """P poses in the odom frame, each with the footprint grown by its own scale, in G groups of
    P / G consecutive poses."""

    x: FloatArray  # (P,) m
    y: FloatArray  # (P,) m
    yaw: FloatArray  # (P,) rad
    scale: FloatArray  # (P,)
    groups: int

    @property
    def per_group(self) -> int:
        """How many poses each group holds."""
        return len(self.x) // self.groups


def least_gaps(edges: Edges, poses: Poses, lethal: FloatArray, side: float) -> FloatArray:
    """The least signed distance (m) from the footprint at any pose of each group to a lethal
    cell centre (N, 2), shape (G,), inf if there is none; the cells grouped in squares of `side`
    m to skip those that cannot be nearest."""
    table = np.stack(
        [poses.x, poses.y, poses.yaw, np.cos(poses.yaw), np.sin(poses.yaw), poses.scale]
    )
    least: FloatArray = least_per_group(
        edges.normals, edges.offsets, table, poses.groups, _cells(lethal), side, ROUNDING
    )
    return least


def cell_within(points: FloatArray, lethal: FloatArray, reach: float) -> npt.NDArray[np.bool_]:
    """Whether a lethal cell centre (N, 2) m lies within `reach` m of each point (P, 2) m,
    shape (P,)."""
    near: npt.NDArray[np.bool_] = any_within(_cells(points), _cells(lethal), reach)
    return near


def _cells(points: FloatArray) -> FloatArray:
    """Points (N, 2) m as the kernels take them: float64, C-contiguous."""
    return np.ascontiguousarray(points, dtype=np.float64).reshape(-1, 2)
