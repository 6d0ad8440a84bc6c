"""A Nav2 costmap's parameters: its rolling window, its footprint and its layers (one obstacle
or voxel layer with one LaserScan source, an inflation layer, a static layer), as
nav2_costmap_2d reads them (costmap_2d_ros.cpp, plugins/obstacle_layer.cpp, voxel_layer.cpp,
inflation_layer.cpp at jazzy f4108e5b)."""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np

from pytest_lasertest.model.geometry import crossing_edges
from pytest_lasertest.model.robot import MAX_CORNERS, MAX_FOOTPRINT_REACH, pad_footprint
from pytest_lasertest.nav.move_base.settings import MAX_CELLS
from pytest_lasertest.nav.nav2.node_parameters import NodeParameters
from pytest_lasertest.nav.nav2.settings import (
    DEFAULT_FOOTPRINT_PADDING,
    DEFAULT_ROBOT_RADIUS,
    CostmapConfig,
    radius_footprint,
)

OBSTACLE_LAYERS = ("nav2_costmap_2d::ObstacleLayer", "nav2_costmap_2d::VoxelLayer")
INFLATION_LAYER = "nav2_costmap_2d::InflationLayer"
STATIC_LAYER = "nav2_costmap_2d::StaticLayer"


def read_costmap(node: NodeParameters, config: CostmapConfig, rolls: bool) -> CostmapConfig:
    """A costmap: its window, footprint and layers (one laser source, inflation, static). A
    costmap that `rolls` is a window of `width`; the global costmap, unless rolling_window
    says it rolls, spans the map, here the window over the route `config` sets."""
    width = node.number("width", config.costmap.size)
    if node.number("height", width) != width:
        raise node.problem(
            "height",
            "differs from width; the imitation's rolling window is square",
            "write the same width and height",
        )
    rolling = node.flag("rolling_window", False)  # costmap_2d_ros.cpp:129 at jazzy f4108e5b
    costmap = dataclasses.replace(
        config.costmap,
        size=width if rolls or rolling else config.costmap.size,
        resolution=node.number("resolution", config.costmap.resolution),
        update_frequency=node.number("update_frequency", config.costmap.update_frequency),
        track_unknown_space=node.flag("track_unknown_space", config.costmap.track_unknown_space),
    )
    _check_cells(node, costmap.size, costmap.resolution)
    config = dataclasses.replace(config, costmap=costmap, footprint=_footprint(node, config))
    return _layers(node, config)


def _check_cells(node: NodeParameters, size: float, resolution: float) -> None:
    """Refuse a costmap of more cells than the gate marks, inflates and plans through."""
    cells = size / resolution
    if cells > MAX_CELLS:
        raise node.problem(
            "resolution",
            f"{size:g} m at {resolution:g} m a cell is {cells:,.0f} cells a side, more than the "
            f"{MAX_CELLS} the gate accepts ({cells**2:,.0f} cells, raytraced and inflated at "
            "every update)",
            f"coarsen resolution to at least {size / MAX_CELLS:g} m, or narrow the costmap",
        )


def has_static_layer(node: NodeParameters) -> bool:
    """Whether the costmap has an enabled static layer: Costmap2DROS's default plugins
    (static, obstacle, inflation) do."""
    return any(
        kind == STATIC_LAYER and node.flag(f"{name}.enabled", True)
        for name, kind in layer_kinds(node).items()
    )


# Costmap2DROS's plugins where the file names none, and their types (costmap_2d_ros.cpp:96-100,
# 123, 424-429 at jazzy f4108e5b).
DEFAULT_LAYERS = {
    "static_layer": STATIC_LAYER,
    "obstacle_layer": OBSTACLE_LAYERS[0],
    "inflation_layer": INFLATION_LAYER,
}


def layer_kinds(node: NodeParameters) -> dict[str, str]:
    """Each layer the costmap's `plugins` names, with its plugin type: the default layers'
    default types for the default list, else the type each must name."""
    plugins = node.names("plugins", tuple(DEFAULT_LAYERS))
    default = plugins == tuple(DEFAULT_LAYERS)
    imitated = (*OBSTACLE_LAYERS, INFLATION_LAYER, STATIC_LAYER)
    return {
        name: node.plugin(
            name, imitated, "costmap layer", DEFAULT_LAYERS[name] if default else None
        )
        for name in plugins
    }


def _footprint(
    node: NodeParameters, config: CostmapConfig
) -> tuple[tuple[float, float], ...] | None:
    """`footprint` (a string of [[x, y], ...]) if set, else a polygon of `robot_radius` (0.1 m
    if unset, costmap_2d_ros.cpp:128, 449 at jazzy f4108e5b), either padded by
    footprint_padding."""
    text = node.text("footprint", "[]")
    padding = node.number("footprint_padding", DEFAULT_FOOTPRINT_PADDING)
    if text.strip() not in ("", "[]"):
        name, footprint = "footprint", pad_footprint(_polygon(node, text), padding)
    else:
        radius = node.number("robot_radius", DEFAULT_ROBOT_RADIUS)
        name, footprint = "robot_radius", radius_footprint(radius, padding)
    reach = max(math.hypot(x, y) for x, y in footprint)
    if reach > MAX_FOOTPRINT_REACH:
        raise node.problem(
            name,
            f"reaches {reach:g} m from the robot's origin: no mobile robot is that large, and "
            "the costmaps rasterise the footprint cell by cell",
            f"give the robot's outline in m, within {MAX_FOOTPRINT_REACH:g} m of its origin",
        )
    return footprint


FOOTPRINT_EXAMPLE = '"[[0.5, 0.4], [0.5, -0.4], [-0.5, -0.4], [-0.5, 0.4]]"'


def _polygon(node: NodeParameters, text: str) -> tuple[tuple[float, float], ...]:
    """`footprint_from_string`, its refusal a problem at `footprint`; so is an outline of more
    corners than a robot file may give, or one whose edges cross, which Nav2 would take."""
    try:
        corners = footprint_from_string(text)
    except ValueError as error:
        raise node.problem(
            "footprint", f"{error}: {text!r}", f"write e.g. {FOOTPRINT_EXAMPLE}"
        ) from None
    if len(corners) > MAX_CORNERS:
        raise node.problem(
            "footprint",
            f"has {len(corners)} corners, more than the {MAX_CORNERS} the gate accepts: the "
            "costmaps test every edge at every cell they check",
            "give the robot's outline with fewer corners (a rectangle has 4)",
        )
    _check_outline(node, corners)
    return corners


def _check_outline(node: NodeParameters, corners: tuple[tuple[float, float], ...]) -> None:
    """Refuse a footprint whose edges cross (a bow tie, a star): it outlines no body, and the
    costmaps would clear and the collision checks test a shape no robot has."""
    crossing = crossing_edges(corners)
    if crossing is None:
        return
    first, second = (_edge(corners, index) for index in crossing)
    raise node.problem(
        "footprint",
        f"has edges that cross each other, {first} and {second}: it outlines no body, and the "
        "costmaps and collision checks would read a shape the robot does not have",
        f"list the corners in order round the robot, e.g. {FOOTPRINT_EXAMPLE}",
    )


def _edge(corners: tuple[tuple[float, float], ...], index: int) -> str:
    """The edge from corner `index` to the next, as a message names it."""
    (x0, y0), (x1, y1) = corners[index], corners[(index + 1) % len(corners)]
    return f"from ({x0:g}, {y0:g}) to ({x1:g}, {y1:g})"


def footprint_from_string(text: str) -> tuple[tuple[float, float], ...]:
    """makeFootprintFromString (nav2_costmap_2d/src/footprint.cpp at jazzy f4108e5b): at least
    three [x, y] pairs, read as parseVVF reads them; ValueError with the reason otherwise."""
    try:
        rows = parse_vvf(text)
    except ValueError as error:
        raise ValueError(f"cannot be read as a list of [x, y] points: {error}") from None
    if len(rows) < 3 or any(len(row) != 2 for row in rows):
        raise ValueError("is not a polygon of three or more [x, y] points")
    return tuple((x, y) for x, y in rows)


# One number as C++'s `stream >> float` reads it: no nan, no inf, no hexadecimal.
_FLOAT_MAX = float(np.finfo(np.float32).max)
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")


def parse_vvf(text: str) -> list[list[float]]:
    """A list of lists of numbers, as nav2_util::parseVVF reads one (array_parser.cpp at jazzy
    f4108e5b): brackets at most two deep, numbers only inside the inner ones, commas, spaces
    and tabs between; each number a float (32 bits). Raises ValueError with parseVVF's
    reason; a number that is not finite is refused too (it would reach the ray tracer)."""
    rows: list[list[float]] = []
    depth, at, row = 0, 0, list[float]()
    while at < len(text):
        char = text[at]
        if char in ", \t":
            at += 1
        elif char in "[]":
            depth += 1 if char == "[" else -1
            if depth > 2 or depth < 0:
                raise ValueError("brackets deeper than 2" if depth > 2 else "more ] than [")
            if char == "[":
                row = []
            elif depth == 1:
                rows.append(row)
            at += 1
        else:
            at = _number(text, at, depth, row)
    if depth != 0:
        raise ValueError("an unterminated list")
    return rows


def _number(text: str, at: int, depth: int, row: list[float]) -> int:
    """Reads the number at `at` onto `row`; where the text goes on after it."""
    if depth != 2:
        raise ValueError(f"{text[at]!r} outside an inner [...]")
    match = _NUMBER.match(text, at)
    if match is None:
        raise ValueError(f"{text[at : at + 12]!r} is not a number")
    value = float(match.group())
    if not abs(value) <= _FLOAT_MAX:
        raise ValueError(f"{match.group()} is out of a float's range")
    row.append(float(np.float32(value)))
    return match.end()


def _layers(node: NodeParameters, config: CostmapConfig) -> CostmapConfig:
    kinds = layer_kinds(node)
    obstacle = [name for name, kind in kinds.items() if kind in OBSTACLE_LAYERS]
    inflation = [name for name, kind in kinds.items() if kind == INFLATION_LAYER]
    if len(obstacle) > 1 or len(inflation) > 1:
        raise node.problem(
            "plugins", "names more than one obstacle or inflation layer", "keep one of each"
        )
    if inflation and node.flag(f"{inflation[0]}.enabled", True):
        config = _inflation(node, inflation[0], config)
    else:
        config = _without_inflation(config)
    if obstacle and node.flag(f"{obstacle[0]}.enabled", True):
        return _obstacle_layer(node, obstacle[0], kinds[obstacle[0]], config)
    # Nothing marks or clears: the costmap is blind to the scan.
    source = dataclasses.replace(config.source, marking=False, clearing=False)
    return dataclasses.replace(config, source=source)


def _inflation(node: NodeParameters, layer: str, config: CostmapConfig) -> CostmapConfig:
    costmap = dataclasses.replace(
        config.costmap,
        inflation_radius=node.number(f"{layer}.inflation_radius", 0.55),
        cost_scaling_factor=node.number(f"{layer}.cost_scaling_factor", 10.0),
    )
    return dataclasses.replace(config, costmap=costmap)


def _without_inflation(config: CostmapConfig) -> CostmapConfig:
    # No inflation layer: the costmap holds its lethal cells alone.
    costmap = dataclasses.replace(config.costmap, inflation_radius=0.0, cost_scaling_factor=0.0)
    return dataclasses.replace(config, costmap=costmap)


def _obstacle_layer(
    node: NodeParameters, layer: str, kind: str, config: CostmapConfig
) -> CostmapConfig:
    """The layer's one laser source: its ranges, heights and inf_is_valid."""
    sources = node.names(f"{layer}.observation_sources", ())  # "" by default: none
    if len(sources) != 1:
        how = (
            "names no source: the layer would never see the scan"
            if not sources
            else (f"names {len(sources)} sources; the imitation feeds its layer one laser scan")
        )
        raise node.problem(
            f"{layer}.observation_sources",
            how,
            "name one LaserScan source, e.g. observation_sources: scan",
        )
    prefix = f"{layer}.{sources[0]}."
    if node.text(f"{prefix}data_type", "LaserScan") != "LaserScan":
        raise node.problem(
            f"{prefix}data_type", "must be LaserScan: the source is the scanner", "write LaserScan"
        )
    node.text(f"{prefix}topic", "")
    layer_heights = ("layer_min_obstacle_height", "layer_max_obstacle_height")
    source = node.fields(prefix, config.source, exclude=layer_heights)
    top = node.number(f"{layer}.max_obstacle_height", 2.0)
    if kind == OBSTACLE_LAYERS[1]:
        column = node.number(f"{layer}.z_voxels", 10, whole=True)
        column *= node.number(f"{layer}.z_resolution", 0.2)
        top = min(top, node.number(f"{layer}.origin_z", 0.0) + column)
    source = dataclasses.replace(
        source,
        layer_min_obstacle_height=node.number(f"{layer}.min_obstacle_height", 0.0),
        layer_max_obstacle_height=top,
    )
    inf_is_valid = node.flag(f"{prefix}inf_is_valid", False)
    costmap = dataclasses.replace(config.costmap, inf_is_valid=inf_is_valid)
    return dataclasses.replace(config, source=source, costmap=costmap)
