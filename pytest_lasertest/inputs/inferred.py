"""A scanner profile inferred from a recording of the real scanner (`bags.py` reads it).

What a recording tells, and how (each trait that is inferred, or cannot be, gets a note):
- Beams: samples = len(ranges), min_angle = angle_min, max_angle = angle_min + (N - 1)
  angle_increment: consumers (laser_geometry, the costmaps, AMCL) place beam i at angle_min +
  i angle_increment and never read angle_max (the header's angle_max stands in for it when the
  two agree within float32's error, SAME_END). Scans of other layouts (N, angle_min,
  angle_increment) than the most common are noted and left out; when no layout is shared by at
  least half of the scans, the recording is refused.
- A scan with a negative angle_increment turns clockwise and says so: every consumer places its
  beams right, so the profile gets ascending angles and keeps `beam_order: counter-clockwise`.
  The model's `clockwise` is a driver whose ranges run against its header (rplidar_ros #55),
  which no recording can show: the header is all a bag has to go by.
- range.min is the most common range_min; range_max is `fixed` when every scan has the same,
  else `per_scan`, and range.max is the largest seen.
- update_rate = 1 / the median step between header stamps; when the stamps do not advance,
  1 / scan_time; when neither tells, the median step between the times the bag logged them.
- no_return is the most frequent of NaN, +inf, 0.0 and a reading of exactly the scan's
  range_max (with a per-scan range_max, the one reading in each scan that set it is a return,
  not counted); none of them: left at inf (REP 117).
- too_near: only -inf (REP 117) tells a reading nearer than range_min from a no-return; a
  driver's 0 or NaN for it looks the same as its no-return, so too_near is left at -inf.
- stamp: a sweep is published after it ends, so a stamp less than half a scan period older
  than the scan's arrival in the bag (median) cannot mark the sweep's start: `end`; otherwise
  `start`. An age below minus half a period, or above what a driver's delay can be, means the
  bag's clock is not the driver's (another machine, simulated time): left at `start`.
- latency cannot be measured: a bag holds when a scan arrived, not when it was measured. 0 s.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from pytest_lasertest.inputs.bags import RECORD_ONE, BagError, Recording, Scan, read_recording
from pytest_lasertest.model.driver import (
    DEFAULT_DRIVER,
    MAX_LATENCY,
    NO_RETURN,
    Driver,
    Encoding,
    RangeMax,
    Stamp,
    differing,
)
from pytest_lasertest.model.sensor import LaserProfile, ProfileError

LATENCY_NOTE = (
    "latency cannot be measured from a recording (a bag holds when a scan arrived, not when it "
    "was measured): left at 0 s; write `driver: {latency: S}` if a datasheet or a measurement "
    "says more"
)


@dataclass(frozen=True)
class InferredProfile:
    """The profile a recording shows, and what a person should know about how it was read."""

    profile: LaserProfile
    topic: str
    messages: int  # scans it was inferred from
    arrival_age: float | None  # s, median of log time - stamp; None when the stamps tell nothing
    notes: tuple[str, ...]


def profile_from_bag(path: Path, topic: str | None = None) -> InferredProfile:
    """The profile the LaserScan messages on `topic` (the bag's only LaserScan topic when None)
    show; BagError when the bag cannot give one."""
    return infer_profile(read_recording(path, topic))


def profile_fields(profile: LaserProfile) -> dict[str, object]:
    """The fields a pairs file writes for an inferred profile, flattened as `read_fields` gives
    them (`range.max`, `driver.no_return`): the driver's traits only where they are not
    Gazebo's."""
    written: dict[str, object] = {
        "samples": profile.samples,
        "min_angle": profile.min_angle,
        "max_angle": profile.max_angle,
        "range.min": profile.range_min,
        "range.max": profile.range_max,
        "update_rate": profile.update_rate,
    }
    for trait in differing(DEFAULT_DRIVER, profile.driver):
        written[f"driver.{trait}"] = getattr(profile.driver, trait)
    return written


Layout = tuple[int, float, float]  # beams, angle_min rad, angle_increment rad
# float32's angle_increment times N - 1 is off by up to ~4e-7 rad over a full turn: a header
# angle_max this close to it is the same end.
SAME_END = 1e-6  # rad
CLOCKWISE_NOTE = (
    "the scans turn clockwise (angle_increment < 0) and their header says so, so every consumer "
    "places the beams right: the profile gives the same beams counter-clockwise (`beam_order: "
    "clockwise` is a driver whose ranges run against its header)"
)


def infer_profile(recording: Recording) -> InferredProfile:
    """The profile a recording shows (the rules are in this module's docstring)."""
    scans, notes = recording.scans, _read_notes(recording)
    layout = _layout(recording, notes)
    min_angle, max_angle = _angles(layout, scans, notes)
    range_min, range_max, range_mode = _ranges(scans, notes)
    period, from_stamps = _period(recording, notes)
    no_return = _no_return(scans, range_mode, notes)
    _too_near(scans, notes)
    stamp, age = _stamp(scans, period, notes) if from_stamps else _unstamped(notes)
    notes.append(LATENCY_NOTE)
    profile = _built(
        recording.path,
        samples=layout[0],
        min_angle=min_angle,
        max_angle=max_angle,
        range_min=range_min,
        range_max=range_max,
        update_rate=float(f"{1.0 / period:.4g}"),  # more digits are clock jitter
        driver=Driver(no_return=no_return, range_max=range_mode, stamp=stamp),
    )
    return InferredProfile(profile, recording.topic, len(scans), age, tuple(notes))


def _built(path: Path, **fields: Any) -> LaserProfile:
    """The profile, or a BagError when the recording's figures make none the gate accepts."""
    try:
        return LaserProfile(**fields)
    except ProfileError as error:
        problem = f"its scans make no profile the gate accepts: {error.field}: {error.problem}"
        raise BagError(path, problem, error.fix, about="topic") from None


# The layouts an error or a note names, the most common first: a bag holds thousands of scans.
SHOWN = 3


def _check_finite(recording: Recording) -> None:
    """Refuse scans whose beams' geometry is no number: no layout can be made of it."""
    fields = ("angle_min", "angle_increment", "angle_max", "range_min", "range_max")
    for field in fields:
        broken = [scan for scan in recording.scans if not math.isfinite(getattr(scan, field))]
        if broken:
            raise BagError(
                recording.path,
                f"{len(broken)} of its {len(recording.scans)} scans give {field} as "
                f"{getattr(broken[0], field)}: no beam layout can be made of it",
                "record the scanner's driver as it publishes for navigation: every LaserScan "
                "field but the ranges a number",
                about="topic",
            )


def _read_notes(recording: Recording) -> list[str]:
    count = len(recording.scans)
    if recording.total <= count:
        return []
    return [f"read the first {count} of the topic's {recording.total} messages"]


def _layout(recording: Recording, notes: list[str]) -> Layout:
    """The beams most scans share; BagError when fewer than half share any."""
    scans, path = recording.scans, recording.path
    _check_finite(recording)
    layouts = Counter((scan.beams, scan.angle_min, scan.angle_increment) for scan in scans)
    layout, agree = layouts.most_common(1)[0]
    if 2 * agree < len(scans):
        shown = "; ".join(
            f"{count} with {_layout_text(key)}" for key, count in layouts.most_common(SHOWN)
        )
        if len(layouts) > SHOWN:
            shown += f"; and {len(layouts) - SHOWN} layouts more"
        problem = f"its scans disagree on their beams, no layout shared by half of them: {shown}"
        fix = "record one configuration of the scanner at a time, or cut the bag to one"
        raise BagError(path, problem, fix, about="topic")
    if layout[0] == 0:
        raise BagError(path, "its scans hold no ranges", RECORD_ONE, about="topic")
    others = [
        f"{count} had {_layout_text(key)}" for key, count in layouts.most_common() if key != layout
    ]
    if len(others) > SHOWN:
        others = [*others[:SHOWN], f"{len(others) - SHOWN} layouts more"]
    if others:
        notes.append(
            f"{len(scans) - agree} of {len(scans)} scans had other beams ({'; '.join(others)}); "
            f"the profile follows the other {agree}, with {_layout_text(layout)}"
        )
    return layout


def _layout_text(layout: Layout) -> str:
    beams, first, step = layout
    return f"{beams} beams from {first:g} rad every {step:g} rad"


def _angles(layout: Layout, scans: Sequence[Scan], notes: list[str]) -> tuple[float, float]:
    """min_angle and max_angle, ascending, of the beams as consumers place them."""
    beams, first, step = layout
    last = first + (beams - 1) * step
    said = next(
        scan.angle_max
        for scan in scans
        if (scan.beams, scan.angle_min, scan.angle_increment) == layout
    )
    if abs(said - last) <= SAME_END:
        last = said  # the end the driver meant, without float32's error times N - 1
    elif beams > 1 and abs(said - last) > abs(step) / 2:
        notes.append(
            f"the scans' angle_max, {said:g} rad, is not angle_min + (N - 1) angle_increment, "
            f"{last:g} rad: the profile places the beams as consumers do, by angle_increment"
        )
    if step < 0:
        notes.append(CLOCKWISE_NOTE)
    return min(first, last), max(first, last)


def _ranges(scans: Sequence[Scan], notes: list[str]) -> tuple[float, float, RangeMax]:
    """range.min, range.max, and whether range_max is fixed or set per scan."""
    minimums = Counter(scan.range_min for scan in scans)
    range_min = minimums.most_common(1)[0][0]
    if len(minimums) > 1:
        notes.append(
            f"range_min varied between scans ({min(minimums):g} to {max(minimums):g} m): the "
            f"profile takes the most common, {range_min:g} m"
        )
    maximums = {scan.range_max for scan in scans}
    if len(maximums) == 1:
        return range_min, maximums.pop(), "fixed"
    notes.append(
        f"range_max moved between scans ({min(maximums):g} to {max(maximums):g} m): "
        f"range_max per_scan, and range.max the largest seen, {max(maximums):g} m, which may "
        "fall short of what the scanner reaches (check its datasheet)"
    )
    return range_min, max(maximums), "per_scan"


def _period(recording: Recording, notes: list[str]) -> tuple[float, bool]:
    """The scan period (s), and whether the header stamps gave it."""
    scans = recording.scans
    stepped = _median_step([scan.stamp for scan in scans])
    scan_time = float(np.median([scan.scan_time for scan in scans]))
    if stepped is not None:
        if scan_time > 0 and abs(scan_time - stepped) > 0.1 * stepped:
            notes.append(
                f"scan_time says {scan_time:g} s, but the stamps advance every {stepped:g} s "
                "(median): update_rate follows the stamps"
            )
        return stepped, True
    if scan_time > 0:
        notes.append("the header stamps do not advance: update_rate is 1 / scan_time")
        return scan_time, False
    logged = _median_step([scan.log_time for scan in scans])
    if logged is not None:
        notes.append(
            "neither the header stamps nor scan_time tell the scan rate: update_rate is from "
            "the times the bag logged the scans"
        )
        return logged, False
    problem = "its scans do not tell the scan rate: one scan, or stamps that do not advance"
    raise BagError(recording.path, problem, "record a few seconds of scans", about="topic")


def _median_step(times: Sequence[int]) -> float | None:
    """The median step (s) between successive times (ns), or None when they do not advance."""
    if len(times) < 2:
        return None
    step = float(np.median(np.diff(np.asarray(times, dtype=np.int64))))
    return step / 1e9 if step > 0 else None


# How notes name the values a driver may publish for no return.
_SHOWN = {"nan": "NaN", "inf": "+inf", "zero": "0.0", "range_max": "range_max"}


def _no_return(scans: Sequence[Scan], range_mode: RangeMax, notes: list[str]) -> Encoding:
    """The value most readings without a return were published as."""
    # With a per-scan range_max, one reading of each scan is the return that set it.
    set_it = 1 if range_mode == "per_scan" else 0
    seen = {
        "nan": sum(scan.readings.nan for scan in scans),
        "inf": sum(scan.readings.inf for scan in scans),
        "zero": sum(scan.readings.zero for scan in scans),
        "range_max": sum(max(scan.readings.at_range_max - set_it, 0) for scan in scans),
    }
    counted = {name: count for name, count in seen.items() if count}
    if not counted:
        notes.append(
            "no reading went without a return (none was NaN, +inf, 0.0 or range_max): "
            "no_return is left at inf (REP 117)"
        )
        return "inf"
    chosen = max(NO_RETURN, key=lambda name: (seen[name], -NO_RETURN.index(name)))
    if len(counted) > 1:
        listed = ", ".join(f"{count} {_SHOWN[name]}" for name, count in counted.items())
        notes.append(
            f"readings without a return were published several ways ({listed}): no_return is "
            f"the most frequent, {chosen}"
        )
    return chosen


def _too_near(scans: Sequence[Scan], notes: list[str]) -> None:
    nearer = sum(scan.readings.neg_inf for scan in scans)
    if nearer:
        notes.append(f"{nearer} readings were -inf, nearer than range_min (REP 117)")
    else:
        notes.append(
            "no reading was -inf: too_near is left at -inf (REP 117), as a driver's 0.0 or NaN "
            "for a reading nearer than range_min looks the same as its no-return"
        )


def _stamp(scans: Sequence[Scan], period: float, notes: list[str]) -> tuple[Stamp, float]:
    """Which sweep instant the stamps mark, from how long after them the scans arrived."""
    age = float(np.median([scan.log_time - scan.stamp for scan in scans])) / 1e9  # s
    arrived = (
        f"the scans arrived {age * 1e3:.1f} ms after their stamps (median), the scan period "
        f"being {period * 1e3:.1f} ms"
    )
    if age < -period / 2 or age > MAX_LATENCY:
        notes.append(
            f"{arrived}: the bag's clock is not the driver's (another machine, or simulated "
            "time), so stamp is left at start"
        )
        return "start", age
    if age < period / 2:
        notes.append(
            f"{arrived}: under half a period, so the stamp cannot mark the sweep's start (a "
            "sweep is published after it ends): stamp end"
        )
        return "end", age
    notes.append(f"{arrived}: stamp start, as a stamp that old can mark the sweep's start")
    return "start", age


def _unstamped(notes: list[str]) -> tuple[Stamp, None]:
    notes.append("the stamps do not advance, so what they mark cannot be told: stamp left start")
    return "start", None
