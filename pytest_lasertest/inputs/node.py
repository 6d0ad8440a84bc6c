"""A YAML value that knows where it was written, with typed reads that fail as SpecError."""

from __future__ import annotations

import difflib
import math
import re
from collections.abc import Collection, Mapping
from dataclasses import dataclass
from pathlib import Path

from pytest_lasertest.inputs.errors import Location, SpecError
from pytest_lasertest.inputs.yamlfile import YamlList, YamlMap, load_yaml
from pytest_lasertest.model.figures import shown


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

    def truth(self) -> bool:
        """This value as true or false."""
        if not isinstance(self.value, bool):
            raise self.error(
                f"{self.field.rsplit('.', 1)[-1]} is true or false, not {describe(self.value)}",
                "write true or false",
            )
        return self.value

    def number(self, unit: str) -> float:
        """This value as a finite real number in `unit`."""
        value = self.value
        if isinstance(value, str):
            raise self.error(*_text_for_number(value, unit))
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.error(
                f"expected a number in {unit}, got {describe(value)}", f"write a number in {unit}"
            )
        number = _as_float(value)
        if isinstance(value, int) and not math.isfinite(number):
            raise self.error(
                f"{describe(value)} is too large for a number", f"write a number in {unit}"
            )
        if not math.isfinite(number):
            raise self.error(
                f"{describe(value)} is not a finite number",
                f"write a finite number in {unit}: the gate takes no .inf or .nan",
            )
        return number

    def number_in(self, bounds: Bounds) -> float:
        """This value as a number within `bounds`, which say why values outside are refused."""
        return bounds.check(self, self.number(bounds.unit))

    def whole_number(self) -> int:
        """This value as an integer."""
        value = self.value
        if isinstance(value, str) and _LEADING_ZERO.fullmatch(value.strip()):
            raise self.error(*_text_for_number(value, ""))
        if isinstance(value, str) and _EXPONENT.fullmatch(value.strip()):
            problem, _ = _text_for_number(value, "")
            meant = float(value.replace("_", ""))
            whole = f"{meant:.0f}" if abs(meant) < 1e15 and meant == round(meant) else None
            raise self.error(problem, f"write {whole}" if whole else "write an integer, e.g. 720")
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.error(
                f"expected a whole number, got {describe(value)}", "write an integer, e.g. 720"
            )
        return value

    def whole_number_in(self, bounds: Bounds) -> int:
        """This value as an integer within `bounds`."""
        number = self.whole_number()
        bounds.check(self, number)
        return number

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


@dataclass(frozen=True)
class Bounds:
    """The values a field accepts, and why the rest are refused: what a larger one would cost
    (time, memory) or why it cannot be meant."""

    low: float
    high: float
    unit: str
    too_low: str  # why a value below `low` (or at it, when `above_low`) is refused
    too_high: str  # why a value above `high` is refused
    above_low: bool = False  # `low` itself is refused: a rate or a size must be above it

    def check(self, node: SpecNode, value: float) -> float:
        """`value`, as `node` wrote it, or a SpecError at `node` saying why it is refused."""
        unit = f" {self.unit}" if self.unit else ""
        if value < self.low or (self.above_low and value == self.low):
            relation = "not above" if self.above_low else "below"
            raise node.error(
                f"{shown(value)}{unit} is {relation} {shown(self.low)}{unit}: {self.too_low}",
                f"write a value {self.span()}",
            )
        if value > self.high:
            raise node.error(
                f"{shown(value)}{unit} is above {shown(self.high)}{unit}, the most the gate "
                f"accepts: {self.too_high}",
                f"write a value {self.span()}",
            )
        return value

    def span(self) -> str:
        """`from 1 to 100 Hz`, or `above 0 and at most 100 m`."""
        unit = f" {self.unit}" if self.unit else ""
        low, high = shown(self.low), shown(self.high)
        if self.above_low:
            return f"above {low} and at most {high}{unit}"
        return f"from {low} to {high}{unit}"


# YAML 1.1 reads 0720 as octal, 0789 as text.
_LEADING_ZERO = re.compile(r"[-+]?0[0-9_]+")
# A number YAML 1.1 reads as text: 1e6, 1.0e6 (its floats need a dot and a signed exponent).
_EXPONENT = re.compile(r"[-+]?([0-9][0-9_]*(\.[0-9_]*)?|\.[0-9][0-9_]*)[eE][-+]?[0-9]+")
# A number followed by its unit: 10 m, 50Hz.
_WITH_UNIT = re.compile(r"([-+]?[0-9.]+(?:[eE][-+]?[0-9]+)?)\s*([A-Za-z/^0-9]+)")


def _text_for_number(text: str, unit: str) -> tuple[str, str]:
    """Why a text is not the number in `unit` it may look like, and the fix."""
    written = text.strip()
    if _EXPONENT.fullmatch(written):
        return (
            f"{written!r} was read as text: YAML 1.1 (PyYAML's) reads a number with an "
            "exponent only with a dot and a signed exponent",
            f"write {_yaml11_float(written)}",
        )
    if _LEADING_ZERO.fullmatch(written):
        return (
            f"{written!r} was read as text: YAML 1.1 takes an integer with a leading zero for "
            "octal, and one with an 8 or 9 after it for text",
            f"write it without the leading zero: {_without_leading_zeros(written)}",
        )
    if _WITH_UNIT.fullmatch(written):
        return (
            f"expected a number in {unit}, got the text {written!r}",
            f"write a number in {unit}, without a unit (the field's unit is {unit})",
        )
    return f"expected a number in {unit}, got {describe(text)}", f"write a number in {unit}"


def _without_leading_zeros(text: str) -> str:
    """`-0789` as `-789`."""
    sign = text[0] if text[0] in "+-" else ""
    return sign + (text.lstrip("+-").replace("_", "").lstrip("0") or "0")


def _yaml11_float(text: str) -> str:
    """`1e6` and `1.0e6` as YAML 1.1 reads them as numbers: `1.0e+6`."""
    mantissa, exponent = re.split("[eE]", text.replace("_", ""))
    if "." not in mantissa:
        mantissa += ".0"
    elif mantissa.endswith("."):
        mantissa += "0"
    if mantissa.lstrip("+-").startswith("."):
        mantissa = mantissa.replace(".", "0.", 1)
    if exponent[0] not in "+-":
        exponent = f"+{exponent}"
    return f"{mantissa}e{exponent}"


def _as_float(value: int | float) -> float:
    """The value as a float; an integer too large for one becomes infinity."""
    try:
        return float(value)
    except OverflowError:
        return math.inf


def describe(value: object) -> str:
    """How a YAML value reads to the user, for 'expected X, got Y'."""
    if value is None:
        return "nothing (null)"
    if isinstance(value, int) and not isinstance(value, bool):
        return shown(value)
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


def read_root(path: Path, *, what: str, needs: str, ros_params: bool = False) -> SpecNode:
    """The top-level mapping of a YAML file; an empty file is an error that says what it needs.
    `ros_params`: a ROS 2 params file, read as ROS 2 reads one (`load_yaml`)."""
    value = load_yaml(path, ros_params)
    if value is None:
        raise SpecError(Location(path, 1), "", f"the {what} is empty", f"it needs {needs}")
    return SpecNode(value, Location(path, getattr(value, "line", 1)), "")
