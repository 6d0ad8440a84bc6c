"""A team's Nav2 parameters, as a ROS 2 params file sets them, made into `Nav2Settings`.

Parameters come as (node, dotted name, value): ("controller_server", "FollowPath.vx_max", 0.5),
the node's namespace dropped (`local_costmap: {local_costmap: {ros__parameters: ...}}` is the
node local_costmap). Plugins are found as Nav2 finds them: `controller_plugins` names the
controller whose `<name>.plugin` says what it is, a costmap's `plugins` its layers, a layer's
`observation_sources` its sources. The default behaviour tree asks for the controller FollowPath
and the planner GridBased.

What we imitate is read, checked and applied; a plugin we do not imitate, where its absence
would change what the robot does, is a `ParameterProblem` naming the parameter and the fix;
every parameter we read no further is listed in `Nav2Config.unmodelled`, so that a report can
say once what was left out.
"""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from pytest_lasertest.model.robot import ParameterValue
from pytest_lasertest.nav.nav2.collision_monitor import CollisionMonitorSettings
from pytest_lasertest.nav.nav2.dwb import CRITICS as DWB_CRITICS
from pytest_lasertest.nav.nav2.dwb import DwbSettings
from pytest_lasertest.nav.nav2.settings import (
    CRITICS,
    CostmapConfig,
    MppiCritic,
    Nav2Settings,
)

Parameter = tuple[str, str, ParameterValue]
# Rates, sizes, counts and times that must be above zero; the rest may be zero.
POSITIVE = frozenset(
    {
        "controller_frequency",
        "update_frequency",
        "width",
        "height",
        "resolution",
        "time_steps",
        "model_dt",
        "batch_size",
        "iteration_count",
        "temperature",
        "vx_max",
        "wz_max",
        "smoothing_frequency",
        "time_before_collision",
        "simulation_time_step",
        "min_points",
        "robot_radius",
    }
)
# Lower limits and decelerations, negative by nature.
MAY_BE_NEGATIVE = frozenset(
    {
        "vx_min",
        "ax_min",
        "ay_min",
        "min_velocity",
        "max_decel",
        "min_vel_x",
        "decel_lim_x",
        "decel_lim_theta",
        "lookahead_time",
    }
)
# Past these a figure is a typo, and the cycle would take seconds and gigabytes.
LARGEST = {"batch_size": 100_000, "time_steps": 1_000, "iteration_count": 100}
MPPI = "nav2_mppi_controller::MPPIController"
DWB = "dwb_core::DWBLocalPlanner"
OBSTACLE_LAYERS = ("nav2_costmap_2d::ObstacleLayer", "nav2_costmap_2d::VoxelLayer")
INFLATION_LAYER = "nav2_costmap_2d::InflationLayer"
STATIC_LAYER = "nav2_costmap_2d::StaticLayer"
NAVFN = "nav2_navfn_planner::NavfnPlanner"
# Read but not imitated, for a reason the README gives: the routes here have no goal heading.
NOT_IMITATED_CRITICS = frozenset({"GoalAngleCritic"})


class ParameterProblem(ValueError):
    """A parameter we cannot run as given: which, what is wrong and how to fix it."""

    def __init__(self, node: str, name: str, problem: str, fix: str) -> None:
        super().__init__(f"{node}: {name}: {problem}")
        self.node, self.name, self.problem, self.fix = node, name, problem, fix


@dataclass(frozen=True)
class Nav2Config:
    """The settings a params file makes, and what in it we did not read: one line per node,
    "amcl: every parameter (37)" or "controller_server: failure_tolerance, ...", file order."""

    settings: Nav2Settings
    unmodelled: tuple[str, ...]


def configure(parameters: Iterable[Parameter], release: str = "jazzy") -> Nav2Config:
    """Jazzy's defaults with `parameters` set; raises `ParameterProblem`."""
    nodes: dict[str, dict[str, ParameterValue]] = {}
    for node, name, value in parameters:
        nodes.setdefault(node, {})[name] = value
    used: set[tuple[str, str]] = set()
    settings = Nav2Settings(release=release)
    for node, read in READERS.items():
        if node in nodes:
            settings = read(_Node(node, nodes[node], used), settings)
    return Nav2Config(settings, _unmodelled(nodes, used))


def _unmodelled(
    nodes: dict[str, dict[str, ParameterValue]], used: set[tuple[str, str]]
) -> tuple[str, ...]:
    lines = []
    for node, values in nodes.items():
        left = [name for name in values if (node, name) not in used]
        if node not in READERS:
            lines.append(f"{node}: every parameter ({len(left)})")
        elif left:
            lines.append(f"{node}: {', '.join(left)}")
    return tuple(lines)


class _Node:
    """One node's parameters, read typed; each read is marked used."""

    def __init__(
        self, node: str, values: dict[str, ParameterValue], used: set[tuple[str, str]]
    ) -> None:
        self.node, self.values, self.used = node, values, used

    def problem(self, name: str, problem: str, fix: str) -> ParameterProblem:
        return ParameterProblem(self.node, name, problem, fix)

    def get(self, name: str) -> ParameterValue | None:
        if name not in self.values:
            return None
        self.used.add((self.node, name))
        return self.values[name]

    def number(self, name: str, default: float, whole: bool = False) -> float:
        value = self.get(name)
        if value is None:
            return default
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.problem(name, f"is a number, not {value!r}", "write a number")
        if whole and value != int(value):
            raise self.problem(name, f"is a whole number, not {value}", "write a whole number")
        return _checked(self, name, float(value))

    def flag(self, name: str, default: bool) -> bool:
        value = self.get(name)
        if value is None:
            return default
        if not isinstance(value, bool):
            raise self.problem(name, f"is true or false, not {value!r}", "write true or false")
        return value

    def text(self, name: str, default: str) -> str:
        value = self.get(name)
        if value is None:
            return default
        if not isinstance(value, str):
            raise self.problem(name, f"is a string, not {value!r}", "write a string")
        return value

    def names(self, name: str, default: tuple[str, ...]) -> tuple[str, ...]:
        """A list of names, or one string of them separated by spaces (as
        observation_sources is written)."""
        value = self.get(name)
        if value is None:
            return default
        if isinstance(value, str):
            return tuple(value.split())
        if isinstance(value, tuple) and all(isinstance(item, str) for item in value):
            return tuple(str(item) for item in value)
        raise self.problem(name, f"is a list of names, not {value!r}", 'write e.g. ["FollowPath"]')

    def numbers(self, name: str, default: tuple[float, ...]) -> tuple[float, ...]:
        value = self.get(name)
        if value is None:
            return default
        if not (
            isinstance(value, tuple)
            and len(value) == len(default)
            and all(isinstance(v, int | float) and not isinstance(v, bool) for v in value)
        ):
            raise self.problem(
                name,
                f"is a list of {len(default)} numbers, not {value!r}",
                "write e.g. [0.5, 0.0, 2.0]",
            )
        return tuple(float(v) for v in value)  # type: ignore[arg-type]

    def plugin(self, name: str, imitated: tuple[str, ...], what: str) -> str:
        """`<name>.plugin`, which must be one we imitate (`pkg::Class` or `pkg/Class`)."""
        kind = self.text(f"{name}.plugin", imitated[0]).replace("/", "::")
        if kind not in imitated:
            raise self.problem(
                f"{name}.plugin",
                f"{kind} is a {what} the Nav2 imitation does not have",
                f"use {' or '.join(imitated)}, or drive with your own controller",
            )
        return kind

    def fields(self, prefix: str, values: Any, renamed: dict[str, str] | None = None) -> Any:
        """A dataclass with each of its fields the node sets under `prefix` read at its type;
        `renamed` maps the file's names to the fields'."""
        names = {field.name: field.name for field in dataclasses.fields(values)}
        names.update(renamed or {})
        changes: dict[str, float | bool] = {}
        for name, attribute in names.items():
            current = getattr(values, attribute)
            key = f"{prefix}{name}"
            if isinstance(current, bool):
                changes[attribute] = self.flag(key, current)
            elif isinstance(current, int | float):
                found = self.number(key, current, whole=isinstance(current, int))
                changes[attribute] = int(found) if isinstance(current, int) else found
        return dataclasses.replace(values, **changes)


def _checked(node: _Node, name: str, value: float) -> float:
    leaf = name.rsplit(".", 1)[-1]
    if leaf in POSITIVE and value <= 0.0:
        raise node.problem(name, f"must be above zero, not {value}", f"write a positive {leaf}")
    if leaf not in MAY_BE_NEGATIVE and value < 0.0:
        raise node.problem(name, f"cannot be negative ({value})", "write zero or more")
    if leaf in LARGEST and value > LARGEST[leaf]:
        raise node.problem(
            name,
            f"{value:g} is beyond any Nav2 configuration (at most {LARGEST[leaf]})",
            "check the figure: the controller would take seconds per cycle",
        )
    return value


def _controller_server(node: _Node, settings: Nav2Settings) -> Nav2Settings:
    """controller_server: its rate, the FollowPath controller (MPPI), the progress and goal
    checkers."""
    if "FollowPath" not in node.names("controller_plugins", ("FollowPath",)):
        raise node.problem(
            "controller_plugins",
            "does not name FollowPath, the controller the default behaviour tree asks for",
            'write controller_plugins: ["FollowPath"] and FollowPath\'s parameters',
        )
    if node.plugin("FollowPath", (MPPI, DWB), "controller") == DWB:
        settings = _dwb(node, settings)
    else:
        settings = _mppi(node, settings)
    progress = node.names("progress_checker_plugins", ("progress_checker",))[0]
    node.plugin(progress, ("nav2_controller::SimpleProgressChecker",), "progress checker")
    goal = node.names("goal_checker_plugins", ("goal_checker",))[0]
    node.plugin(goal, ("nav2_controller::SimpleGoalChecker",), "goal checker")
    return dataclasses.replace(
        settings,
        controller_frequency=node.number("controller_frequency", settings.controller_frequency),
        required_movement_radius=node.number(
            f"{progress}.required_movement_radius", settings.required_movement_radius
        ),
        movement_time_allowance=node.number(
            f"{progress}.movement_time_allowance", settings.movement_time_allowance
        ),
        xy_goal_tolerance=node.number(f"{goal}.xy_goal_tolerance", settings.xy_goal_tolerance),
    )


def _mppi(node: _Node, settings: Nav2Settings) -> Nav2Settings:
    """MPPI as FollowPath: the optimizer's parameters, its critics and theirs."""
    if node.text("FollowPath.motion_model", "DiffDrive") != "DiffDrive":
        raise node.problem(
            "FollowPath.motion_model", "the robots here are differential drives", "write DiffDrive"
        )
    return dataclasses.replace(
        settings,
        mppi=node.fields("FollowPath.", settings.mppi),
        critics=_critics(node, settings.critics),
        prune_distance=node.number("FollowPath.prune_distance", settings.prune_distance),
    )


def _dwb(node: _Node, settings: Nav2Settings) -> Nav2Settings:
    """DWB as FollowPath: its own parameters, its critics and theirs (`Critic.scale`,
    `PathAlign.forward_point_distance`, `RotateToGoal.slowing_factor`, ...)."""
    critics = node.names("FollowPath.critics", DWB_CRITICS)
    unknown = [name for name in critics if name not in DWB_CRITICS]
    if unknown:
        raise node.problem(
            "FollowPath.critics",
            f"{unknown[0]} is a critic the DWB imitation does not have",
            f"leave it out, or use those it has: {', '.join(DWB_CRITICS)}",
        )
    dwb = dataclasses.replace(node.fields("FollowPath.", DwbSettings()), critics=critics)
    renamed = {
        f"{critic}.{leaf}": field.name
        for field in dataclasses.fields(dwb)
        for critic in DWB_CRITICS
        for leaf in _critic_leaves(field.name, critic)
    }
    dwb = node.fields("FollowPath.", dwb, renamed)
    if dwb.lookahead_time >= 0.0:
        raise node.problem(
            "FollowPath.RotateToGoal.lookahead_time",
            "only a negative lookahead_time (the trajectory's last pose) is imitated",
            "write -1.0, Nav2's default",
        )
    prune = dwb.prune_distance
    return dataclasses.replace(settings, dwb=dwb, prune_distance=prune)


def _critic_leaves(field: str, critic: str) -> list[str]:
    """The names under `critic.` in a params file that set DwbSettings' `field`:
    path_align_scale is PathAlign.scale, slowing_factor RotateToGoal.slowing_factor."""
    prefix = "".join("_" + c.lower() if c.isupper() else c for c in critic).lstrip("_") + "_"
    if field.startswith(prefix):
        return [field.removeprefix(prefix)]
    owned = {
        "RotateToGoal": ("slowing_factor", "lookahead_time"),
        "Oscillation": ("oscillation_reset_dist", "oscillation_reset_angle", "x_only_threshold"),
    }
    return [field] if field in owned.get(critic, ()) else []


def _critics(node: _Node, defaults: tuple[MppiCritic, ...]) -> tuple[MppiCritic, ...]:
    """MPPI's critics in the order FollowPath.critics lists them, each with its parameters;
    one with enabled false is left out."""
    by_name = {type(critic).__name__: critic for critic in defaults}
    listed = node.names("FollowPath.critics", tuple(by_name))
    critics = []
    for name in listed:
        if name in NOT_IMITATED_CRITICS:
            continue
        if name not in CRITICS:
            raise node.problem(
                "FollowPath.critics",
                f"{name} is a critic the MPPI imitation does not have",
                f"leave it out, or use those it has: {', '.join(CRITICS)}",
            )
        critic = by_name[name]
        renamed = {"cost_weight": "weight", "cost_power": "power"}
        if node.flag(f"FollowPath.{name}.enabled", True):
            critics.append(node.fields(f"FollowPath.{name}.", critic, renamed))
    return tuple(critics)


def _costmap(node: _Node, config: CostmapConfig) -> CostmapConfig:
    """A costmap: its window, footprint and layers (one laser source, inflation, static)."""
    width = node.number("width", config.costmap.size)
    if node.number("height", width) != width:
        raise node.problem(
            "height",
            "differs from width; the imitation's rolling window is square",
            "write the same width and height",
        )
    costmap = dataclasses.replace(
        config.costmap,
        size=width,
        resolution=node.number("resolution", config.costmap.resolution),
        update_frequency=node.number("update_frequency", config.costmap.update_frequency),
        track_unknown_space=node.flag("track_unknown_space", config.costmap.track_unknown_space),
    )
    node.flag("rolling_window", True)
    config = dataclasses.replace(config, costmap=costmap, footprint=_footprint(node, config))
    return _layers(node, config)


def _footprint(node: _Node, config: CostmapConfig) -> tuple[tuple[float, float], ...] | None:
    """`footprint` (a string of [[x, y], ...]) if set, else a polygon of `robot_radius` if
    set, padded by footprint_padding; None, the robot's own, if neither is set."""
    text = node.text("footprint", "[]")
    padding = node.number("footprint_padding", 0.01)
    if text.strip() not in ("", "[]"):
        points = _polygon(node, text)
        return tuple((x + _sign(x) * padding, y + _sign(y) * padding) for x, y in points)
    radius = node.number("robot_radius", 0.0)
    if "robot_radius" not in node.values:
        return config.footprint
    # costmap_2d's makeFootprintFromRadius: 16 points on the circle.
    return tuple(
        (radius * math.cos(2 * math.pi * i / 16), radius * math.sin(2 * math.pi * i / 16))
        for i in range(16)
    )


def _sign(value: float) -> float:
    return (value > 0) - (value < 0)


def _polygon(node: _Node, text: str) -> tuple[tuple[float, float], ...]:
    try:
        points = json.loads(text)
        polygon = tuple((float(x), float(y)) for x, y in points)
    except (ValueError, TypeError):
        polygon = ()
    if len(polygon) < 3:
        raise node.problem(
            "footprint",
            f"is not a polygon of three or more [x, y] points: {text!r}",
            'write e.g. "[[0.5, 0.4], [0.5, -0.4], [-0.5, -0.4], [-0.5, 0.4]]"',
        )
    return polygon


def _layers(node: _Node, config: CostmapConfig) -> CostmapConfig:
    plugins = node.names("plugins", ())
    kinds = {
        name: node.plugin(name, (*OBSTACLE_LAYERS, INFLATION_LAYER, STATIC_LAYER), "costmap layer")
        for name in plugins
    }
    obstacle = [name for name, kind in kinds.items() if kind in OBSTACLE_LAYERS]
    inflation = [name for name, kind in kinds.items() if kind == INFLATION_LAYER]
    if len(obstacle) > 1 or len(inflation) > 1:
        raise node.problem(
            "plugins", "names more than one obstacle or inflation layer", "keep one of each"
        )
    if inflation and node.flag(f"{inflation[0]}.enabled", True):
        config = _inflation(node, inflation[0], config)
    elif plugins:
        config = _without_inflation(config)
    if obstacle and node.flag(f"{obstacle[0]}.enabled", True):
        return _obstacle_layer(node, obstacle[0], kinds[obstacle[0]], config)
    if plugins:
        # Nothing marks or clears: the costmap is blind to the scan.
        source = dataclasses.replace(config.source, marking=False, clearing=False)
        return dataclasses.replace(config, source=source)
    return config


def _inflation(node: _Node, layer: str, config: CostmapConfig) -> CostmapConfig:
    costmap = dataclasses.replace(
        config.costmap,
        inflation_radius=node.number(f"{layer}.inflation_radius", 0.55),
        cost_scaling_factor=node.number(f"{layer}.cost_scaling_factor", 10.0),
    )
    return dataclasses.replace(config, costmap=costmap)


def _without_inflation(config: CostmapConfig) -> CostmapConfig:
    # No inflation layer: only lethal cells, and those the footprint's inscribed circle
    # reaches (the smallest inflation the costmap can hold).
    costmap = dataclasses.replace(config.costmap, inflation_radius=0.0, cost_scaling_factor=0.0)
    return dataclasses.replace(config, costmap=costmap)


def _obstacle_layer(node: _Node, layer: str, kind: str, config: CostmapConfig) -> CostmapConfig:
    """The layer's one laser source: its ranges, heights and inf_is_valid."""
    sources = node.names(f"{layer}.observation_sources", ())
    if len(sources) != 1:
        raise node.problem(
            f"{layer}.observation_sources",
            f"names {len(sources)} sources; the imitation feeds its layer one laser scan",
            "name one LaserScan source, e.g. observation_sources: scan",
        )
    prefix = f"{layer}.{sources[0]}."
    if node.text(f"{prefix}data_type", "PointCloud2") != "LaserScan":
        raise node.problem(
            f"{prefix}data_type", "must be LaserScan: the source is the scanner", "write LaserScan"
        )
    node.text(f"{prefix}topic", "")
    source = node.fields(prefix, config.source)
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


def _local_costmap(node: _Node, settings: Nav2Settings) -> Nav2Settings:
    return dataclasses.replace(settings, local=_costmap(node, settings.local))


def _global_costmap(node: _Node, settings: Nav2Settings) -> Nav2Settings:
    config = _costmap(node, settings.global_)
    # The worlds here are open ground: as a static layer would know their map all free.
    costmap = dataclasses.replace(config.costmap, track_unknown_space=False)
    return dataclasses.replace(settings, global_=dataclasses.replace(config, costmap=costmap))


def _planner_server(node: _Node, settings: Nav2Settings) -> Nav2Settings:
    if "GridBased" not in node.names("planner_plugins", ("GridBased",)):
        raise node.problem(
            "planner_plugins",
            "does not name GridBased, the planner the default behaviour tree asks for",
            'write planner_plugins: ["GridBased"] with NavFn',
        )
    node.plugin("GridBased", (NAVFN,), "planner")
    if node.flag("GridBased.use_astar", False):
        raise node.problem(
            "GridBased.use_astar", "A* is not imitated: NavFn here is Dijkstra", "write false"
        )
    navfn = dataclasses.replace(
        settings.navfn,
        default_tolerance=node.number("GridBased.tolerance", settings.navfn.default_tolerance),
        allow_unknown=node.flag("GridBased.allow_unknown", settings.navfn.allow_unknown),
    )
    return dataclasses.replace(settings, navfn=navfn)


def _velocity_smoother(node: _Node, settings: Nav2Settings) -> Nav2Settings:
    s = settings.smoother
    if node.text("feedback", "OPEN_LOOP") != "OPEN_LOOP":
        raise node.problem("feedback", "only OPEN_LOOP is imitated", "write OPEN_LOOP")

    def pair(name: str, default: tuple[float, float]) -> tuple[float, float]:
        x, _, theta = node.numbers(name, (default[0], 0.0, default[1]))
        return x, theta

    smoother = dataclasses.replace(
        s,
        smoothing_frequency=node.number("smoothing_frequency", s.smoothing_frequency),
        max_velocity=pair("max_velocity", s.max_velocity),
        min_velocity=pair("min_velocity", s.min_velocity),
        max_accel=pair("max_accel", s.max_accel),
        max_decel=pair("max_decel", s.max_decel),
    )
    return dataclasses.replace(settings, smoother=smoother)


def _collision_monitor(node: _Node, settings: Nav2Settings) -> Nav2Settings:
    """The collision monitor: one FootprintApproach polygon on one scan source, or none."""
    polygons = node.names("polygons", ("FootprintApproach",))
    enabled = [name for name in polygons if node.flag(f"{name}.enabled", True)]
    if not enabled:
        return dataclasses.replace(settings, collision_monitor=None)
    if len(enabled) > 1 or node.text(f"{enabled[0]}.action_type", "approach") != "approach":
        raise node.problem(
            f"{enabled[0]}.action_type",
            "the imitation has one polygon, of action_type approach on the footprint",
            "keep one approach polygon, as nav2_bringup's FootprintApproach",
        )
    polygon = enabled[0]
    monitor = node.fields(f"{polygon}.", CollisionMonitorSettings())
    node.text(f"{polygon}.type", "polygon")
    node.text(f"{polygon}.footprint_topic", "")
    sources = node.names("observation_sources", ("scan",))
    if len(sources) != 1:
        raise node.problem(
            "observation_sources", "the imitation's monitor reads one scan", "name one source"
        )
    if not node.flag(f"{sources[0]}.enabled", True):
        return dataclasses.replace(settings, collision_monitor=None)  # it reads nothing
    monitor = node.fields(f"{sources[0]}.", monitor)
    node.text(f"{sources[0]}.type", "scan")
    node.text(f"{sources[0]}.topic", "")
    return dataclasses.replace(settings, collision_monitor=monitor)


READERS = {
    "controller_server": _controller_server,
    "local_costmap": _local_costmap,
    "global_costmap": _global_costmap,
    "planner_server": _planner_server,
    "velocity_smoother": _velocity_smoother,
    "collision_monitor": _collision_monitor,
}
