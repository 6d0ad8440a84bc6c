"""The simulated laser: the rays of one scan, and the LaserScan ranges they give (REP 117).

Two ways to cast them: in PyBullet (`PhysicsWorld.cast`, what the scene really holds) or flat,
against the obstacles as upright prisms with the exact ray cast of `geometry` (every obstacle
here is one, standing on the ground). A test holds the two equal beam for beam.
"""

from __future__ import annotations

import numpy as np

from pytest_lasertest.geometry import FloatArray, Obstacle, ray_distances
from pytest_lasertest.sensor import LaserProfile


def scan_rays(profile: LaserProfile, pose: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The scan's rays from the scanner at robot pose [x, y, yaw] out to range_max, in the scan
    plane: starts and ends, each shape (N, 3), m."""
    origins, directions = profile.rays(pose[np.newaxis, :])
    height = np.full((profile.beam_count, 1), profile.scan_height)
    starts = np.hstack([origins[0], height])
    ends = np.hstack([origins[0] + profile.range_max * directions[0], height])
    return starts, ends


def ranges_from_fractions(profile: LaserProfile, fractions: FloatArray) -> FloatArray:
    """LaserScan ranges (N,) from where each ray of `scan_rays` first met something, as a fraction
    of range_max (1.0: nothing): +inf for no return, -inf nearer than range_min (REP 117)."""
    distances = np.where(fractions < 1.0, fractions * profile.range_max, np.inf)
    return _rep117(profile, distances)


def planar_ranges(
    profile: LaserProfile, pose: FloatArray, obstacles: tuple[Obstacle, ...]
) -> FloatArray:
    """LaserScan ranges (N,) of the scan at robot pose [x, y, yaw], cast flat against the
    obstacles that reach above the scan plane."""
    origins, directions = profile.rays(pose[np.newaxis, :])
    distances = np.full(profile.beam_count, np.inf)
    for obstacle in obstacles:
        if obstacle.height > profile.scan_height:
            distances = np.minimum(distances, ray_distances(origins[0], directions[0], obstacle))
    return _rep117(profile, np.where(distances <= profile.range_max, distances, np.inf))


def noisy(profile: LaserProfile, ranges: FloatArray, rng: np.random.Generator) -> FloatArray:
    """The ranges as the scanner reports them: Gaussian noise on in-range readings only, clamped
    to [range_min, range_max], then quantised to range.resolution when it is set."""
    reported = ranges.copy()
    in_range = np.isfinite(reported)
    if profile.noise is not None and profile.noise.stddev > 0.0:
        noise = rng.normal(profile.noise.mean, profile.noise.stddev, int(in_range.sum()))
        reported[in_range] = np.clip(
            reported[in_range] + noise, profile.range_min, profile.range_max
        )
    if profile.range_resolution > 0.0:
        steps = np.round(reported[in_range] / profile.range_resolution)
        reported[in_range] = steps * profile.range_resolution
    return reported


def _rep117(profile: LaserProfile, distances: FloatArray) -> FloatArray:
    ranges: FloatArray = np.where(distances < profile.range_min, -np.inf, distances)
    return ranges
