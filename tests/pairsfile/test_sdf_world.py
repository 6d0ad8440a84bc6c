"""The `sdf:` of a world (`pairsfile/sdf_world.py`): the static models of a Gazebo world file
read as walls, with poses composed as SDFormat composes them; what the gate cannot stand as a
wall is an error at its line in the world file."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.inputs.node import SpecNode, read_root
from pytest_lasertest.model.obstacles import Box
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.pairsfile.sdf_world import read_sdf_walls
from tests.helpers import DATA
from tests.helpers.runs import Case, assert_spec_error
from tests.helpers.texts import write

# Line numbers matter: the cases below break one line of each.
PAIRS = """\
robot: husky
world:
  sdf: worlds/corridor.world
  start: {x: 0.5, y: 0.0, yaw: 0.0}
  goal: {x: 6.0, y: 0.0}
  time_limit: 60.0
pairs:
  fewer_beams:
    baseline: {model: clearpath_lms1xx_gazebo}
    candidate: {model: clearpath_lms1xx_gazebo, samples: 180}
"""
# A corridor as Gazebo's building editor writes one: a static model whose links are the walls,
# a post in a model nested in it, the ground and the sun, and a cart that can be pushed.
WORLD = """\
<?xml version="1.0"?>
<sdf version="1.7">
  <world name="default">
    <include><uri>model://ground_plane</uri></include>
    <include><uri>model://sun</uri></include>
    <model name="corridor">
      <static>true</static>
      <pose>2 0 0 0 0 0</pose>
      <link name="wall_left">
        <pose>3 1.5 1.25 0 0 0</pose>
        <collision name="collision">
          <geometry><box><size>8 0.2 2.5</size></box></geometry>
        </collision>
      </link>
      <link name="wall_right">
        <pose>3 -1.5 1.25 0 0 0</pose>
        <collision name="collision">
          <geometry><box><size>8 0.2 2.5</size></box></geometry>
        </collision>
      </link>
      <model name="post">
        <pose>6 0.9 0 0 0 1.5</pose>
        <link name="link">
          <collision name="collision">
            <pose>0 0 0.5 0 0 0</pose>
            <geometry><box><size>0.3 0.2 1</size></box></geometry>
          </collision>
        </link>
      </model>
    </model>
    <model name="cart">
      <pose>4 0 0 0 0 0</pose>
      <link name="link">
        <collision name="collision">
          <geometry><cylinder><radius>0.3</radius><length>1</length></cylinder></geometry>
        </collision>
      </link>
    </model>
  </world>
</sdf>
"""


def sdf_node(tmp_path: Path, world: str = WORLD, pairs: str = PAIRS) -> SpecNode:
    """The `sdf:` of the pairs file `pairs`, written to tmp_path beside worlds/corridor.world."""
    write(tmp_path / "worlds", world, "corridor.world")
    root = read_root(write(tmp_path, pairs), what="pairs file", needs="world")
    return root.entries(what="sections")["world"].entries(what="world fields")["sdf"]


def test_the_static_models_box_collisions_are_the_walls_posed_as_sdformat_composes_them(
    tmp_path: Path,
) -> None:
    left, right, post = read_sdf_walls(sdf_node(tmp_path))

    assert left == pytest.approx(Box(5.0, 1.5, 0.0, 8.0, 0.2, 2.5))
    assert right == pytest.approx(Box(5.0, -1.5, 0.0, 8.0, 0.2, 2.5))
    # The nested model is static with its parent: at (2 + 6, 0.9), turned 1.5 rad, 1 m high.
    assert post == pytest.approx(Box(8.0, 0.9, 1.5, 0.3, 0.2, 1.0))


def test_the_ground_the_sun_and_a_model_that_is_not_static_are_no_walls(tmp_path: Path) -> None:
    walls = read_sdf_walls(sdf_node(tmp_path))
    assert len(walls) == 3
    assert all(not (math.isclose(wall.x, 4.0) and math.isclose(wall.y, 0.0)) for wall in walls)


def test_a_static_floor_box_is_no_wall_and_fuels_ground_plane_is_included_as_gazebos(
    tmp_path: Path,
) -> None:
    floor = """\
    <model name="floor">
      <static>true</static>
      <link name="link">
        <pose>0 0 -0.05 0 0 0</pose>
        <collision name="collision"><geometry><box><size>40 40 0.1</size></box></geometry>
        </collision>
      </link>
    </model>
  </world>"""
    fuel = "https://fuel.gazebosim.org/1.0/OpenRobotics/models/Ground Plane"
    world = WORLD.replace("  </world>", floor).replace("model://ground_plane", fuel)

    assert len(read_sdf_walls(sdf_node(tmp_path, world))) == 3


def test_an_include_nested_in_a_model_is_refused_as_one_in_the_world_is(tmp_path: Path) -> None:
    shelf = '<include><uri>model://shelf</uri></include>\n      <model name="post">'
    nested = WORLD.replace('<model name="post">', shelf)
    with pytest.raises(SpecError) as raised:
        read_sdf_walls(sdf_node(tmp_path, nested))
    assert raised.value.location.line == 21
    assert "model://shelf" in raised.value.problem


def test_more_static_boxes_than_the_simulator_casts_against_is_an_error_at_the_sdf_line(
    tmp_path: Path,
) -> None:
    link = '<link name="l{i}"><pose>{i} 5 0.5 0 0 0</pose><collision name="c"><geometry>'
    link += "<box><size>0.5 0.5 1</size></box></geometry></collision></link>"
    many = "\n".join(link.format(i=i) for i in range(500))
    world = WORLD.replace('<link name="wall_left">', many + '\n      <link name="wall_left">')
    with pytest.raises(SpecError) as raised:
        read_sdf_walls(sdf_node(tmp_path, world))
    assert (raised.value.location.path.name, raised.value.location.line) == (
        "gate.lasertest.yaml",
        3,
    )
    assert "503 static boxes, more than the 500 walls" in raised.value.problem


def test_a_pairs_file_with_an_sdf_world_drives_between_its_walls(tmp_path: Path) -> None:
    write(tmp_path / "worlds", WORLD, "corridor.world")
    spec = load_pairs_file(write(tmp_path, PAIRS))

    walls = spec.world.walls
    assert len(walls.boxes) == 3
    assert walls.grid is not None  # drawn into the map the navigation stacks are given
    # Inside the corridor both long walls are 1.4 m from its middle line.
    assert walls.distances(np.array([[3.0, 0.0]]))[0] == pytest.approx(1.4, abs=0.05)


def test_an_sdf_world_and_listed_walls_are_walls_together(tmp_path: Path) -> None:
    pairs = PAIRS.replace(
        "  sdf: worlds/corridor.world\n",
        "  sdf: worlds/corridor.world\n"
        "  walls:\n"
        "    - {x: 7.5, y: -0.9, length: 0.3, width: 0.3}\n",
    )
    write(tmp_path / "worlds", WORLD, "corridor.world")
    spec = load_pairs_file(write(tmp_path, pairs))
    assert len(spec.world.walls.boxes) == 4


# Each breaks one line of WORLD; the error is at that line of the world file.
WORLD_CASES = {
    "a static cylinder": Case(
        "<box><size>0.3 0.2 1</size></box>",
        "<cylinder><radius>0.2</radius><length>1</length></cylinder>",
        26,
        "<geometry>",
        "a static <cylinder> is not a wall the gate can stand",
        "the gate's walls are boxes standing upright on the ground",
    ),
    "a tilted box": Case(
        "<pose>0 0 0.5 0 0 0</pose>",
        "<pose>0 0 0.5 0.3 0 0</pose>",
        24,
        "<collision>",
        "the box is tilted",
        "list it under `walls:`",
    ),
    "a box floating above the ground": Case(
        "<pose>0 0 0.5 0 0 0</pose>",
        "<pose>0 0 2.5 0 0 0</pose>",
        24,
        "<collision>",
        "the box's bottom lies 2.000 m above the ground",
        "boxes standing upright on the ground",
    ),
    "a box's size of two numbers": Case(
        "<size>0.3 0.2 1</size>",
        "<size>0.3 0.2</size>",
        26,
        "<size>",
        "a box's <size> holds '0.3 0.2', not three lengths",
        "write its length, width and height in m",
    ),
    "a model included from Gazebo's model path": Case(
        "<include><uri>model://sun</uri></include>",
        "<include><uri>model://bookshelf</uri></include>",
        5,
        "<include>",
        "the world includes 'model://bookshelf', which the gate cannot read",
        "copy the model's static collision boxes into the world file",
    ),
    "a pose relative to another frame": Case(
        "<pose>6 0.9 0 0 0 1.5</pose>",
        '<pose relative_to="wall_left">6 0.9 0 0 0 1.5</pose>',
        22,
        "<pose>",
        "a pose relative_to 'wall_left' is not read by the gate",
        "leave out relative_to",
    ),
    "a model file, not a world": Case(
        '<world name="default">',
        '<model name="default">',
        2,
        "<sdf>",
        "the file is not an SDF world",
        "point `sdf:` at a Gazebo world file",
    ),
}


@pytest.mark.parametrize("case", WORLD_CASES.values(), ids=WORLD_CASES.keys())
def test_what_the_gate_cannot_stand_as_a_wall_is_an_error_at_its_line_in_the_world_file(
    tmp_path: Path, case: Case
) -> None:
    assert case.old in WORLD
    world = WORLD.replace(case.old, case.new, 1)
    if case.new.startswith("<model"):  # the closing tag too, so that the file stays XML
        world = world.replace("</world>", "</model>")
    with pytest.raises(SpecError) as raised:
        read_sdf_walls(sdf_node(tmp_path, world))
    assert_spec_error(raised.value, "corridor.world", case)


def test_an_sdf_file_that_is_not_xml_is_an_error_at_the_line_that_breaks(tmp_path: Path) -> None:
    with pytest.raises(SpecError) as raised:
        read_sdf_walls(sdf_node(tmp_path, WORLD.replace("</link>", "</lnk>", 1)))
    assert raised.value.location.path.name == "corridor.world"
    assert raised.value.location.line == 14


PAIRS_CASES = {
    "a world file that does not exist": Case(
        "sdf: worlds/corridor.world",
        "sdf: worlds/office.world",
        3,
        "world.sdf",
        "the SDF world file worlds/office.world does not exist",
        "give the path of a Gazebo world file",
    ),
    "a directory for a world file": Case(
        "sdf: worlds/corridor.world",
        "sdf: worlds",
        3,
        "world.sdf",
        "worlds is a directory",
        "point `sdf:` at the world file itself",
    ),
    "a world with no static box": Case(
        "sdf: worlds/corridor.world",
        "sdf: worlds/carts.world",
        3,
        "world.sdf",
        "worlds/carts.world holds no static model with a box collision: no wall",
        "name the world whose static models are the walls",
    ),
}


@pytest.mark.parametrize("case", PAIRS_CASES.values(), ids=PAIRS_CASES.keys())
def test_an_sdf_world_the_pairs_file_cannot_use_is_an_error_at_the_pairs_files_line(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, case: Case
) -> None:
    monkeypatch.chdir(tmp_path)  # paths in messages are shown relative to the working directory
    carts = WORLD.replace("<static>true</static>", "<static>false</static>")
    write(tmp_path / "worlds", carts, "carts.world")
    with pytest.raises(SpecError) as raised:
        read_sdf_walls(sdf_node(tmp_path, pairs=PAIRS.replace(case.old, case.new)))
    assert_spec_error(raised.value, "gate.lasertest.yaml", case)


def test_gz_sims_example_world_is_refused_at_its_floating_lidar_box_not_at_its_movable_cube(
    tmp_path: Path,
) -> None:
    # A real world (gz-sim's examples/worlds/export_occupancy_grid.sdf, in the description
    # corpus): a static model carrying a lidar on a 0.1 m box half a metre up, a movable cube and
    # a ground plane. The box is no wall standing on the ground.
    world = (DATA / "corpus/gz-sim/main/examples/worlds/export_occupancy_grid.sdf").read_text()
    with pytest.raises(SpecError) as raised:
        read_sdf_walls(sdf_node(tmp_path, world))
    assert (raised.value.location.line, raised.value.field) == (67, "<collision>")
    assert raised.value.problem == "the box's bottom lies 0.450 m above the ground"


def _line_of(text: str, marker: str) -> int:
    return next(number for number, line in enumerate(text.splitlines(), 1) if marker in line)


def test_a_second_world_in_the_file_is_refused_at_it_as_gazebo_loads_one(tmp_path: Path) -> None:
    second = '  </world>\n  <world name="other"><model name="m"/></world>\n</sdf>'
    world = WORLD.replace("  </world>\n</sdf>", second)
    with pytest.raises(SpecError) as raised:
        read_sdf_walls(sdf_node(tmp_path, world))
    assert raised.value.location.line == _line_of(world, '<world name="other">')
    assert "a second <world>" in raised.value.problem


SAVED = """\
    <state world_name="default">
      <model name="corridor"><pose>{pose}</pose></model>
      <model name="cart"><pose>9 9 0 0 0 0</pose></model>
    </state>
  </world>"""


@pytest.mark.parametrize(
    ("pose", "refused"),
    [("2 0 0 0 0 0", False), ("2 0 0 0 0 6.283185307179586", False), ("2 2 0 0 0 0", True)],
    ids=["as-posed", "a-full-turn", "moved"],
)
def test_a_saved_worlds_state_that_moves_a_static_model_is_refused_at_the_state(
    tmp_path: Path, pose: str, refused: bool
) -> None:
    # Gazebo writes every model's pose at saving into <state>; the cart, not static, is no wall.
    world = WORLD.replace("  </world>", SAVED.format(pose=pose))
    if not refused:
        assert len(read_sdf_walls(sdf_node(tmp_path, world))) == 3
        return
    with pytest.raises(SpecError) as raised:
        read_sdf_walls(sdf_node(tmp_path, world))
    assert raised.value.location.line == _line_of(world, '<model name="corridor"><pose>2 2')
    assert "puts the model 'corridor' at 2 2 0 0 0 0, not at its <pose> 2 0 0" in (
        raised.value.problem
    )


def test_a_population_of_models_is_refused_at_its_line(tmp_path: Path) -> None:
    population = """\
    <population name="cans">
      <model name="can"><static>true</static><link name="l"><collision name="c"><geometry>
        <box><size>0.1 0.1 0.3</size></box></geometry></collision></link></model>
      <pose>3 0 0 0 0 0</pose><box><size>2 2 0.01</size></box><model_count>10</model_count>
      <distribution><type>random</type></distribution>
    </population>
  </world>"""
    world = WORLD.replace("  </world>", population)
    with pytest.raises(SpecError) as raised:
        read_sdf_walls(sdf_node(tmp_path, world))
    assert raised.value.location.line == _line_of(world, "<population")
    assert "a <population> of models is not read" in raised.value.problem
