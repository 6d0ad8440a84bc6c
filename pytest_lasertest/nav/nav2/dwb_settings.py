"""DWB's parameters (FollowPath's, with Nav2's names): Humble's nav2_bringup values as
`DwbSettings`' defaults, and DWB's own code defaults (`CODE_DEFAULTS`), which a team's params
file reads over. Read in ros-navigation/navigation2 at
humble@3c3db59d6969d8ecee8e68468693d006397f4a0c (nav2_bringup/params/nav2_params.yaml, and the
nav2_dwb_controller sources cited below)."""

from __future__ import annotations

from dataclasses import dataclass

CRITICS = (
    "RotateToGoal",
    "Oscillation",
    "BaseObstacle",
    "GoalAlign",
    "PathAlign",
    "PathDist",
    "GoalDist",
)
# Their scale is multiplied by half the costmap's resolution (MapGridCritic::getScale).
MAP_GRID_CRITICS = frozenset({"GoalAlign", "PathAlign", "PathDist", "GoalDist"})


@dataclass(frozen=True)
class DwbSettings:
    """FollowPath's parameters, with Nav2's names; defaults from Humble's nav2_params.yaml, or
    the sources' where it sets none."""

    min_vel_x: float = 0.0  # m/s
    max_vel_x: float = 0.26  # m/s
    max_vel_theta: float = 1.0  # rad/s
    min_speed_xy: float = 0.0  # m/s
    max_speed_xy: float = 0.26  # m/s
    min_speed_theta: float = 0.0  # rad/s
    acc_lim_x: float = 2.5  # m/s^2
    acc_lim_theta: float = 3.2  # rad/s^2
    decel_lim_x: float = -2.5  # m/s^2
    decel_lim_theta: float = -3.2  # rad/s^2
    vx_samples: int = 20
    vtheta_samples: int = 20
    sim_time: float = 1.7  # s
    linear_granularity: float = 0.05  # m
    angular_granularity: float = 0.025  # rad
    xy_goal_tolerance: float = 0.25  # m
    trans_stopped_velocity: float = 0.25  # m/s
    short_circuit_trajectory_evaluation: bool = True  # changes no result: see the module
    prune_distance: float = 2.0  # m (source default)
    forward_prune_distance: float = 2.0  # m (source default)
    critics: tuple[str, ...] = CRITICS
    rotate_to_goal_scale: float = 32.0
    oscillation_scale: float = 1.0  # (source default)
    base_obstacle_scale: float = 0.02
    goal_align_scale: float = 24.0
    path_align_scale: float = 32.0
    path_dist_scale: float = 32.0
    goal_dist_scale: float = 24.0
    path_align_forward_point_distance: float = 0.1  # m
    goal_align_forward_point_distance: float = 0.1  # m
    slowing_factor: float = 5.0  # RotateToGoal's
    lookahead_time: float = -1.0  # s, RotateToGoal's: negative, the last pose
    oscillation_reset_dist: float = 0.05  # m (source default)
    oscillation_reset_angle: float = 0.2  # rad (source default)
    x_only_threshold: float = 0.05  # m/s, Oscillation's (source default)
    include_last_point: bool = True  # (source default, standard_traj_generator.cpp:76)

    def __post_init__(self) -> None:
        if self.lookahead_time >= 0.0:
            raise ValueError("only a negative lookahead_time (the last pose) is imitated")
        unknown = set(self.critics) - set(CRITICS)
        if unknown:
            raise ValueError(f"critics not imitated: {sorted(unknown)}")

    def scale(self, critic: str) -> float:
        """The critic's scale parameter."""
        return float(getattr(self, _snake(critic) + "_scale"))


def _snake(name: str) -> str:
    return "".join("_" + c.lower() if c.isupper() else c for c in name).lstrip("_")


# DWB's own defaults, for a params file that leaves a parameter out: the kinematic limits 0
# (kinematic_parameters.cpp:74-99), linear_granularity 0.5 (standard_traj_generator.cpp:68-70),
# every critic's scale 1.0 (trajectory_critic.hpp:105-110) and the align critics'
# forward_point_distance 0.325 (path_align.cpp:55-57, goal_align.cpp:55-57), at humble 3c3db59d
# as at jazzy f4108e5b; the rest as DwbSettings holds them (the code's own figures).
CODE_DEFAULTS = DwbSettings(
    max_vel_x=0.0,
    max_vel_theta=0.0,
    max_speed_xy=0.0,
    acc_lim_x=0.0,
    acc_lim_theta=0.0,
    decel_lim_x=0.0,
    decel_lim_theta=0.0,
    linear_granularity=0.5,
    rotate_to_goal_scale=1.0,
    base_obstacle_scale=1.0,
    goal_align_scale=1.0,
    path_align_scale=1.0,
    path_dist_scale=1.0,
    goal_dist_scale=1.0,
    path_align_forward_point_distance=0.325,
    goal_align_forward_point_distance=0.325,
)
