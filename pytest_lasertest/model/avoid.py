"""Placements both scanners read that the robot must steer round: where a scanner change breaks
the software that reads the scan, rather than the scanner itself.

An obstacle one scanner misses tests the new hardware; a fault in the filters, drivers and
costmap settings that read the scan shows where both scanners read the obstacle, but
differently (one beam on it instead of four, later, nearer the edge of the field of view), and
the robot must act on the reading. So each placement here stands partly in the robot's way: it
reaches into the footprint the robot sweeps along the nominal path, so that the robot must go
round it, from beside the path's centre line, so that it can. Both scanners read it at the
anchor, LOOKAHEAD before it on the path, and the robot braking from there stays clear of it:
the reading, not the reaction time, is what differs. `verify` judges each with a placement
without a direction.

The seeds come in a fixed order, each where such faults showed in the mutation benchmark
(benchmarks/fault_finding.py): a thin pole just beside the first leg, read by few beams of a
sparse scanner; a wider obstacle before the goal, which the robot must squeeze past to arrive;
a thin pole beside the last leg on the other side, read first while the robot turns onto it;
and so on. A seed that does not verify on this path is passed over.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pytest_lasertest.model.obstacles import Cylinder
from pytest_lasertest.model.plan import Witness
from pytest_lasertest.model.route import Leg
from pytest_lasertest.model.verify import Placement, Scene, verify

LOOKAHEAD = 2.5  # m of path from the anchor to the obstacle
ABOVE_PLANES = 0.5  # m: how far the obstacle stands above the higher scan plane
WIDE = 0.4  # m, the diameter of a wide seed, within the pairs file's sizes


@dataclass(frozen=True)
class Seed:
    """Where a placement starts: on which leg, how far along it, how far beside it, how wide."""

    leg: int  # 0: the first leg; -1: the last
    along: float  # a share of the leg's length, or (negative) m before the leg's end
    beside: float  # m left of the leg's centre line; negative: right
    wide: bool  # WIDE across, else the thinnest obstacle the pairs file places


SEEDS = (
    Seed(0, 0.6, 0.12, wide=False),
    Seed(-1, -1.0, 0.1, wide=True),
    Seed(-1, 0.6, -0.12, wide=False),
    Seed(0, 0.45, -0.2, wide=True),
    Seed(0, 0.75, -0.12, wide=False),
    Seed(-1, 0.4, 0.2, wide=True),
)


def avoid_witnesses(scene: Scene, sizes: tuple[float, float]) -> tuple[Witness, ...]:
    """The verified placements both scanners read and the robot must steer round, in the order
    of SEEDS; `sizes` (m) are the thinnest and widest obstacle the pairs file places."""
    witnesses: list[Witness] = []
    legs = scene.path.legs()
    for seed in SEEDS if legs else ():
        placement = _placement(scene, legs[seed.leg], seed, sizes)
        verification = verify(scene, placement)
        if verification.holds():
            x, y, yaw = (
                float(value) for value in scene.path.poses_at(np.array([placement.anchor]))[0]
            )
            witnesses.append(Witness(len(witnesses), placement, verification, (x, y, yaw)))
    return tuple(witnesses)


def _placement(scene: Scene, leg: Leg, seed: Seed, sizes: tuple[float, float]) -> Placement:
    """The seed's cylinder on `leg`, anchored LOOKAHEAD before it on the path (or at the start)."""
    smallest, widest = sizes
    along = seed.along * leg.length if seed.along >= 0.0 else leg.length + seed.along
    x, y = leg.point_at(along)
    left = (-math.sin(leg.heading), math.cos(leg.heading))
    diameter = min(max(WIDE, smallest), widest) if seed.wide else smallest
    height = max(scene.baseline.scan_height, scene.candidate.scan_height) + ABOVE_PLANES
    obstacle = Cylinder(
        x + seed.beside * left[0], y + seed.beside * left[1], diameter / 2.0, height
    )
    reached = leg.begins + along / scene.path.speed  # s, when the robot's origin passes it
    anchor = max(0.0, reached - LOOKAHEAD / scene.path.speed)
    return Placement(obstacle, None, anchor, anchor)
