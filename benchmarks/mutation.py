"""How a fault of the mutation analysis (fault_finding.py) is put into a navigation stack.

A fault is a bug class written as a team would have it: a filter, driver or relay in front of the
stack, tuned for the scanner the robot had (the baseline), or the parameters the team set for it.
`Mutant` names one, its source and its stack (`Stack`: move_base, or Nav2, the default);
`mutant.factory(baseline)` builds the stack as the plugin builds it for the robot, with the
mutant's parameters, and puts the fault in front of it through the public controller interface
(`Clocked`, an `InFront`: every optional attribute of the stack kept). `bare(stack)` builds the
same stack without a fault. The faults themselves are in mutants.py (move_base) and
nav2_faults.py (Nav2).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

from pytest_lasertest.model.geometry import FloatArray, Point2D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.nav.move_base import MoveBase
from pytest_lasertest.nav.move_base.settings import NavigationSettings
from pytest_lasertest.nav.nav2.nav2 import Nav2
from pytest_lasertest.nav.nav2.params import configured
from pytest_lasertest.nav.nav2.settings import Nav2Settings
from pytest_lasertest.nav.protocol import (
    Controller,
    ControllerFactory,
    InFront,
    LaserScan,
    Odometry,
)

Command = tuple[float, float]  # m/s, rad/s
# The navigation stacks a fault can be put into.
Stack = Literal["move_base", "nav2"]
# The navigation parameters the team set for the baseline scanner, from the robot's own.
Setting = Callable[[NavigationSettings, LaserProfile], NavigationSettings]
Nav2Setting = Callable[[Nav2Settings, LaserProfile], Nav2Settings]


class Fault:
    """What the faulty code does to a scan on its way to the stack, and to the command back.
    One instance serves one run: a fault with memory (a median over scans) starts empty."""

    def scan(self, scan: LaserScan, odometry: Odometry) -> LaserScan:
        return scan

    def command(self, command: Command, scan: LaserScan) -> Command:
        return command

    def tick(self, time: float) -> None:
        """The time (s) of each call of the stack, scans' and its own clock's: a fault that
        keeps a clock of its own (a watchdog) reads it here."""


@dataclass(frozen=True)
class Mutant:
    """A fault class, where it comes from, and how to make it for a baseline scanner."""

    name: str
    bug: str  # what the code does wrong
    source: str  # the real case or the real code it imitates
    make: Callable[[LaserProfile], Fault]  # the fault, tuned for the baseline scanner
    equivalent: bool = False  # changes nothing the stack does with what the simulator publishes
    navigation: Setting | None = None  # move_base's parameters as the fault has them
    stack: Stack = "move_base"  # the stack it is put into
    nav2: Nav2Setting | None = None  # Nav2's parameters as the fault has them

    def __post_init__(self) -> None:
        other = self.nav2 if self.stack == "move_base" else self.navigation
        if other is not None:
            raise ValueError(f"{self.name} sets the parameters of a stack it is not put into")

    def factory(self, baseline: LaserProfile) -> ControllerFactory:
        """The stack, its parameters as the fault has them, with the fault tuned for `baseline`
        in front of it."""

        def make(robot: Robot, route: tuple[Point2D, ...]) -> Controller:
            fault = self.make(baseline)
            # In front of the stack as a filter node is, its optional attributes kept
            # (goal_tolerance, stuck_window, receive_map, ...): a fault changes scans only.
            return Clocked(
                self._stack(robot, route, baseline),
                lambda scan, odometry, time: fault.scan(scan, odometry),
                fault.command,
                fault=fault,
            )

        return make

    def _stack(
        self, robot: Robot, route: tuple[Point2D, ...], baseline: LaserProfile
    ) -> Controller:
        """The stack as the plugin builds it for `robot`, its parameters as the fault has them
        for `baseline` (`__post_init__` holds each setting to its own stack)."""
        if self.nav2 is not None:
            own = configured(robot.nav2, robot.nav2_release).settings
            return Nav2(robot, route, self.nav2(own, baseline))
        if self.navigation is not None:
            settings = NavigationSettings.from_parameters(robot.navigation)
            return MoveBase(robot, route, self.navigation(settings, baseline))
        return bare(self.stack)(robot, route)


def bare(stack: Stack) -> ControllerFactory:
    """The stack as the plugin builds it for the robot (its `controller: nav2` or the Husky's
    move_base), without a fault."""
    return Nav2 if stack == "nav2" else MoveBase


@dataclass
class Clocked(InFront):
    """`InFront` that tells its fault the time of every call, between scans too: InFront hands
    its filter only each new scan, and a fault on a clock of its own (a watchdog) acts between."""

    fault: Fault = dataclasses.field(default_factory=Fault)

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> Command:
        self.fault.tick(time)
        return super().observe(scan, odometry, time)


def with_ranges(scan: LaserScan, ranges: FloatArray, **meta: float) -> LaserScan:
    """`scan` reading `ranges` (m), its meta changed by `meta`, as a fault passes it on."""
    return LaserScan(scan.stamp, ranges, dataclasses.replace(scan.meta, **meta), scan.mount)
