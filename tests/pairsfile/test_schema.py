"""The pairs file's JSON Schema: shipped as the code makes it, printed by `lasertest schema`,
met by every example, and refusing each bad file the loader refuses, at the same field."""

from __future__ import annotations

import copy
import json
from collections.abc import Callable
from pathlib import Path
from typing import Any

import jsonschema
import pytest
import yaml

from pytest_lasertest import cli
from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.pairsfile.schema import SHIPPED, pairs_file_schema, schema_text
from pytest_lasertest.pairsfile.schema import world as world_schema
from tests.helpers import EXAMPLES, REPO
from tests.helpers.schema import dotted, schema_errors
from tests.helpers.texts import write

# One of every section, and of most kinds of value.
GATE = """\
robot: husky
world:
  start: {x: 0.0, y: 0.0, yaw: 0.0}
  goal: {x: 8.0, y: 0.0}
  time_limit: 60.0
  walls:
    - {x: 4.0, y: 2.0, length: 8.0, width: 0.2}
    - {from: {x: 0.0, y: -2.0}, to: {x: 8.0, y: -2.0}, thickness: 0.2}
settings: {witnesses: 1, min_obstacle_size: 0.05, solver_rlimit: 5000000}
constraints: ["x > 1"]
controller: move_base
navigation:
  dwa: {max_vel_x: 0.5}
  nav2_version: 1.3.11
pairs:
  size:
    baseline: {model: clearpath_lms1xx_gazebo, samples: 32, range: {max: 10.0}}
    candidate:
      model: clearpath_lms1xx_gazebo
      samples: 16
      noise: {type: gaussian, stddev: 0.01}
      driver: {no_return: nan, latency: 0.002}
      pose: {xyz: [0.337, 0.0, 0.44]}
    placements:
      - obstacle: {shape: cylinder, x: 5.0, y: 0.2, radius: 0.03, height: 0.5}
        seed: 1
        direction: candidate-misses
"""
IN_PLACE = {
    "name": "bot",
    "body": {"height": 0.3},
    "laser_mount": {"xyz": [0.2, 0.0, 0.3], "rpy": [0.0, 0.0, 0.0]},
    "footprint": [[-0.3, -0.2], [0.3, -0.2], [0.3, 0.2], [-0.3, 0.2]],
    "max_linear_velocity": 0.8,
    "max_linear_acceleration": 1.5,
    "max_angular_velocity": 1.2,
    "max_angular_acceleration": 3.0,
}
CANDIDATE = "pairs.size.candidate"
PLACEMENT = "pairs.size.placements.0"
BOX = {"box": {"size": [0.6, 0.4, 0.2]}, "xyz": [0.0, 0.0, 0.1]}
Edit = Callable[[dict[str, Any]], None]


def put(path: str, value: object) -> Edit:
    """An edit that sets the field at dotted `path` (list indices as numbers)."""

    def edit(tree: dict[str, Any]) -> None:
        *parents, last = path.split(".")
        holder = _walk(tree, parents)
        holder[int(last) if isinstance(holder, list) else last] = value

    return edit


def drop(path: str) -> Edit:
    """An edit that removes the field at dotted `path`."""

    def edit(tree: dict[str, Any]) -> None:
        *parents, last = path.split(".")
        del _walk(tree, parents)[last]

    return edit


def _walk(tree: Any, parts: list[str]) -> Any:
    for part in parts:
        tree = tree[int(part)] if isinstance(tree, list) else tree[part]
    return tree


def in_place(**changes: object) -> Edit:
    """An edit that writes the robot in place, with `changes` to its fields."""
    return put("robot", {**copy.deepcopy(IN_PLACE), **changes})


BAD = {
    "an unknown section": put("robots", "husky"),
    "no pairs section": drop("pairs"),
    "a world without a start": drop("world.start"),
    "a goal and a route both": put("world.route", [{"x": 5.0, "y": 0.0}]),
    "neither a goal nor a route": drop("world.goal"),
    "a time limit in words": put("world.time_limit", "sixty"),
    "a time limit under a second": put("world.time_limit", 0.5),
    "a start heading of more than a turn": put("world.start.yaw", 7.0),
    "a segment of wall without a thickness": drop("world.walls.1.thickness"),
    "a box of wall with a thickness": put("world.walls.0.thickness", 0.2),
    "a wall thinner than a centimetre": put("world.walls.0.width", 0.001),
    "walls that are not a list": put("world.walls", {"x": 1.0}),
    "a map that is not a path": put("world.map", 5),
    "no witnesses": put("settings.witnesses", 0),
    "a fraction of a witness": put("settings.witnesses", 1.5),
    "an obstacle size of 20 m": put("settings.min_obstacle_size", 20.0),
    "a solver rlimit of zero": put("settings.solver_rlimit", 0),
    "constraints that are not a list": put("constraints", "x > 1"),
    "a controller that is a number": put("controller", 42),
    "an unknown navigation section": put("navigation.teb", {"max_vel_x": 0.5}),
    "an unknown DWA parameter": put("navigation.dwa.colour", 1),
    "a backward top speed": put("navigation.dwa.max_vel_x", -1.0),
    "a recovery switch written as a word": put("navigation.move_base", {"back_up_recovery": "yes"}),
    "a Nav2 release not imitated": put("navigation.nav2_version", "1.3.14"),
    "a pair name with a space": put(
        "pairs",
        {"the size": {"baseline": {"model": "rplidar_a1"}, "candidate": {"model": "rplidar_a2"}}},
    ),
    "no pairs": put("pairs", {}),
    "a pair without a candidate": drop(CANDIDATE),
    "a LaserScan name for the range": put(f"{CANDIDATE}.range_max", 5.0),
    "a model not in the catalogue": put(f"{CANDIDATE}.model", "lms999"),
    "no samples": put(f"{CANDIDATE}.samples", 0),
    "a fraction of a sample": put(f"{CANDIDATE}.samples", 16.5),
    "a range beyond a kilometre": put(f"{CANDIDATE}.range", {"max": 2000.0}),
    "a negative minimum range": put(f"{CANDIDATE}.range", {"min": -0.1}),
    "no scans a second": put(f"{CANDIDATE}.update_rate", 0),
    "an angle of two turns": put(f"{CANDIDATE}.max_angle", 12.6),
    "uniform noise": put(f"{CANDIDATE}.noise.type", "uniform"),
    "a negative noise deviation": put(f"{CANDIDATE}.noise.stddev", -0.01),
    "a no-return reading no driver publishes": put(f"{CANDIDATE}.driver.no_return", "infinity"),
    "a driver latency of a minute": put(f"{CANDIDATE}.driver.latency", 60.0),
    "a mount of two numbers": put(f"{CANDIDATE}.pose.xyz", [0.3, 0.4]),
    "a profile without its range": put(
        CANDIDATE, {"samples": 720, "min_angle": -1.0, "max_angle": 1.0, "update_rate": 50.0}
    ),
    "a bag without its path": put(CANDIDATE, {"bag": {"topic": "/scan"}}),
    "an empty placements list": put("pairs.size.placements", []),
    "a placement without its seed": drop(f"{PLACEMENT}.seed"),
    "a negative seed": put(f"{PLACEMENT}.seed", -1),
    "a placement both scanners miss": put(f"{PLACEMENT}.direction", "both"),
    "a sphere of an obstacle": put(f"{PLACEMENT}.obstacle.shape", "sphere"),
    "a cylinder with a yaw": put(f"{PLACEMENT}.obstacle.yaw", 0.3),
    "an obstacle of no radius": put(f"{PLACEMENT}.obstacle.radius", 0.0),
    "a robot written in place with nothing": put("robot", {}),
    "a footprint of two corners": in_place(footprint=[[-0.3, -0.2], [0.3, 0.2]]),
    "a laser mount without its rpy": in_place(laser_mount={"xyz": [0.2, 0.0, 0.3]}),
    "a robot that cannot move": in_place(max_linear_velocity=0.0),
    "a footprint padded by 2 m": in_place(footprint_padding=2.0),
    "a body that is not the Husky": in_place(body="tank"),
    "a body of a height and collisions": in_place(body={"height": 0.3, "collisions": [BOX]}),
    "a collision of two shapes": in_place(
        body={"collisions": [{**BOX, "sphere": {"radius": 0.1}}]}
    ),
    "a collision without its place": in_place(body={"collisions": [{"box": BOX["box"]}]}),
    "a wheel flag in words": in_place(body={"collisions": [{**BOX, "wheel": "yes please"}]}),
}


def written(tmp_path: Path, edit: Edit | None = None) -> tuple[Path, str]:
    """GATE with `edit` made, written to a pairs file; its path and text."""
    tree = yaml.safe_load(GATE)
    if edit is not None:
        edit(tree)
    text = yaml.safe_dump(tree, sort_keys=False)
    path = tmp_path / "gate.lasertest.yaml"
    path.write_text(text)
    return path, text


def test_the_shipped_schema_is_the_one_the_code_makes() -> None:
    assert SHIPPED.read_text() == schema_text(), (
        "regenerate it: lasertest schema > pytest_lasertest/pairsfile/schema/pairs-file.schema.json"
    )


def test_the_schema_is_a_valid_draft_7_schema() -> None:
    jsonschema.Draft7Validator.check_schema(pairs_file_schema())


def test_lasertest_schema_prints_the_schema_and_with_path_where_it_is_installed(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert cli.main(["schema"]) == 0
    assert json.loads(capsys.readouterr().out) == pairs_file_schema()
    assert cli.main(["schema", "--path"]) == 0
    assert Path(capsys.readouterr().out.strip()) == SHIPPED


@pytest.mark.parametrize(
    "example",
    sorted(EXAMPLES.glob("**/*.lasertest.yaml")),
    ids=lambda path: str(path.relative_to(EXAMPLES)),
)
def test_every_example_meets_the_schema(example: Path) -> None:
    assert [error.message for error in schema_errors(example.read_text())] == []


def test_the_readme_s_annotated_example_meets_the_schema() -> None:
    readme = (REPO / "README.md").read_text()
    annotated = readme.split("```yaml\n", 1)[1].split("```", 1)[0]
    assert [error.message for error in schema_errors(annotated)] == []


def test_the_file_every_bad_case_breaks_meets_the_schema_and_loads(tmp_path: Path) -> None:
    path, text = written(tmp_path)
    assert schema_errors(text) == []
    assert load_pairs_file(path).pairs[0].placements


@pytest.mark.parametrize("edit", list(BAD.values()), ids=list(BAD))
def test_the_schema_and_the_loader_both_refuse_a_bad_file_at_the_same_field(
    tmp_path: Path, edit: Edit
) -> None:
    path, text = written(tmp_path, edit)
    with pytest.raises(SpecError) as refused:
        load_pairs_file(path)
    fields = [dotted(error) for error in schema_errors(text)]
    assert fields, "the schema lets through a file the loader refuses"
    assert any(refused.value.field.startswith(field) for field in fields), (
        f"the loader refuses {refused.value.field}; the schema {fields}"
    )


def test_a_key_the_loader_reads_and_the_schema_lacks_stops_the_schema_being_made(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    keys = (*world_schema.world.WORLD_KEYS, "gravity")
    monkeypatch.setattr(world_schema.world, "WORLD_KEYS", keys)
    with pytest.raises(KeyError, match="gravity"):
        pairs_file_schema()


@pytest.mark.parametrize(
    "driver",
    ["{no_return: .nan, too_near: -.inf}", "{no_return: 0, too_near: .inf}", "{no_return: nan}"],
    ids=["nan-and-minus-inf", "zero-and-inf", "words"],
)
def test_the_schema_takes_every_driver_spelling_the_loader_takes(
    tmp_path: Path, driver: str
) -> None:
    text = EXAMPLE_DRIVER.format(driver=driver)
    assert [error.message for error in schema_errors(text)] == []
    load_pairs_file(write(tmp_path, text))


EXAMPLE_DRIVER = """\
robot: husky
world: {{start: {{x: 0, y: 0}}, goal: {{x: 5, y: 0}}, time_limit: 30}}
pairs:
  nan:
    baseline: {{model: hokuyo_ust_10lx}}
    candidate: {{model: hokuyo_ust_10lx, driver: {driver}}}
"""
