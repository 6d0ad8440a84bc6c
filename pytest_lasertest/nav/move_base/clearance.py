"""How near a footprint comes to lethal cells: the least signed distance over each group of poses
(a rollout's steps), exact, computed only where it can be least.

The signed distance from a convex footprint at a pose to a point is the largest of its edge
lines' (normal . point - offset): <= 0 inside, and outside at most the Euclidean distance (less
by a corner). DWA needs only its least over a rollout's steps and the cells near them. With
walls in the map that is thousands of cells at thousands of poses, so the cells are grouped in
squares first. The signed distance is a maximum of functions of slope 1, so it changes by no
more than a point moves: a square's cells lie within its radius of its centre, and lie no
nearer than the centre's distance less that radius, nor further than it plus the radius. A
square whose nearest bound is beyond the best furthest bound of its group of poses cannot hold
the least, and its cells are not measured there. Every cell that is measured is measured as
the direct computation does, operation for operation, so the least is the same to the bit.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.geometry import FloatArray

IntArray = npt.NDArray[np.int64]

# Below this many cells the squares cost more than they save.
DIRECT_CELLS = 64
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


@dataclass(frozen=True)
class _Frames:
    """The distinct poses' frames, each computed once: where the footprint stands and faces."""

    x: FloatArray  # (K, 1) m
    y: FloatArray  # (K, 1) m
    cos: FloatArray  # (K, 1)
    sin: FloatArray  # (K, 1)
    offsets: FloatArray  # (K, V) m, the edges' offsets grown by the pose's scale

    def at(self, rows: IntArray) -> _Frames:
        return _Frames(
            self.x[rows], self.y[rows], self.cos[rows], self.sin[rows], self.offsets[rows]
        )


@dataclass(frozen=True)
class _Squares:
    """Lethal cells grouped in squares: each square's centre, radius and cells."""

    centres: FloatArray  # (B, 2) m
    radius: FloatArray  # (B,) m, to the square's furthest cell
    points: FloatArray  # (B, M, 2) m, its cells, its first repeated to fill its row


def least_gaps(edges: Edges, poses: Poses, lethal: FloatArray, side: float) -> FloatArray:
    """The least signed distance (m) from the footprint at any pose of each group to a lethal
    cell centre (N, 2), shape (G,); the cells grouped in squares of `side` m to skip those that
    cannot be nearest."""
    pose = _distinct(poses)
    starts = np.searchsorted(pose, np.arange(poses.groups) * poses.per_group)
    frames = _frames(edges, poses, pose)
    if len(lethal) <= DIRECT_CELLS:
        direct = _signed(edges, frames, lethal[np.newaxis]).min(axis=1)
        least: FloatArray = np.minimum.reduceat(direct, starts)
        return least
    squares = _squares(lethal, side)
    at_centres = _bounds(edges, frames, squares.centres)  # (K, B)
    furthest = np.minimum.reduceat((at_centres + squares.radius).min(axis=1), starts)  # (G,)
    bound = np.repeat(furthest, np.diff(np.r_[starts, len(pose)]))[:, np.newaxis]
    row, square = np.nonzero(at_centres - squares.radius <= bound)
    measured = _signed(edges, frames.at(row), squares.points[square]).min(axis=1)
    # Each group keeps at least the square its furthest bound came from.
    result: FloatArray = np.minimum.reduceat(measured, np.searchsorted(row, starts))
    return result


def _distinct(poses: Poses) -> IntArray:
    """The poses (K,) that are not the pose before them in their group: a rollout that ends
    before the longest stays at its last pose, and measuring it again changes no least."""
    same = (np.diff(poses.x) == 0.0) & (np.diff(poses.y) == 0.0) & (np.diff(poses.yaw) == 0.0)
    # A group's first pose is no repeat of the group before's last.
    same[poses.per_group - 1 :: poses.per_group] = False
    distinct: IntArray = np.flatnonzero(np.r_[True, ~same])
    return distinct


def _frames(edges: Edges, poses: Poses, pose: IntArray) -> _Frames:
    """The frames of poses[pose] (K,)."""
    yaw = poses.yaw[pose][:, np.newaxis]
    offsets = poses.scale[pose][:, np.newaxis] * edges.offsets
    return _Frames(
        poses.x[pose][:, np.newaxis],
        poses.y[pose][:, np.newaxis],
        np.cos(yaw),
        np.sin(yaw),
        offsets,
    )


def _signed(edges: Edges, frames: _Frames, points: FloatArray) -> FloatArray:
    """The signed distance of points (K or 1, M, 2) from the footprint in each frame (K,),
    shape (K, M): an element is computed by the same operations whichever way it is reached,
    so the least is the same to the bit."""
    dx, dy = points[..., 0] - frames.x, points[..., 1] - frames.y
    cos, sin = frames.cos, frames.sin
    forward, left = dx * cos + dy * sin, dy * cos - dx * sin
    signed = np.full(forward.shape, -np.inf)
    for edge, (normal_x, normal_y) in enumerate(edges.normals):
        np.maximum(
            signed,
            normal_x * forward + normal_y * left - frames.offsets[:, edge : edge + 1],
            out=signed,
        )
    return signed


def _bounds(edges: Edges, frames: _Frames, points: FloatArray) -> FloatArray:
    """The signed distance of points (B, 2) from the footprint in each frame (K,), shape (K, B),
    within ROUNDING of `_signed`'s: each edge's normal turned into the odom frame once per pose,
    so a point costs five operations an edge instead of seven."""
    bounds = np.full((len(frames.x), len(points)), -np.inf)
    for edge, (normal_x, normal_y) in enumerate(edges.normals):
        turned_x = normal_x * frames.cos - normal_y * frames.sin  # (K, 1)
        turned_y = normal_x * frames.sin + normal_y * frames.cos
        offset = turned_x * frames.x + turned_y * frames.y + frames.offsets[:, edge : edge + 1]
        np.maximum(bounds, turned_x * points[:, 0] + turned_y * points[:, 1] - offset, out=bounds)
    return bounds


def _squares(lethal: FloatArray, side: float) -> _Squares:
    """The cells (N, 2) grouped by the `side` m square of the plane each lies in."""
    keys = np.floor(lethal / side).astype(np.int64)
    _, square = np.unique(keys, axis=0, return_inverse=True)
    square = square.ravel()
    order = np.argsort(square, kind="stable")
    ordered = square[order]
    starts = np.flatnonzero(np.r_[True, ordered[1:] != ordered[:-1]])
    rank = np.arange(len(order)) - np.repeat(starts, np.diff(np.r_[starts, len(order)]))
    cells = np.repeat(order[starts][:, np.newaxis], int(rank.max()) + 1, axis=1)
    cells[ordered, rank] = order
    ordered_cells = lethal[order]
    low, high = (
        np.minimum.reduceat(ordered_cells, starts),
        np.maximum.reduceat(ordered_cells, starts),
    )
    centres = (low + high) / 2.0
    points = lethal[cells]  # (B, M, 2)
    reach = points - centres[:, np.newaxis]
    # The margin covers the rounding of the bounds, which `_bounds` computes another way.
    radius = np.hypot(reach[..., 0], reach[..., 1]).max(axis=1) + ROUNDING
    return _Squares(centres, radius, points)
