"""The JSON Schema (draft-07) terms the pairs file's schema is written in: a number within the
loader's own Bounds, a whole number, a choice, a mapping of known keys, a list.

Each term carries the description an editor shows on hover and the docs' reference prints, and
is as strict as the loader on what it can state (types, keys, ranges, choices); what depends on
other values or on files (a convex footprint, a goal inside a wall) is the loader's alone.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Any

from pytest_lasertest.inputs.node import Bounds

Schema = dict[str, Any]


def number(bounds: Bounds, description: str) -> Schema:
    """A finite number within `bounds`, in their unit."""
    low = "exclusiveMinimum" if bounds.above_low else "minimum"
    return {
        "type": "number",
        low: bounds.low,
        "maximum": bounds.high,
        "description": _with_unit(description, bounds.unit),
    }


def real(description: str, unit: str, *, low: float | None = None) -> Schema:
    """A finite number in `unit`, at least `low` if given, whose range the loader checks
    against other values."""
    term: Schema = {"type": "number", "description": _with_unit(description, unit)}
    return term if low is None else {**term, "minimum": low}


def whole(low: int, high: int, description: str) -> Schema:
    """A whole number from `low` to `high`."""
    return {"type": "integer", "minimum": low, "maximum": high, "description": description}


def text(description: str, *, examples: Iterable[str] = ()) -> Schema:
    """A non-empty string; `examples` are what editors offer."""
    term: Schema = {"type": "string", "minLength": 1, "description": description}
    listed = list(examples)
    return {**term, "examples": listed} if listed else term


def truth(description: str) -> Schema:
    """true or false."""
    return {"type": "boolean", "description": description}


def choice(values: Sequence[str], description: str) -> Schema:
    """One of `values`."""
    return {"type": "string", "enum": list(values), "description": description}


def triple(unit: str, description: str) -> Schema:
    """[x, y, z] or [roll, pitch, yaw] in `unit`."""
    return {
        "type": "array",
        "items": {"type": "number"},
        "minItems": 3,
        "maxItems": 3,
        "description": _with_unit(description, unit),
    }


def mounted(description: str, required: Sequence[str] = ()) -> Schema:
    """A pose in the robot's base frame as URDF writes an origin: `{xyz: [...], rpy: [...]}`."""
    return mapping(
        description,
        {
            "xyz": triple("m", "The position in the robot's base frame (base_footprint)"),
            "rpy": triple("rad", "Roll, pitch and yaw"),
        },
        required,
    )


def mapping(
    description: str,
    properties: Mapping[str, Schema],
    required: Sequence[str] = (),
    **more: Any,
) -> Schema:
    """A mapping of the keys `properties` names, and no other."""
    term: Schema = {
        "type": "object",
        "description": description,
        "properties": dict(properties),
        "additionalProperties": False,
    }
    if required:
        term["required"] = list(required)
    return {**term, **more}


def listing(description: str, items: Schema, *, least: int = 0, most: int | None = None) -> Schema:
    """A list of `items`, from `least` to `most` of them."""
    term: Schema = {"type": "array", "description": description, "items": items}
    if least:
        term["minItems"] = least
    return term if most is None else {**term, "maxItems": most}


def one_of(description: str, *alternatives: Schema) -> Schema:
    """Exactly one of `alternatives`."""
    return {"description": description, "oneOf": list(alternatives)}


def keyed(keys: Sequence[str], terms: Mapping[str, Schema]) -> dict[str, Schema]:
    """`terms` for exactly the loader's `keys`, in their order: a key table and the schema
    cannot drift apart, as a key missing from either raises here."""
    missing = [key for key in keys if key not in terms]
    extra = [key for key in terms if key not in keys]
    if missing or extra:
        raise KeyError(f"schema terms missing {missing}, or not read by the loader {extra}")
    return {key: terms[key] for key in keys}


def _with_unit(description: str, unit: str) -> str:
    return f"{description} ({unit})" if unit else description
