"""Pinned placements (`placements:` in a pair): reading them, and every way to write one wrong."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.model.obstacles import Box, Cylinder, Obstacle
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.pairsfile.placements import obstacle_fields
from tests.helpers.model import RECORDED
from tests.helpers.runs import Case, assert_one_clean_error
from tests.helpers.texts import VALID_PAIRS, write

# Line numbers matter: the cases below break one line of it.
PINNED = """\
robot: husky
world:
  start: {x: 0.0, y: 0.0, yaw: 0.0}
  goal: {x: 10.0, y: 0.0}
  time_limit: 60.0
pairs:
  size:
    baseline: {model: clearpath_lms1xx_gazebo, samples: 32, range: {max: 10.0}}
    candidate: {model: clearpath_lms1xx_gazebo, samples: 16, range: {max: 10.0}}
    placements:
      - obstacle: {shape: cylinder, x: 5.943, y: 0.249, radius: 0.025, height: 0.323}   # m
        seed: 1234
        direction: candidate-misses
      - obstacle: {shape: box, x: 6.7, y: 0.0, length: 0.657, width: 0.657, height: 0.328}
        seed: 7
      - obstacle:
          shape: box
          x: 4.0
          y: -0.5
          yaw: 0.3
          length: 0.2
          width: 0.1
          height: 1.0
        seed: 4294967295
        direction: baseline-misses
"""
SECOND_BOX = (
    "      - obstacle: {shape: box, x: 6.7, y: 0.0, length: 0.657, width: 0.657, height: 0.328}"
)
FIRST = "pairs.size.placements[0]"
SECOND = "pairs.size.placements[1]"
THIRD = "pairs.size.placements[2]"
POSITIVE_FIX = "write a positive {} in m"

CASES = {
    "a misspelt placement key": Case(
        "seed: 7", "sed: 7", 15, f"{SECOND}.sed", "unknown key 'sed'", "did you mean 'seed'?"
    ),
    "a misspelt placements key": Case(
        "    placements:",
        "    placement:",
        10,
        "pairs.size.placement",
        "unknown key 'placement'",
        "did you mean 'placements'?",
    ),
    "no seed": Case(
        "        seed: 7\n",
        "",
        14,
        f"{SECOND}.seed",
        "seed is missing",
        "write the scan-noise seed the case was recorded with",
    ),
    "no obstacle": Case(
        f"{SECOND_BOX}\n        seed: 7",
        "      - seed: 7",
        14,
        f"{SECOND}.obstacle",
        "obstacle is missing",
        "write the obstacle to place, e.g. `obstacle: {shape: cylinder",
    ),
    "a placement that is not a mapping": Case(
        f"{SECOND_BOX}\n        seed: 7",
        "      - [6.7, 0.0]",
        14,
        SECOND,
        "expected a mapping of placement fields (obstacle, seed, direction), got a list",
        "write `key: value` pairs",
    ),
    "an obstacle that is a list": Case(
        SECOND_BOX,
        "      - obstacle: [box, 6.7, 0.0]",
        14,
        f"{SECOND}.obstacle",
        "expected a mapping of obstacle fields, got a list",
        "write `key: value` pairs",
    ),
    "no shape": Case(
        "{shape: box, x: 6.7",
        "{x: 6.7",
        14,
        f"{SECOND}.obstacle.shape",
        "shape is missing",
        "write `shape: box` or `shape: cylinder`",
    ),
    "a misspelt shape": Case(
        "shape: cylinder",
        "shape: cylindre",
        11,
        f"{FIRST}.obstacle.shape",
        "unknown shape 'cylindre'",
        "did you mean 'cylinder'? write one of: box, cylinder",
    ),
    "a shape that is not modelled": Case(
        "shape: cylinder",
        "shape: cone",
        11,
        f"{FIRST}.obstacle.shape",
        "unknown shape 'cone'",
        "write one of: box, cylinder",
    ),
    "a shape that is a number": Case(
        "shape: cylinder",
        "shape: 3",
        11,
        f"{FIRST}.obstacle.shape",
        "expected a shape (box, cylinder), got 3",
        "write one of: box, cylinder",
    ),
    "a yaw on a cylinder": Case(
        "{shape: cylinder, x: 5.943,",
        "{shape: cylinder, yaw: 0.1, x: 5.943,",
        11,
        f"{FIRST}.obstacle.yaw",
        "unknown key 'yaw'",
        "a cylinder looks the same at every yaw; remove yaw",
    ),
    "a length on a cylinder": Case(
        "radius: 0.025",
        "length: 0.025",
        11,
        f"{FIRST}.obstacle.length",
        "unknown key 'length'",
        "`length` belongs to a box; write radius, or shape: box",
    ),
    "a radius on a box": Case(
        "length: 0.657, width: 0.657,",
        "radius: 0.657,",
        14,
        f"{SECOND}.obstacle.radius",
        "unknown key 'radius'",
        "`radius` belongs to a cylinder; write length and width, or shape: cylinder",
    ),
    "a misspelt box field": Case(
        "          width: 0.1",
        "          widht: 0.1",
        22,
        f"{THIRD}.obstacle.widht",
        "unknown key 'widht'",
        "did you mean 'width'?",
    ),
    "a box without its width": Case(
        "          width: 0.1\n",
        "",
        16,
        f"{THIRD}.obstacle.width",
        "width is missing",
        "write the box's width in m",
    ),
    "a cylinder without its radius": Case(
        "radius: 0.025, ",
        "",
        11,
        f"{FIRST}.obstacle.radius",
        "radius is missing",
        "write the cylinder's radius in m",
    ),
    "a cylinder without its centre": Case(
        "x: 5.943, ", "", 11, f"{FIRST}.obstacle.x", "x is missing", "write the cylinder's x in m"
    ),
    "a zero radius": Case(
        "radius: 0.025",
        "radius: 0",
        11,
        f"{FIRST}.obstacle.radius",
        "a radius of 0 m is no obstacle",
        POSITIVE_FIX.format("radius"),
    ),
    "a negative height": Case(
        "          height: 1.0",
        "          height: -1.0",
        23,
        f"{THIRD}.obstacle.height",
        "a height of -1.0 m is no obstacle",
        POSITIVE_FIX.format("height"),
    ),
    "a negative length": Case(
        "          length: 0.2",
        "          length: -0.2",
        21,
        f"{THIRD}.obstacle.length",
        "a length of -0.2 m is no obstacle",
        POSITIVE_FIX.format("length"),
    ),
    "a zero width": Case(
        "width: 0.657,",
        "width: 0.0,",
        14,
        f"{SECOND}.obstacle.width",
        "a width of 0.0 m is no obstacle",
        POSITIVE_FIX.format("width"),
    ),
    "text where a coordinate belongs": Case(
        "          x: 4.0",
        "          x: four",
        18,
        f"{THIRD}.obstacle.x",
        "expected a number in m, got the text 'four'",
        "write a number in m",
    ),
    "a yaw in degrees": Case(
        "yaw: 0.3",
        "yaw: 30deg",
        20,
        f"{THIRD}.obstacle.yaw",
        "expected a number in rad, got the text '30deg'",
        "write a number in rad",
    ),
    "a coordinate that is not finite": Case(
        "y: -0.5",
        "y: .nan",
        19,
        f"{THIRD}.obstacle.y",
        "nan is not a finite number",
        "write a finite number in m",
    ),
    "a negative seed": Case(
        "seed: 7",
        "seed: -1",
        15,
        f"{SECOND}.seed",
        "the seed -1 is not a 32-bit seed",
        "write a whole number from 0 to 4294967295",
    ),
    "a seed beyond 32 bits": Case(
        "seed: 4294967295",
        "seed: 4294967296",
        24,
        f"{THIRD}.seed",
        "the seed 4294967296 is not a 32-bit seed",
        "write a whole number from 0 to 4294967295",
    ),
    "a fraction of a seed": Case(
        "seed: 1234",
        "seed: 12.5",
        12,
        f"{FIRST}.seed",
        "expected a whole number, got 12.5",
        "write an integer",
    ),
    "an unknown direction": Case(
        "direction: candidate-misses",
        "direction: candidate",
        13,
        f"{FIRST}.direction",
        "unknown direction 'candidate'",
        "write candidate-misses or baseline-misses, or remove direction",
    ),
    "a direction that is a number": Case(
        "direction: baseline-misses",
        "direction: 1",
        25,
        f"{THIRD}.direction",
        "expected a direction (candidate-misses or baseline-misses), got 1",
        "write candidate-misses or baseline-misses",
    ),
}
PLACEMENTS_HEAD = PINNED.split("    placements:")[0]
# Ways to write `placements:` that hold no placement at all.
EMPTY_CASES = {
    "an empty list": (
        "    placements: []\n",
        "pairs.size.placements",
        "the placements list is empty",
        "list at least one placement, or remove placements:",
    ),
    "nothing": (
        "    placements:\n",
        "pairs.size.placements",
        "expected a list of placements",
        "write one `- item` per line",
    ),
    "a single placement without its dash": (
        "    placements:\n      obstacle: {shape: box, x: 1, y: 0, length: 1, width: 1}\n",
        "pairs.size.placements",
        "expected a list of placements, each `- obstacle: {...}` with its `seed:`, got a mapping",
        "write one `- item` per line",
    ),
}


# Reading


def test_a_cylinder_and_boxes_are_read_with_their_values_seeds_directions_and_lines(
    tmp_path: Path,
) -> None:
    pair = load_pairs_file(write(tmp_path, PINNED)).pairs[0]
    cylinder, box, block = pair.placements
    assert cylinder.obstacle == Cylinder(x=5.943, y=0.249, radius=0.025, height=0.323)
    assert (cylinder.seed, cylinder.direction, cylinder.location.line) == (
        1234,
        "candidate-misses",
        11,
    )
    assert box.obstacle == Box(x=6.7, y=0.0, yaw=0.0, length=0.657, width=0.657, height=0.328)
    assert (box.seed, box.direction, box.location.line) == (7, None, 14)
    assert block.obstacle == Box(x=4.0, y=-0.5, yaw=0.3, length=0.2, width=0.1, height=1.0)
    assert (block.seed, block.direction, block.location.line) == (4294967295, "baseline-misses", 16)
    assert cylinder.location.path == tmp_path / "gate.lasertest.yaml"


def test_whole_numbers_are_read_as_metres_and_the_seed_may_be_zero(tmp_path: Path) -> None:
    text = PLACEMENTS_HEAD + (
        "    placements:\n"
        "      - {obstacle: {shape: cylinder, x: 5, y: 0, radius: 1, height: 2}, seed: 0}\n"
    )
    (placement,) = load_pairs_file(write(tmp_path, text)).pairs[0].placements
    assert placement.obstacle == Cylinder(5.0, 0.0, 1.0, 2.0)
    assert isinstance(placement.obstacle.x, float)
    assert placement.seed == 0


def test_a_pair_without_placements_has_none(tmp_path: Path) -> None:
    spec = load_pairs_file(write(tmp_path, VALID_PAIRS))
    assert [pair.placements for pair in spec.pairs] == [(), ()]


@pytest.mark.parametrize("case", CASES.values(), ids=CASES.keys())
def test_a_broken_placement_is_a_spec_error_naming_its_line_field_problem_and_fix(
    tmp_path: Path, case: Case
) -> None:
    assert PINNED.count(case.old) == 1
    path = write(tmp_path, PINNED.replace(case.old, case.new))
    with pytest.raises(SpecError) as raised:
        load_pairs_file(path)
    error = raised.value
    assert (error.location.path, error.location.line, error.field) == (path, case.line, case.field)
    assert case.problem in error.problem
    assert case.fix in error.fix


@pytest.mark.parametrize("case", EMPTY_CASES.values(), ids=EMPTY_CASES.keys())
def test_placements_that_hold_no_placement_are_an_error_on_their_line(
    tmp_path: Path, case: tuple[str, str, str, str]
) -> None:
    tail, field, problem, fix = case
    path = write(tmp_path, PLACEMENTS_HEAD + tail)
    with pytest.raises(SpecError) as raised:
        load_pairs_file(path)
    assert (raised.value.location.line, raised.value.field) == (10, field)
    assert problem in raised.value.problem
    assert fix in raised.value.fix


@pytest.mark.parametrize(
    "name", ["a misspelt shape", "a negative seed", "no obstacle"], ids=lambda name: name
)
def test_a_broken_placement_is_one_clean_collection_error(
    pytester: pytest.Pytester, name: str
) -> None:
    case = CASES[name]
    (pytester.path / "gate.lasertest.yaml").write_text(PINNED.replace(case.old, case.new))
    result = pytester.runpytest()
    assert_one_clean_error(result, case.line, case.field, case)


# obstacle_fields


@pytest.mark.parametrize(
    ("obstacle", "expected"),
    [
        (
            Box(1.0, -2.0, 0.5, 0.3, 0.2, 1.5),
            {
                "shape": "box",
                "x": 1.0,
                "y": -2.0,
                "yaw": 0.5,
                "length": 0.3,
                "width": 0.2,
                "height": 1.5,
            },
        ),
        (
            Cylinder(1.0, -2.0, 0.3, 1.5),
            {"shape": "cylinder", "x": 1.0, "y": -2.0, "radius": 0.3, "height": 1.5},
        ),
    ],
    ids=["box", "cylinder"],
)
def test_obstacle_fields_are_the_shape_then_the_fields_a_placement_is_written_with(
    obstacle: Obstacle, expected: dict[str, object]
) -> None:
    fields = obstacle_fields(obstacle)
    assert fields == expected
    assert list(fields) == list(expected)


def test_obstacle_fields_turn_numpy_floats_into_floats_yaml_can_write() -> None:
    fields = obstacle_fields(RECORDED)
    assert all(type(value) is float for key, value in fields.items() if key != "shape")
    yaml.safe_dump(fields)
