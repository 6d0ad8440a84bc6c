"""Validating a pairs file against the JSON Schema the wheel ships, as an editor would."""

from __future__ import annotations

import json
from functools import cache

import jsonschema
import yaml

from pytest_lasertest.pairsfile.schema import SHIPPED


@cache
def validator() -> jsonschema.Draft7Validator:
    """A validator of the shipped schema."""
    return jsonschema.Draft7Validator(json.loads(SHIPPED.read_text()))


def schema_errors(text: str) -> list[jsonschema.ValidationError]:
    """What the schema finds wrong with the pairs file `text`."""
    return list(validator().iter_errors(yaml.safe_load(text)))


def dotted(error: jsonschema.ValidationError) -> str:
    """Where an error is, written as the loader's field names are: `pairs.size.placements[0]`."""
    field = ""
    for part in error.absolute_path:
        field += f"[{part}]" if isinstance(part, int) else f".{part}" if field else str(part)
    return field
