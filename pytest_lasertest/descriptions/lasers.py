"""Laser scanners read from robot descriptions: URDF, xacro and SDFormat files.

A description is read as written when it is plain XML, and expanded with xacro first when it
uses xacro. Its lasers are Gazebo `<sensor>`s of a laser type: in URDF, `<gazebo
reference="LINK">` blocks; in SDF, a model's links. Each comes with its profile fields, at the
lines that wrote them, and its mount (`mounts.py`). When there is no laser, the error says why as
far as the files show (`absent.py`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

from pytest_lasertest.descriptions.absent import no_laser_error
from pytest_lasertest.descriptions.collisions import collisions
from pytest_lasertest.descriptions.laser_block import (
    Locate,
    check_planar,
    is_laser,
    read_laser_block,
    vertical_samples,
)
from pytest_lasertest.descriptions.mounts import Mount, sdf_mount, urdf_mount
from pytest_lasertest.descriptions.xacro_expand import FileReader, expand_xacro, origin
from pytest_lasertest.descriptions.xmlfile import XmlElement, parse_xml
from pytest_lasertest.inputs.errors import Location, SpecError
from pytest_lasertest.inputs.files import UnreadableFile
from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.model.body import Collision


@dataclass(frozen=True)
class DescriptionFile:
    """Which description to read, and how: where its files come from, xacro args, packages."""

    path: Path
    reader: FileReader
    args: Mapping[str, str] = field(default_factory=dict)
    packages: Mapping[str, Path] = field(default_factory=dict)


@dataclass(frozen=True)
class _Found:
    """A laser `<sensor>` and the elements that carry it."""

    sensor: XmlElement
    link: str
    models: tuple[XmlElement, ...]  # URDF: (robot,); SDF: the nested models, outermost first
    link_element: XmlElement | None  # SDF only


@dataclass(frozen=True)
class Laser:
    """One laser of a description. Its fields and mount are read when asked for, so that a
    broken laser the pairs file does not choose breaks nothing."""

    name: str
    link: str
    kind: str  # the <sensor> type: ray, gpu_ray, lidar or gpu_lidar
    node: SpecNode  # the <sensor> element, where it was written
    vertical_samples: SpecNode | None
    _found: _Found
    _locate: Locate

    @property
    def planar(self) -> bool:
        """Whether it scans one plane (a 2D laser)."""
        return self.vertical_samples is None or self.vertical_samples.value == 1

    def check_planar(self) -> None:
        """SpecError when it is a 3D lidar."""
        check_planar(self.vertical_samples, self.name)

    def fields(self) -> dict[str, SpecNode]:
        """Its profile fields, each at the line that wrote it."""
        return read_laser_block(self._found.sensor, self._locate)

    def mount(self) -> Mount:
        """Where it sits in the robot's base frame."""
        found, locate = self._found, self._locate
        if found.link_element is not None:
            return sdf_mount(found.models, found.link_element, found.sensor, locate)
        if not found.link:
            raise locate(found.sensor).error(
                'the sensor\'s <gazebo> block names no link (reference="...")',
                'attach it to the laser\'s link: <gazebo reference="LINK">',
            )
        return urdf_mount(found.models[0], found.link, found.sensor, locate)

    def collisions(self) -> tuple[Collision, ...] | None:
        """The collision geometry of the robot carrying it, in its base frame (`collisions.py`);
        None for an SDF model, or where a collision is a mesh."""
        if self._found.link_element is not None:
            return None

        def locate(element: XmlElement) -> SpecNode:  # named for itself, not for the laser
            return dataclasses.replace(self._locate(element), field=f"<{element.tag}>")

        return collisions(self._found.models[0], self.mount().base, locate)


def read_lasers(description: DescriptionFile) -> tuple[Laser, ...]:
    """Every laser of a description; SpecError when it has none, saying why."""
    document = _read(description)
    root = document.root
    if root.tag not in ("robot", "sdf"):
        raise SpecError(
            root.location,
            "",
            f"the root element is <{root.tag}>: this is neither a URDF (<robot>) nor an SDFormat "
            "file (<sdf>)",
            "point `urdf:` at the robot's URDF, xacro or SDF file",
        )
    found = _urdf_lasers(root) if root.tag == "robot" else _sdf_lasers(root)
    if not found:
        raise no_laser_error(document.path, document.root, document.sources)
    return tuple(_laser(document, item) for item in found)


def choose_laser(
    lasers: tuple[Laser, ...], wanted: str | None, where: SpecNode, file: str
) -> Laser:
    """The laser `sensor:` names (a sensor's name, else its link's), or the only 2D one; errors
    point at `where` and name the description `file`."""
    if wanted is None:
        planar = [laser for laser in lasers if laser.planar]
        if not planar:
            lasers[0].check_planar()
        if len(planar) == 1:
            return planar[0]
        listing = ", ".join(f"{laser.name!r} ({_place(laser, lasers)})" for laser in planar)
        raise where.error(
            f"{file} has {len(planar)} 2D lasers: {listing}",
            "say which one the gate reads with `sensor: NAME`",
        )
    for key in ("name", "link"):
        chosen = [laser for laser in lasers if getattr(laser, key) == wanted]
        if len(chosen) == 1:
            chosen[0].check_planar()
            return chosen[0]
        if chosen:
            listing = ", ".join(f"{laser.kind} at {_place(laser, lasers)}" for laser in chosen)
            raise where.error(
                f"{file} has {len(chosen)} lasers whose {key} is {wanted!r}: {listing}",
                "give each laser its own sensor name, and choose one with `sensor: NAME`",
            )
    names = ", ".join(repr(laser.name) for laser in lasers)
    raise where.error(
        f"{file} has no laser sensor or link named {wanted!r}", f"its lasers: {names}"
    )


def _place(laser: Laser, lasers: tuple[Laser, ...]) -> str:
    """`line 17` when every laser is written in one file, else `file:line`."""
    if len({other.node.location.path for other in lasers}) == 1:
        return f"line {laser.node.location.line}"
    return str(laser.node.location)


class _Document:
    """A read description: the tree to search, and the files that wrote it."""

    def __init__(
        self, path: Path, root: XmlElement, sources: Mapping[Path, XmlElement | None]
    ) -> None:
        self.path = path
        self.root = root
        self.sources = {key: value for key, value in sources.items() if value is not None}
        self.expanded = root is not self.sources.get(path)

    def locator(self, sensor: XmlElement) -> Locate:
        """Where to report an element of a sensor: its own line in a plain file; in an
        expanded one, the line of the file that wrote it."""
        name = sensor.get("name") or "sensor"

        def locate(element: XmlElement) -> SpecNode:
            label = name if element is sensor else f"{name}: <{element.tag}>"
            return SpecNode(None, self._location(element), label)

        return locate

    def _location(self, element: XmlElement) -> Location:
        if not self.expanded:
            return element.location
        return origin(element) or Location(self.path, 1)


def _read(description: DescriptionFile) -> _Document:
    path, reader = description.path, description.reader
    try:
        data = reader.read(path)
    except FileNotFoundError:
        raise SpecError(
            Location(path, 1),
            "",
            f"{reader.name(path)} does not exist",
            "check the path (relative to the pairs file) and its spelling",
        ) from None
    except UnreadableFile as error:
        raise SpecError(Location(path, 1), "", error.problem, error.fix) from None
    root = parse_xml(data, path)
    if not _uses_xacro(root, path):
        return _Document(path, root, {path: root})
    expansion = expand_xacro(path, reader, description.args, description.packages)
    return _Document(path, expansion.root, expansion.sources)


def _uses_xacro(root: XmlElement, path: Path) -> bool:
    if path.name.endswith(".xacro") or "xmlns:xacro" in root.attributes:
        return True
    return any(element.tag.startswith("xacro:") for element in root.walk())


def _urdf_lasers(robot: XmlElement) -> list[_Found]:
    return [
        _Found(sensor, gazebo.get("reference") or "", (robot,), None)
        for gazebo in robot.all("gazebo")
        for sensor in gazebo.all("sensor")
        if is_laser(sensor)
    ]


def _sdf_lasers(root: XmlElement) -> list[_Found]:
    tops = [*root.all("model"), *(m for world in root.all("world") for m in world.all("model"))]
    return [found for model in tops for found in _model_lasers((model,))]


def _model_lasers(models: tuple[XmlElement, ...]) -> list[_Found]:
    model = models[-1]
    found = [
        _Found(sensor, link.get("name") or "", models, link)
        for link in model.all("link")
        for sensor in link.all("sensor")
        if is_laser(sensor)
    ]
    for nested in model.all("model"):
        found += _model_lasers((*models, nested))
    return found


def _laser(document: _Document, found: _Found) -> Laser:
    sensor = found.sensor
    locate = document.locator(sensor)
    vertical = vertical_samples(sensor, locate)
    return Laser(
        name=sensor.get("name") or found.link,
        link=found.link,
        kind=sensor.get("type") or "",
        node=locate(sensor),
        vertical_samples=vertical,
        _found=found,
        _locate=locate,
    )
