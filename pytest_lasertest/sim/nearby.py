"""Which obstacles can come near the robot, so that PyBullet is asked about those alone at every
physics step: by each obstacle's footprint (a box's rectangle, a cylinder's circle), not its
bounding circle, which for a 12 m wall holds most of a building.

The obstacles are found within `within` + REFRESH of the robot's reach, and found again once the
robot is REFRESH from where they were found: until then every other one is still further than
`within`, and none is looked at.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

from pytest_lasertest.model.obstacles import Box, Obstacle

# m: how far the robot moves before the obstacles near it are found again.
REFRESH = 0.25
# m: covers the rounding of a footprint's distance, so an obstacle kept in doubt is asked about.
ROUNDING = 1e-9


class Footprint(NamedTuple):
    """An obstacle's footprint as a rounded rectangle: its centre (m), its axis's cosine and
    sine, its half length and half width (m), and the rounding's radius (m)."""

    x: float
    y: float
    cos: float
    sin: float
    half_length: float
    half_width: float
    radius: float

    @classmethod
    def of(cls, obstacle: Obstacle) -> Footprint:
        """A box's rectangle, or a cylinder's circle."""
        if isinstance(obstacle, Box):
            cos, sin = math.cos(obstacle.yaw), math.sin(obstacle.yaw)
            half_length, half_width = obstacle.length / 2.0, obstacle.width / 2.0
            return cls(obstacle.x, obstacle.y, cos, sin, half_length, half_width, 0.0)
        return cls(obstacle.x, obstacle.y, 1.0, 0.0, 0.0, 0.0, obstacle.radius)

    def gap(self, x: float, y: float) -> float:
        """The distance (m) from (x, y) to the footprint, at most 0 inside."""
        dx, dy = x - self.x, y - self.y
        along = max(abs(self.cos * dx + self.sin * dy) - self.half_length, 0.0)
        across = max(abs(self.cos * dy - self.sin * dx) - self.half_width, 0.0)
        return math.hypot(along, across) - self.radius


class _Found(NamedTuple):
    """The obstacles found near the robot: where it was (m), within what (m), their bodies."""

    x: float
    y: float
    within: float
    bodies: tuple[int, ...]

    def left(self, x: float, y: float) -> bool:
        """Whether the robot at (x, y) m is REFRESH or more from where they were found."""
        return math.hypot(x - self.x, y - self.y) >= REFRESH


class Nearby:
    """The obstacles near a robot of `reach` m (the radius around its base that holds it)."""

    def __init__(self, bodies: Sequence[int], obstacles: Sequence[Obstacle], reach: float):
        pairs = zip(bodies, obstacles, strict=True)
        self._footprints = [(body, Footprint.of(obstacle)) for body, obstacle in pairs]
        self._reach = reach + REFRESH + ROUNDING  # m
        self._found: _Found | None = None

    def bodies(self, x: float, y: float, within: float) -> tuple[int, ...]:
        """The bodies whose footprint may come within `within` m of the robot at (x, y) m."""
        found = self._found
        if found is None or found.within != within or found.left(x, y):
            near = tuple(
                body
                for body, footprint in self._footprints
                if footprint.gap(x, y) - self._reach < within
            )
            self._found = found = _Found(x, y, within, near)
        return found.bodies
