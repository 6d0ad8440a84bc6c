"""What `lasertest profile` prints: the laser profile the gate reads from a robot description,
so a team can check it before the gate relies on it.

The JSON holds the PROFILE fields of `lasertest plan --json` and where they came from:
`{"sensor", "link", "kind", "file", "ref", "commit", "base_frame", ...PROFILE}`.
"""

from __future__ import annotations

import math

from pytest_lasertest.descriptions.profile import ReadProfile
from pytest_lasertest.inputs.errors import display_path
from pytest_lasertest.reports.formats import profile_json


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
