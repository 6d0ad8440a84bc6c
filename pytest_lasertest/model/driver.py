"""A scanner's driver: how the LaserScan it publishes encodes what the scanner measured.

Two scanners with the same beams can still publish different scans. REP 117 says a reading with
no return is +inf and one nearer than range_min is -inf, and Gazebo's ray sensor publishes so;
real drivers publish NaN (urg_node, whose PR #8 asked for +inf), 0.0 (hokuyo_node #5, SICK
multiScan) or range_max (cob_sick_s300, Webots before PR #2509), set range_max per scan to the
largest reading (sick_scan_xd #509), turn the wrong way round (rplidar_ros #55), or stamp a scan
later than it was measured (navigation2 #3352). Each of these is harmless to one consumer and
breaks another, so a profile holds its driver, and `publish` turns what the scanner measured
into what the driver publishes, before any navigation stack sees it.

Time: a scan's sweep starts at its measurement instant (the simulator casts it there, at one
pose: Gazebo's sensor casts a scan at one instant). A driver's stamp is `latency` seconds after
that, plus the sweep (scan_time) when it stamps the sweep's end, and the scan reaches the stack
at its stamp: a driver that stamps what it receives publishes it at once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Literal

import numpy as np

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.scanner_limits import ProfileError

# How a reading is published: REP 117's infinities, NaN, zero, or the scan's range_max/min.
Encoding = Literal["inf", "-inf", "nan", "zero", "range_max", "range_min"]
NO_RETURN: tuple[Encoding, ...] = ("inf", "nan", "zero", "range_max")
TOO_NEAR: tuple[Encoding, ...] = ("-inf", "nan", "zero", "range_min", "inf")
RangeMax = Literal["fixed", "per_scan"]
RANGE_MAX: tuple[RangeMax, ...] = ("fixed", "per_scan")
BeamOrder = Literal["counter-clockwise", "clockwise"]
BEAM_ORDER: tuple[BeamOrder, ...] = ("counter-clockwise", "clockwise")
Stamp = Literal["start", "end"]
STAMP: tuple[Stamp, ...] = ("start", "end")
# The traits that are one of a few choices, and those choices.
CHOICES: dict[str, tuple[str, ...]] = {
    "no_return": NO_RETURN,
    "too_near": TOO_NEAR,
    "range_max": RANGE_MAX,
    "beam_order": BEAM_ORDER,
    "stamp": STAMP,
}
# A stamp later than this is not a driver's: it is a stalled one.
MAX_LATENCY = 10.0  # s


@dataclass(frozen=True)
class Driver:
    """What a scanner's driver publishes; the defaults are Gazebo's ray sensor (REP 117)."""

    no_return: Encoding = "inf"  # what a beam that met nothing reads
    too_near: Encoding = "-inf"  # what a beam that met something nearer than range_min reads
    range_max: RangeMax = "fixed"  # or the largest reading of each scan (sick_scan_xd)
    # The order of `ranges`; angle_min and angle_increment say counter-clockwise either way.
    beam_order: BeamOrder = "counter-clockwise"
    latency: float = 0.0  # s, how much later than the measurement the stamp is
    stamp: Stamp = "start"  # the sweep instant the stamp marks

    def __post_init__(self) -> None:
        for name, allowed in CHOICES.items():
            value = getattr(self, name)
            if value not in allowed:
                choices = ", ".join(allowed)
                fix = f"write one of: {choices}"
                raise ProfileError(f"driver.{name}", f"{value!r} is not a choice here", fix)
        if not (math.isfinite(self.latency) and 0.0 <= self.latency <= MAX_LATENCY):
            raise ProfileError(
                "driver.latency",
                f"{self.latency} s is not a stamp delay a driver can have",
                f"write the seconds between the measurement and its stamp, 0 to {MAX_LATENCY:g}",
            )

    def delay(self, scan_time: float) -> float:
        """How long after its measurement instant a scan is stamped and delivered (s)."""
        return self.latency + (scan_time if self.stamp == "end" else 0.0)


DEFAULT_DRIVER = Driver()


def publish(
    driver: Driver, ranges: FloatArray, range_min: float, range_max: float
) -> tuple[FloatArray, float]:
    """The ranges (N,) m as the driver publishes them, and the scan's range_max (m), from the
    REP 117 ranges the scanner measured (+inf no return, -inf nearer than range_min) and its
    fixed range_max. A per-scan range_max is the largest finite reading, or the fixed one when
    the scan read nothing."""
    if driver == DEFAULT_DRIVER:
        return ranges, range_max
    if driver.range_max == "per_scan":
        finite = ranges[np.isfinite(ranges)]
        range_max = float(finite.max()) if len(finite) else range_max
    published = ranges.copy()
    published[ranges == np.inf] = _value(driver.no_return, range_min, range_max)
    published[ranges == -np.inf] = _value(driver.too_near, range_min, range_max)
    if driver.beam_order == "clockwise":
        published = published[::-1].copy()
    return published, range_max


def _value(encoding: Encoding, range_min: float, range_max: float) -> float:
    return {
        "inf": math.inf,
        "-inf": -math.inf,
        "nan": math.nan,
        "zero": 0.0,
        "range_max": range_max,
        "range_min": range_min,
    }[encoding]


def differing(first: Driver, second: Driver) -> tuple[str, ...]:
    """The traits (Driver's field names) in which two drivers publish differently."""
    return tuple(
        item.name
        for item in fields(Driver)
        if getattr(first, item.name) != getattr(second, item.name)
    )


def differences(baseline: Driver, candidate: Driver) -> tuple[tuple[str, str], ...]:
    """Each trait the candidate's driver publishes differently from the baseline's: its name,
    and in words what the candidate publishes and what that does downstream."""
    return tuple(
        (trait, _consequence(trait, getattr(candidate, trait)))
        for trait in differing(baseline, candidate)
    )


def describe(driver: Driver) -> str:
    """The driver's traits that differ from Gazebo's, in words, or that it publishes as Gazebo."""
    traits = [
        f"{_WORDS[trait]} {_say(trait, getattr(driver, trait))}"
        for trait in differing(DEFAULT_DRIVER, driver)
    ]
    return "; ".join(traits) or "publishes as Gazebo's ray sensor (REP 117)"


_WORDS = {
    "no_return": "no return published as",
    "too_near": "a reading nearer than range_min published as",
    "range_max": "range_max",
    "beam_order": "beam order",
    "latency": "stamp later than the measurement by",
    "stamp": "stamp marks the sweep's",
}


def _say(name: str, value: object) -> str:
    if name == "latency":
        return f"{value:g} s"
    if name == "range_max":
        return "fixed" if value == "fixed" else "the largest reading of each scan"
    return str(value)


def _consequence(trait: str, value: object) -> str:
    """What publishing a trait's value does to the consumers of the scan (ROS 1 and 2 alike:
    laser_geometry's projection keeps range_min <= r < range_max, and costmap_2d's
    inf_is_valid turns +inf into range_max - 1e-4; Nav2's collision monitor keeps
    range_min <= r <= range_max)."""
    said = f"{_WORDS[trait]} {_say(trait, value)}"
    if trait == "no_return" or trait == "too_near":
        return f"{said}: {_READ_AS[str(value)]}"
    if trait == "range_max" and value == "per_scan":
        return (
            f"{said}: with inf_is_valid, each no-return becomes a reading 1e-4 m short of it, a "
            "wall wherever that falls within the obstacle range (sick_scan_xd #509)"
        )
    if trait == "beam_order" and value == "clockwise":
        return (
            f"{said}: the ranges run against the header's angles, so every reading is mirrored "
            "across the laser's x axis (rplidar_ros #55)"
        )
    if trait == "latency" or trait == "stamp":
        return (
            f"{said}: a stack places the scan where the robot is at the stamp, not where it was "
            "measured, turned by the turn rate times the delay (navigation2 #3352)"
        )
    return said


_READ_AS = {
    "inf": "REP 117; with inf_is_valid a costmap clears along it",
    "-inf": "REP 117; no consumer takes it for a reading",
    "nan": "every consumer drops it, so it clears nothing even with inf_is_valid",
    "zero": "a costmap drops it below range_min, so it clears nothing; a consumer that takes "
    "0.0 for a reading sees something at the laser itself",
    "range_max": "a costmap drops it (r < range_max), so it clears nothing; Nav2's collision "
    "monitor counts it (r <= range_max), a point range_max away",
    "range_min": "a reading at range_min: every consumer takes it for something right there",
}
