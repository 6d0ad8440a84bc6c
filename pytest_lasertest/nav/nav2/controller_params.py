"""The controller server's parameters, as a params file sets them: its rate, the FollowPath
controller (MPPI or DWB) with its critics, and the progress and goal checkers. params.py reads
the other nodes and calls `read_controller_server` for this one."""

from __future__ import annotations

import dataclasses

from pytest_lasertest.nav.move_base.settings import MAX_ROLLOUT_POSES
from pytest_lasertest.nav.nav2.dwb_settings import CODE_DEFAULTS, DwbSettings
from pytest_lasertest.nav.nav2.dwb_settings import CRITICS as DWB_CRITICS
from pytest_lasertest.nav.nav2.dwb_trajectories import rollout_poses
from pytest_lasertest.nav.nav2.mppi import SAME_PERIOD
from pytest_lasertest.nav.nav2.node_parameters import NodeParameters
from pytest_lasertest.nav.nav2.settings import (
    CRITICS,
    MppiCritic,
    Nav2Settings,
    code_default_critics,
)

MPPI = "nav2_mppi_controller::MPPIController"
DWB = "dwb_core::DWBLocalPlanner"
# MPPI's samples x steps a cycle: nav2_params.yaml's 2000 x 56 is 112,000.
MAX_MPPI_POINTS = 1_000_000
# Read but not imitated, for a reason docs/explanation/navigation.md gives: the routes here
# have no goal heading.
NOT_IMITATED_CRITICS = frozenset({"GoalAngleCritic"})


def read_controller_server(node: NodeParameters, settings: Nav2Settings) -> Nav2Settings:
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
    # The goal's heading, read and checked, acts on nothing: a route's goal has none
    # (docs/explanation/navigation.md), as GoalAngleCritic is read and left out.
    node.flag(f"{goal}.stateful", True)
    node.number(f"{goal}.yaw_goal_tolerance", 0.25)
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
    defaults (`dwb_settings.CODE_DEFAULTS`)."""
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
    _check_lateral(node)
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


def _check_lateral(node: NodeParameters) -> None:
    """DWB's lateral limits, 0 by default (kinematic_parameters.cpp:75-96, vy_samples 5 at
    xy_theta_iterator.cpp:58, at jazzy f4108e5b), where a differential drive's file sets them:
    DWB samples lateral speeds between the limits as far as acc_lim_y and decel_lim_y reach
    from the robot's 0 (projectVelocity, one_d_velocity_iterator.hpp), so they sample 0 alone
    where the limits are both 0, or the accelerations are. Any other setting would roll out
    sideways motion these robots cannot make."""
    low = node.number("FollowPath.min_vel_y", 0.0)
    high = node.number("FollowPath.max_vel_y", 0.0)
    accel = node.number("FollowPath.acc_lim_y", 0.0)
    decel = node.number("FollowPath.decel_lim_y", 0.0)
    node.number("FollowPath.vy_samples", 5.0, whole=True)
    if (low, high) != (0.0, 0.0) and (accel, decel) != (0.0, 0.0):
        raise node.problem(
            "FollowPath.max_vel_y",
            f"DWB would sample lateral speeds from {low:g} to {high:g} m/s, which the "
            "robots here (differential drives) cannot make",
            "write min_vel_y: 0.0 and max_vel_y: 0.0",
        )


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
