"""The repro of a failing item: a pairs file holding its pair and one pinned placement, which
loads from wherever it is written and gives back the same robot, world, scanners and obstacle."""

from __future__ import annotations

import dataclasses
import math
import os
import shutil
import sys
import uuid
from collections.abc import Iterator
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from pytest_lasertest.artifacts.repro import repro_yaml, write_repro
from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.model.obstacles import Box, Cylinder, Obstacle
from pytest_lasertest.pairsfile import Pair, PairsFile, load_pairs_file
from pytest_lasertest.pairsfile.placements import PinnedPlacement
from tests.helpers import EXAMPLES
from tests.helpers.git import commit_everything
from tests.helpers.model import RECORDED
from tests.helpers.schema import schema_errors
from tests.helpers.texts import MY_ROBOT, PAIRS, ROBOT, VALID_PAIRS, write

HEADER = ("lasertest repro of gate.lasertest.yaml::size[candidate-misses-0]", "replay: pytest X")


def pair_named(spec: PairsFile, name: str) -> Pair:
    return next(pair for pair in spec.pairs if pair.name == name)


def pinned_for(pair: Pair, obstacle: Obstacle = RECORDED, seed: int = 1234) -> PinnedPlacement:
    return PinnedPlacement(obstacle, seed, "candidate-misses", pair.location)


def replay(spec: PairsFile, name: str, pinned: PinnedPlacement, destination: Path) -> PairsFile:
    """The repro of `pinned` on pair `name`, written at `destination` and loaded from there."""
    pair = pair_named(spec, name)
    write_repro(destination, spec, pair, pinned, HEADER)
    return load_pairs_file(destination)


def assert_replays(
    original: PairsFile, name: str, pinned: PinnedPlacement, repro: PairsFile
) -> None:
    """The repro holds the original's robot, world and pair, with `pinned` as its one placement."""
    assert repro.robot == original.robot
    assert repro.world == original.world
    (pair,) = repro.pairs
    assert pair.name == name
    assert pair.baseline == pair_named(original, name).baseline
    assert pair.candidate == pair_named(original, name).candidate
    (placement,) = pair.placements
    assert_within_a_micrometre(placement.obstacle, pinned.obstacle)
    replayed = dataclasses.replace(placement, obstacle=pinned.obstacle, location=pinned.location)
    assert replayed == pinned


def assert_within_a_micrometre(replayed: Obstacle, pinned: Obstacle) -> None:
    """The repro pins each of the obstacle's numbers (m, rad) to 6 decimals, nothing coarser."""
    assert type(replayed) is type(pinned)
    for field in dataclasses.fields(pinned):
        written, given = getattr(replayed, field.name), getattr(pinned, field.name)
        assert written == pytest.approx(given, rel=0.0, abs=5e-7), field.name


# The repro


def test_the_paper_s_size_failure_replays_from_its_repro_in_another_directory(
    tmp_path: Path,
) -> None:
    original = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
    pinned = pinned_for(pair_named(original, "size"))
    destination = tmp_path / "artifacts" / "paper" / "size-candidate-misses-0.lasertest.yaml"
    assert_replays(original, "size", pinned, replay(original, "size", pinned, destination))


def test_a_repro_keeps_the_model_overrides_as_written_and_drops_settings_and_other_pairs(
    tmp_path: Path,
) -> None:
    original = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
    pair = pair_named(original, "size")
    written = yaml.safe_load(repro_yaml(original, pair, pinned_for(pair), tmp_path / "r.yaml", ()))
    # The controller too: a replay drives as the original did.
    assert list(written) == ["robot", "world", "controller", "pairs"]
    assert written["controller"] == "move_base"
    assert list(written["pairs"]) == ["size"]
    assert written["pairs"]["size"]["candidate"] == {
        "model": "clearpath_lms1xx_gazebo",
        "samples": 16,
        "min_angle": -1.57,
        "max_angle": 1.57,
        "range": {"max": 10.0},
    }
    # RECORDED's numbers, as the repro pins them: to 6 decimals.
    obstacle = {"shape": "cylinder", "x": 5.943, "y": 0.3, "radius": 0.033333, "height": 0.323}
    assert written["pairs"]["size"]["placements"] == [
        {"obstacle": obstacle, "seed": 1234, "direction": "candidate-misses"}
    ]


def test_a_repro_starts_with_the_header_as_comments_then_a_blank_line(tmp_path: Path) -> None:
    original = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
    pair = pair_named(original, "size")
    header = ["first line", "", "two\nlines"]
    text = repro_yaml(original, pair, pinned_for(pair), tmp_path / "r.yaml", header)
    assert text.startswith("# first line\n#\n# two\n# lines\n\nrobot: husky\n")


def test_a_placement_without_a_direction_is_written_without_one(tmp_path: Path) -> None:
    original = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
    pair = pair_named(original, "size")
    pinned = PinnedPlacement(Box(6.7, 0.0, 0.1, 0.657, 0.657, 0.328), 7, None, pair.location)
    destination = tmp_path / "box.lasertest.yaml"
    assert_replays(original, "size", pinned, replay(original, "size", pinned, destination))
    assert "direction" not in destination.read_text()


@pytest.mark.parametrize("written", ["robots/mybot", "robots/mybot/robot.yaml", "./robots/mybot"])
@pytest.mark.parametrize(
    "destination",
    ["artifacts/gate/to_lms111.lasertest.yaml", "project/regressions/to_lms111.lasertest.yaml"],
)
def test_a_robot_directory_given_by_relative_path_is_found_from_the_repro_s_directory(
    tmp_path: Path, written: str, destination: str
) -> None:
    robot_dir = tmp_path / "project" / "robots" / "mybot"
    write(robot_dir, MY_ROBOT, "robot.yaml")
    text = VALID_PAIRS.replace("robot: husky", f"robot: {written}")
    original = load_pairs_file(write(tmp_path / "project", text))
    pinned = pinned_for(pair_named(original, "to_lms111"))
    repro = replay(original, "to_lms111", pinned, tmp_path / destination)
    assert_replays(original, "to_lms111", pinned, repro)
    assert repro.robot.name == "My bot"
    robot = yaml.safe_load((tmp_path / destination).read_text())["robot"]
    assert not Path(robot).is_absolute()


def test_a_robot_path_that_would_read_as_a_bundled_name_stays_a_path(tmp_path: Path) -> None:
    write(tmp_path / "robots" / "husky", MY_ROBOT, "robot.yaml")
    text = VALID_PAIRS.replace("robot: husky", "robot: ../robots/husky")
    original = load_pairs_file(write(tmp_path / "project", text))
    pinned = pinned_for(pair_named(original, "same"))
    destination = tmp_path / "robots" / "same.lasertest.yaml"
    repro = replay(original, "same", pinned, destination)
    assert repro.robot.name == "My bot"
    assert yaml.safe_load(destination.read_text())["robot"] == "./husky"


def test_an_absolute_robot_path_is_kept_as_written(tmp_path: Path) -> None:
    robot_file = write(tmp_path / "robots" / "mybot", MY_ROBOT, "robot.yaml")
    text = VALID_PAIRS.replace("robot: husky", f"robot: {robot_file}")
    original = load_pairs_file(write(tmp_path / "project", text))
    pinned = pinned_for(pair_named(original, "same"))
    destination = tmp_path / "elsewhere" / "same.lasertest.yaml"
    assert_replays(original, "same", pinned, replay(original, "same", pinned, destination))
    assert yaml.safe_load(destination.read_text())["robot"] == str(robot_file)


# A corridor of two walls, one listed as a box, one as a segment, around a route along x.
WALLED_PAIRS = VALID_PAIRS.replace(
    "  goal: {x: 9.0, y: 0.0}\n",
    "  route: [{x: 9.0, y: 0.0}]\n"
    "  walls:\n"
    "    - {x: 5.0, y: 2.0, length: 14.0, width: 0.2}\n"
    "    - {from: {x: -2.0, y: -2.0}, to: {x: 12.0, y: -2.0}, thickness: 0.2}\n",
)


def with_map(path: Path, written: str) -> None:
    """The pairs file at `path` given `map: written` in its world after it was loaded: the
    repro copies the world as written, and only rewrites the map's path, never reads it."""
    text = path.read_text()
    path.write_text(text.replace("world:\n", f"world:\n  map: {written}\n", 1))


def test_a_world_s_listed_walls_replay_from_a_repro_in_another_directory(tmp_path: Path) -> None:
    original = load_pairs_file(write(tmp_path / "project", WALLED_PAIRS))
    assert len(original.world.walls.boxes) == 2
    pinned = pinned_for(pair_named(original, "same"))
    destination = tmp_path / "artifacts" / "gate" / "same.lasertest.yaml"
    assert_replays(original, "same", pinned, replay(original, "same", pinned, destination))
    written = yaml.safe_load(destination.read_text())["world"]
    assert written["walls"][1] == {
        "from": {"x": -2.0, "y": -2.0},
        "to": {"x": 12.0, "y": -2.0},
        "thickness": 0.2,
    }


@pytest.mark.parametrize("written", ["maps/doorway.yaml", "./maps/doorway.yaml"])
@pytest.mark.parametrize(
    "destination",
    [
        "artifacts/gate/same.lasertest.yaml",
        "project/regressions/same.lasertest.yaml",
        "project/same-repro.lasertest.yaml",
    ],
)
def test_a_relative_map_path_is_rewritten_so_the_repro_finds_the_same_map_file(
    tmp_path: Path, written: str, destination: str
) -> None:
    project = tmp_path / "project"
    map_file = write(project / "maps", "image: doorway.pgm\n", "doorway.yaml")
    path = write(project, VALID_PAIRS)
    original = load_pairs_file(path)
    with_map(path, written)
    pair = pair_named(original, "same")
    repro = tmp_path / destination
    world = yaml.safe_load(repro_yaml(original, pair, pinned_for(pair), repro, ()))["world"]
    assert not Path(world["map"]).is_absolute()
    assert (repro.parent / world["map"]).resolve() == map_file.resolve()
    # The rest of the world as written, in its order.
    assert list(world) == ["map", "start", "goal", "time_limit"]
    assert world["goal"] == {"x": 9.0, "y": 0.0}


def test_a_map_path_beside_the_repro_is_written_as_the_user_wrote_it(tmp_path: Path) -> None:
    path = write(tmp_path / "project", VALID_PAIRS)
    original = load_pairs_file(path)
    with_map(path, "maps/doorway.yaml")
    pair = pair_named(original, "same")
    destination = tmp_path / "project" / "same-repro.lasertest.yaml"
    text = repro_yaml(original, pair, pinned_for(pair), destination, ())
    assert yaml.safe_load(text)["world"]["map"] == "maps/doorway.yaml"


def test_an_absolute_map_path_is_kept_as_written(tmp_path: Path) -> None:
    map_file = write(tmp_path / "maps", "image: doorway.pgm\n", "doorway.yaml")
    path = write(tmp_path / "project", VALID_PAIRS)
    original = load_pairs_file(path)
    with_map(path, str(map_file))
    pair = pair_named(original, "same")
    destination = tmp_path / "elsewhere" / "same.lasertest.yaml"
    text = repro_yaml(original, pair, pinned_for(pair), destination, ())
    assert yaml.safe_load(text)["world"]["map"] == str(map_file)


def test_navigation_overrides_are_copied_so_the_repro_s_robot_navigates_the_same(
    tmp_path: Path,
) -> None:
    text = VALID_PAIRS.replace(
        "settings:",
        "navigation:\n"
        "  move_base: {controller_frequency: 10.0, back_up_recovery: true}\n"
        "  dwa: {min_vel_x: -0.1, vx_samples: 8}\n"
        "settings:",
    )
    original = load_pairs_file(write(tmp_path / "project", text))
    assert ("dwa", "min_vel_x", -0.1) in original.robot.navigation
    pinned = pinned_for(pair_named(original, "to_lms111"))
    destination = tmp_path / "artifacts" / "to_lms111.lasertest.yaml"
    assert_replays(
        original, "to_lms111", pinned, replay(original, "to_lms111", pinned, destination)
    )


def test_profiles_shared_through_yaml_anchors_are_written_out_in_full(tmp_path: Path) -> None:
    text = VALID_PAIRS.replace(
        "    baseline:\n      samples: 720", "    baseline: &paper\n      samples: 720"
    )
    text = text.replace("    candidate:\n      model: sick_lms111", "    candidate: *paper")
    original = load_pairs_file(write(tmp_path, text))
    pinned = pinned_for(pair_named(original, "to_lms111"))
    destination = tmp_path / "repro" / "to_lms111.lasertest.yaml"
    assert_replays(
        original, "to_lms111", pinned, replay(original, "to_lms111", pinned, destination)
    )
    assert "&" not in destination.read_text()
    assert "*" not in destination.read_text()


finite = st.floats(-50.0, 50.0, allow_nan=False)
positive = st.floats(1e-6, 5.0, allow_nan=False)
obstacles = st.one_of(
    st.builds(Box, finite, finite, st.floats(-math.pi, math.pi), positive, positive, positive),
    st.builds(Cylinder, finite, finite, positive, positive),
)


@settings(
    max_examples=30, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(obstacle=obstacles, seed=st.integers(0, 2**32 - 1))
def test_every_obstacle_and_seed_comes_back_equal_from_its_repro(
    tmp_path: Path, obstacle: Obstacle, seed: int
) -> None:
    original = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
    pinned = pinned_for(pair_named(original, "size"), obstacle, seed)
    repro = replay(original, "size", pinned, tmp_path / "property.lasertest.yaml")
    assert_within_a_micrometre(repro.pairs[0].placements[0].obstacle, obstacle)
    assert repro.pairs[0].placements[0].seed == seed


def test_a_repro_writes_the_pinned_obstacle_s_numbers_rounded_not_in_full(tmp_path: Path) -> None:
    original = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
    pair = pair_named(original, "size")
    box = Box(3.5999999999999996, 0.1 + 0.2, -1e-12, 1.0 / 30.0, 0.05, 0.323)
    text = repro_yaml(original, pair, pinned_for(pair, box), tmp_path / "r.lasertest.yaml", ())
    assert (
        "{shape: box, x: 3.6, y: 0.3, yaw: 0.0, length: 0.033333, width: 0.05, height: 0.323}"
        in text
    )


def test_a_size_too_small_to_round_is_written_in_full_so_the_obstacle_stays(
    tmp_path: Path,
) -> None:
    original = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
    pinned = pinned_for(pair_named(original, "size"), Cylinder(5.0, 0.0, 4e-7, 0.5))
    repro = replay(original, "size", pinned, tmp_path / "thin.lasertest.yaml")
    assert repro.pairs[0].placements[0].obstacle == Cylinder(5.0, 0.0, 4e-7, 0.5)


@pytest.fixture
def controller_module(tmp_path: Path) -> Iterator[str]:
    """A controller module next to tmp_path/project's pairs file, named uniquely, and unloaded
    after the test: the import system keeps a module once imported."""
    name = f"repro_controller_{uuid.uuid4().hex}"
    write(tmp_path / "project", "def make(robot, route):\n    return None\n", f"{name}.py")
    yield name
    sys.modules.pop(name, None)


def test_a_controller_module_next_to_the_pairs_file_is_noted_in_a_repro_written_elsewhere(
    tmp_path: Path, controller_module: str
) -> None:
    text = f"controller: {controller_module}:make\n{VALID_PAIRS}"
    original = load_pairs_file(write(tmp_path / "project", text))
    pair = pair_named(original, "same")
    destination = tmp_path / "artifacts" / "same.lasertest.yaml"
    repro_text = repro_yaml(original, pair, pinned_for(pair), destination, HEADER)
    comments = [line for line in repro_text.splitlines() if line.startswith("#")]
    assert comments[:2] == [f"# {line}" for line in HEADER]
    assert f"controller: {controller_module}:make is the module" in comments[2]
    assert "make it importable" in comments[2]
    assert yaml.safe_load(repro_text)["controller"] == f"{controller_module}:make"


def test_a_repro_next_to_the_pairs_file_finds_its_controller_module_with_no_note(
    tmp_path: Path, controller_module: str
) -> None:
    text = f"controller: {controller_module}:make\n{VALID_PAIRS}"
    original = load_pairs_file(write(tmp_path / "project", text))
    pinned = pinned_for(pair_named(original, "same"))
    destination = tmp_path / "project" / "same-repro.lasertest.yaml"
    repro = replay(original, "same", pinned, destination)
    assert_replays(original, "same", pinned, repro)
    assert repro.controller is not None
    assert original.controller is not None
    assert repro.controller.factory is original.controller.factory
    assert "importable" not in destination.read_text()


def test_a_pair_gone_from_the_file_since_it_was_read_is_a_spec_error(tmp_path: Path) -> None:
    path = write(tmp_path, VALID_PAIRS)
    original = load_pairs_file(path)
    pair = pair_named(original, "same")
    path.write_text(VALID_PAIRS.replace("  same:", "  renamed:"))
    with pytest.raises(SpecError, match="the pair is gone from the file"):
        repro_yaml(original, pair, pinned_for(pair), tmp_path / "r.yaml", ())


# Writing atomically


def test_write_repro_makes_the_directories_and_leaves_only_the_repro(tmp_path: Path) -> None:
    original = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
    pair = pair_named(original, "size")
    destination = tmp_path / "a" / "b" / "size.lasertest.yaml"
    assert write_repro(destination, original, pair, pinned_for(pair), HEADER) == destination
    expected = repro_yaml(original, pair, pinned_for(pair), destination, HEADER)
    assert destination.read_text(encoding="utf-8") == expected
    assert os.listdir(destination.parent) == [destination.name]


def test_a_failed_write_keeps_the_previous_repro_and_leaves_no_temporary_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    original = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
    pair = pair_named(original, "size")
    destination = write(tmp_path / "artifacts", "previous repro\n", "size.lasertest.yaml")

    def full_disk(source: str, target: str) -> None:
        raise OSError(28, "No space left on device")

    # The last step failing leaves the most behind: a complete temporary file.
    monkeypatch.setattr(os, "replace", full_disk)
    with pytest.raises(OSError, match="No space left"):
        write_repro(destination, original, pair, pinned_for(pair), HEADER)
    assert destination.read_text() == "previous repro\n"
    assert os.listdir(destination.parent) == [destination.name]


def test_a_repro_that_cannot_be_made_writes_nothing(tmp_path: Path) -> None:
    path = write(tmp_path / "project", VALID_PAIRS)
    original = load_pairs_file(path)
    pair = pair_named(original, "same")
    path.write_text(VALID_PAIRS.replace("  same:", "  renamed:"))
    destination = tmp_path / "artifacts" / "same.lasertest.yaml"
    with pytest.raises(SpecError):
        write_repro(destination, original, pair, pinned_for(pair), HEADER)
    assert not destination.parent.exists()


def test_a_scanner_read_from_a_description_is_pinned_as_the_profile_it_read(
    tmp_path: Path,
) -> None:
    (tmp_path / "robot.urdf").write_text(ROBOT)
    pairs = tmp_path / "gate.lasertest.yaml"
    pairs.write_text(PAIRS)
    commit_everything(tmp_path)
    (tmp_path / "robot.urdf").write_text(
        ROBOT.replace("<samples>32</samples>", "<samples>16</samples>")
    )
    original = load_pairs_file(pairs)
    pair = pair_named(original, "swap")
    destination = tmp_path / "elsewhere" / "swap.lasertest.yaml"
    text = repro_yaml(original, pair, pinned_for(pair), destination, ())
    assert text.startswith("# baseline: front in robot.urdf at HEAD (")
    assert "urdf" not in yaml.safe_load(text)["pairs"]["swap"]["candidate"]
    assert schema_errors(text) == []  # an editor opens it without a complaint
    # The description moves on; the repro keeps what was read.
    (tmp_path / "robot.urdf").unlink()
    destination.parent.mkdir()
    destination.write_text(text)
    replayed = pair_named(load_pairs_file(destination), "swap")
    assert replayed.baseline.profile == pair.baseline.profile
    assert replayed.candidate.profile == pair.candidate.profile
    assert replayed.candidate.profile.samples == 16


def test_a_relative_sdf_world_path_is_rewritten_so_the_repro_finds_the_same_world_file(
    tmp_path: Path,
) -> None:
    project = tmp_path / "project"
    world_file = write(project / "worlds", "<sdf/>\n", "corridor.world")
    path = write(project, VALID_PAIRS)
    original = load_pairs_file(path)
    text = path.read_text().replace("world:\n", "world:\n  sdf: worlds/corridor.world\n", 1)
    path.write_text(text)
    pair = pair_named(original, "same")
    repro = tmp_path / "artifacts" / "gate" / "same.lasertest.yaml"
    world = yaml.safe_load(repro_yaml(original, pair, pinned_for(pair), repro, ()))["world"]
    assert (repro.parent / world["sdf"]).resolve() == world_file.resolve()


# A robot written in place around robot.urdf, its body read from the description.
IN_PLACE = (
    "robot:\n"
    "  urdf: robot.urdf\n"
    "  footprint: [[-0.3, -0.2], [0.3, -0.2], [0.3, 0.2], [-0.3, 0.2]]\n"
    "  max_linear_velocity: 0.8\n"
    "  max_linear_acceleration: 1.5\n"
    "  max_angular_velocity: 1.2\n"
    "  max_angular_acceleration: 3.0\n"
)


def test_a_robot_written_around_its_description_replays_with_the_mount_it_read(
    tmp_path: Path,
) -> None:
    project = tmp_path / "project"
    write(project, ROBOT, "robot.urdf")
    in_place = IN_PLACE.replace(
        "  urdf: robot.urdf\n", "  urdf: robot.urdf\n  body: {height: 0.3}\n"
    )
    original = load_pairs_file(write(project, VALID_PAIRS.replace("robot: husky\n", in_place)))
    pinned = pinned_for(pair_named(original, "same"))
    destination = tmp_path / "artifacts" / "gate" / "same.lasertest.yaml"
    # The description moves on: the repro keeps the mount the run read.
    (project / "robot.urdf").write_text(ROBOT.replace('xyz="0.3 0 0.2"', 'xyz="0.1 0 0.2"'))

    assert_replays(original, "same", pinned, replay(original, "same", pinned, destination))
    text = destination.read_text()
    assert "robot: its laser mount and body as read from robot.urdf, pinned as read" in text
    assert "urdf" not in yaml.safe_load(text)["robot"]


def test_a_body_read_from_the_description_replays_as_read_after_the_description_moves_on(
    tmp_path: Path,
) -> None:
    project = tmp_path / "project"
    wheels = "".join(
        f'<link name="{side}"><collision><origin rpy="1.5708 0 0"/>'
        '<geometry><cylinder radius="0.1" length="0.05"/></geometry></collision></link>'
        f'<joint name="{side}_joint" type="continuous"><parent link="base_link"/>'
        f'<child link="{side}"/><origin xyz="0 {y} 0"/></joint>'
        for side, y in (("left", 0.25), ("right", -0.25))
    )
    chassis = (
        '<link name="base_link"><collision><origin xyz="0 0 0.1"/>'
        '<geometry><box size="0.6 0.4 0.2"/></geometry></collision></link>'
    ) + wheels
    write(project, ROBOT.replace('<link name="base_link"/>', chassis), "robot.urdf")
    original = load_pairs_file(write(project, VALID_PAIRS.replace("robot: husky\n", IN_PLACE)))
    assert original.robot.body.steering == "differential"
    pinned = pinned_for(pair_named(original, "same"))
    destination = tmp_path / "artifacts" / "gate" / "same.lasertest.yaml"
    # The chassis grows after the run: the repro keeps the one the run drove.
    grown = chassis.replace('size="0.6 0.4 0.2"', 'size="0.9 0.4 0.2"')
    (project / "robot.urdf").write_text(ROBOT.replace('<link name="base_link"/>', grown))

    assert_replays(original, "same", pinned, replay(original, "same", pinned, destination))
    body = yaml.safe_load(destination.read_text())["robot"]["body"]
    assert body["collisions"][0]["box"] == {"size": [0.6, 0.4, 0.2]}
    # It rolls on the wheels it rolled on.
    assert [c.get("wheel", False) for c in body["collisions"]] == [False, True, True]
    assert schema_errors(destination.read_text()) == []  # an editor opens it without a complaint


def test_the_params_files_navigation_names_are_found_from_a_repro_in_another_directory(
    tmp_path: Path,
) -> None:
    # The chain and the Nav2 file are the pairs file's, found from wherever the repro goes.
    project = tmp_path / "project"
    chain = "scan_filter_chain:\n- {name: r, type: laser_filters/LaserScanRangeFilter}\n"
    write(project / "config", chain, "filters.yaml")
    shutil.copy(EXAMPLES / "nav2" / "cropped.nav2.yaml", project / "config" / "nav2.yaml")
    navigation = "navigation:\n  scan_filters: config/filters.yaml\n  nav2: config/nav2.yaml\n"
    original = load_pairs_file(write(project, navigation + VALID_PAIRS))
    assert original.scan_filters is not None
    pinned = pinned_for(pair_named(original, "same"))
    destination = tmp_path / "artifacts" / "gate" / "same.lasertest.yaml"
    replayed = replay(original, "same", pinned, destination)
    assert replayed.scan_filters is not None
    assert replayed.scan_filters.path == original.scan_filters.path
    assert replayed.scan_filters.filters == original.scan_filters.filters
    assert replayed.robot.nav2 == original.robot.nav2
