"""Placements both scanners read that the robot must act on: where a scanner change breaks the
software that reads the scan, rather than the scanner itself.

An obstacle one scanner misses tests the new hardware; a fault in the filters, drivers and
costmap settings that read the scan shows where both scanners read the obstacle, but
differently (one beam on it instead of four, later, nearer the edge of the field of view, nearer
than the new range_min), and the robot must act on the reading. So each placement here either
stands partly in the robot's way, reaching into the footprint it sweeps along the nominal path
from beside the path's centre line, so that the robot must go round it and can; or, when the
candidate's range_min is the larger, it stands clear of the robot where the candidate reads it
too near (REP 117's -inf) as the robot passes, and the baseline still reads it in range. Both
scanners read it at the anchor, LOOKAHEAD before it on the path, and the robot braking from there
stays clear of it: the reading, not the reaction time, is what differs. `verify` judges each
with a placement without a direction.

The placements read too near come first: straight on beyond each turn, where the robot stops and
turns away, and beside the first leg. The seeds in the way follow in a fixed order, each where
such faults showed in the mutation benchmark (benchmarks/fault_finding.py): a thin pole just
beside the first leg, read by few beams of a sparse scanner; a wider obstacle before the goal,
which the robot must squeeze past to arrive; a thin pole beside the last leg on the other side,
read first while the robot turns onto it; and so on. A placement that does not verify on this
path is passed over.
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
NEAR_CLEARANCE = 0.05  # m between what the robot sweeps and an obstacle it reads too near


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
    """The verified placements both scanners read and the robot must act on: those read too near
    first, then those in its way in the order of SEEDS; `sizes` (m) are the thinnest and widest
    obstacle the pairs file places."""
    witnesses: list[Witness] = []
    for placement in (*_read_too_near(scene, sizes), *_in_the_way(scene, sizes)):
        verification = verify(scene, placement)
        if verification.holds():
            x, y, yaw = (
                float(value) for value in scene.path.poses_at(np.array([placement.anchor]))[0]
            )
            witnesses.append(Witness(len(witnesses), placement, verification, (x, y, yaw)))
    return tuple(witnesses)


def _in_the_way(scene: Scene, sizes: tuple[float, float]) -> list[Placement]:
    """The SEEDS' cylinders."""
    legs = scene.path.legs()
    placements = []
    for seed in SEEDS if legs else ():
        leg = legs[seed.leg]
        along = seed.along * leg.length if seed.along >= 0.0 else leg.length + seed.along
        diameter = _wide(sizes) if seed.wide else sizes[0]
        placements.append(_cylinder(scene, leg, along, seed.beside, diameter))
    return placements


def _read_too_near(scene: Scene, sizes: tuple[float, float]) -> list[Placement]:
    """Where a candidate with a larger range_min reads an obstacle too near (-inf) while the
    robot drives past it untouched: straight on beyond each turn, where the robot stops and turns
    away, and beside the first leg. Each stands clear of what the robot sweeps (turning in place,
    the disc of its footprint), as near as half the band between the two range_mins allows."""
    baseline, candidate = scene.baseline, scene.candidate
    legs = scene.path.legs()
    if candidate.range_min <= baseline.range_min or not legs:
        return []
    footprint = scene.robot.footprint_array()
    mount_x, mount_y, _ = candidate.pose.xyz
    band = (baseline.range_min + candidate.range_min) / 2.0  # m from the scanner
    swing = float(np.max(np.hypot(footprint[:, 0], footprint[:, 1])))  # m
    ahead = max(mount_x + band, swing + NEAR_CLEARANCE)  # m from the robot's origin
    beside = max(mount_y + band, float(np.max(footprint[:, 1])) + NEAR_CLEARANCE)
    diameter = _wide(sizes)
    placements = [
        _cylinder(scene, leg, leg.length + ahead + diameter / 2.0, 0.0, diameter)
        for leg in legs[:-1]
    ]
    first = legs[0]
    placements.append(_cylinder(scene, first, first.length / 2, beside + diameter / 2.0, diameter))
    return placements


def _wide(sizes: tuple[float, float]) -> float:
    smallest, widest = sizes
    return min(max(WIDE, smallest), widest)


def _cylinder(scene: Scene, leg: Leg, along: float, beside: float, diameter: float) -> Placement:
    """A cylinder `along` m down `leg` (past its end, if longer) and `beside` m left of its centre
    line, anchored LOOKAHEAD before the robot's origin reaches it (or at the start)."""
    x, y = leg.point_at(along)
    left = (-math.sin(leg.heading), math.cos(leg.heading))
    height = max(scene.baseline.scan_height, scene.candidate.scan_height) + ABOVE_PLANES
    obstacle = Cylinder(x + beside * left[0], y + beside * left[1], diameter / 2.0, height)
    reached = leg.begins + along / scene.path.speed  # s, when the robot's origin passes it
    anchor = max(0.0, reached - LOOKAHEAD / scene.path.speed)
    return Placement(obstacle, None, anchor, anchor)
