"""A LaserProfile built from profile fields as a file wrote them (flattened Gazebo `<ray>` names,
such as `range.max`), whether a pairs file, the catalogue or a robot description wrote them;
an impossible value is an error at the line that wrote it."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.model.driver import CHOICES, DEFAULT_DRIVER, Driver
from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.sensor import GaussianNoise, LaserProfile, ProfileError

# A profile's `driver:` group: what its driver publishes (model/driver.py).
DRIVER_KEYS = tuple(item.name for item in dataclasses.fields(Driver))

REQUIRED = ("samples", "min_angle", "max_angle", "range.min", "range.max", "update_rate")
REQUIRED_FIX = (
    "a profile needs samples, min_angle, max_angle, range.min, range.max and update_rate; "
    "write them, or start from a catalogue model with `model: NAME` (`lasertest catalogue` "
    "lists them)"
)


def build_profile(
    fields: Mapping[str, SpecNode], where: SpecNode, default_pose: Pose3D
) -> LaserProfile:
    """A validated LaserProfile from flattened fields; errors point at the field's own line."""
    for key in REQUIRED:
        if key not in fields:
            raise where.missing(key, REQUIRED_FIX)
    try:
        return LaserProfile(
            samples=fields["samples"].whole_number(),
            min_angle=fields["min_angle"].number("rad"),
            max_angle=fields["max_angle"].number("rad"),
            range_min=fields["range.min"].number("m"),
            range_max=fields["range.max"].number("m"),
            update_rate=fields["update_rate"].number("Hz"),
            resolution=_optional(fields, "resolution", 1.0, "times samples"),
            range_resolution=_optional(fields, "range.resolution", 0.0, "m"),
            noise=_noise(fields),
            pose=_pose(fields, default_pose),
            driver=_driver(fields),
        )
    except ProfileError as error:
        # A value taken from a default (the robot's mount) has no line of its own.
        culprit = fields.get(error.field, where)
        field = culprit.field if culprit is not where else f"{where.field}.{error.field}"
        raise SpecError(culprit.location, field, error.problem, error.fix) from None


def _optional(fields: Mapping[str, SpecNode], key: str, default: float, unit: str) -> float:
    node = fields.get(key)
    return default if node is None else node.number(unit)


def _noise(fields: Mapping[str, SpecNode]) -> GaussianNoise | None:
    if not any(key.startswith("noise.") for key in fields):
        return None
    kind = fields.get("noise.type")
    if kind is not None and kind.text(what="a noise type", fix="write `gaussian`") != "gaussian":
        raise kind.error(
            f"noise type {kind.value!r} is not modelled",
            "use `type: gaussian` as Gazebo's <ray> does",
        )
    return GaussianNoise(
        mean=_optional(fields, "noise.mean", 0.0, "m"),
        stddev=_optional(fields, "noise.stddev", 0.0, "m"),
    )


def _pose(fields: Mapping[str, SpecNode], default: Pose3D) -> Pose3D:
    xyz, rpy = fields.get("pose.xyz"), fields.get("pose.rpy")
    return Pose3D(
        xyz=default.xyz if xyz is None else xyz.triple("m"),
        rpy=default.rpy if rpy is None else rpy.triple("rad"),
    )


def _driver(fields: Mapping[str, SpecNode]) -> Driver:
    """The `driver:` group, each trait one of its choices; what is not written is Gazebo's."""
    written = {key: fields.get(f"driver.{key}") for key in DRIVER_KEYS}
    if not any(written.values()):
        return DEFAULT_DRIVER
    traits: dict[str, object] = {
        key: _spelled(node) for key, node in written.items() if node is not None and key in CHOICES
    }
    latency = written["latency"]
    if latency is not None:
        traits["latency"] = latency.number("s")
    # Driver refuses what is not one of a trait's choices; build_profile puts it at its line.
    return Driver(**traits)  # type: ignore[arg-type]


def _spelled(node: SpecNode) -> object:
    """A trait's choice as written, or as YAML writes some of them: .inf, -.inf, .nan, 0."""
    value = node.value
    if isinstance(value, float) and math.isnan(value):
        return "nan"
    if isinstance(value, int | float) and not isinstance(value, bool):
        return {math.inf: "inf", -math.inf: "-inf", 0.0: "zero"}.get(float(value), value)
    return value
