"""What `lasertest explain` prints: which beams of each scanner read one witness's obstacle.

Three scans are explained: the detector's and the misser's at the witness's anchor pose, and the
misser's last scan at or before the witness's `until` instant. A placement both scanners read, which
the robot must act on (an `avoid-K` witness, `model/avoid.py`), has no misser: both scanners' scans
at the anchor are explained, with what the robot must do about it and, where the candidate reads
it nearer than its range_min, that scan. The JSON is a stable contract (documented in
docs/reference/cli.md): `{"pair", "witness", "obstacle", "margins", "scans": [{"scanner", "role",
"time", "pose", "hits": [{"beam", "angle", "range"}], "too_near", "misses", "clearance"}]}`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from pytest_lasertest.model.plan import Witness
from pytest_lasertest.model.route import scan_times
from pytest_lasertest.model.verify import (
    EXACT_WITHIN,
    REQUIRED_MARGIN,
    ROLES,
    Scanner,
    Scene,
    Verification,
    miss_margins,
    readings,
)
from pytest_lasertest.reports.failure import margins_text, too_near_lines
from pytest_lasertest.reports.formats import obstacle_json, pose_text

Role = Literal["detector", "misser"]
# The ray cast's margins (`Verification`), as `lasertest explain --json` gives them.
MARGINS = ("detection", "concealment", "clearance", "obstruction", "too_near", "walls")


@dataclass(frozen=True)
class Hit:
    """A beam that reads the obstacle in range."""

    beam: int
    angle: float  # rad, laser frame
    range: float  # m


@dataclass(frozen=True)
class ScanExplanation:
    """One scan of one scanner: its hits, its beams nearer than range_min, and how many miss."""

    scanner: Scanner
    role: Role
    time: float  # s
    pose: tuple[float, float, float]  # m, m, rad: the robot when it scans
    hits: tuple[Hit, ...]
    too_near: tuple[int, ...]  # beams that read -inf (REP 117: nearer than range_min)
    misses: int  # beams that read +inf
    clearance: float | None  # m, the misser's nearest beam from the obstacle; None for the detector
    below_plane: float  # m, how far the obstacle's top is below the scan plane; <= 0: it crosses it


def explain_scans(scene: Scene, witness: Witness) -> tuple[ScanExplanation, ...]:
    """The detector and the misser at the anchor, then the misser's last scan up to `until`;
    both scanners at the anchor for a placement both read."""
    placement = witness.placement
    direction = placement.direction
    if direction is None:
        return tuple(
            explain_scan(scene, witness, reader, "detector", placement.anchor)
            for reader in placement.readers
        )
    misser = scene.misser(direction)
    detector_name, misser_name = ROLES[direction]
    until = scan_times(misser.update_rate, max(placement.until, placement.anchor))[-1]
    return (
        explain_scan(scene, witness, detector_name, "detector", placement.anchor),
        explain_scan(scene, witness, misser_name, "misser", placement.anchor),
        explain_scan(scene, witness, misser_name, "misser", float(until)),
    )


def explain_scan(
    scene: Scene, witness: Witness, scanner: Scanner, role: Role, time: float
) -> ScanExplanation:
    """What one scanner reads of the witness's obstacle from the nominal path at `time`."""
    profile = scene.baseline if scanner == "baseline" else scene.candidate
    obstacle = witness.placement.obstacle
    poses = scene.path.poses_at(np.array([time]))
    ranges = readings(profile, poses, obstacle)[0]
    angles = profile.beam_angles()
    hit_beams = np.flatnonzero(np.isfinite(ranges))
    clearance = float(miss_margins(profile, poses, obstacle)[0]) if role == "misser" else None
    x, y, yaw = (float(value) for value in poses[0])
    return ScanExplanation(
        scanner=scanner,
        role=role,
        time=time,
        pose=(x, y, yaw),
        hits=tuple(Hit(int(k), float(angles[k]), float(ranges[k])) for k in hit_beams),
        too_near=tuple(int(k) for k in np.flatnonzero(np.isneginf(ranges))),
        misses=int(np.count_nonzero(np.isposinf(ranges))),
        clearance=clearance,
        below_plane=profile.scan_height - obstacle.height,
    )


def explain_json(
    pair: str, witness: Witness, scans: tuple[ScanExplanation, ...]
) -> dict[str, object]:
    """The JSON contract of `lasertest explain --json`."""
    verification = witness.verification
    return {
        "pair": pair,
        "witness": witness.id,
        "obstacle": obstacle_json(witness.placement.obstacle),
        # m; inf where a margin does not apply (no misser to conceal it, no walls), and -inf for
        # too_near where the placement is not judged on being read too near.
        "margins": {name: getattr(verification, name) for name in MARGINS},
        "scans": [_scan_json(scan) for scan in scans],
    }


def _scan_json(scan: ScanExplanation) -> dict[str, object]:
    return {
        "scanner": scan.scanner,
        "role": scan.role,
        "time": scan.time,
        "pose": list(scan.pose),
        "hits": [{"beam": hit.beam, "angle": hit.angle, "range": hit.range} for hit in scan.hits],
        "too_near": list(scan.too_near),
        "misses": scan.misses,
        "clearance": scan.clearance,
    }


def explain_text(
    pair: str,
    witness: Witness,
    scans: tuple[ScanExplanation, ...],
    *,
    scene: Scene | None = None,
) -> str:
    """A heading, then a few lines per scan for people; for a placement both scanners read,
    what the robot must do about it, its margins and, given the `scene`, where the candidate
    reads it too near."""
    placement = witness.placement
    if placement.direction is not None:
        lines = [
            f"{pair} {witness.id}: {placement.obstacle.describe()}",
            f"  anchor t = {placement.anchor:.2f} s, until t = {placement.until:.2f} s",
        ]
    else:
        lines = _avoid_heading(pair, witness)
    for index, scan in enumerate(scans):
        later = placement.direction is not None and index == len(scans) - 1
        lines.append(_scan_heading(scan, later=later, both=placement.direction is None))
        lines.extend(f"    {line}" for line in _scan_body(scan))
    if placement.direction is None and scene is not None:
        lines += too_near_lines(scene, placement.obstacle)
    return "\n".join(lines)


def _avoid_heading(pair: str, witness: Witness) -> list[str]:
    """What a placement both scanners read is, what the robot must do, and its margins."""
    placement, verification = witness.placement, witness.verification
    return [
        f"{pair} {witness.id}: {placement.obstacle.describe()}",
        "  a placement both scanners read, which the robot must act on: "
        + "; and ".join(_avoid_reasons(verification)),
        f"  anchor t = {placement.anchor:.2f} s: both read it there, and the robot braking from "
        "there stops clear of it",
        f"  margins {margins_text(verification)}",
    ]


def _avoid_reasons(verification: Verification) -> list[str]:
    """Why the robot must act on a placement both read: it stands in the robot's way, or the
    candidate reads it too near as the robot passes (`model/avoid.py`), or both."""
    in_the_way = (
        f"it reaches {verification.obstruction * 1000:.0f} mm into what the robot sweeps along "
        "its path, so the robot must steer round it"
    )
    too_near = (
        "the candidate reads it nearer than its range_min (-inf, which a costmap drops) as the "
        "robot passes, where the baseline reads it in range"
    )
    reasons = [
        reason
        for reason, margin in (
            (in_the_way, verification.obstruction),
            (too_near, verification.too_near),
        )
        if margin >= REQUIRED_MARGIN
    ]
    return reasons or [in_the_way]


def _scan_heading(scan: ScanExplanation, *, later: bool, both: bool = False) -> str:
    """`candidate (misser), last scan up to until, t = 3.78 s, pose (...): still misses it`;
    a scanner of a placement both read is named without a role."""
    when = "last scan up to until" if later else "at the anchor"
    if scan.role == "detector":
        verdict = "reads it" if scan.hits else "DOES NOT READ IT"
    else:
        verdict = "READS IT" if scan.hits else "still misses it" if later else "misses it"
    who = scan.scanner if both else f"{scan.scanner} ({scan.role})"
    return f"  {who} {when}, t = {scan.time:.2f} s, pose {pose_text(*scan.pose)}: {verdict}"


def _scan_body(scan: ScanExplanation) -> list[str]:
    """The runs of hits, the beams nearer than range_min, the count of misses, the clearance."""
    lines = [_run_text(run) for run in hit_runs(scan.hits)]
    if scan.too_near:
        lines.append(f"nearer than range_min (-inf): beams {_beam_list(scan.too_near)}")
    beams = len(scan.hits) + len(scan.too_near) + scan.misses
    misses = f"{scan.misses} of {beams} beams miss"
    if scan.below_plane > 0:
        misses += f"; its top is {scan.below_plane * 1000:.1f} mm below the scan plane"
    elif scan.clearance is not None:
        misses += f"; {_clearance_text(scan.clearance)}"
    return [*lines, misses]


def hit_runs(hits: tuple[Hit, ...]) -> list[tuple[Hit, ...]]:
    """The hits grouped into runs of consecutive beam indices."""
    runs: list[list[Hit]] = []
    for hit in hits:
        if runs and runs[-1][-1].beam == hit.beam - 1:
            runs[-1].append(hit)
        else:
            runs.append([hit])
    return [tuple(run) for run in runs]


def _run_text(run: tuple[Hit, ...]) -> str:
    """`beams 353-366 (angles -0.027..0.030 rad): 9.68-9.71 m`, or one beam alone."""
    low, high = min(hit.range for hit in run), max(hit.range for hit in run)
    ranges = f"{low:.2f} m" if f"{low:.2f}" == f"{high:.2f}" else f"{low:.2f}-{high:.2f} m"
    first, last = run[0], run[-1]
    if first is last:
        return f"beam {first.beam} (angle {first.angle:.3f} rad): {ranges}"
    return (
        f"beams {first.beam}-{last.beam} (angles {first.angle:.3f}..{last.angle:.3f} rad): {ranges}"
    )


def _beam_list(beams: tuple[int, ...]) -> str:
    """Beam indices, consecutive ones as `a-b`."""
    groups: list[list[int]] = []
    for beam in beams:
        if groups and groups[-1][-1] == beam - 1:
            groups[-1].append(beam)
        else:
            groups.append([beam])
    return ", ".join(str(g[0]) if len(g) == 1 else f"{g[0]}-{g[-1]}" for g in groups)


def _clearance_text(clearance: float) -> str:
    """The nearest beam's clearance; beyond EXACT_WITHIN it is only a lower bound."""
    if clearance < 0:
        return f"a beam passes {-clearance * 1000:.1f} mm inside it"
    if math.isinf(clearance):
        return "no beam comes near it"
    if clearance >= EXACT_WITHIN:
        return f"nearest beam clears it by at least {clearance * 1000:.0f} mm"
    return f"nearest beam clears it by {clearance * 1000:.1f} mm"
