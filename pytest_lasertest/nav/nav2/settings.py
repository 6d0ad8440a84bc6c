"""Nav2's parameters as the imitation holds them, and the release whose obstacle layer marks
the scan (`RELEASES`).

Without a params file they are Jazzy's nav2_params.yaml (nav2_bringup/params/nav2_params.yaml
at jazzy f4108e5b), and the robot's own footprint. A team's params file sets them through
`params.py` over `code_defaults`: what it leaves out takes the value Nav2's code declares for
the release, as a launch given that file alone would run.
"""

from __future__ import annotations

import dataclasses
import math
import re
from dataclasses import dataclass, field

from pytest_lasertest.model.robot import pad_footprint
from pytest_lasertest.nav.move_base.costmap import CostmapSettings
from pytest_lasertest.nav.move_base.navfn import NavfnSettings
from pytest_lasertest.nav.move_base.static_layer import StaticLayerSettings
from pytest_lasertest.nav.nav2.behaviors import BehaviorSettings
from pytest_lasertest.nav.nav2.collision_monitor import CollisionMonitorSettings
from pytest_lasertest.nav.nav2.critics import (
    ConstraintCritic,
    CostCritic,
    GoalCritic,
    PathAlignCritic,
    PathAngleCritic,
    PathFollowCritic,
    PreferForwardCritic,
)
from pytest_lasertest.nav.nav2.dwb_settings import DwbSettings
from pytest_lasertest.nav.nav2.mppi import MppiSettings
from pytest_lasertest.nav.nav2.obstacle_layer import Marking, ObservationSource
from pytest_lasertest.nav.nav2.velocity_smoother import SmootherSettings

MppiCritic = (
    ConstraintCritic
    | CostCritic
    | GoalCritic
    | PathAlignCritic
    | PathAngleCritic
    | PathFollowCritic
    | PreferForwardCritic
)
# The critics of Jazzy's nav2_params.yaml we imitate, by the names a params file lists them.
CRITICS: dict[str, type[MppiCritic]] = {
    kind.__name__: kind
    for kind in (
        ConstraintCritic,
        CostCritic,
        GoalCritic,
        PathAlignCritic,
        PathFollowCritic,
        PathAngleCritic,
        PreferForwardCritic,
    )
}
# How each release's ObstacleLayer decides that a point is near enough to mark (read in
# navigation2: kilted 71a1d84f; jazzy f4108e5b, release 1.3.13, with #5775 first released in
# 1.3.11 and #6119 in 1.3.12; humble 3c3db59d6, where #5891 backported #5775 and #6092's
# pre-filter has not followed).
RELEASES: dict[str, Marking] = {
    "kilted": Marking.EUCLIDEAN,
    "jazzy": Marking.CELLS_PREFILTERED,
    "humble": Marking.CELLS,
}
NEWEST_JAZZY = 13  # 1.3.13, the newest Jazzy release read
_JAZZY_RELEASE = re.compile(r"1\.3\.(\d+)")


def marking_of(release: str) -> Marking | None:
    """The marking rule of a release (`jazzy`, `kilted`, `humble`, or a Jazzy release number
    from 1.3.0 to 1.3.13); None for any other."""
    if release in RELEASES:
        return RELEASES[release]
    number = _JAZZY_RELEASE.fullmatch(release)
    if number is None or int(number.group(1)) > NEWEST_JAZZY:
        return None
    patch = int(number.group(1))
    if patch <= 10:
        return Marking.EUCLIDEAN
    return Marking.CELLS if patch == 11 else Marking.CELLS_PREFILTERED


def _default_critics() -> tuple[MppiCritic, ...]:
    return (
        ConstraintCritic(MppiSettings()),
        CostCritic(),
        GoalCritic(),
        PathAlignCritic(),
        PathFollowCritic(),
        PathAngleCritic(),
        PreferForwardCritic(),
    )


@dataclass(frozen=True)
class CostmapConfig:
    """One of Nav2's two costmaps: its window and inflation, its laser source, the
    footprint it plans for (None: the robot's), and its static layer if it takes the world's
    map (only the global costmap's is read: see `Nav2.receive_map`)."""

    costmap: CostmapSettings
    source: ObservationSource = field(default_factory=ObservationSource)
    footprint: tuple[tuple[float, float], ...] | None = None  # m
    # With the costmap's track_unknown_space as configured: without a map `costmap` has it
    # false, the static layer standing for an open field's map, all free.
    static_layer: StaticLayerSettings | None = None


def _local() -> CostmapConfig:
    return CostmapConfig(
        CostmapSettings(
            size=3.0, inflation_radius=0.70, cost_scaling_factor=3.0, update_frequency=5.0
        )
    )


def _global() -> CostmapConfig:
    # Nav2 tracks unknown space here, but its static layer has the map's free space known
    # from the start; a world without a map is open ground, its map all free. Given the world's
    # map, the costmap tracks unknown space as nav2_params.yaml sets it (true).
    return CostmapConfig(
        CostmapSettings(
            size=100.0,
            inflation_radius=0.70,
            cost_scaling_factor=3.0,
            update_frequency=1.0,
            track_unknown_space=False,
        ),
        static_layer=StaticLayerSettings.nav2(track_unknown_space=True),
    )


@dataclass(frozen=True)
class Nav2Settings:
    """Nav2's parameters as Jazzy's nav2_params.yaml sets them, and the release imitated."""

    release: str = "jazzy"
    mppi: MppiSettings = field(default_factory=MppiSettings)
    # FollowPath: MPPI (Jazzy's default), or DWB (Humble's) when this is set.
    dwb: DwbSettings | None = None
    critics: tuple[MppiCritic, ...] = field(default_factory=_default_critics)
    local: CostmapConfig = field(default_factory=_local)
    global_: CostmapConfig = field(default_factory=_global)
    navfn: NavfnSettings = field(
        default_factory=lambda: NavfnSettings(allow_unknown=True, default_tolerance=0.5)
    )
    # Ours, not Nav2's: NavFn searches the rectangle spanning the robot and its goal widened
    # by this much (as move_base's here), not the whole global costmap; a plan that must
    # leave it is not found. Nav2's NavFn stops once its wave reaches the robot, so it seldom
    # looks much further.
    planner_margin: float = 5.0  # m
    controller_frequency: float = 20.0  # Hz
    replan_period: float = 1.0  # s, the behaviour tree's RateController
    prune_distance: float = 1.7  # m
    # MPPI's path handler's bound on its search for the plan's pose nearest the robot; None:
    # half the local costmap's side, its default (path_handler.cpp getMaxCostmapDist).
    max_robot_pose_search_dist: float | None = None  # m
    xy_goal_tolerance: float = 0.25  # m
    required_movement_radius: float = 0.5  # m
    movement_time_allowance: float = 10.0  # s
    number_of_retries: int = 6  # the tree's NavigateRecovery
    collision_monitor: CollisionMonitorSettings | None = field(
        default_factory=CollisionMonitorSettings
    )
    smoother: SmootherSettings = field(default_factory=SmootherSettings)
    behaviors: BehaviorSettings = field(default_factory=BehaviorSettings)

    @property
    def marking(self) -> Marking:
        """The release's marking rule (`release` is checked where it is read)."""
        marking = marking_of(self.release)
        if marking is None:
            raise ValueError(f"no Nav2 release {self.release!r}")
        return marking


def describe(settings: Nav2Settings) -> str:
    """`Nav2 jazzy: NavFn, MPPI, collision monitor 1.2 s`: what the imitation runs."""
    follow = "MPPI" if settings.dwb is None else "DWB"
    monitor = settings.collision_monitor
    guard = (
        "no collision monitor"
        if monitor is None
        else (f"collision monitor {monitor.time_before_collision:g} s")
    )
    return f"Nav2 {settings.release}: NavFn, {follow}, {guard}"


# Costmap2DROS's robot_radius and footprint_padding where a file sets neither footprint nor
# robot_radius (costmap_2d_ros.cpp:114, :128 at jazzy f4108e5b; the same at humble 3c3db59d).
DEFAULT_ROBOT_RADIUS = 0.1  # m
DEFAULT_FOOTPRINT_PADDING = 0.01  # m


def radius_footprint(radius: float, padding: float) -> tuple[tuple[float, float], ...]:
    """makeFootprintFromRadius: 16 points on the circle, padded as Costmap2DROS pads every
    footprint it is given (setRobotFootprint, costmap_2d_ros.cpp:487-490 at jazzy f4108e5b)."""
    circle = tuple(
        (radius * math.cos(2 * math.pi * i / 16), radius * math.sin(2 * math.pi * i / 16))
        for i in range(16)
    )
    return pad_footprint(circle, padding)


def code_defaults(release: str) -> Nav2Settings:
    """The settings of a params file that sets nothing: each parameter as Nav2's code declares
    it (read at jazzy f4108e5b and humble 3c3db59d; kilted and the Jazzy release numbers as
    Jazzy). Where the code gives no default (DWB's critics, the collision monitor's polygons
    and sources) the params reader asks the file for it."""
    return Nav2Settings(
        release=release,
        # optimizer.cpp:72, noise_generator.cpp:35
        mppi=MppiSettings(batch_size=1000, regenerate_noises=False),
        critics=(),  # critic_manager.cpp:39: no critic unless `critics` lists it
        local=dataclasses.replace(_code_default_costmap(5.0), static_layer=None),
        # Not rolling by default (costmap_2d_ros.cpp:129): the global costmap spans the map,
        # here the window over the route (see `global_costmap.make_global_costmap`).
        global_=_code_default_costmap(_global().costmap.size),
        prune_distance=1.5,  # MPPI's, path_handler.cpp:38
        collision_monitor=CollisionMonitorSettings(time_before_collision=2.0, min_points=4),
        smoother=SmootherSettings(max_velocity=(0.5, 2.5), min_velocity=(-0.5, -2.5)),
        # The rest as nav2_params.yaml sets them, the same figures as the code's:
        # controller_server.cpp:52, simple_goal_checker.cpp:73-75, simple_progress_checker.cpp
        # :40-43, navfn_planner.cpp:84-88, behavior_server.cpp:50 and spin.cpp:53-71.
    )


def code_default_critics(release: str) -> dict[str, MppiCritic]:
    """Each MPPI critic as its own initialize() declares its parameters (mppi/src/critics at
    jazzy f4108e5b; PathAngleCritic's weight and angle at humble 3c3db59d)."""
    humble = release == "humble"
    return {
        "ConstraintCritic": ConstraintCritic(MppiSettings()),
        "CostCritic": CostCritic(near_goal_distance=0.5),  # cost_critic.cpp:32
        "GoalCritic": GoalCritic(),
        "PathAlignCritic": PathAlignCritic(weight=10.0, max_path_occupancy_ratio=0.07),  # :27, :29
        "PathFollowCritic": PathFollowCritic(offset_from_furthest=6),  # path_follow_critic.cpp:30
        # path_angle_critic.cpp:39, :43-45 (humble :37, :41-43)
        "PathAngleCritic": PathAngleCritic(
            weight=2.0 if humble else 2.2, max_angle_to_furthest=1.2 if humble else 0.785398
        ),
        "PreferForwardCritic": PreferForwardCritic(),
    }


def _code_default_costmap(size: float) -> CostmapConfig:
    """Costmap2DROS's own defaults (costmap_2d_ros.cpp:114-136 at jazzy f4108e5b): a window of
    `size` m (the code's 5 for a rolling one) of 0.1 m cells at 5 Hz, the default layers'
    inflation (inflation_layer.cpp:93-94), a source that clears nothing and keeps only points at
    most 0.0 m high (obstacle_layer.cpp:149-157), the 0.1 m circle, and a static layer (the
    default plugins list it first; only the global costmap's is read, see `Nav2.receive_map`)."""
    return CostmapConfig(
        CostmapSettings(size=size, resolution=0.1, update_frequency=5.0),
        source=ObservationSource(clearing=False, max_obstacle_height=0.0),
        footprint=radius_footprint(DEFAULT_ROBOT_RADIUS, DEFAULT_FOOTPRINT_PADDING),
        static_layer=StaticLayerSettings.nav2(track_unknown_space=False),
    )
