"""The `sdf:` of a pairs file's world: the static models of an SDF world file (a Gazebo `.world`
or `.sdf`), read as walls.

    world: {sdf: worlds/office.world, start: ..., goal: ...}

Every box collision of every static model is a wall: its pose composed from the model's `<pose>`
(and those of the models it is nested in), its link's and its collision's, as SDFormat composes
poses relative to their parents (sdformat's spec, http://sdformat.org/spec?elem=model, and
Gazebo's building editor, which writes each wall as a static model's box link). A model is static
when it or a model it is nested in says `<static>true</static>`. Models that are not static
(robots, things that can be pushed) are not walls and are left out; so are planes and boxes no
higher than GROUND (the ground, floors), the included ground plane and sun, and the world's
lights and plugins.

The gate's walls are boxes standing on the ground. A static collision it cannot stand as one (a
cylinder, a sphere, a mesh, a box tilted or floating above the ground), or a model it cannot
read (an `<include>` of a model from Gazebo's model path other than the ground plane and the
sun), is an error at that element's line: dropping it would let the robot drive through it.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from pytest_lasertest.descriptions.laser_block import Locate
from pytest_lasertest.descriptions.mounts import sdf_pose
from pytest_lasertest.descriptions.xmlfile import XmlElement, parse_xml
from pytest_lasertest.inputs.errors import display_path
from pytest_lasertest.inputs.files import (
    MAX_FILE_BYTES,
    FileKind,
    UnreadableFile,
    read_regular_file,
)
from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.obstacles import Box
from pytest_lasertest.pairsfile.walls import COORDINATE, EXTENT, HEIGHT, MAX_WALLS

# Gazebo's own models that hold no wall, the ground and the light, by the last part of their URI
# (`model://ground_plane`, or Fuel's `https://fuel.gazebosim.org/1.0/OpenRobotics/models/Ground
# Plane`).
NOT_WALLS = ("ground_plane", "sun")
# A box tilted further than this is not a wall standing upright.
LEVEL = 1e-6  # of the box's vertical axis's cosine
# A box whose bottom lies further above the ground than this does not stand on it; one whose top
# lies no higher is floor, not wall.
GROUND = 0.01  # m
SDF_WORLD = FileKind(
    "an SDF world file",
    MAX_FILE_BYTES,
    "point `sdf:` at the world file itself",
    "point `sdf:` at a Gazebo world file; one this large holds meshes or heightmaps inline, "
    "which the gate does not read",
)
FIX_BOX = (
    "the gate's walls are boxes standing upright on the ground: make it one in a copy of the "
    "world, or list it under `walls:` and leave it out of the SDF file"
)


def read_sdf_walls(node: SpecNode) -> tuple[Box, ...]:
    """The walls of the SDF world file `node` names, relative to the file `node` is written in."""
    path = node.location.path.parent / node.text(
        what="a path to an SDF world file",
        fix="write the path of the world file relative to this file, e.g. worlds/office.world",
    )
    root, locate = _parse(path, node), _locator()
    worlds = root.all("world")
    if root.tag != "sdf" or not worlds:
        raise locate(root).error(
            "the file is not an SDF world: its root is no <sdf> holding a <world>",
            "point `sdf:` at a Gazebo world file (.world or .sdf)",
        )
    if len(worlds) > 1:
        raise locate(worlds[1]).error(
            "the file holds a second <world>: Gazebo loads one world from a file",
            "keep the world the robot drives in, one <world> to the file",
        )
    walls = tuple(_world_walls(worlds[0], locate))
    if len(walls) > MAX_WALLS:
        raise node.error(
            f"{display_path(path)} holds {len(walls)} static boxes, more than the {MAX_WALLS} "
            "walls the simulator casts every scan against",
            "merge walls that meet in a line into one box, or draw the building as a `map:`",
        )
    if not walls:
        raise node.error(
            f"{display_path(path)} holds no static model with a box collision: no wall",
            "name the world whose static models are the walls, or leave `sdf:` out",
        )
    return walls


def _parse(path: Path, node: SpecNode) -> XmlElement:
    """The file's XML; a missing or unreadable file is an error at `node`."""
    try:
        data = read_regular_file(path, SDF_WORLD)
    except FileNotFoundError:
        raise node.error(
            f"the SDF world file {display_path(path)} does not exist",
            "give the path of a Gazebo world file (.world or .sdf) relative to this file",
        ) from None
    except UnreadableFile as error:
        raise node.error(error.problem, error.fix) from None
    return parse_xml(data, path)


def _locator() -> Locate:
    """Where to report an element: its own line in the world file."""

    def locate(element: XmlElement) -> SpecNode:
        return SpecNode(None, element.location, f"<{element.tag}>")

    return locate


def _world_walls(world: XmlElement, locate: Locate) -> list[Box]:
    """The walls of one `<world>`: its static models' boxes; an unreadable include refused."""
    for include in (element for element in world.walk() if element.tag == "include"):
        uri_element = include.child("uri")
        uri = uri_element.text.strip().rstrip("/") if uri_element is not None else ""
        if uri.rsplit("/", 1)[-1].lower().replace(" ", "_") not in NOT_WALLS:
            raise locate(include).error(
                f"the world includes {uri or 'a model'!r}, which the gate cannot read: it does "
                "not search Gazebo's model path",
                "copy the model's static collision boxes into the world file, or list them "
                "under `walls:`, and remove the <include>",
            )
    for population in (element for element in world.walk() if element.tag == "population"):
        raise locate(population).error(
            "a <population> of models is not read by the gate: dropping it would let the "
            "robot drive through them",
            "write each model of the population out as a <model> with its <pose>, or list "
            "their boxes under `walls:`",
        )
    models = world.all("model")
    _check_state(world, models, locate)
    return [box for model in models for box in _model_walls(model, Pose3D(), False, locate)]


# m, rad: a state's pose further than this from a model's own moves it.
MOVED = 1e-6


def _check_state(world: XmlElement, models: tuple[XmlElement, ...], locate: Locate) -> None:
    """Refuse a model a `<state>` (what Gazebo writes when it saves a world) puts elsewhere than
    its own `<pose>`: the gate reads the `<pose>`, and Gazebo would load the world as saved."""
    by_name = {model.get("name"): model for model in models if _is_static(model)}
    for state in world.all("state"):
        for moved in state.all("model"):
            model = by_name.get(moved.get("name"))
            if model is None or moved.child("pose") is None:
                continue
            saved = sdf_pose(moved.child("pose"), locate)
            own = sdf_pose(model.child("pose"), locate)
            if _moves(saved, own):
                raise locate(moved).error(
                    f"the world's <state> puts the model {moved.get('name')!r} at "
                    f"{_shown(saved)}, not at its <pose> {_shown(own)}: Gazebo saved the world "
                    "with it moved, and the gate reads the <pose>",
                    "copy the state's pose into the model's <pose>, or delete the <state>",
                )


def _moves(saved: Pose3D, own: Pose3D) -> bool:
    """Whether two poses differ, in position or in rotation (however the angles are written)."""
    moved = np.abs(np.subtract(saved.xyz, own.xyz)).max()
    return bool(moved > MOVED or np.abs(saved.rotation() - own.rotation()).max() > MOVED)


def _shown(pose: Pose3D) -> str:
    return " ".join(f"{value:g}" for value in (*pose.xyz, *pose.rpy))


def _model_walls(model: XmlElement, parent: Pose3D, static: bool, locate: Locate) -> list[Box]:
    """The boxes of a model and the models nested in it, `parent` the pose of its frame in the
    world's, `static` whether a model it is nested in is static."""
    static = static or _is_static(model)
    pose = parent.then(sdf_pose(model.child("pose"), locate))
    walls: list[Box] = []
    for link in model.all("link") if static else ():
        link_pose = pose.then(sdf_pose(link.child("pose"), locate))
        for collision in link.all("collision"):
            wall = None if _is_plane(collision) else _wall(collision, link_pose, locate)
            if wall is not None:  # neither the ground nor a floor
                walls.append(wall)
    for nested in model.all("model"):
        walls += _model_walls(nested, pose, static, locate)
    return walls


def _is_static(model: XmlElement) -> bool:
    flag = model.child("static")
    return flag is not None and flag.text.strip().lower() in ("true", "1")


def _is_plane(collision: XmlElement) -> bool:
    geometry = collision.child("geometry")
    return geometry is not None and geometry.child("plane") is not None


def _wall(collision: XmlElement, link: Pose3D, locate: Locate) -> Box | None:
    """A box collision of a link at pose `link` (in the world), as a wall standing on the
    ground; None for a floor."""
    length, width, depth = _size(_box(collision, locate), locate)
    pose = link.then(sdf_pose(collision.child("pose"), locate))
    rotation = pose.rotation()
    if abs(rotation[2, 2]) < 1.0 - LEVEL:
        raise locate(collision).error("the box is tilted: it does not stand upright", FIX_BOX)
    x, y, z = (float(value) for value in pose.xyz)
    bottom, top = z - depth / 2.0, z + depth / 2.0
    if top <= GROUND:
        return None
    where = locate(collision)
    if bottom > GROUND:
        raise where.error(f"the box's bottom lies {bottom:.3f} m above the ground", FIX_BOX)
    for value, bounds in ((x, COORDINATE), (y, COORDINATE), (length, EXTENT), (width, EXTENT)):
        bounds.check(where, value)
    yaw = math.atan2(rotation[1, 0], rotation[0, 0])
    return Box(x, y, yaw, length, width, HEIGHT.check(where, top))


def _box(collision: XmlElement, locate: Locate) -> XmlElement:
    """The collision's `<box>`; any other geometry is an error at its line."""
    geometry = collision.child("geometry")
    box = geometry.child("box") if geometry is not None else None
    if box is None:
        shapes = [child.tag for child in geometry.children] if geometry is not None else []
        raise locate(geometry if geometry is not None else collision).error(
            f"a static {'<' + shapes[0] + '>' if shapes else 'collision without a geometry'} "
            "is not a wall the gate can stand",
            FIX_BOX,
        )
    return box


def _size(box: XmlElement, locate: Locate) -> tuple[float, float, float]:
    size = box.child("size")
    words = size.text.split() if size is not None else []
    try:
        numbers = np.array([float(word) for word in words])
    except ValueError:
        numbers = np.array([])
    if len(numbers) != 3 or not np.all(np.isfinite(numbers)) or np.any(numbers <= 0.0):
        raise locate(size if size is not None else box).error(
            f"a box's <size> holds {' '.join(words)!r}, not three lengths",
            "write its length, width and height in m, e.g. <size>4 0.2 2.5</size>",
        )
    return float(numbers[0]), float(numbers[1]), float(numbers[2])
