"""The navigation stack's parameters, section by section, with ROS's names and defaults.

A robot's configuration (`robots/husky/navigation.yaml`) and a pairs file's `navigation:` set
some of them; everything else keeps the default of the ROS package it imitates. The sections:

- `move_base`: the state machine (`MoveBaseSettings`);
- `costmap`: costmap_2d's obstacle and inflation layers, shared by the global and the local
  costmap (`CostmapSettings`; its `size` is the local window's);
- `global_costmap`: the global costmap's own width (`GlobalCostmapSettings`);
- `navfn`: the global planner (`NavfnSettings`);
- `dwa`: the local planner (`DwaSettings`).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any

from pytest_lasertest.nav.move_base.costmap import CostmapSettings
from pytest_lasertest.nav.move_base.dwa import DwaSettings
from pytest_lasertest.nav.move_base.navfn import NavfnSettings

# One parameter as a configuration sets it: (section, name, value).
Parameter = tuple[str, str, float | bool]


@dataclass(frozen=True)
class MoveBaseSettings:
    """move_base's parameters, with its names; the defaults are its own."""

    controller_frequency: float = 20.0  # Hz
    planner_frequency: float = 0.0  # Hz; 0 plans only for a new goal or when control fails
    planner_patience: float = 5.0  # s without a plan before recovering
    controller_patience: float = 15.0  # s without a valid command before recovering
    oscillation_timeout: float = 0.0  # s; 0 never looks for oscillation
    oscillation_distance: float = 0.5  # m the robot must move to count as not oscillating
    recovery_behavior_enabled: bool = True
    clearing_rotation_allowed: bool = True
    conservative_reset_dist: float = 3.0  # m
    # Ours, not move_base's: back up before rotating in place, as a team would add it.
    back_up_recovery: bool = False
    back_up_distance: float = 0.5  # m
    back_up_speed: float = 0.1  # m/s
    # Ours: the planner searches the rectangle spanning the robot and its goal, widened by
    # this much on every side (navfn's planner_window_x/y restricts it the same way).
    planner_margin: float = 5.0  # m


@dataclass(frozen=True)
class GlobalCostmapSettings:
    """The global costmap's own parameters: it rolls with the robot as the local one does."""

    size: float = 100.0  # m, its width and height
    track_unknown_space: bool = True


@dataclass(frozen=True)
class NavigationSettings:
    """Every parameter of the navigation stack."""

    move_base: MoveBaseSettings = field(default_factory=MoveBaseSettings)
    costmap: CostmapSettings = field(default_factory=CostmapSettings)
    global_costmap: GlobalCostmapSettings = field(default_factory=GlobalCostmapSettings)
    navfn: NavfnSettings = field(default_factory=NavfnSettings)
    dwa: DwaSettings = field(default_factory=DwaSettings)

    @classmethod
    def from_parameters(cls, parameters: tuple[Parameter, ...]) -> NavigationSettings:
        """The defaults with `parameters` set, later ones winning. The names must be those of
        `parameter_types()`, as the pairs-file reader checks them; another fails here."""
        sections: dict[str, dict[str, Any]] = {}
        for section, name, value in parameters:
            sections.setdefault(section, {})[name] = value
        settings = cls()
        for section, values in sections.items():
            current = getattr(settings, section)
            settings = dataclasses.replace(
                settings, **{section: dataclasses.replace(current, **values)}
            )
        return settings


@dataclass(frozen=True)
class Limit:
    """The values a parameter accepts (its sign aside, which the reader checks), and why the
    rest are refused: what a value beyond would cost, or why it cannot be meant. Every limit is
    well beyond what ROS configurations use, so none of them is refused."""

    low: float
    high: float
    unit: str
    why: str  # why a value above `high` is refused
    why_low: str = ""  # why one below `low` is, when that is another reason

    @property
    def below(self) -> str:
        """Why a value below `low` is refused."""
        return self.why_low or self.why


_RATE = "the simulation steps at 50 Hz, and each cycle computes a plan or a command"
_PATIENCE = "no run lasts more than an hour (the largest time_limit)"
_DISTANCE = "a distance that large is beyond any route the gate drives"
_SPEED = "at 20 m/s the robot moves 0.4 m in one 20 ms physics step"
_TURN = "at 20 rad/s the robot turns 0.4 rad in one 20 ms physics step"
_WEIGHT = "a weight that large drowns every other term of the score"
_SELDOM = "less often than every 10 s, the robot drives on without looking"
_COARSE = "a cell wider than 1 m swallows the obstacles the gate places"
_CELLS = (
    "the costmap is size / resolution cells a side, and every update raytraces and inflates them"
)
LIMITS: dict[str, dict[str, Limit]] = {
    "move_base": {
        "controller_frequency": Limit(0.1, 100.0, "Hz", _RATE, _SELDOM),
        "planner_frequency": Limit(0.0, 100.0, "Hz", _RATE),
        "planner_patience": Limit(0.0, 3600.0, "s", _PATIENCE),
        "controller_patience": Limit(0.0, 3600.0, "s", _PATIENCE),
        "oscillation_timeout": Limit(0.0, 3600.0, "s", _PATIENCE),
        "oscillation_distance": Limit(0.0, 100.0, "m", _DISTANCE),
        "conservative_reset_dist": Limit(0.0, 1000.0, "m", _DISTANCE),
        "back_up_distance": Limit(0.0, 100.0, "m", _DISTANCE),
        "back_up_speed": Limit(0.0, 20.0, "m/s", _SPEED),
        "planner_margin": Limit(0.0, 1000.0, "m", "navfn searches every cell of the margin"),
    },
    "costmap": {
        "size": Limit(0.5, 200.0, "m", _CELLS, "the window must hold the robot"),
        "resolution": Limit(0.005, 1.0, "m", _COARSE, _CELLS),
        "obstacle_range": Limit(0.0, 1000.0, "m", "no 2D scanner reaches further"),
        "raytrace_range": Limit(0.0, 1000.0, "m", "no 2D scanner reaches further"),
        "inflation_radius": Limit(0.0, 50.0, "m", "every lethal cell inflates this far round it"),
        "cost_scaling_factor": Limit(0.0, 1000.0, "1/m", "the costs fall to nothing in a cell"),
        "update_frequency": Limit(0.1, 100.0, "Hz", _RATE, _SELDOM),
    },
    "global_costmap": {"size": Limit(1.0, 1000.0, "m", _CELLS, "the map must hold the robot")},
    "navfn": {
        "default_tolerance": Limit(0.0, 100.0, "m", _DISTANCE),
        "neutral_cost": Limit(
            1, 252, "", "navfn's costs are bytes below its lethal 253", "a free cell must cost"
        ),
        "cost_factor": Limit(0.0, 100.0, "", _WEIGHT),
    },
    "dwa": {
        "max_vel_x": Limit(0.0, 20.0, "m/s", _SPEED),
        "min_vel_x": Limit(-20.0, 20.0, "m/s", _SPEED),
        "max_trans_vel": Limit(0.0, 20.0, "m/s", _SPEED),
        "min_trans_vel": Limit(0.0, 20.0, "m/s", _SPEED),
        "max_rot_vel": Limit(0.0, 20.0, "rad/s", _TURN),
        "min_rot_vel": Limit(0.0, 20.0, "rad/s", _TURN),
        "acc_lim_x": Limit(0.0, 100.0, "m/s^2", "10 g is beyond any wheeled robot"),
        "acc_lim_theta": Limit(0.0, 1000.0, "rad/s^2", "no wheeled robot turns that fast"),
        "sim_time": Limit(0.0, 30.0, "s", "every trajectory is rolled out that far ahead"),
        "sim_granularity": Limit(0.001, 10.0, "m", "finer, every trajectory takes more steps"),
        "angular_sim_granularity": Limit(0.001, 10.0, "rad", "finer, more steps"),
        "vx_samples": Limit(1, 100, "", "every cycle rolls out vx_samples x vth_samples"),
        "vth_samples": Limit(1, 200, "", "every cycle rolls out vx_samples x vth_samples"),
        "path_distance_bias": Limit(0.0, 10_000.0, "", _WEIGHT),
        "goal_distance_bias": Limit(0.0, 10_000.0, "", _WEIGHT),
        "occdist_scale": Limit(0.0, 10_000.0, "", _WEIGHT),
        "forward_point_distance": Limit(0.0, 10.0, "m", "the nose point lies on the robot"),
        "scaling_speed": Limit(0.0, 20.0, "m/s", _SPEED),
        "max_scaling_factor": Limit(0.0, 10.0, "", "the footprint grows by this factor"),
        "xy_goal_tolerance": Limit(0.0, 10.0, "m", "the goal would be reached before setting off"),
        "oscillation_reset_dist": Limit(0.0, 100.0, "m", _DISTANCE),
        "oscillation_reset_angle": Limit(0.0, 6.2832, "rad", "a turn is 6.2832 rad"),
    },
}
# A costmap of this many cells a side holds 16 million cells: 4000 at the default 0.05 m is 200 m.
MAX_CELLS = 4000
# DWA rolls out every sample for sim_time at every control cycle: poses = samples x steps. The
# Husky's configuration rolls out about 5,000.
MAX_ROLLOUT_POSES = 200_000


@dataclass(frozen=True)
class Clash:
    """Parameters that are each within their limits but not together: which, why, the fix."""

    names: tuple[tuple[str, str], ...]  # (section, name)
    problem: str
    fix: str


def clashes(settings: NavigationSettings) -> list[Clash]:
    """What is wrong with these parameters together: a costmap too large for its resolution,
    more DWA rollout poses than a control cycle can afford, a least speed above the most."""
    found = [*_too_many_cells(settings), *_inverted(settings.dwa)]
    poses = rollout_poses(settings.dwa)
    if poses > MAX_ROLLOUT_POSES:
        found.append(
            Clash(
                tuple(("dwa", name) for name in _ROLLOUT_NAMES),
                f"DWA would roll out {poses:,} poses every control cycle (vx_samples x "
                "vth_samples trajectories, each of sim_time / sim_granularity steps), more "
                f"than the {MAX_ROLLOUT_POSES:,} the gate accepts: a run would take hours",
                "lower vx_samples, vth_samples or sim_time, or raise sim_granularity and "
                "angular_sim_granularity",
            )
        )
    return found


_ROLLOUT_NAMES = (
    "vx_samples",
    "vth_samples",
    "sim_time",
    "sim_granularity",
    "angular_sim_granularity",
    "max_vel_x",
    "min_vel_x",
    "max_trans_vel",
    "max_rot_vel",
)


def rollout_poses(dwa: DwaSettings) -> int:
    """The most poses DWA rolls out in one control cycle: the sampled velocities (with the 0
    DWA adds between a negative and a positive one), each for sim_time in steps of at most
    sim_granularity m and angular_sim_granularity rad."""
    speed = max(min(dwa.max_vel_x, dwa.max_trans_vel), abs(dwa.min_vel_x))  # m/s
    steps = math.ceil(
        dwa.sim_time
        * max(speed / dwa.sim_granularity, dwa.max_rot_vel / dwa.angular_sim_granularity)
    )
    samples = (max(dwa.vx_samples, 2) + 1) * (max(dwa.vth_samples, 2) + 1)
    return samples * max(steps, 1)


def _too_many_cells(settings: NavigationSettings) -> list[Clash]:
    """The local costmap: the global one's width depends on the route (`costmap_cells`)."""
    cells = costmap_cells(settings.costmap.size, settings.costmap.resolution)
    if cells is None:
        return []
    return [Clash((("costmap", "size"), ("costmap", "resolution")), *cells)]


def costmap_cells(size: float, resolution: float, what: str = "local") -> tuple[str, str] | None:
    """Why a costmap `size` m wide at `resolution` m has too many cells, and the fix; None
    when it has few enough."""
    cells = size / resolution
    if cells <= MAX_CELLS:
        return None
    return (
        f"the {what} costmap would be {size:g} m / {resolution:g} m = {cells:,.0f} cells a "
        f"side, more than the {MAX_CELLS} the gate accepts: {cells**2:,.0f} cells, raytraced "
        "and inflated at every update",
        f"coarsen costmap.resolution to at least {size / MAX_CELLS:g} m, or make the costmap "
        f"at most {MAX_CELLS * resolution:g} m wide",
    )


def global_costmap_size(settings: NavigationSettings, span: float) -> float:
    """How wide the global costmap of a run is (m): global_costmap.size, cut to what a run whose
    start and waypoints lie within `span` m of each other can mark, clear and plan through."""
    common, move_base = settings.costmap, settings.move_base
    needed = 2.0 * (
        span + move_base.planner_margin + common.inflation_radius + common.raytrace_range
    )
    return min(settings.global_costmap.size, needed)


def _inverted(dwa: DwaSettings) -> list[Clash]:
    found = []
    for least, most in (
        ("min_vel_x", "max_vel_x"),
        ("min_trans_vel", "max_trans_vel"),
        ("min_rot_vel", "max_rot_vel"),
    ):
        low, high = getattr(dwa, least), getattr(dwa, most)
        if low > high:
            found.append(
                Clash(
                    (("dwa", least), ("dwa", most)),
                    f"{least} ({low:g}) is above {most} ({high:g}): DWA would sample no "
                    "velocity it may drive, and the robot would never move",
                    f"make {least} at most {most}",
                )
            )
    return found


def parameter_types() -> dict[str, dict[str, type]]:
    """Each section's parameters and the type of their values: bool, int or float."""
    defaults = NavigationSettings()
    return {
        section.name: {
            parameter.name: type(getattr(getattr(defaults, section.name), parameter.name))
            for parameter in dataclasses.fields(getattr(defaults, section.name))
        }
        for section in dataclasses.fields(defaults)
    }
