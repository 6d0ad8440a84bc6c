"""What a candidate scanner covers compared with its baseline, exactly, in the robot base frame.

Each attribute that limits what a 2D scanner can see is compared on its own: the scanned sector
(after the mount's yaw and mirroring), the far and near range limits, the beam spacing (as the
distance out to which an obstacle of a given width is sure to be hit by a beam), the scan rate and
the scan plane height. A change is *worse* when it leaves the candidate blind somewhere the
baseline was not.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass

from pytest_lasertest.model.driver import Driver, differences
from pytest_lasertest.model.geometry import FULL_TURN, wrap_angle
from pytest_lasertest.model.sensor import LaserProfile

ANGLE_TOLERANCE = 1e-6  # rad, below any scanner's angular accuracy
LENGTH_TOLERANCE = 1e-9  # m


@dataclass(frozen=True)
class Sector:
    """An arc of directions in the base frame, counter-clockwise from `start`."""

    start: float  # rad, in [-pi, pi)
    extent: float  # rad, in [0, 2 pi]

    @property
    def end(self) -> float:
        """Where the arc stops (rad); may exceed pi when the arc crosses the rear."""
        return self.start + self.extent

    def __str__(self) -> str:
        return f"[{self.start:.3f}, {self.end:.3f}] rad ({math.degrees(self.extent):.1f} deg)"


@dataclass(frozen=True)
class CoverageChange:
    """One sensing attribute that differs between the baseline and the candidate."""

    attribute: str
    baseline: float | str  # a figure in `unit`, or a driver's choice (model/driver.py)
    candidate: float | str
    unit: str
    worse: bool  # the candidate is blind somewhere the baseline was not
    detail: str


@dataclass(frozen=True)
class CoverageComparison:
    """Every sensing difference of a pair, and the sectors the candidate lost or gained."""

    changes: tuple[CoverageChange, ...]
    lost_sectors: tuple[Sector, ...]
    gained_sectors: tuple[Sector, ...]

    @property
    def losses(self) -> tuple[CoverageChange, ...]:
        """The changes that leave the candidate blind where the baseline saw."""
        return tuple(change for change in self.changes if change.worse)


def compare_coverage(
    baseline: LaserProfile,
    candidate: LaserProfile,
    *,
    min_obstacle_size: float,  # m
    max_speed: float,  # m/s
) -> CoverageComparison:
    """Compare what two scanners on the same robot can see."""
    before, after = Sector(*baseline.sector_in_base()), Sector(*candidate.sector_in_base())
    lost, gained = sector_difference(before, after), sector_difference(after, before)
    changes = [
        *_field_of_view(before, after, lost, gained),
        *_ranges(baseline, candidate),
        *_beam_spacing(baseline, candidate, min_obstacle_size),
        *_update_rate(baseline, candidate, max_speed),
        *_scan_height(baseline, candidate),
        *_other(baseline, candidate),
        *_driver(baseline.driver, candidate.driver),
    ]
    return CoverageComparison(tuple(changes), tuple(lost), tuple(gained))


def sector_difference(kept: Sector, removed: Sector) -> list[Sector]:
    """The parts of `kept` that `removed` does not cover, at most two arcs."""
    if removed.extent >= FULL_TURN:
        return []
    offset = (removed.start - kept.start) % FULL_TURN
    pieces = [(0.0, kept.extent)]
    for low in (offset, offset - FULL_TURN):
        pieces = [part for piece in pieces for part in _cut(piece, low, low + removed.extent)]
    return [
        Sector(wrap_angle(kept.start + low), high - low)
        for low, high in pieces
        if high - low > ANGLE_TOLERANCE
    ]


def sure_detection_distance(profile: LaserProfile, size: float) -> float:
    """How far out an obstacle `size` wide is sure to be crossed by a beam (m), range aside.

    A beam passes within size/2 of the centre of a disc at distance r when its angular offset
    from the centre is at most asin(size / 2r); the worst offset is half the beam spacing.
    """
    if profile.beam_count == 1:
        return 0.0
    return size / (2.0 * math.sin(profile.angle_increment / 2.0))


def _cut(piece: tuple[float, float], low: float, high: float) -> list[tuple[float, float]]:
    start, stop = piece
    return [
        part for part in ((start, min(stop, low)), (max(start, high), stop)) if part[1] > part[0]
    ]


def _field_of_view(
    before: Sector, after: Sector, lost: list[Sector], gained: list[Sector]
) -> Iterator[CoverageChange]:
    if not lost and not gained:
        return
    parts = []
    if lost:
        parts.append("no longer scans " + " and ".join(map(str, lost)))
    if gained:
        parts.append("newly scans " + " and ".join(map(str, gained)))
    yield CoverageChange(
        "field of view",
        before.extent,
        after.extent,
        "rad",
        worse=bool(lost),
        detail="; ".join(parts) + " (base frame)",
    )


def _ranges(baseline: LaserProfile, candidate: LaserProfile) -> Iterator[CoverageChange]:
    if abs(candidate.range_max - baseline.range_max) > LENGTH_TOLERANCE:
        near, far = sorted((candidate.range_max, baseline.range_max))
        who = "no longer" if candidate.range_max < baseline.range_max else "now"
        yield CoverageChange(
            "range.max",
            baseline.range_max,
            candidate.range_max,
            "m",
            worse=candidate.range_max < baseline.range_max,
            detail=f"obstacles between {near:.2f} and {far:.2f} m are {who} seen",
        )
    if abs(candidate.range_min - baseline.range_min) > LENGTH_TOLERANCE:
        near, far = sorted((candidate.range_min, baseline.range_min))
        yield CoverageChange(
            "range.min",
            baseline.range_min,
            candidate.range_min,
            "m",
            worse=candidate.range_min > baseline.range_min,
            detail=f"obstacles between {near:.2f} and {far:.2f} m from the scanner "
            f"{'now read' if candidate.range_min > baseline.range_min else 'no longer read'} "
            "-inf (too close)",
        )


def _beam_spacing(
    baseline: LaserProfile, candidate: LaserProfile, size: float
) -> Iterator[CoverageChange]:
    before, after = baseline.angle_increment, candidate.angle_increment
    if math.isclose(after, before, rel_tol=1e-9):
        return
    sure_before = sure_detection_distance(baseline, size)
    sure_after = sure_detection_distance(candidate, size)
    yield CoverageChange(
        "beam spacing",
        before,
        after,
        "rad",
        worse=sure_after < sure_before,
        detail=f"a {size:.3f} m wide obstacle is sure to be hit by a beam out to "
        f"{sure_after:.2f} m, was {sure_before:.2f} m "
        f"({candidate.beam_count} beams, was {baseline.beam_count})",
    )


def _update_rate(
    baseline: LaserProfile, candidate: LaserProfile, max_speed: float
) -> Iterator[CoverageChange]:
    if math.isclose(candidate.update_rate, baseline.update_rate, rel_tol=1e-9):
        return
    yield CoverageChange(
        "update_rate",
        baseline.update_rate,
        candidate.update_rate,
        "Hz",
        worse=candidate.update_rate < baseline.update_rate,
        detail=f"a scan every {candidate.scan_period * 1e3:.1f} ms, was "
        f"{baseline.scan_period * 1e3:.1f} ms: at {max_speed:.2f} m/s the robot drives "
        f"{candidate.scan_period * max_speed * 100:.1f} cm between scans, was "
        f"{baseline.scan_period * max_speed * 100:.1f} cm",
    )


def _scan_height(baseline: LaserProfile, candidate: LaserProfile) -> Iterator[CoverageChange]:
    before, after = baseline.scan_height, candidate.scan_height
    if abs(after - before) <= LENGTH_TOLERANCE:
        return
    low, high = sorted((before, after))
    yield CoverageChange(
        "scan height",
        before,
        after,
        "m",
        worse=after > before,
        detail=f"scan plane {'raised' if after > before else 'lowered'} from {before:.3f} to "
        f"{after:.3f} m above the base: an obstacle whose top lies between {low:.3f} and "
        f"{high:.3f} m is {'no longer' if after > before else 'now'} seen",
    )


def _other(baseline: LaserProfile, candidate: LaserProfile) -> Iterator[CoverageChange]:
    shift = math.dist(baseline.pose.xyz[:2], candidate.pose.xyz[:2])
    if shift > LENGTH_TOLERANCE:
        yield CoverageChange(
            "mount position",
            0.0,
            shift,
            "m",
            worse=False,
            detail=f"the scanner moved {shift:.3f} m in the base plane, from "
            f"({baseline.pose.xyz[0]:.3f}, {baseline.pose.xyz[1]:.3f}) to "
            f"({candidate.pose.xyz[0]:.3f}, {candidate.pose.xyz[1]:.3f}) m",
        )
    sigma_before = baseline.noise.stddev if baseline.noise else 0.0
    sigma_after = candidate.noise.stddev if candidate.noise else 0.0
    if abs(sigma_after - sigma_before) > LENGTH_TOLERANCE:
        yield CoverageChange(
            "noise.stddev",
            sigma_before,
            sigma_after,
            "m",
            worse=False,
            detail=f"range noise {sigma_after * 1e3:.1f} mm (1 sigma), was "
            f"{sigma_before * 1e3:.1f} mm",
        )


def _driver(baseline: Driver, candidate: Driver) -> Iterator[CoverageChange]:
    """Each trait the two drivers publish differently: the scanner sees as much, but what it
    publishes reads differently to a costmap, a collision monitor or a controller."""
    for trait, detail in differences(baseline, candidate):
        yield CoverageChange(
            f"driver.{trait}",
            getattr(baseline, trait),
            getattr(candidate, trait),
            "s" if trait == "latency" else "",
            worse=False,
            detail=detail,
        )
