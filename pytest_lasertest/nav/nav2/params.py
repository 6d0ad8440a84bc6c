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
import difflib
import functools
from collections.abc import Iterable
from dataclasses import dataclass

from pytest_lasertest.model.robot import ParameterValue
from pytest_lasertest.nav.move_base.settings import MAX_ROLLOUT_POSES
from pytest_lasertest.nav.move_base.static_layer import StaticLayerSettings
from pytest_lasertest.nav.nav2.costmap_params import has_static_layer, read_costmap
from pytest_lasertest.nav.nav2.dwb import CODE_DEFAULTS, DwbSettings, rollout_poses
from pytest_lasertest.nav.nav2.dwb import CRITICS as DWB_CRITICS
from pytest_lasertest.nav.nav2.mppi import SAME_PERIOD
from pytest_lasertest.nav.nav2.node_parameters import NodeParameters
from pytest_lasertest.nav.nav2.settings import (
    CRITICS,
    MppiCritic,
    Nav2Settings,
    code_default_critics,
    code_defaults,
)

Parameter = tuple[str, str, ParameterValue]
MPPI = "nav2_mppi_controller::MPPIController"
DWB = "dwb_core::DWBLocalPlanner"
NAVFN = "nav2_navfn_planner::NavfnPlanner"
# MPPI's samples x steps a cycle: nav2_params.yaml's 2000 x 56 is 112,000.
MAX_MPPI_POINTS = 1_000_000
# Read but not imitated, for a reason docs/explanation/navigation.md gives: the routes here
# have no goal heading.
NOT_IMITATED_CRITICS = frozenset({"GoalAngleCritic"})


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


def _controller_server(node: NodeParameters, settings: Nav2Settings) -> Nav2Settings:
    """controller_server: its rate, the FollowPath controller (MPPI or DWB), the progress and goal
    checkers. A plugin list left as its default names its default plugin: FollowPath is DWB
    (controller_server.cpp:40-58, 93-118 at jazzy f4108e5b)."""
    listed = node.names("controller_plugins", ("FollowPath",))
    if "FollowPath" not in listed:
        raise node.problem(
            "controller_plugins",
            "does not name FollowPath, the controller the default behaviour tree asks for",
            'write controller_plugins: ["FollowPath"] and FollowPath\'s parameters',
        )
    frequency = node.number("controller_frequency", settings.controller_frequency)
    default = DWB if listed == ("FollowPath",) else None
    if node.plugin("FollowPath", (MPPI, DWB), "controller", default) == DWB:
        settings = _dwb(node, settings)
    else:
        settings = _mppi(node, settings)
        _check_period(node, frequency, settings.mppi.model_dt)
    progress = _checker(node, settings.release, "progress_checker", PROGRESS_CHECKER)
    goal = _checker(node, settings.release, "goal_checker", GOAL_CHECKER)
    return dataclasses.replace(
        settings,
        controller_frequency=frequency,
        required_movement_radius=node.number(
            f"{progress}.required_movement_radius", settings.required_movement_radius
        ),
        movement_time_allowance=node.number(
            f"{progress}.movement_time_allowance", settings.movement_time_allowance
        ),
        xy_goal_tolerance=node.number(f"{goal}.xy_goal_tolerance", settings.xy_goal_tolerance),
    )


PROGRESS_CHECKER = "nav2_controller::SimpleProgressChecker"
GOAL_CHECKER = "nav2_controller::SimpleGoalChecker"


def _checker(node: NodeParameters, release: str, name: str, kind: str) -> str:
    """The progress or goal checker's name: the first of `<name>_plugins` (`name` by default),
    or Humble's one progress_checker_plugin (controller_server.cpp:53, 84-89 at humble
    3c3db59d); its plugin must be `kind`, the default only for the default name."""
    if release == "humble" and name == "progress_checker":
        listed: tuple[str, ...] = (node.text("progress_checker_plugin", name),)
    else:
        listed = node.names(f"{name}_plugins", (name,))
    node.plugin(listed[0], (kind,), name.replace("_", " "), kind if listed == (name,) else None)
    return listed[0]


def _mppi(node: NodeParameters, settings: Nav2Settings) -> Nav2Settings:
    """MPPI as FollowPath: the optimizer's parameters, its critics and theirs."""
    if node.text("FollowPath.motion_model", "DiffDrive") != "DiffDrive":
        raise node.problem(
            "FollowPath.motion_model", "the robots here are differential drives", "write DiffDrive"
        )
    mppi = node.fields("FollowPath.", settings.mppi)
    if mppi.batch_size * mppi.time_steps > MAX_MPPI_POINTS:
        raise node.problem(
            "FollowPath.batch_size",
            f"{mppi.batch_size:,} samples of {mppi.time_steps} steps are "
            f"{mppi.batch_size * mppi.time_steps:,} points every cycle, more than the "
            f"{MAX_MPPI_POINTS:,} the gate accepts: a run would take hours",
            "lower batch_size or time_steps (nav2_params.yaml: 2000 x 56)",
        )
    # Optimizer::getParams takes ax_max's magnitude and turns a positive ax_min negative,
    # with a warning (optimizer.cpp:90-97 at jazzy f4108e5b).
    mppi = dataclasses.replace(mppi, ax_max=abs(mppi.ax_max), ax_min=-abs(mppi.ax_min))
    return dataclasses.replace(
        settings,
        mppi=mppi,
        critics=_critics(node, settings.release),
        prune_distance=node.number("FollowPath.prune_distance", settings.prune_distance),
        max_robot_pose_search_dist=_search_distance(node, settings.max_robot_pose_search_dist),
    )


def _search_distance(node: NodeParameters, default: float | None) -> float | None:
    """FollowPath.max_robot_pose_search_dist, if the file sets it."""
    name = "FollowPath.max_robot_pose_search_dist"
    return node.number(name, 0.0) if name in node.values else default


def _check_period(node: NodeParameters, frequency: float, model_dt: float) -> None:
    """MPPI refuses to start where the controller's period is longer than a step of its
    model (Optimizer::setOffset, optimizer.cpp:115-136 at jazzy f4108e5b)."""
    if 1.0 / frequency > model_dt + SAME_PERIOD:
        raise node.problem(
            "controller_frequency",
            f"{frequency:g} Hz is a period longer than MPPI's model_dt ({model_dt:g} s): Nav2's "
            'MPPI refuses to start ("Controller period more then model dt")',
            f"write controller_frequency: {1.0 / model_dt:g}, or a shorter model_dt",
        )


def _dwb(node: NodeParameters, settings: Nav2Settings) -> Nav2Settings:
    """DWB as FollowPath: its own parameters, its critics and theirs (`Critic.scale`,
    `PathAlign.forward_point_distance`, `RotateToGoal.slowing_factor`, ...), over the code's
    defaults (`dwb.CODE_DEFAULTS`)."""
    if "FollowPath.critics" not in node.values:
        # Declared without a default (dwb_local_planner.cpp:81-83, 204-206 at jazzy f4108e5b).
        raise node.problem(
            "FollowPath.critics",
            'is not set: DWB refuses to configure ("No critics defined for FollowPath")',
            f"list the critics, e.g. critics: [{', '.join(DWB_CRITICS)}]",
        )
    critics = node.names("FollowPath.critics", DWB_CRITICS)
    unknown = [name for name in critics if name not in DWB_CRITICS]
    if unknown:
        raise node.problem(
            "FollowPath.critics",
            f"{unknown[0]} is a critic the DWB imitation does not have",
            f"leave it out, or use those it has: {', '.join(DWB_CRITICS)}",
        )
    if node.number("FollowPath.RotateToGoal.lookahead_time", -1.0) >= 0.0:
        raise node.problem(
            "FollowPath.RotateToGoal.lookahead_time",
            "only a negative lookahead_time (the trajectory's last pose) is imitated",
            "write -1.0, Nav2's default",
        )
    renamed = {
        f"{critic}.{leaf}": field.name
        for field in dataclasses.fields(DwbSettings)
        for critic in DWB_CRITICS
        for leaf in _critic_leaves(field.name, critic)
    }
    dwb = node.fields("FollowPath.", CODE_DEFAULTS, renamed, exclude=("critics",))
    dwb = dataclasses.replace(dwb, critics=critics)
    poses = rollout_poses(dwb)
    if poses > MAX_ROLLOUT_POSES:
        raise node.problem(
            "FollowPath.vx_samples",
            f"DWB would roll out {poses:,} poses every cycle (vx_samples x vtheta_samples "
            "trajectories of sim_time over the granularities' steps), more than the "
            f"{MAX_ROLLOUT_POSES:,} the gate accepts: a run would take hours",
            "lower vx_samples, vtheta_samples or sim_time, or raise linear_granularity and "
            "angular_granularity",
        )
    return dataclasses.replace(settings, dwb=dwb, prune_distance=dwb.prune_distance)


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


def _critics(node: NodeParameters, release: str) -> tuple[MppiCritic, ...]:
    """MPPI's critics in the order FollowPath.critics lists them (none if it is not set,
    critic_manager.cpp:39 at jazzy f4108e5b), each with its parameters over its own defaults;
    one with enabled false is left out."""
    by_name = code_default_critics(release)
    critics = []
    for name in node.names("FollowPath.critics", ()):
        if name in NOT_IMITATED_CRITICS:
            continue
        if name not in CRITICS:
            raise node.problem(
                "FollowPath.critics",
                f"{name} is a critic the MPPI imitation does not have",
                f"leave it out, or use those it has: {', '.join(CRITICS)}",
            )
        renamed = {"cost_weight": "weight", "cost_power": "power"}
        if node.flag(f"FollowPath.{name}.enabled", True):
            critics.append(node.fields(f"FollowPath.{name}.", by_name[name], renamed))
    return tuple(critics)


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
        _check_signs(node, name, (x, y, theta))
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


def _behavior_server(node: NodeParameters, settings: Nav2Settings) -> Nav2Settings:
    """The behaviour server's rate, its look ahead for collisions and Spin's speeds."""
    return dataclasses.replace(settings, behaviors=node.fields("", settings.behaviors))


READERS = {
    "controller_server": _controller_server,
    "local_costmap": _local_costmap,
    "global_costmap": _global_costmap,
    "planner_server": _planner_server,
    "velocity_smoother": _velocity_smoother,
    "collision_monitor": _collision_monitor,
    "behavior_server": _behavior_server,
}
