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
say once what was left out. The controller server's readers (FollowPath's MPPI or DWB, the
checkers) are in controller_params.py.
"""

from __future__ import annotations

import dataclasses
import difflib
import functools
from collections.abc import Iterable
from dataclasses import dataclass

from pytest_lasertest.model.robot import ParameterValue
from pytest_lasertest.nav.move_base.static_layer import StaticLayerSettings
from pytest_lasertest.nav.nav2.controller_params import read_controller_server
from pytest_lasertest.nav.nav2.costmap_params import has_static_layer, read_costmap
from pytest_lasertest.nav.nav2.node_parameters import NodeParameters
from pytest_lasertest.nav.nav2.settings import (
    Nav2Settings,
    code_defaults,
)

Parameter = tuple[str, str, ParameterValue]
NAVFN = "nav2_navfn_planner::NavfnPlanner"


@dataclass(frozen=True)
class Nav2Config:
    """The settings a params file makes, and what in it we did not read: one line per node,
    "amcl: every parameter (37)" or "controller_server: failure_tolerance, ...", file order."""

    settings: Nav2Settings
    unmodelled: tuple[str, ...]


@functools.cache
def configured(parameters: tuple[Parameter, ...], release: str) -> Nav2Config:
    """`configure`, once per params file and release: each drive's Nav2 asks again."""
    return configure(parameters, release)


def configure(parameters: Iterable[Parameter], release: str = "jazzy") -> Nav2Config:
    """The settings of a params file's `parameters` for `release`; raises `ParameterProblem`.
    No parameters, no params file: nav2_bringup's nav2_params.yaml. A file's nodes are read
    over Nav2's code defaults (`code_defaults`), a node it leaves out too, as a launch given
    that file alone would run it."""
    given = tuple(parameters)
    if not given:
        return Nav2Config(Nav2Settings(release=release), ())
    nodes = _by_node(given)
    used: set[tuple[str, str]] = set()
    asked: set[tuple[str, str]] = set()
    settings = code_defaults(release)
    for node, read in READERS.items():
        settings = read(NodeParameters(node, nodes.get(node, {}), used, asked), settings)
    return Nav2Config(settings, _unmodelled(given, nodes, used, asked))


# The node a params file's "/**" (or a node named "*") sets: every node.
WILDCARD = "/**"


def _by_node(parameters: tuple[Parameter, ...]) -> dict[str, dict[str, ParameterValue]]:
    """Each node's parameters, the wildcard's among them, the later in the file winning as
    rclcpp resolves overrides (resolve_parameter_overrides)."""
    named = {node for node, _, _ in parameters if node != WILDCARD} | set(READERS)
    nodes: dict[str, dict[str, ParameterValue]] = {}
    for node, name, value in parameters:
        for target in named if node == WILDCARD else (node,):
            nodes.setdefault(target, {})[name] = value
    return nodes


def _unmodelled(
    parameters: tuple[Parameter, ...],
    nodes: dict[str, dict[str, ParameterValue]],
    used: set[tuple[str, str]],
    asked: set[tuple[str, str]],
) -> tuple[str, ...]:
    """One line per node of what no reader read, with the name meant where one is near it:
    "amcl: every parameter (37)", "controller_server: failure_tolerance, ..."."""
    wild = {name for node, name, _ in parameters if node == WILDCARD}
    own = {(node, name) for node, name, _ in parameters if node != WILDCARD}
    lines = []
    for node, values in nodes.items():
        left = [name for name in values if (node, name) not in used and (node, name) in own]
        if node not in READERS and left:
            lines.append(f"{node}: every parameter ({len(left)}){_meant(node, READERS)}")
        elif left:
            # A name the file sets beside the one it resembles is no misspelling of it:
            # min_vel_y beside min_vel_x is DWB's own, for a holonomic robot.
            read = {name for asked_node, name in asked if asked_node == node} - set(values)
            lines.append(f"{node}: {', '.join(name + _meant(name, read) for name in left)}")
    unread = [name for name in wild if not any((node, name) in used for node in READERS)]
    if unread:
        lines.append(f"{WILDCARD}: {', '.join(sorted(unread))}")
    return tuple(lines)


def _meant(name: str, known: Iterable[str]) -> str:
    """The note ' (did you mean X?)' for the known name X nearest a misspelt `name`, if any."""
    near = difflib.get_close_matches(name, sorted(known), n=1, cutoff=0.85)
    return f" (did you mean {near[0]}?)" if near else ""


def _local_costmap(node: NodeParameters, settings: Nav2Settings) -> Nav2Settings:
    return dataclasses.replace(settings, local=read_costmap(node, settings.local, rolls=True))


def _global_costmap(node: NodeParameters, settings: Nav2Settings) -> Nav2Settings:
    config = read_costmap(node, settings.global_, rolls=False)
    if has_static_layer(node):
        # A world without a map is open ground: a static layer knows its map all free.
        # Without one (Nav2's nav2_no_map_params.yaml) unknown space stays unknown until
        # scanned, and a world's map has nowhere to go.
        static = _static_layer(node, config.costmap.track_unknown_space)
        costmap = dataclasses.replace(config.costmap, track_unknown_space=False)
        config = dataclasses.replace(config, costmap=costmap, static_layer=static)
    else:
        config = dataclasses.replace(config, static_layer=None)
    return dataclasses.replace(settings, global_=config)


def _static_layer(node: NodeParameters, track_unknown_space: bool) -> StaticLayerSettings:
    """The static layer's parameters. Nav2's StaticLayer::getParameters reads them from the
    costmap node, not from under the layer's name (nav2_costmap_2d/plugins/static_layer.cpp at
    a3a97043), with Costmap2DROS's defaults; track_unknown_space is the costmap's."""
    settings: StaticLayerSettings = node.fields("", StaticLayerSettings.nav2(track_unknown_space))
    return settings


def _planner_server(node: NodeParameters, settings: Nav2Settings) -> Nav2Settings:
    if "GridBased" not in node.names("planner_plugins", ("GridBased",)):  # planner_server.cpp:46
        raise node.problem(
            "planner_plugins",
            "does not name GridBased, the planner the default behaviour tree asks for",
            'write planner_plugins: ["GridBased"] with NavFn',
        )
    listed = node.names("planner_plugins", ("GridBased",))
    node.plugin("GridBased", (NAVFN,), "planner", NAVFN if listed == ("GridBased",) else None)
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


def _velocity_smoother(node: NodeParameters, settings: Nav2Settings) -> Nav2Settings:
    s = settings.smoother
    if node.text("feedback", "OPEN_LOOP") != "OPEN_LOOP":
        raise node.problem("feedback", "only OPEN_LOOP is imitated", "write OPEN_LOOP")

    def pair(name: str, default: tuple[float, float]) -> tuple[float, float]:
        x, y, theta = node.numbers(name, (default[0], 0.0, default[1]))
        if name in _SMOOTHER_SIGNS:  # Nav2 checks no deadband's sign
            _check_signs(node, name, (x, y, theta))
        return x, theta

    smoother = dataclasses.replace(
        s,
        smoothing_frequency=node.number("smoothing_frequency", s.smoothing_frequency),
        max_velocity=pair("max_velocity", s.max_velocity),
        min_velocity=pair("min_velocity", s.min_velocity),
        max_accel=pair("max_accel", s.max_accel),
        max_decel=pair("max_decel", s.max_decel),
        scale_velocities=node.flag("scale_velocities", s.scale_velocities),
        deadband_velocity=pair("deadband_velocity", s.deadband_velocity),
        velocity_timeout=_velocity_timeout(node, s.velocity_timeout, settings),
    )
    return dataclasses.replace(settings, smoother=smoother)


def _velocity_timeout(node: NodeParameters, default: float, settings: Nav2Settings) -> float:
    """velocity_timeout, which must outlast the controller's cycle: the stacks here command
    every cycle, and a smoother that times out between two of them brakes the robot to a stop
    (smootherTimer, velocity_smoother.cpp:331-339 at jazzy f4108e5b), which is not imitated."""
    timeout = node.number("velocity_timeout", default)
    period = 1.0 / settings.controller_frequency  # s
    if timeout <= period:
        raise node.problem(
            "velocity_timeout",
            f"{timeout:g} s is no longer than the controller's cycle ({period:g} s): Nav2's "
            "smoother would brake the robot between commands, which the imitation does not do",
            f"write a velocity_timeout above {period:g} s (Nav2's default is 1.0)",
        )
    return timeout


# The sign each of the smoother's limits must have, or it fails to configure
# (VelocitySmoother::on_configure, velocity_smoother.cpp:77-101 at jazzy f4108e5b).
_SMOOTHER_SIGNS = {"max_velocity": 1, "min_velocity": -1, "max_accel": 1, "max_decel": -1}


def _check_signs(node: NodeParameters, name: str, values: tuple[float, ...]) -> None:
    sign = _SMOOTHER_SIGNS[name]
    if any(value * sign < 0.0 for value in values):
        word = "negative" if sign > 0 else "positive"
        raise node.problem(
            name,
            f"has a {word} value {list(values)}: Nav2's velocity smoother refuses to start",
            f"write each of {name} {'zero or more' if sign > 0 else 'zero or less'}",
        )


def _collision_monitor(node: NodeParameters, settings: Nav2Settings) -> Nav2Settings:
    """The collision monitor: one FootprintApproach polygon on one scan source, or none. A file
    without the node runs none (Humble's bringup launches none; Jazzy's would fail to start
    it). polygons, observation_sources, a polygon's type and action_type have no default
    (collision_monitor_node.cpp:303-311, 356-359, polygon.cpp:332-335 at jazzy f4108e5b;
    Humble's polygons is an empty list, collision_monitor_node.cpp:245-246 at 3c3db59d)."""
    if not node.values:
        return dataclasses.replace(settings, collision_monitor=None)
    if settings.release == "humble" and "polygons" not in node.values:
        return dataclasses.replace(settings, collision_monitor=None)
    polygons = _required_names(node, "polygons", "FootprintApproach")
    enabled = [name for name in polygons if node.flag(f"{name}.enabled", True)]
    if not enabled:
        return dataclasses.replace(settings, collision_monitor=None)
    polygon = enabled[0]
    _check_type(node, f"{polygon}.type", "polygon", POLYGON_TYPES, required=True)
    action = f"{polygon}.action_type"
    if len(enabled) > 1 or _required_text(node, action, "approach") != "approach":
        raise node.problem(
            action,
            "the imitation has one polygon, of action_type approach on the footprint",
            "keep one approach polygon, as nav2_bringup's FootprintApproach",
        )
    assert settings.collision_monitor is not None  # the code defaults hold one
    monitor = node.fields(f"{polygon}.", settings.collision_monitor)
    if f"{polygon}.max_points" in node.values:
        # Deprecated, and still read over min_points (Polygon::getCommonParameters,
        # polygon.cpp:359-369 at jazzy f4108e5b).
        most = int(node.number(f"{polygon}.max_points", 0, whole=True))
        monitor = dataclasses.replace(monitor, min_points=most + 1)
    node.text(f"{polygon}.footprint_topic", "")
    sources = _required_names(node, "observation_sources", "scan")
    if len(sources) != 1:
        raise node.problem(
            "observation_sources", "the imitation's monitor reads one scan", "name one source"
        )
    if not node.flag(f"{sources[0]}.enabled", True):
        return dataclasses.replace(settings, collision_monitor=None)  # it reads nothing
    _check_type(node, f"{sources[0]}.type", "scan", SOURCE_TYPES, required=False)
    node.text(f"{sources[0]}.topic", "")
    return dataclasses.replace(settings, collision_monitor=monitor)


def _required_names(node: NodeParameters, name: str, example: str) -> tuple[str, ...]:
    """A list the collision monitor declares without a default."""
    if name not in node.values:
        raise node.problem(
            name,
            "is not set: Nav2's collision monitor refuses to configure without it",
            f'write {name}: ["{example}"], or leave the collision_monitor node out of the '
            "file to run none",
        )
    return node.names(name, ())


def _required_text(node: NodeParameters, name: str, example: str) -> str:
    """A string the collision monitor declares without a default."""
    if name not in node.values:
        raise node.problem(
            name,
            "is not set: Nav2's collision monitor refuses to configure without it",
            f"write {name}: {example}",
        )
    return node.text(name, example)


# The types the collision monitor knows (CollisionMonitor::configurePolygons and
# configureSources, collision_monitor_node.cpp:313-331, 366-403 at jazzy f4108e5b).
POLYGON_TYPES = ("polygon", "circle", "velocity_polygon")
SOURCE_TYPES = ("scan", "pointcloud", "range", "polygon")


def _check_type(
    node: NodeParameters, name: str, imitated: str, known: tuple[str, ...], required: bool
) -> None:
    """A polygon's or source's type: one Nav2 knows (else it refuses to configure), and the
    one the imitation has."""
    kind = _required_text(node, name, imitated) if required else node.text(name, imitated)
    if kind not in known:
        why = f"{kind!r} is not a type Nav2's collision monitor knows ({', '.join(known)})"
    elif kind != imitated:
        why = f"{kind!r} is not imitated: the monitor here has one footprint polygon on the scan"
    else:
        return
    raise node.problem(name, why, f"write {imitated}")


# The behaviour server's plugins when the file lists none (BehaviorServer's default_ids_ and
# default_types_, behavior_server.cpp:28-32 at jazzy f4108e5b), and the types it may load.
DEFAULT_BEHAVIORS = {
    "spin": "nav2_behaviors::Spin",
    "backup": "nav2_behaviors::BackUp",
    "drive_on_heading": "nav2_behaviors::DriveOnHeading",
    "wait": "nav2_behaviors::Wait",
}
BEHAVIOR_TYPES = (*DEFAULT_BEHAVIORS.values(), "nav2_behaviors::AssistedTeleop")
# The action servers the default behaviour tree's recoveries call, each the plugin of that name
# (navigate_to_pose_w_replanning_and_recovery.xml: Spin, Wait and BackUp, by their default
# server names): what the imitation runs.
RECOVERY_BEHAVIORS = ("spin", "backup", "wait")


def _behavior_server(node: NodeParameters, settings: Nav2Settings) -> Nav2Settings:
    """The behaviour server's rate, its look ahead for collisions and Spin's speeds; its plugins
    (`_check_behaviors`); transform_tolerance, which acts on nothing here (the simulator's
    transforms are never late)."""
    _check_behaviors(node)
    node.number("transform_tolerance", 0.1)
    return dataclasses.replace(settings, behaviors=node.fields("", settings.behaviors))


def _check_behaviors(node: NodeParameters) -> None:
    """behavior_plugins, each of a type the server loads, serving the recoveries the behaviour
    tree calls by name with the plugins the imitation runs."""
    listed = node.names("behavior_plugins", tuple(DEFAULT_BEHAVIORS))
    defaults = DEFAULT_BEHAVIORS if listed == tuple(DEFAULT_BEHAVIORS) else {}
    kinds = {
        name: node.plugin(name, BEHAVIOR_TYPES, "behavior", defaults.get(name)) for name in listed
    }
    for name in RECOVERY_BEHAVIORS:
        wanted = DEFAULT_BEHAVIORS[name]
        if name not in kinds:
            raise node.problem(
                "behavior_plugins",
                f"does not list {name}, which the behaviour tree's recoveries call: Nav2's "
                "recovery would fail at once",
                f"add {name} (plugin {wanted}) to behavior_plugins",
            )
        if kinds[name] != wanted:
            raise node.problem(
                f"{name}.plugin",
                f"is {kinds[name]}, but the behaviour tree's recoveries call {name} for {wanted}",
                f"write {name}.plugin: {wanted}",
            )


READERS = {
    "controller_server": read_controller_server,
    "local_costmap": _local_costmap,
    "global_costmap": _global_costmap,
    "planner_server": _planner_server,
    "velocity_smoother": _velocity_smoother,
    "collision_monitor": _collision_monitor,
    "behavior_server": _behavior_server,
}
