"""The `placements:` of a pair: fixed obstacles a pair is always tested on.

A recorded failure becomes a permanent regression test by pinning its obstacle and the seed of
its scan noise:

    placements:
      - obstacle: {shape: cylinder, x: 5.943, y: 0.249, radius: 0.025, height: 0.323}   # m
        seed: 1234
        direction: candidate-misses   # optional: which scanner must miss it

The fields of each shape are those of `obstacles.Box` and `obstacles.Cylinder`, so that
`obstacle_fields` writes exactly what `read_placements` reads back.
"""

from __future__ import annotations

import dataclasses
import difflib
from dataclasses import dataclass

from pytest_lasertest.inputs.errors import Location
from pytest_lasertest.inputs.node import Bounds, SpecNode
from pytest_lasertest.model.obstacles import Box, Cylinder, Obstacle

# The range --laser-seed accepts, so that any recorded run's seed can be pinned.
from pytest_lasertest.model.seeds import MAX_SEED
from pytest_lasertest.model.verify import DIRECTIONS, Direction
from pytest_lasertest.pairsfile.world import COORDINATE, YAW

PLACEMENT_KEYS = ("obstacle", "seed", "direction")
SHAPES: dict[str, type[Box] | type[Cylinder]] = {"box": Box, "cylinder": Cylinder}
DEFAULTS = {"yaw": 0.0}  # rad: a box written without yaw stands square to the world axes
# Sizes and heights: zero or less is no obstacle.
POSITIVE = frozenset({"length", "width", "radius", "height"})
UNITS = {"yaw": "rad"}  # every other field is in m
# Keys that belong to the other shape, and what to write instead.
SHAPE_HINTS = {
    "box": {"radius": "`radius` belongs to a cylinder; write length and width, or shape: cylinder"},
    "cylinder": {
        "yaw": "a cylinder looks the same at every yaw; remove yaw",
        "length": "`length` belongs to a box; write radius, or shape: box",
        "width": "`width` belongs to a box; write radius, or shape: box",
    },
}
# Each placement is a test item that drives both robots: a recorded failure is one of a few.
MAX_PLACEMENTS = 1000
# The gate's obstacles are at most settings.max_obstacle_size (10 m) wide, and stand on the
# route's ground; beyond these a figure is a typo.
_WALL = "an obstacle that large is a wall; the gate places obstacles up to 10 m wide"
BOUNDS = {
    "length": Bounds(0.0, 10.0, "m", "no obstacle", _WALL, above_low=True),
    "width": Bounds(0.0, 10.0, "m", "no obstacle", _WALL, above_low=True),
    "radius": Bounds(0.0, 5.0, "m", "no obstacle", _WALL, above_low=True),
    "height": Bounds(0.0, 100.0, "m", "no obstacle", "no obstacle is that tall", above_low=True),
    "x": COORDINATE,
    "y": COORDINATE,
    "yaw": YAW,
}
OBSTACLE_EXAMPLE = "e.g. `obstacle: {shape: cylinder, x: 5.0, y: 0.0, radius: 0.05, height: 0.5}`"


@dataclass(frozen=True)
class PinnedPlacement:
    """An obstacle a pair is always tested on, with the noise seed it was recorded with."""

    obstacle: Obstacle
    seed: int  # of the scan noise
    direction: Direction | None  # which scanner must miss it; None when not recorded
    location: Location  # of its `- ` item in the pairs file


def read_placements(node: SpecNode) -> tuple[PinnedPlacement, ...]:
    """The placements of one pair's `placements:` list; an empty list is an error."""
    items = node.items(what="placements, each `- obstacle: {...}` with its `seed:`")
    if not items:
        raise node.error(
            "the placements list is empty", "list at least one placement, or remove placements:"
        )
    if len(items) > MAX_PLACEMENTS:
        raise node.error(
            f"{len(items)} placements are more than the {MAX_PLACEMENTS} the gate accepts for a "
            "pair: each is a test item that drives both robots",
            "keep the recorded failures that matter, or split them over pairs",
        )
    return tuple(_read_placement(item) for item in items)


def obstacle_fields(obstacle: Obstacle) -> dict[str, object]:
    """The mapping `read_placements` reads `obstacle` from: its shape, then its fields."""
    shape = next(name for name, kind in SHAPES.items() if isinstance(obstacle, kind))
    # float(): solver output may hold numpy floats, which yaml.safe_dump refuses.
    values = {field.name: float(getattr(obstacle, field.name)) for field in _fields(shape)}
    return {"shape": shape, **values}


def _read_placement(node: SpecNode) -> PinnedPlacement:
    fields = node.mapping(PLACEMENT_KEYS, what="placement fields (obstacle, seed, direction)")
    if "obstacle" not in fields:
        raise node.missing("obstacle", f"write the obstacle to place, {OBSTACLE_EXAMPLE}")
    if "seed" not in fields:
        raise node.missing(
            "seed", "write the scan-noise seed the case was recorded with, e.g. `seed: 0`"
        )
    direction = fields.get("direction")
    return PinnedPlacement(
        obstacle=_read_obstacle(fields["obstacle"]),
        seed=_seed(fields["seed"]),
        direction=_direction(direction) if direction is not None else None,
        location=node.location,
    )


def _read_obstacle(node: SpecNode) -> Obstacle:
    shape = _shape(node)
    names = [field.name for field in _fields(shape)]
    fields = node.mapping(
        ("shape", *names), what=f"{shape} fields ({', '.join(names)})", hints=SHAPE_HINTS[shape]
    )
    values: dict[str, float] = {}
    for name in names:
        if name in fields:
            values[name] = _value(fields[name])
        elif name in DEFAULTS:
            values[name] = DEFAULTS[name]
        else:
            raise node.missing(name, f"write the {shape}'s {name} in {UNITS.get(name, 'm')}")
    return SHAPES[shape](**values)


def _shape(node: SpecNode) -> str:
    """The `shape:` of an obstacle mapping, one of SHAPES."""
    choices = ", ".join(SHAPES)
    shape = node.entries(what="obstacle fields").get("shape")
    if shape is None:
        raise node.missing("shape", f"write `shape: box` or `shape: cylinder`, {OBSTACLE_EXAMPLE}")
    name = shape.text(what=f"a shape ({choices})", fix=f"write one of: {choices}")
    if name not in SHAPES:
        close = difflib.get_close_matches(name, list(SHAPES), n=1, cutoff=0.6)
        hint = f"did you mean {close[0]!r}? " if close else ""
        raise shape.error(f"unknown shape {name!r}", f"{hint}write one of: {choices}")
    return name


def _value(node: SpecNode) -> float:
    name = node.field.rsplit(".", 1)[-1]
    unit = UNITS.get(name, "m")
    value = node.number(unit)
    if name in POSITIVE and value <= 0:
        raise node.error(
            f"a {name} of {node.value} {unit} is no obstacle", f"write a positive {name} in {unit}"
        )
    return node.number_in(BOUNDS[name])


def _seed(node: SpecNode) -> int:
    seed = node.whole_number()
    if not 0 <= seed <= MAX_SEED:
        raise node.error(
            f"the seed {seed} is not a 32-bit seed",
            f"write a whole number from 0 to {MAX_SEED}, as --laser-seed takes",
        )
    return seed


def _direction(node: SpecNode) -> Direction:
    choices = " or ".join(DIRECTIONS)
    text = node.text(what=f"a direction ({choices})", fix=f"write {choices}, or remove direction")
    for direction in DIRECTIONS:
        if text == direction:
            return direction
    raise node.error(f"unknown direction {text!r}", f"write {choices}, or remove direction")


def _fields(shape: str) -> tuple[dataclasses.Field[object], ...]:
    return dataclasses.fields(SHAPES[shape])
