"""What `lasertest profile` prints: the laser profile the gate reads from a robot description,
so a team can check it before the gate relies on it.

The JSON holds the PROFILE fields of `lasertest plan --json` and where they came from:
`{"sensor", "link", "kind", "file", "ref", "commit", "base_frame", ...PROFILE}`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from pytest_lasertest.reports.plan import profile_json
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.pairsfile.described import laser_profile
from pytest_lasertest.descriptions.lasers import DescriptionFile, Laser, choose_laser, read_lasers
from pytest_lasertest.inputs.errors import Location, display_path
from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.descriptions.readers import AtRevision, reader_at


@dataclass(frozen=True)
class ReadProfile:
    """A laser read from a description, and what it was read from."""

    laser: Laser
    profile: LaserProfile
    base_frame: str  # the frame the mount is given in
    file: Path
    ref: str | None
    commit: str | None


def read_profile(
    path: Path,
    *,
    sensor: str | None,
    ref: str | None,
    args: Mapping[str, str],
    packages: Mapping[str, Path],
) -> ReadProfile:
    """The laser of a description as the gate reads it (SpecError, GitError when it cannot)."""
    path = path.absolute()
    reader = reader_at(ref, path.parent)
    lasers = read_lasers(DescriptionFile(path, reader, args, packages))
    where = SpecNode(sensor, Location(path, 1), "--sensor")
    laser = choose_laser(lasers, sensor, where, reader.name(path))
    commit = reader.revision.commit if isinstance(reader, AtRevision) else None
    return ReadProfile(laser, laser_profile(laser, {}), laser.mount().base, path, ref, commit)


def profile_read_json(read: ReadProfile) -> dict[str, object]:
    """The JSON `lasertest profile --json` prints."""
    laser = read.laser
    return {
        "sensor": laser.name,
        "link": laser.link,
        "kind": laser.kind,
        "file": display_path(read.file),
        "ref": read.ref,
        "commit": read.commit,
        "base_frame": read.base_frame,
        **profile_json(read.profile),
    }


def profile_read_text(read: ReadProfile) -> str:
    """The profile as a table a person checks against the datasheet."""
    laser, profile = read.laser, read.profile
    at = f" at {read.ref} ({read.commit[:7]})" if read.ref and read.commit else ""
    noise = profile.noise
    meta = profile.to_laserscan_meta()
    rows = [
        ("sensor", f"{laser.name} ({laser.kind}) on link {laser.link}, {laser.node.location}"),
        ("file", f"{display_path(read.file)}{at}"),
        (
            "samples",
            f"{profile.samples} x resolution {profile.resolution:g} = {profile.beam_count} beams",
        ),
        (
            "angles",
            f"{profile.min_angle:g} to {profile.max_angle:g} rad "
            f"({math.degrees(profile.max_angle - profile.min_angle):.1f} deg)",
        ),
        (
            "range",
            f"{profile.range_min:g} to {profile.range_max:g} m, "
            f"resolution {profile.range_resolution:g} m",
        ),
        ("update_rate", f"{profile.update_rate:g} Hz"),
        (
            "noise",
            "none"
            if noise is None
            else f"gaussian, mean {noise.mean:g} m, stddev {noise.stddev:g} m",
        ),
        (
            "mount",
            f"xyz {_triple(profile.pose.xyz)} m, rpy {_triple(profile.pose.rpy)} rad "
            f"in {read.base_frame}" + (", upside down" if profile.pose.is_upside_down() else ""),
        ),
        (
            "laserscan",
            f"angle_min {meta.angle_min:g}, angle_max {meta.angle_max:g}, "
            f"angle_increment {meta.angle_increment:.6g} rad, scan_time {meta.scan_time:g} s",
        ),
    ]
    width = max(len(name) for name, _ in rows)
    return "\n".join(f"{name.ljust(width)}  {value}" for name, value in rows)


def _triple(values: tuple[float, float, float]) -> str:
    return "(" + ", ".join(f"{value:.6g}" for value in values) + ")"
