"""Why a description has no laser, as far as its files show.

The common causes, each from a real description: a file that only defines the laser's xacro
macro and never calls it; macros called without the `xacro:` prefix, which xacro 1.14 and later
leave in the output as plain elements; a laser switched off by a xacro arg's default; and other
kinds of sensor (an IMU, a depth camera) where a laser was expected.
"""

from __future__ import annotations

import re
from collections.abc import Iterator, Mapping
from pathlib import Path

from pytest_lasertest.descriptions.laser_block import LASER_TYPES, is_laser
from pytest_lasertest.descriptions.xacro_expand import origin
from pytest_lasertest.descriptions.xmlfile import XmlElement
from pytest_lasertest.inputs.errors import Location, SpecError

# xacro args whose names suggest a laser, and among them those that switch something on.
LASER_ARG = re.compile(r"laser|lidar|scan|lms|hokuyo|ust|sick", re.IGNORECASE)
SWITCH_ARG = re.compile(r"enable|use_|with_|_on\b|visual", re.IGNORECASE)
NO_LASER_FIX = (
    f"point `urdf:` at the robot description that holds the laser's <sensor> "
    f"(type {', '.join(LASER_TYPES)})"
)


def no_laser_error(path: Path, root: XmlElement, sources: Mapping[Path, XmlElement]) -> SpecError:
    """The error for a description without a laser, with the likeliest reasons."""
    macros = _macros(sources)
    bare = _bare_calls(root, macros)
    if bare:
        return SpecError(
            bare[0][1],
            "",
            f"no laser: the macro call <{bare[0][0]}> has no `xacro:` prefix, and xacro 1.14 and "
            "later leave such calls unexpanded (ROS kinetic and melodic expanded them)",
            f"write <xacro:{bare[0][0]} .../> for each such call: "
            + ", ".join(f"<{name}> (line {where.line})" for name, where in bare),
        )
    uncalled = _uncalled_laser_macros(sources, macros)
    if uncalled:
        names = ", ".join(f"{name!r} (line {macros[name].location.line})" for name in uncalled)
        return SpecError(
            macros[uncalled[0]].location,
            "",
            f"no laser: the description only defines the xacro macro {names}, which holds a "
            "laser sensor, and nothing calls it",
            "point `urdf:` at the robot description that calls the macro, or at a file of your "
            f"own that includes this one and calls <xacro:{uncalled[0]} .../>",
        )
    return SpecError(Location(path, 1), "", _plain_reason(root, sources), NO_LASER_FIX)


def _plain_reason(root: XmlElement, sources: Mapping[Path, XmlElement]) -> str:
    reason = "no laser: the description has no Gazebo laser sensor"
    others = [e for e in root.walk() if e.tag == "sensor" and not is_laser(e)]
    if others:
        reason += ", only " + ", ".join(f"{e.get('type')} {e.get('name')!r}" for e in others)
    named = [
        arg
        for written in sources.values()
        for arg in written.walk()
        if arg.tag == "xacro:arg" and LASER_ARG.search(arg.get("name") or "")
    ]
    switches = [arg for arg in named if SWITCH_ARG.search(arg.get("name") or "")] or named
    if switches:
        listed = ", ".join(f"{a.get('name')} (default {a.get('default')!r})" for a in switches)
        reason += (
            f"; these xacro args may switch one on: {listed}; set one under `args:`, e.g. "
            f"`args: {{{switches[0].get('name')}: 1}}`"
        )
    return reason


def _macros(sources: Mapping[Path, XmlElement]) -> dict[str, XmlElement]:
    macros: dict[str, XmlElement] = {}
    for written in sources.values():
        for element in written.walk():
            name = element.get("name")
            if element.tag == "xacro:macro" and name:
                macros.setdefault(name, element)
    return macros


def _bare_calls(root: XmlElement, macros: Mapping[str, XmlElement]) -> list[tuple[str, Location]]:
    """Elements of the expanded tree named like a macro: calls xacro left alone, each where a
    file writes it."""
    return [
        (element.tag, origin(element) or macros[element.tag].location)
        for element in root.walk()
        if element.tag in macros
    ]


def _uncalled_laser_macros(
    sources: Mapping[Path, XmlElement], macros: Mapping[str, XmlElement]
) -> list[str]:
    """Top-level macros nobody calls whose bodies (or the macros they call) hold a laser."""
    called = {
        element.tag.removeprefix("xacro:")
        for written in sources.values()
        for top in _outside_macros(written)
        for element in top.walk()
    }
    return [
        name
        for name, macro in macros.items()
        if name not in called
        and _is_top_level(macro, sources)
        and _holds_laser(macro, macros, set())
    ]


def _outside_macros(root: XmlElement) -> Iterator[XmlElement]:
    """The elements of a file that are not inside a macro definition."""
    if root.tag == "xacro:macro":
        return
    yield root
    for child in root.children:
        yield from _outside_macros(child)


def _holds_laser(macro: XmlElement, macros: Mapping[str, XmlElement], seen: set[str]) -> bool:
    for element in macro.walk():
        if element.tag == "sensor" and (is_laser(element) or "$" in (element.get("type") or "")):
            return True
        name = element.tag.removeprefix("xacro:")
        if element.tag.startswith("xacro:") and name in macros and name not in seen:
            seen.add(name)
            if _holds_laser(macros[name], macros, seen):
                return True
    return False


def _is_top_level(macro: XmlElement, sources: Mapping[Path, XmlElement]) -> bool:
    return any(macro is child for root in sources.values() for child in _outside_children(root))


def _outside_children(root: XmlElement) -> Iterator[XmlElement]:
    """Macro definitions not nested in another macro."""
    for element in _outside_macros(root):
        yield from (child for child in element.children if child.tag == "xacro:macro")
