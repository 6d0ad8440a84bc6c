"""A scanner a pairs file reads from a robot description:
`{urdf: robots/r.urdf.xacro, ref: origin/main, sensor: front_laser, args: {...}, packages: {...}}`,
optionally with profile fields that override what the description says."""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from pytest_lasertest.descriptions.gitref import GitError
from pytest_lasertest.descriptions.lasers import (
    DescriptionFile,
    Laser,
    choose_laser,
    read_lasers,
)
from pytest_lasertest.descriptions.profile import laser_profile
from pytest_lasertest.descriptions.readers import AtRevision, WorkingTree, reader_at
from pytest_lasertest.descriptions.xacro_expand import FileReader
from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.model.sensor import LaserProfile

DESCRIPTION_KEYS = ("urdf", "sdf", "ref", "sensor", "args", "packages")


@dataclass(frozen=True)
class DescribedLaser:
    """A laser read from a description, and how reports name it."""

    profile: LaserProfile
    label: str  # "front_laser in robots/r.urdf.xacro at origin/main (1a2b3c4)"
    laser: Laser  # as the description has it: its robot's geometry is read from it on demand


def is_described(fields: Mapping[str, SpecNode]) -> bool:
    """Whether a scanner's fields name a description file."""
    return "urdf" in fields or "sdf" in fields


def read_described(node: SpecNode, fields: dict[str, SpecNode]) -> DescribedLaser:
    """The laser a scanner's `urdf:` (or `sdf:`) names, with the scanner's other profile fields
    as overrides. An error in the description names the description's line, then this one."""
    file_node = _file_node(node, fields)
    here = node.location.path.parent
    path = _path(file_node, here, what="a description file")
    reader = _reader(fields.pop("ref", None), path)
    description = DescriptionFile(
        path=path,
        reader=reader,
        args=_args(fields.pop("args", None)),
        packages=_packages(fields.pop("packages", None), here),
    )
    sensor = fields.pop("sensor", None)
    try:
        laser = choose_laser(
            read_lasers(description),
            sensor.text(what="a sensor name") if sensor else None,
            sensor or file_node,
            reader.name(description.path),
        )
        profile = laser_profile(laser, fields)
    except SpecError as error:
        raise _in_context(error, file_node) from None
    # Named as the pairs file writes it, which reads the same from any working directory.
    revision = f" at {reader.revision.label}" if isinstance(reader, AtRevision) else ""
    return DescribedLaser(profile, f"{laser.name} in {file_node.value}{revision}", laser)


def _file_node(node: SpecNode, fields: dict[str, SpecNode]) -> SpecNode:
    if "urdf" in fields and "sdf" in fields:
        raise fields["sdf"].error(
            "a scanner names one description: `urdf:` or `sdf:`, not both", "drop one of them"
        )
    if "model" in fields:
        raise fields["model"].error(
            "a scanner is read from a catalogue `model:` or from a description, not both",
            "drop `model:`, or drop `urdf:` and write the mount with `pose:`",
        )
    return fields.pop("urdf") if "urdf" in fields else fields.pop("sdf")


def _reader(ref: SpecNode | None, path: Path) -> FileReader:
    """Where the description at `path` is read: at `ref` of the repository that holds it."""
    if ref is None:
        return WorkingTree()
    # A ref YAML reads as a number (a short commit id such as 1234567) is still a ref.
    text = str(ref.value) if isinstance(ref.value, int) else ref.text(what="a git ref")
    try:
        return reader_at(text, path)
    except GitError as error:
        raise ref.error(error.problem, error.fix) from None


def _args(node: SpecNode | None) -> dict[str, str]:
    """xacro args, NAME: VALUE, as the text `xacro FILE NAME:=VALUE` would pass."""
    if node is None:
        return {}
    args = {}
    for name, value in node.entries(what="xacro args, NAME: VALUE").items():
        if isinstance(value.value, bool):
            args[name] = str(value.value).lower()
        elif isinstance(value.value, str | int | float):
            args[name] = str(value.value)
        else:
            raise value.error(
                f"a xacro arg is one value, not {type(value.value).__name__}",
                f"write `{name}: VALUE`, as `xacro FILE {name}:=VALUE` would take it",
            )
    return args


def _packages(node: SpecNode | None, here: Path) -> dict[str, Path]:
    """ROS package name -> its directory, for `$(find PKG)`; relative to the pairs file."""
    if node is None:
        return {}
    return {
        name: _path(value, here, what="a package directory")
        for name, value in node.entries(what="packages, NAME: DIRECTORY").items()
    }


def _path(node: SpecNode, here: Path, *, what: str) -> Path:
    """A path the pairs file writes, relative to its directory."""
    text = node.text(what=what)
    if "\x00" in text:
        raise node.error(
            f"the path {text!r} holds a NUL character, which no file name can hold",
            "write the path as it is on disk",
        )
    return Path(os.path.abspath(here / text))


def _in_context(error: SpecError, file_node: SpecNode) -> SpecError:
    """The error, saying which scanner of the pairs file read the description."""
    if error.location.path == file_node.location.path:
        return error
    return SpecError(
        error.location,
        error.field,
        f"{error.problem} (read for {file_node.field} at {file_node.location})",
        error.fix,
    )
