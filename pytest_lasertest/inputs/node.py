"""A YAML value that knows where it was written, with typed reads that fail as SpecError."""

from __future__ import annotations

import difflib
import math
from collections.abc import Collection, Mapping
from dataclasses import dataclass
from pathlib import Path

from pytest_lasertest.inputs.errors import Location, SpecError
from pytest_lasertest.inputs.yamlfile import YamlList, YamlMap, load_yaml


@dataclass(frozen=True)
class SpecNode:
    """One value of a file the user wrote, its line, and its dotted field name from the root."""

    value: object
    location: Location
    field: str

    def error(self, problem: str, fix: str) -> SpecError:
        """A SpecError pointing at this value."""
        return SpecError(self.location, self.field, problem, fix)

    def missing(self, key: str, fix: str) -> SpecError:
        """A SpecError for a required key absent from this mapping."""
        return SpecError(self.location, _join(self.field, key), f"{key} is missing", fix)

    def entries(self, *, what: str) -> dict[str, SpecNode]:
        """The entries of this mapping, whatever their keys."""
        if not isinstance(self.value, YamlMap):
            raise self.error(
                f"expected a mapping of {what}, got {describe(self.value)}",
                "write `key: value` pairs, indented below this line",
            )
        path, lines = self.location.path, self.value.key_lines
        return {
            key: SpecNode(value, Location(path, lines[key]), _join(self.field, key))
            for key, value in self.value.items()
        }

    def mapping(
        self, allowed: Collection[str], *, what: str, hints: Mapping[str, str] | None = None
    ) -> dict[str, SpecNode]:
        """The entries of this mapping, refusing keys outside `allowed`."""
        children = self.entries(what=what)
        for key, child in children.items():
            if key not in allowed:
                raise child.error(f"unknown key '{key}'", suggest_key(key, allowed, hints or {}))
        return children

    def items(self, *, what: str) -> list[SpecNode]:
        """The items of this sequence."""
        if not isinstance(self.value, YamlList):
            raise self.error(
                f"expected a list of {what}, got {describe(self.value)}",
                "write one `- item` per line, or `[a, b]`",
            )
        return [
            SpecNode(value, Location(self.location.path, line), f"{self.field}[{index}]")
            for index, (value, line) in enumerate(
                zip(self.value, self.value.item_lines, strict=True)
            )
        ]

    def text(self, *, what: str = "text", fix: str = "write a name or a path") -> str:
        """This value as a non-empty string; `what` and `fix` say what belongs here."""
        if not isinstance(self.value, str) or not self.value.strip():
            raise self.error(f"expected {what}, got {describe(self.value)}", fix)
        return self.value

    def number(self, unit: str) -> float:
        """This value as a finite real number in `unit`."""
        value = self.value
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.error(
                f"expected a number in {unit}, got {describe(value)}", f"write a number in {unit}"
            )
        if not math.isfinite(value):
            raise self.error(f"{value} is not a finite number", f"write a finite number in {unit}")
        return float(value)

    def whole_number(self) -> int:
        """This value as an integer."""
        value = self.value
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.error(
                f"expected a whole number, got {describe(value)}", "write an integer, e.g. 720"
            )
        return value

    def vector(self, length: int, unit: str) -> tuple[float, ...]:
        """This value as a list of `length` finite numbers in `unit`."""
        values = self.items(what=f"{length} numbers in {unit}")
        if len(values) != length:
            raise self.error(
                f"expected {length} numbers in {unit}, got {len(values)}",
                f"write [{', '.join(['0.0'] * length)}]",
            )
        return tuple(value.number(unit) for value in values)

    def triple(self, unit: str) -> tuple[float, float, float]:
        """This value as [x, y, z] or [roll, pitch, yaw] in `unit`."""
        x, y, z = self.vector(3, unit)
        return x, y, z


def describe(value: object) -> str:
    """How a YAML value reads to the user, for 'expected X, got Y'."""
    if value is None:
        return "nothing (null)"
    if isinstance(value, bool):
        return f"{str(value).lower()} (a yes/no value)"
    if isinstance(value, str):
        return f"the text {value!r}"
    if isinstance(value, YamlMap):
        return "a mapping"
    if isinstance(value, YamlList):
        return "a list"
    return repr(value)


def suggest_key(key: str, allowed: Collection[str], hints: Mapping[str, str]) -> str:
    """A 'did you mean' for an unknown key, then the keys that are accepted here."""
    known = f"known keys here: {', '.join(sorted(allowed))}"
    if key in hints:
        return f"{hints[key]}; {known}"
    close = difflib.get_close_matches(key, list(allowed), n=1, cutoff=0.6)
    if close:
        return f"did you mean '{close[0]}'? {known}"
    return known


def _join(field: str, key: str) -> str:
    return f"{field}.{key}" if field else key


def read_root(path: Path, *, what: str, needs: str) -> SpecNode:
    """The top-level mapping of a YAML file; an empty file is an error that says what it needs."""
    value = load_yaml(path)
    if value is None:
        raise SpecError(Location(path, 1), "", f"the {what} is empty", f"it needs {needs}")
    return SpecNode(value, Location(path, getattr(value, "line", 1)), "")
