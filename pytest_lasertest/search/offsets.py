"""Offsets from a witness, and the box of offsets within which it stays discriminating.

A perturbation moves, turns, resizes or raises a witness's obstacle. Only perturbations that
keep the placement discriminating (the exact ray cast in `placement.verify`, at the witness's
anchor) test the hardware change; the others test nothing. The box is found around each witness
by that same verifier: along each axis alone, the furthest offset in each direction that still
verifies (a coarse outward scan, then bisection), then the whole box shrunk until nearly all of
a fixed sample of its corners and inner points verify too, so that a search drawing from it
rarely has to reject a draw.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from pytest_lasertest.model.verify import REQUIRED_MARGIN, Placement, Scene, verify

AXES = ("x", "y", "yaw", "size", "height")
# How far the search looks along each axis: beyond these the obstacle is another placement.
REACH = {"x": 0.5, "y": 0.5, "yaw": math.pi / 4.0, "size": 0.5, "height": 0.3}  # m, m, rad, m, m
SCAN_STEPS = 8  # coarse steps outward along an axis before bisecting
BISECTIONS = 6  # halvings of the last coarse step
CALIBRATION_POINTS = 64  # uniform draws from the box, besides its corners
TOLERATED_REJECTIONS = 0.05  # of the calibration sample
SHRINK = 0.75  # of the box per calibration round
ROUNDS = 8


class Untested(Exception):
    """A trial declined to drive an offset; the reason is what the search counts it as."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


@dataclass(frozen=True)
class Offset:
    """A perturbation of an obstacle; zero on every axis is the witness itself."""

    x: float = 0.0  # m, world frame
    y: float = 0.0  # m, world frame
    yaw: float = 0.0  # rad; a cylinder has none
    size: float = 0.0  # m, added to a box's length and width, or a cylinder's diameter
    height: float = 0.0  # m

    def axis(self, name: str) -> float:
        """The offset along one of AXES."""
        value: float = getattr(self, name)
        return value

    def describe(self) -> str:
        """`x +0.012 m, yaw -0.100 rad` (nonzero axes only), or `none` for the witness."""
        units = {"yaw": "rad"}
        parts = [
            f"{name} {self.axis(name):+.3f} {units.get(name, 'm')}"
            for name in AXES
            if self.axis(name) != 0.0
        ]
        return ", ".join(parts) or "none"


@dataclass(frozen=True)
class OffsetBox:
    """The offsets a search may draw: each axis from its low to its high end, zero inside."""

    low: Offset
    high: Offset

    def scaled(self, factor: float) -> OffsetBox:
        """The box shrunk (factor < 1) toward zero."""
        return OffsetBox(_scaled(self.low, factor), _scaled(self.high, factor))

    def bounds(self, name: str) -> tuple[float, float]:
        """The low and high end of one axis."""
        return self.low.axis(name), self.high.axis(name)


def perturbed(placement: Placement, offset: Offset) -> Placement:
    """The placement with its obstacle moved, turned, resized and raised by `offset`."""
    obstacle = placement.obstacle.perturbed(**dataclasses.asdict(offset))
    return dataclasses.replace(placement, obstacle=obstacle)


def discriminates(scene: Scene, placement: Placement, sizes: tuple[float, float]) -> bool:
    """Whether the placement verifies and its obstacle's size stays within `sizes` (m): the
    smallest obstacle the robot must see, and the largest the pairs file places."""
    smallest, largest = sizes
    thinnest, widest = placement.obstacle.sides
    if thinnest < smallest or widest > largest or placement.obstacle.height <= 0.0:
        return False
    return verify(scene, placement).holds(REQUIRED_MARGIN)


def offset_box(
    scene: Scene, placement: Placement, sizes: tuple[float, float], rng: np.random.Generator
) -> OffsetBox:
    """The box of offsets around `placement` that keep it discriminating (see the module)."""

    def holds(offset: Offset) -> bool:
        return discriminates(scene, perturbed(placement, offset), sizes)

    if not holds(Offset()):
        return OffsetBox(Offset(), Offset())
    turns = placement.obstacle.has_yaw
    low, high = {}, {}
    for name in AXES:
        reach = REACH[name] if turns or name != "yaw" else 0.0
        low[name] = -_extent(holds, name, -reach)
        high[name] = _extent(holds, name, reach)
    return _calibrated(OffsetBox(Offset(**low), Offset(**high)), holds, rng)


def _extent(holds: Callable[[Offset], bool], name: str, reach: float) -> float:
    """How far (absolute) along one axis, toward `reach`, every offset still holds."""
    if reach == 0.0:
        return 0.0
    good = 0.0
    for step in range(1, SCAN_STEPS + 1):
        trial = reach * step / SCAN_STEPS
        if not holds(Offset(**{name: trial})):
            bad = trial
            break
        good = trial
    else:
        return abs(reach)
    for _ in range(BISECTIONS):
        middle = (good + bad) / 2.0
        good, bad = (middle, bad) if holds(Offset(**{name: middle})) else (good, middle)
    return abs(good)


def _calibrated(
    box: OffsetBox, holds: Callable[[Offset], bool], rng: np.random.Generator
) -> OffsetBox:
    """The box shrunk until at most TOLERATED_REJECTIONS of its sample fails to hold."""
    unit = rng.uniform(0.0, 1.0, size=(CALIBRATION_POINTS, len(AXES)))
    corners = np.array(np.meshgrid(*[[0.0, 1.0]] * len(AXES))).reshape(len(AXES), -1).T
    sample = np.concatenate([corners, unit])
    tolerated = math.floor(TOLERATED_REJECTIONS * len(sample))
    for _ in range(ROUNDS):
        if _failures(box, sample, holds, tolerated) <= tolerated:
            return box
        box = box.scaled(SHRINK)
    return box.scaled(0.0)


def _failures(
    box: OffsetBox, sample: np.ndarray, holds: Callable[[Offset], bool], tolerated: int
) -> int:
    """How many of the `sample` (fractions of the box) fail to hold, counted only up to one
    past `tolerated`: the box is shrunk either way, and each count is an exact ray cast."""
    failures = 0
    for fractions in sample:
        failures += not holds(_at(box, fractions))
        if failures > tolerated:
            break
    return failures


def _at(box: OffsetBox, fractions: np.ndarray) -> Offset:
    """The offset at `fractions` (0 = low end, 1 = high end) of each axis of the box."""
    values = {}
    for name, fraction in zip(AXES, fractions.tolist(), strict=True):
        low, high = box.bounds(name)
        values[name] = low + fraction * (high - low)
    return Offset(**values)


def _scaled(offset: Offset, factor: float) -> Offset:
    return Offset(**{name: offset.axis(name) * factor for name in AXES})
