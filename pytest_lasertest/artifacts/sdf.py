"""A Gazebo world holding a failing item's obstacle and its world's walls, to replay it in the
user's own stack.

SDF 1.6 (Gazebo 9 and later read it). The sun and the ground plane are written inline rather
than included as `model://sun` and `model://ground_plane`, which need Gazebo's model database:
the world loads offline.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from pathlib import Path

from pytest_lasertest.artifacts.files import write_text
from pytest_lasertest.model.obstacles import Box, Obstacle

SDF_VERSION = "1.6"
STEP = 0.001  # s, the physics step
GRAVITY = (0.0, 0.0, -9.8)  # m/s^2
GROUND_SIZE = (100.0, 100.0)  # m
OBSTACLE_COLOUR = (0.3, 0.3, 0.3, 1.0)  # RGBA, the dark grey of the picture's obstacle
WALL_COLOUR = (0.48, 0.48, 0.48, 1.0)  # RGBA, the lighter grey of the picture's walls
GROUND_COLOUR = (0.8, 0.8, 0.8, 1.0)  # RGBA

# Characters XML 1.0 cannot hold, escaped or not.
_FORBIDDEN = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")


def world_sdf(name: str, obstacles: Sequence[Obstacle], walls: Sequence[Box] = ()) -> str:
    """An SDF 1.6 world: sun, ground plane, one static model per obstacle (`obstacle_0`, ...)
    and one static box per wall (`wall_0`, ...).

    Raises ValueError for a name XML cannot hold, or an obstacle or wall with a size that is not
    a positive finite number or a position that is not finite.
    """
    if _FORBIDDEN.search(name):
        raise ValueError(f"XML cannot hold the world name {name!r}")
    root = ET.Element("sdf", version=SDF_VERSION)
    world = ET.SubElement(root, "world", name=name)
    _text(world, "gravity", _numbers(GRAVITY))
    _physics(world)
    _sun(world)
    _ground(world)
    for index, obstacle in enumerate(obstacles):
        _obstacle(world, f"obstacle_{index}", obstacle, OBSTACLE_COLOUR)
    for index, wall in enumerate(walls):
        _obstacle(world, f"wall_{index}", wall, WALL_COLOUR)
    ET.indent(root)
    return '<?xml version="1.0"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


def write_world(
    path: Path, name: str, obstacles: Sequence[Obstacle], walls: Sequence[Box] = ()
) -> Path:
    """Write `world_sdf` at `path` atomically."""
    return write_text(path, world_sdf(name, obstacles, walls))


def _physics(world: ET.Element) -> None:
    """ODE at a 1 ms step, in real time."""
    physics = ET.SubElement(world, "physics", name="default_physics", type="ode")
    _text(physics, "max_step_size", _number(STEP))
    _text(physics, "real_time_factor", _number(1.0))
    # Steps per wall-clock second: with the step above, what real time needs.
    _text(physics, "real_time_update_rate", _number(1.0 / STEP))


def _sun(world: ET.Element) -> None:
    """A directional light, as Gazebo's own `sun` model has it."""
    light = ET.SubElement(world, "light", name="sun", type="directional")
    _text(light, "cast_shadows", "true")
    _text(light, "pose", _numbers((0.0, 0.0, 10.0, 0.0, 0.0, 0.0)))
    _text(light, "diffuse", _numbers((0.8, 0.8, 0.8, 1.0)))
    _text(light, "specular", _numbers((0.2, 0.2, 0.2, 1.0)))
    attenuation = ET.SubElement(light, "attenuation")
    for tag, value in (
        ("range", 1000.0),
        ("constant", 0.9),
        ("linear", 0.01),
        ("quadratic", 0.001),
    ):
        _text(attenuation, tag, _number(value))
    _text(light, "direction", _numbers((-0.5, 0.1, -0.9)))


def _ground(world: ET.Element) -> None:
    """A static plane at z = 0 facing up, as Gazebo's own `ground_plane` model has it."""
    link = _static_model(world, "ground_plane", (0.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    for geometry in _shapes(link, GROUND_COLOUR):
        plane = ET.SubElement(geometry, "plane")
        _text(plane, "normal", _numbers((0.0, 0.0, 1.0)))
        _text(plane, "size", _numbers(GROUND_SIZE))


def _obstacle(
    world: ET.Element, name: str, obstacle: Obstacle, colour: tuple[float, float, float, float]
) -> None:
    """A static model of the obstacle (or wall) standing on the ground, its shape as collision
    and visual."""
    shape, sizes = _shape(obstacle)
    place = (obstacle.x, obstacle.y, obstacle.yaw)
    # `not 0 < size < inf` also rejects NaN.
    positive = all(0.0 < size < math.inf for values in sizes.values() for size in values)
    if not positive or not all(map(math.isfinite, place)):
        raise ValueError(f"cannot write {obstacle} to a Gazebo world: it needs finite sizes > 0")
    # SDF poses are of the shape's centre, so half the height lifts it onto the ground.
    pose = (obstacle.x, obstacle.y, obstacle.height / 2.0, 0.0, 0.0, obstacle.yaw)
    link = _static_model(world, name, pose)
    for geometry in _shapes(link, colour):
        element = ET.SubElement(geometry, shape)
        for tag, values in sizes.items():
            _text(element, tag, _numbers(values))


def _shape(obstacle: Obstacle) -> tuple[str, dict[str, tuple[float, ...]]]:
    """The obstacle's SDF geometry: its element and the sizes it holds, m."""
    if isinstance(obstacle, Box):
        return "box", {"size": (obstacle.length, obstacle.width, obstacle.height)}
    return "cylinder", {"radius": (obstacle.radius,), "length": (obstacle.height,)}


def _static_model(world: ET.Element, name: str, pose: tuple[float, ...]) -> ET.Element:
    """A static model at `pose` with one link; returns the link."""
    model = ET.SubElement(world, "model", name=name)
    _text(model, "static", "true")
    _text(model, "pose", _numbers(pose))
    return ET.SubElement(model, "link", name="link")


def _shapes(link: ET.Element, colour: tuple[float, float, float, float]) -> list[ET.Element]:
    """A collision and a coloured visual in the link; returns their empty geometry elements."""
    collision = ET.SubElement(link, "collision", name="collision")
    visual = ET.SubElement(link, "visual", name="visual")
    material = ET.SubElement(visual, "material")
    # The same colour lit and unlit, as Gazebo shows ambient where the sun does not reach.
    _text(material, "ambient", _numbers(colour))
    _text(material, "diffuse", _numbers(colour))
    return [ET.SubElement(collision, "geometry"), ET.SubElement(visual, "geometry")]


def _text(parent: ET.Element, tag: str, text: str) -> ET.Element:
    """A child element holding `text`."""
    child = ET.SubElement(parent, tag)
    child.text = text
    return child


def _numbers(values: Sequence[float]) -> str:
    """Space-separated numbers, each as `_number` writes it."""
    return " ".join(_number(value) for value in values)


def _number(value: float) -> str:
    """The shortest text that reads back as the same double: positions keep every digit."""
    return repr(float(value))
