"""The laser profile the gate reads from a robot description: for `lasertest profile`, and
for the pairs file's scanners written `urdf:` or `sdf:`."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from pytest_lasertest.descriptions.lasers import DescriptionFile, Laser, choose_laser, read_lasers
from pytest_lasertest.descriptions.readers import AtRevision, reader_at
from pytest_lasertest.inputs.errors import Location
from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.inputs.profile import REQUIRED, build_profile
from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.sensor import LaserProfile

# How a Gazebo <sensor> writes each required field, for "the sensor sets no ..." messages.
XML_NAMES = {
    "samples": "<scan><horizontal><samples>",
    "min_angle": "<scan><horizontal><min_angle>",
    "max_angle": "<scan><horizontal><max_angle>",
    "range.min": "<range><min>",
    "range.max": "<range><max>",
    "update_rate": "<update_rate>",
}


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
    reader = reader_at(ref, path)
    lasers = read_lasers(DescriptionFile(path, reader, args, packages))
    where = SpecNode(sensor, Location(path, 1), "--sensor")
    laser = choose_laser(lasers, sensor, where, reader.name(path))
    commit = reader.revision.commit if isinstance(reader, AtRevision) else None
    return ReadProfile(laser, laser_profile(laser, {}), laser.mount().base, path, ref, commit)


def laser_profile(laser: Laser, overrides: Mapping[str, SpecNode]) -> LaserProfile:
    """The laser's profile, its fields overridden by `overrides` (flattened profile fields)."""
    fields = {**laser.fields(), **overrides}
    for key in REQUIRED:
        if key not in fields:
            raise laser.node.error(
                f"the {laser.kind} sensor sets no {XML_NAMES[key]}",
                f"write it in the <sensor>, or give `{key}:` next to `urdf:` in the pairs file",
            )
    # A mount the pairs file gives in full is not composed, so it rescues a sensor whose link
    # the description leaves unplaced (a Gazebo fragment).
    overridden = "pose.xyz" in overrides and "pose.rpy" in overrides
    mount = Pose3D() if overridden else laser.mount().pose
    return build_profile(fields, laser.node, mount)
