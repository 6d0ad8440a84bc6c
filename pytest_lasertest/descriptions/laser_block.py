"""The profile fields of one Gazebo laser `<sensor>`: its `<ray>` (or SDFormat `<lidar>`) block
and its `<update_rate>`, read as the flattened fields `build_profile` takes.

URDF `<gazebo>` blocks and SDF files write the block alike. The LMS1xx xacro's names for three
fields (`sample_size`, `min_range`, `max_range`) are read as the Gazebo fields they stand for.
"""

from __future__ import annotations

import re
from collections.abc import Callable

from pytest_lasertest.descriptions.xmlfile import XmlElement
from pytest_lasertest.inputs.node import SpecNode

LASER_TYPES = ("ray", "gpu_ray", "lidar", "gpu_lidar")
# Flattened profile field -> where the block writes it, then the LMS1xx alias.
FIELD_PATHS: dict[str, tuple[tuple[str, ...], ...]] = {
    "samples": (("scan", "horizontal", "samples"), ("scan", "horizontal", "sample_size")),
    "resolution": (("scan", "horizontal", "resolution"),),
    "min_angle": (("scan", "horizontal", "min_angle"),),
    "max_angle": (("scan", "horizontal", "max_angle"),),
    "range.min": (("range", "min"), ("range", "min_range")),
    "range.max": (("range", "max"), ("range", "max_range")),
    "range.resolution": (("range", "resolution"),),
    "noise.type": (("noise", "type"),),
    "noise.mean": (("noise", "mean"),),
    "noise.stddev": (("noise", "stddev"),),
}
WHOLE = re.compile(r"[+-]?\d+\Z")
BLOCK_FIX = (
    "give the sensor a <ray> block (<lidar> in SDFormat 1.7+) with <scan><horizontal> samples, "
    "min_angle and max_angle, and <range> min and max"
)

# Where a value read from a description is reported: its element, or the line that wrote it.
Locate = Callable[[XmlElement], SpecNode]


def is_laser(sensor: XmlElement) -> bool:
    """Whether a `<sensor>` is one of Gazebo's laser types."""
    return sensor.get("type") in LASER_TYPES


def read_laser_block(sensor: XmlElement, locate: Locate) -> dict[str, SpecNode]:
    """The profile fields of a laser `<sensor>`; SpecError at the sensor when it has no block."""
    block = sensor.child("ray") or sensor.child("lidar")
    if block is None:
        raise locate(sensor).error(
            f"the {sensor.get('type')} sensor {sensor.get('name')!r} has no <ray> or <lidar> "
            "block, and SDFormat's defaults (640 samples, all angles and ranges 0) describe no "
            "scanner",
            BLOCK_FIX,
        )
    fields = {}
    for key, paths in FIELD_PATHS.items():
        element = _first(block, paths)
        if element is not None:
            fields[key] = _number(element, locate, text=key == "noise.type")
    noise = block.child("noise")
    if noise is not None and "noise.type" not in fields and noise.get("type") is not None:
        # SDFormat also writes the noise type as an attribute: <noise type="gaussian">.
        fields["noise.type"] = SpecNode(noise.get("type"), locate(noise).location, "noise.type")
    rate = sensor.child("update_rate")
    if rate is not None:
        fields["update_rate"] = _number(rate, locate)
    return fields


def vertical_samples(sensor: XmlElement, locate: Locate) -> SpecNode | None:
    """How many vertical samples the sensor scans, where its block says so."""
    block = sensor.child("ray") or sensor.child("lidar")
    vertical = _first(block, (("scan", "vertical", "samples"),)) if block is not None else None
    return None if vertical is None else _number(vertical, locate)


def _first(block: XmlElement, paths: tuple[tuple[str, ...], ...]) -> XmlElement | None:
    for path in paths:
        element: XmlElement | None = block
        for tag in path:
            element = element.child(tag) if element is not None else None
        if element is not None:
            return element
    return None


def _number(element: XmlElement, locate: Locate, *, text: bool = False) -> SpecNode:
    """The element's value as the number (or, for `text`, the word) it writes."""
    node = locate(element)
    written = element.text.strip()
    if text:
        return SpecNode(written, node.location, node.field)
    try:
        value: int | float = int(written) if WHOLE.match(written) else float(written)
    except ValueError:
        raise node.error(
            f"<{element.tag}> holds {written!r}, not a number", f"write a number in <{element.tag}>"
        ) from None
    return SpecNode(value, node.location, node.field)


def check_planar(vertical: SpecNode | None, name: str) -> None:
    """SpecError when a sensor scans more than one vertical sample: a 3D lidar."""
    if vertical is None or vertical.value == 1:
        return
    raise vertical.error(
        f"the sensor {name!r} scans {vertical.value} vertical samples: it is a 3D lidar, and "
        "the gate models one horizontal scan plane",
        "choose a 2D laser with `sensor: NAME`, or describe one scan plane of it "
        "(<vertical><samples>1</samples>)",
    )
