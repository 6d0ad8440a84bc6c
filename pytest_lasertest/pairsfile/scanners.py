"""The scanners of a pairs file and of the catalogue, written in YAML with Gazebo `<ray>` names:
their fields, flattened to dotted names (`range.max`), and one side of a pair as read."""

from __future__ import annotations

from dataclasses import dataclass

from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.inputs.profile import DRIVER_KEYS
from pytest_lasertest.model.sensor import LaserProfile

# Gazebo `<ray>` names; the nested groups are flattened to dotted names ("range.max").
PROFILE_KEYS = (
    "samples",
    "resolution",
    "min_angle",
    "max_angle",
    "range",
    "update_rate",
    "noise",
    "driver",
)
GROUP_KEYS = {
    "range": ("min", "max", "resolution"),
    "noise": ("type", "mean", "stddev"),
    "pose": ("xyz", "rpy"),
    "driver": DRIVER_KEYS,
}
# Names users bring from other tools, and what to write instead.
ALIAS_HINTS = {
    "sample_size": "`sample_size` is the LMS1xx xacro name; write `samples`",
    "min_range": "write `range: {min: ...}` (Gazebo <ray> names)",
    "max_range": "write `range: {max: ...}` (Gazebo <ray> names)",
    "range_min": "write `range: {min: ...}` (Gazebo <ray> names)",
    "range_max": "write `range: {max: ...}` (Gazebo <ray> names)",
    "angle_min": "`angle_min` is the LaserScan name; write `min_angle` (Gazebo <ray> names)",
    "angle_max": "`angle_max` is the LaserScan name; write `max_angle` (Gazebo <ray> names)",
    "scan_time": "write the scan rate as `update_rate` in Hz",
    "frequency": "write the scan rate as `update_rate` in Hz",
    "origin": "write the mount as `pose: {xyz: [x, y, z], rpy: [roll, pitch, yaw]}`",
}


@dataclass(frozen=True)
class Scanner:
    """One side of a pair: a profile, and the catalogue model or the robot description it was
    read from, if any."""

    profile: LaserProfile
    model: str | None
    source: str | None = None  # the sensor, its description file and revision

    @property
    def label(self) -> str:
        """How reports name this scanner."""
        return self.model or self.source or "inline profile"


def read_fields(node: SpecNode, allowed: tuple[str, ...]) -> dict[str, SpecNode]:
    """The profile fields written in one mapping, nested groups flattened to dotted names."""
    flat: dict[str, SpecNode] = {}
    for key, child in node.mapping(allowed, what="scanner fields", hints=ALIAS_HINTS).items():
        if key not in GROUP_KEYS:
            flat[key] = child
            continue
        for sub, grandchild in child.mapping(GROUP_KEYS[key], what=f"{key} fields").items():
            flat[f"{key}.{sub}"] = grandchild
    return flat
