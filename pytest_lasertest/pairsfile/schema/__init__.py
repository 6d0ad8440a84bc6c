"""The pairs file's JSON Schema (draft-07), for editors (`# yaml-language-server: $schema=...`)
and the docs' field reference, made from the loader's own key tables, bounds and choices: a key
the loader reads and one the schema names cannot drift apart (`terms.keyed`).

The schema refuses what the loader refuses field by field: unknown keys, missing ones, types,
ranges and choices. What the loader judges across fields or files (a convex footprint, a time
limit the route fits in, the laser a description holds) is the loader's alone, and its errors
name the line.
"""

from __future__ import annotations

import json
from pathlib import Path

from pytest_lasertest.pairsfile.constraints import MAX_CONSTRAINTS, MAX_LENGTH, VARIABLES
from pytest_lasertest.pairsfile.controller import registered_controllers
from pytest_lasertest.pairsfile.pairs import (
    MAX_WITNESSES,
    OBSTACLE_SIZE,
    PAIR_KEYS,
    PAIR_NAME,
    REQUIRED_SECTIONS,
    RLIMIT,
    SECTIONS,
    SETTINGS_KEYS,
)
from pytest_lasertest.pairsfile.placements import MAX_PLACEMENTS
from pytest_lasertest.pairsfile.schema.robot import navigation, robot_schema
from pytest_lasertest.pairsfile.schema.scanner import placement, scanner
from pytest_lasertest.pairsfile.schema.terms import (
    Schema,
    keyed,
    listing,
    mapping,
    number,
    text,
    whole,
)
from pytest_lasertest.pairsfile.schema.world import world_schema

DRAFT = "http://json-schema.org/draft-07/schema#"
# The schema as the wheel ships it, for an editor to point at; a test holds it to the code's.
SHIPPED = Path(__file__).with_name("pairs-file.schema.json")
SCANNER = "#/definitions/scanner"


def pairs_file_schema() -> Schema:
    """The JSON Schema of a pairs file (`*.lasertest.yaml`)."""
    sections = {
        "robot": robot_schema(),
        "world": world_schema(),
        "settings": _settings(),
        "constraints": _constraints(),
        "controller": _controller(),
        "navigation": navigation(),
        "pairs": _pairs(),
    }
    whole_file = mapping(
        "A robot, the world it drives in, and named pairs of scanners: the baseline it has and "
        "the candidate that replaces it.",
        keyed(SECTIONS, sections),
        REQUIRED_SECTIONS,
    )
    # Both sides of a pair are scanners: one definition, which the reference shows once.
    definitions = {"scanner": scanner()}
    return {
        "$schema": DRAFT,
        "title": "pytest-lasertest pairs file",
        **whole_file,
        "definitions": definitions,
    }


def schema_text() -> str:
    """The schema as JSON, as `lasertest schema` prints it."""
    return json.dumps(pairs_file_schema(), indent=2) + "\n"


def _settings() -> Schema:
    terms = {
        "min_obstacle_size": number(
            OBSTACLE_SIZE, "The thinnest obstacle the robot must see; 0.05 when left out"
        ),
        "max_obstacle_size": number(
            OBSTACLE_SIZE, "The widest obstacle the solver places; 1.0 when left out"
        ),
        "witnesses": whole(
            1, MAX_WITNESSES, "Placements per pair and direction, each a test item; 3 if left out"
        ),
        "solver_rlimit": whole(
            int(RLIMIT.low),
            int(RLIMIT.high),
            "Z3's resource limit per query, a count of its steps, the same on every machine",
        ),
    }
    return mapping("How the gate searches.", keyed(SETTINGS_KEYS, terms))


def _constraints() -> Schema:
    variables = ", ".join(f"{name} ({unit})" for name, unit in VARIABLES.items())
    condition = text(f"A linear condition over the obstacle's {variables}, e.g. `x > 2`")
    return listing(
        "Conditions every placed obstacle meets.",
        {**condition, "maxLength": MAX_LENGTH},
        most=MAX_CONSTRAINTS,
    )


def _controller() -> Schema:
    ours = sorted(
        name
        for name, point in registered_controllers().items()
        if point.value.startswith("pytest_lasertest.")
    )
    return text(
        "The controller both robots drive with: a registered name, or `module:factory` found "
        "next to this file first; Nav2's imitation when left out",
        examples=[*ours, "my_controller:make_controller"],
    )


def _pairs() -> Schema:
    # Python's `\Z` is JSON Schema's `$`; both anchor the whole name.
    name = "^" + PAIR_NAME.pattern.removesuffix(r"\Z") + "$"
    return {
        "type": "object",
        "description": "The scanner changes to gate, by name; a name is part of test ids.",
        "minProperties": 1,
        "propertyNames": {"pattern": name},
        "additionalProperties": _pair(),
    }


def _pair() -> Schema:
    terms = {
        "baseline": {"$ref": SCANNER, "description": "The scanner the robot has."},
        "candidate": {"$ref": SCANNER, "description": "The scanner that replaces it."},
        "placements": listing(
            "Obstacles the pair is always tested on: recorded failures kept as regression tests.",
            placement(),
            least=1,
            most=MAX_PLACEMENTS,
        ),
    }
    return mapping("One scanner change.", keyed(PAIR_KEYS, terms), ("baseline", "candidate"))
