"""The further draws a regression must survive (`policy.REDRAWS`): each a fresh seed of the scan
noise and a small move of every obstacle, the same on every machine for one run's seed.

Kept apart from `policy`, which the plugin imports at start-up, because it needs numpy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pytest_lasertest.model.obstacles import Obstacle
from pytest_lasertest.model.policy import JITTER
from pytest_lasertest.model.seeds import noise_seed


@dataclass(frozen=True)
class Draw:
    """One further draw of what a regression must not depend on: the scan noise's seed, and how
    far each obstacle stands from where the search put it."""

    noise: int  # the scan noise's seed
    shifts: tuple[tuple[float, float], ...]  # m, each obstacle's move in x and y, within JITTER

    def moved(self, obstacles: tuple[Obstacle, ...]) -> tuple[Obstacle, ...]:
        """The obstacles, each moved by its shift."""
        return tuple(
            obstacle.perturbed(dx, dy, 0.0, 0.0, 0.0)
            for obstacle, (dx, dy) in zip(obstacles, self.shifts, strict=True)
        )


def redraw(seed: int, draw: int, obstacles: int) -> Draw:
    """Draw number `draw` (1, 2, ...) of a run seeded `seed` holding `obstacles` obstacles:
    independent of the run's own draw and of every other, and the same on every machine."""
    noise = noise_seed(seed, draw)
    shifts = np.random.default_rng(noise).uniform(-JITTER, JITTER, (obstacles, 2))
    return Draw(noise, tuple((float(dx), float(dy)) for dx, dy in shifts))
