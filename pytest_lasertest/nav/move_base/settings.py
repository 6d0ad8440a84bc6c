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
