"""MPPI's path handler: the part of the global plan each cycle's optimisation follows, and the
plan it keeps between cycles (nav2_mppi_controller/src/path_handler.cpp at jazzy f4108e5b,
PathHandler::transformPath, getGlobalPlanConsideringBoundsInCostmapFrame and prunePlan; the
iterator helpers min_by and first_after_integrated_distance of nav2_util/geometry_utils.hpp).

The plan is in the costmap's frame here (no tf) and enforce_path_inversion is not imitated.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.geometry import FloatArray

OnWindow = Callable[[FloatArray], npt.NDArray[np.bool_]]  # (P, 2) m -> (P,) inside the costmap


@dataclass(frozen=True)
class HandledPath:
    """One cycle's path (K, 2) m for the optimiser, and the plan (M, 2) m the handler keeps:
    the poses before the one nearest the robot erased, so that the next search starts there."""

    path: FloatArray
    plan: FloatArray


def transform_path(
    plan: FloatArray,
    pose: tuple[float, float, float],
    max_robot_pose_search_dist: float,  # m
    prune_distance: float,  # m
    on_window: OnWindow,
) -> HandledPath:
    """transformPath: the plan's pose nearest the robot among those within
    max_robot_pose_search_dist along it (the last of equals), and from it the poses up to
    prune_distance along it, cut before the first one off the local costmap. An empty `path`
    is Nav2's InvalidPath ("Resulting plan has 0 poses in it")."""
    bound = first_after_integrated_distance(plan, max_robot_pose_search_dist)
    away = np.hypot(plan[:bound, 0] - pose[0], plan[:bound, 1] - pose[1])
    # min_by keeps the later of equals (`comp <= lowest`).
    closest = len(away) - 1 - int(np.argmin(away[::-1])) if len(away) else 0
    kept = plan[closest:]
    ahead = kept[: first_after_integrated_distance(kept, prune_distance)]
    off = np.flatnonzero(~on_window(ahead))
    path = ahead[: off[0]] if len(off) else ahead
    return HandledPath(path, kept)


def max_costmap_dist(cells: int, resolution: float) -> float:
    """getMaxCostmapDist: half the costmap's larger side (m), `cells` a side of `resolution`
    (m): the search's bound where max_robot_pose_search_dist is not set."""
    return cells * resolution * 0.5


def first_after_integrated_distance(poses: FloatArray, distance: float) -> int:
    """The index of the first pose (N, 2) m further than `distance` (m) along the poses from
    the first, summed step by step; N if none is."""
    along = np.cumsum(np.hypot(*np.diff(poses, axis=0).T))  # m, to poses 1 .. N - 1
    beyond = np.flatnonzero(along > distance)
    return int(beyond[0]) + 1 if len(beyond) else len(poses)
