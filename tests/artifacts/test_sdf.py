"""The Gazebo world that replays a failing item's obstacle."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from pytest_lasertest.artifacts.sdf import world_sdf, write_world
from pytest_lasertest.model.obstacles import Box, Cylinder, Obstacle

# Element names from the SDF 1.6 specification (sdformat.org/spec?ver=1.6, and sdf/1.6/*.sdf in
# the sdformat sources): only those this writer uses.
SDF_1_6_ELEMENTS = {
    "sdf",  # root.sdf
    "world",
    "gravity",  # world.sdf: a child of world since 1.6, no longer of physics
    "physics",
    "max_step_size",
    "real_time_factor",
    "real_time_update_rate",  # physics.sdf
    "light",
    "cast_shadows",
    "diffuse",
    "specular",
    "attenuation",
    "range",
    "constant",
    "linear",
    "quadratic",
    "direction",  # light.sdf
    "pose",  # pose.sdf
    "model",
    "static",  # model.sdf
    "link",  # link.sdf
    "collision",  # collision.sdf
    "visual",  # visual.sdf
    "material",
    "ambient",  # material.sdf
    "geometry",  # geometry.sdf
    "box",
    "size",  # box_shape.sdf
    "cylinder",
    "radius",
    "length",  # cylinder_shape.sdf
    "plane",
    "normal",  # plane_shape.sdf (size too)
}

# Which children the specification allows under each parent, for the parents this writer uses.
SDF_1_6_CHILDREN = {
    "sdf": {"world", "model", "actor", "light"},
    "world": {"gravity", "physics", "light", "model", "include", "magnetic_field", "scene"},
    "physics": {"max_step_size", "real_time_factor", "real_time_update_rate", "max_contacts"},
    "light": {"cast_shadows", "pose", "diffuse", "specular", "attenuation", "direction", "spot"},
    "attenuation": {"range", "constant", "linear", "quadratic"},
    "model": {"static", "self_collide", "allow_auto_disable", "pose", "link", "joint", "model"},
    "link": {"gravity", "self_collide", "kinematic", "pose", "inertial", "collision", "visual"},
    "collision": {"laser_retro", "max_contacts", "pose", "geometry", "surface"},
    "visual": {"cast_shadows", "transparency", "pose", "material", "geometry"},
    "material": {"script", "lighting", "ambient", "diffuse", "specular", "emissive"},
    "geometry": {"empty", "box", "cylinder", "plane", "sphere", "mesh", "heightmap"},
    "box": {"size"},
    "cylinder": {"radius", "length"},
    "plane": {"normal", "size"},
}

# Attributes the specification gives each element this writer puts attributes on.
SDF_1_6_ATTRIBUTES = {
    "sdf": {"version"},
    "world": {"name"},
    "physics": {"name", "default", "type"},
    "light": {"name", "type"},
    "model": {"name"},
    "link": {"name"},
    "collision": {"name"},
    "visual": {"name"},
}

BOX = Box(
    x=1.0 / 3.0, y=-2.718281828459045, yaw=0.1234567890123, length=0.4, width=0.25, height=0.5
)
CYLINDER = Cylinder(x=4.0, y=1e-7, radius=0.0507, height=1.25)
WALLS = (
    Box(x=5.0, y=2.0, yaw=0.0, length=14.0, width=0.2, height=2.0),
    Box(x=-1.0 / 3.0, y=-2.1, yaw=-0.7853981633974483, length=3.5, width=0.15, height=0.75),
)


def parse(text: str) -> ET.Element:
    """The document's root element."""
    return ET.fromstring(text)


def numbers(element: ET.Element | None) -> list[float]:
    """The space-separated numbers an element holds."""
    assert element is not None
    assert element.text is not None
    return [float(word) for word in element.text.split()]


def models(world: ET.Element) -> dict[str, ET.Element]:
    """The world's models by name."""
    return {model.attrib["name"]: model for model in world.iter("model")}


def test_the_world_is_an_xml_document_of_sdf_version_1_6() -> None:
    text = world_sdf("replay", [BOX])
    assert text.startswith('<?xml version="1.0"?>\n<sdf version="1.6">')
    root = parse(text)
    assert root.tag == "sdf"
    assert root.attrib == {"version": "1.6"}
    assert [child.tag for child in root] == ["world"]
    assert root[0].attrib == {"name": "replay"}


def test_every_element_is_an_sdf_1_6_element_under_a_parent_that_allows_it() -> None:
    root = parse(world_sdf("replay", [BOX, CYLINDER]))
    assert {element.tag for element in root.iter()} <= SDF_1_6_ELEMENTS
    for parent in root.iter():
        for child in parent:
            assert child.tag in SDF_1_6_CHILDREN[parent.tag], f"<{child.tag}> in <{parent.tag}>"
        assert set(parent.attrib) <= SDF_1_6_ATTRIBUTES.get(parent.tag, set()), parent.tag


def test_leaves_hold_values_and_branches_hold_only_elements() -> None:
    for element in parse(world_sdf("replay", [BOX, CYLINDER])).iter():
        text = (element.text or "").strip()
        assert bool(text) == (len(element) == 0), f"<{element.tag}> holds {text!r}"


def test_gravity_is_the_world_s_and_physics_steps_a_millisecond_in_real_time() -> None:
    world = parse(world_sdf("replay", []))[0]
    assert numbers(world.find("gravity")) == [0.0, 0.0, -9.8]
    physics = world.find("physics")
    assert physics is not None
    assert physics.attrib["type"] == "ode"
    assert numbers(physics.find("max_step_size")) == [0.001]
    assert numbers(physics.find("real_time_factor")) == [1.0]
    assert numbers(physics.find("real_time_update_rate")) == [1000.0]
    assert physics.find("gravity") is None


def test_the_sun_and_the_ground_are_inline_so_no_model_database_is_needed() -> None:
    world = parse(world_sdf("replay", []))[0]
    assert world.find(".//include") is None
    assert world.find(".//uri") is None
    sun = world.find("light")
    assert sun is not None
    assert sun.attrib == {"name": "sun", "type": "directional"}
    assert sun.findtext("cast_shadows") == "true"
    assert numbers(sun.find("attenuation/range")) == [1000.0]
    assert numbers(sun.find("direction"))[2] < 0.0
    ground = models(world)["ground_plane"]
    assert ground.findtext("static") == "true"
    for kind in ("collision", "visual"):
        assert numbers(ground.find(f"link/{kind}/geometry/plane/normal")) == [0.0, 0.0, 1.0]
        assert numbers(ground.find(f"link/{kind}/geometry/plane/size")) == [100.0, 100.0]


def test_the_world_holds_one_static_model_per_obstacle_and_the_ground() -> None:
    world = parse(world_sdf("replay", [BOX, CYLINDER, BOX]))[0]
    found = models(world)
    assert list(found) == ["ground_plane", "obstacle_0", "obstacle_1", "obstacle_2"]
    for model in found.values():
        assert model.findtext("static") == "true"
        assert [link.attrib["name"] for link in model.findall("link")] == ["link"]


def test_a_box_stands_on_the_ground_turned_by_its_yaw_to_the_last_digit() -> None:
    box = models(parse(world_sdf("replay", [BOX]))[0])["obstacle_0"]
    assert numbers(box.find("pose")) == [BOX.x, BOX.y, BOX.height / 2.0, 0.0, 0.0, BOX.yaw]
    for kind in ("collision", "visual"):
        size = numbers(box.find(f"link/{kind}/geometry/box/size"))
        assert size == [BOX.length, BOX.width, BOX.height]
    assert box.find("link/visual/material/diffuse") is not None


def test_a_cylinder_keeps_its_radius_and_its_height_as_length() -> None:
    cylinder = models(parse(world_sdf("replay", [CYLINDER]))[0])["obstacle_0"]
    pose = numbers(cylinder.find("pose"))
    assert pose == [CYLINDER.x, CYLINDER.y, CYLINDER.height / 2.0, 0.0, 0.0, 0.0]
    for kind in ("collision", "visual"):
        shape = f"link/{kind}/geometry/cylinder"
        assert numbers(cylinder.find(f"{shape}/radius")) == [CYLINDER.radius]
        assert numbers(cylinder.find(f"{shape}/length")) == [CYLINDER.height]


def test_a_world_name_with_xml_special_characters_is_escaped() -> None:
    name = "a<b & c>\"d\"'e'"
    text = world_sdf(name, [BOX])
    assert "<world name=\"a&lt;b &amp; c&gt;&quot;d&quot;'e'\">" in text
    assert parse(text)[0].attrib["name"] == name


def test_a_world_name_xml_cannot_hold_is_refused() -> None:
    with pytest.raises(ValueError, match="XML cannot hold"):
        world_sdf("bell\x07", [BOX])


@pytest.mark.parametrize(
    "obstacle",
    [
        Box(x=0.0, y=0.0, yaw=0.0, length=0.0, width=0.25, height=0.5),
        Box(x=0.0, y=0.0, yaw=math.nan, length=0.4, width=0.25, height=0.5),
        Cylinder(x=math.inf, y=0.0, radius=0.2, height=0.5),
        Cylinder(x=0.0, y=0.0, radius=0.2, height=math.nan),
        Cylinder(x=0.0, y=0.0, radius=-0.2, height=0.5),
    ],
    ids=["flat box", "box turned NaN", "cylinder at infinity", "cylinder NaN high", "negative"],
)
def test_an_obstacle_gazebo_could_not_load_is_refused(obstacle: Obstacle) -> None:
    with pytest.raises(ValueError, match="finite sizes"):
        world_sdf("replay", [obstacle])


def test_writing_the_world_is_atomic_and_leaves_no_temporary(tmp_path: Path) -> None:
    path = tmp_path / "worlds" / "item.world"
    assert write_world(path, "replay", [BOX]) == path
    path.write_text("an old world")
    write_world(path, "replay", [CYLINDER])
    assert path.read_text(encoding="utf-8") == world_sdf("replay", [CYLINDER])
    assert list(path.parent.iterdir()) == [path]


def test_a_world_that_cannot_be_made_writes_nothing(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="finite sizes"):
        write_world(tmp_path / "item.world", "replay", [Cylinder(0.0, 0.0, 0.0, 1.0)])
    assert list(tmp_path.iterdir()) == []


# Walls


def test_the_world_holds_one_static_box_per_wall_beside_the_obstacles() -> None:
    world = parse(world_sdf("replay", [CYLINDER], WALLS))[0]
    found = models(world)
    assert list(found) == ["ground_plane", "obstacle_0", "wall_0", "wall_1"]
    for name in ("wall_0", "wall_1"):
        assert found[name].findtext("static") == "true"
        assert [link.attrib["name"] for link in found[name].findall("link")] == ["link"]


@pytest.mark.parametrize("index", range(len(WALLS)))
def test_a_wall_stands_on_the_ground_with_its_size_and_pose_to_the_last_digit(index: int) -> None:
    wall = WALLS[index]
    model = models(parse(world_sdf("replay", [BOX], WALLS))[0])[f"wall_{index}"]
    assert numbers(model.find("pose")) == [wall.x, wall.y, wall.height / 2.0, 0.0, 0.0, wall.yaw]
    for kind in ("collision", "visual"):
        size = numbers(model.find(f"link/{kind}/geometry/box/size"))
        assert size == [wall.length, wall.width, wall.height]


def test_walls_are_coloured_apart_from_the_obstacle() -> None:
    found = models(parse(world_sdf("replay", [BOX], WALLS))[0])
    wall, obstacle = (
        numbers(found[name].find("link/visual/material/diffuse"))
        for name in ("wall_0", "obstacle_0")
    )
    assert wall != obstacle


def test_a_world_with_walls_uses_only_sdf_1_6_elements_where_they_are_allowed() -> None:
    root = parse(world_sdf("replay", [BOX, CYLINDER], WALLS))
    assert {element.tag for element in root.iter()} <= SDF_1_6_ELEMENTS
    for parent in root.iter():
        for child in parent:
            assert child.tag in SDF_1_6_CHILDREN[parent.tag], f"<{child.tag}> in <{parent.tag}>"


def test_a_world_without_walls_is_written_as_before() -> None:
    assert world_sdf("replay", [BOX], ()) == world_sdf("replay", [BOX])
    assert not [name for name in models(parse(world_sdf("replay", [BOX]))[0]) if "wall" in name]


def test_a_wall_gazebo_could_not_load_is_refused_and_nothing_is_written(tmp_path: Path) -> None:
    flat = Box(x=0.0, y=3.0, yaw=0.0, length=4.0, width=0.0, height=2.0)
    with pytest.raises(ValueError, match="finite sizes"):
        write_world(tmp_path / "item.world", "replay", [BOX], (WALLS[0], flat))
    assert list(tmp_path.iterdir()) == []


def test_writing_a_world_with_walls_writes_what_world_sdf_makes(tmp_path: Path) -> None:
    path = write_world(tmp_path / "item.world", "replay", [CYLINDER], WALLS)
    assert path.read_text(encoding="utf-8") == world_sdf("replay", [CYLINDER], WALLS)
