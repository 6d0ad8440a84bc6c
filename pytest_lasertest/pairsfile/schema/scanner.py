"""The schema of one side of a pair (a scanner, with Gazebo `<ray>` names) and of a pinned
placement."""

from __future__ import annotations

import dataclasses

from pytest_lasertest.model.driver import CHOICES, MAX_LATENCY
from pytest_lasertest.model.scanner_limits import (
    MAX_ANGLE,
    MAX_BEAMS,
    MAX_RANGE,
    MAX_UPDATE_RATE,
    MIN_UPDATE_RATE,
)
from pytest_lasertest.model.seeds import MAX_SEED
from pytest_lasertest.model.verify import DIRECTIONS
from pytest_lasertest.pairsfile import placements
from pytest_lasertest.pairsfile.catalogue import load_catalogue
from pytest_lasertest.pairsfile.described import DESCRIPTION_KEYS
from pytest_lasertest.pairsfile.recorded import BAG_KEYS
from pytest_lasertest.pairsfile.scanners import GROUP_KEYS, PROFILE_KEYS
from pytest_lasertest.pairsfile.schema.terms import (
    Schema,
    choice,
    keyed,
    mapping,
    mounted,
    number,
    one_of,
    real,
    text,
    whole,
)

# The fields a scanner written out in full needs; a `model:`, `bag:` or description gives them.
PROFILE_REQUIRED = ("samples", "min_angle", "max_angle", "range", "update_rate")
SOURCES = ("model", "bag", "urdf", "sdf")


def scanner() -> Schema:
    """A scanner: a catalogue model, a recording, a description or a profile written out."""
    terms = {
        "model": choice(sorted(load_catalogue().entries), "A catalogue model to start from"),
        "bag": _bag(),
        **description_terms("the scanner"),
        **_profile_terms(),
        "pose": mounted("Where the scanner sits on the robot; the robot's laser mount if left out"),
    }
    keys = ("model", "bag", *DESCRIPTION_KEYS, *PROFILE_KEYS, "pose")
    return mapping(
        "One side of a pair: a catalogue `model:`, a recording (`bag:`), a description (`urdf:` "
        "or `sdf:`) or a profile written out. Fields written beside a source override it.",
        keyed(keys, terms),
        anyOf=[*({"required": [key]} for key in SOURCES), {"required": list(PROFILE_REQUIRED)}],
    )


def description_terms(what: str) -> dict[str, Schema]:
    """The fields that read `what` from a URDF/xacro or SDF description."""
    value = {"type": ["string", "number", "boolean"]}
    terms = {
        "urdf": text(f"A URDF or xacro file to read {what} from, relative to this file"),
        "sdf": text(f"An SDF file to read {what} from, relative to this file"),
        "ref": {
            "type": ["string", "integer"],
            "description": "The git revision to read the description at; the working tree if "
            "left out",
        },
        "sensor": text("The laser to read, by sensor or link name, when there are several"),
        "args": {
            "type": "object",
            "description": "xacro args, NAME: VALUE, as `xacro FILE NAME:=VALUE` takes them",
            "additionalProperties": value,
        },
        "packages": {
            "type": "object",
            "description": "ROS package directories for `$(find PKG)`, relative to this file",
            "additionalProperties": {"type": "string", "minLength": 1},
        },
    }
    return keyed(DESCRIPTION_KEYS, terms)


def placement() -> Schema:
    """A pinned placement: an obstacle, its noise seed, and which scanner must miss it."""
    terms = {
        "obstacle": one_of(
            "The obstacle to place.",
            *(_obstacle(name) for name in placements.SHAPES),
        ),
        "seed": whole(0, MAX_SEED, "The scan-noise seed it was recorded with"),
        "direction": choice(DIRECTIONS, "Which scanner must miss it"),
    }
    return mapping(
        "A fixed obstacle the pair is tested on.",
        keyed(placements.PLACEMENT_KEYS, terms),
        ("obstacle", "seed"),
    )


def _obstacle(shape: str) -> Schema:
    names = [field.name for field in dataclasses.fields(placements.SHAPES[shape])]
    terms = {"shape": choice([shape], "The obstacle's shape")}
    terms |= {name: number(placements.BOUNDS[name], _OBSTACLE_FIELDS[name]) for name in names}
    required = ["shape", *(name for name in names if name not in placements.DEFAULTS)]
    return mapping(f"A {shape}.", terms, required)


_OBSTACLE_FIELDS = {
    "x": "Its centre's x in the world frame",
    "y": "Its centre's y in the world frame",
    "yaw": "Its heading; 0 when left out",
    "length": "Its side along its heading",
    "width": "Its side across its heading",
    "radius": "Its radius",
    "height": "Its height",
}


def _bag() -> Schema:
    terms = {
        "path": text("The bag (MCAP, SQLite or ROS 1 .bag), relative to this file"),
        "topic": text("Its LaserScan topic; may be left out when the bag has one"),
    }
    return mapping(
        "A recording of the real scanner: its LaserScan messages give the profile.",
        keyed(BAG_KEYS, terms),
        ("path",),
    )


def _profile_terms() -> dict[str, Schema]:
    angle = {"minimum": -MAX_ANGLE, "maximum": MAX_ANGLE}
    terms = {
        "samples": whole(1, MAX_BEAMS, "Beams per scan (Gazebo's `<samples>`)"),
        "resolution": {
            **real("Beams per sample (`<resolution>`); 1 when left out", ""),
            "exclusiveMinimum": 0,
        },
        "min_angle": {**real("The first beam's angle, counter-clockwise from x", "rad"), **angle},
        "max_angle": {**real("The last beam's angle", "rad"), **angle},
        "range": _group("range", "The distances it reads (`<range>`)."),
        "update_rate": {
            **real("Scans a second", "Hz"),
            "minimum": MIN_UPDATE_RATE,
            "maximum": MAX_UPDATE_RATE,
        },
        "noise": _group("noise", "Gaussian noise on every reading (`<noise>`)."),
        "driver": _group(
            "driver", "How its driver publishes the LaserScan; Gazebo's when left out."
        ),
    }
    return keyed(PROFILE_KEYS, terms)


def _group(name: str, description: str) -> Schema:
    terms = _GROUPS[name]()
    return mapping(description, keyed(GROUP_KEYS[name], terms))


def _range_terms() -> dict[str, Schema]:
    return {
        "min": real("The nearest reading", "m", low=0.0),
        "max": {**real("The farthest reading", "m"), "exclusiveMinimum": 0, "maximum": MAX_RANGE},
        "resolution": real("The step readings are rounded to; 0 when left out", "m", low=0.0),
    }


def _noise_terms() -> dict[str, Schema]:
    return {
        "type": choice(["gaussian"], "The noise model, as Gazebo's `<ray>` has it"),
        "mean": real("The noise's mean", "m"),
        "stddev": real("The noise's standard deviation", "m", low=0.0),
    }


def _driver_terms() -> dict[str, Schema]:
    about = {
        "no_return": "What a beam that met nothing reads",
        "too_near": "What a beam that met something nearer than range.min reads",
        "range_max": "A fixed range_max, or each scan's largest reading",
        "beam_order": "The order of `ranges`",
        "stamp": "The sweep instant the header stamp marks",
    }
    terms = {name: choice(CHOICES[name], about[name]) for name in CHOICES}
    for name in ("no_return", "too_near"):
        # YAML writes some of them as numbers, which the loader reads as their words.
        spelled = {"type": "number", "description": "As YAML writes .inf, -.inf, .nan or 0"}
        terms[name] = {"anyOf": [terms[name], spelled], "description": about[name]}
    latency = real("How much later than the measurement the stamp is", "s", low=0.0)
    return terms | {"latency": {**latency, "maximum": MAX_LATENCY}}


_GROUPS = {"range": _range_terms, "noise": _noise_terms, "driver": _driver_terms}
