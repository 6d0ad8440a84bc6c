"""What one planning cycle of a navigation stack costs, against the physics it controls, side
by side.

A cycle is what the stack does with a scan at its clocks: one costmap update (the paper's
720-beam, 50 Hz scan into the local costmap) and one command: DWA's for move_base (the Husky's
navigation stack), MPPI's with 2000 x 56 samples for Nav2 (Jazzy's defaults). The robot drives
the benchmark's four-obstacle scene; each update and each command is timed as the run makes
it. Right after, the same world is stepped bare through
the run's wheel speeds, and the cost of one control period (1 / controller_frequency s) of that
physics is what a cycle is compared with. The
last line reads `planning cycle: C ms; ratio to the physics of one control period: Q` (medians).

    python benchmarks/nav.py [--runs 3] [--controller move_base|nav2]
"""

from __future__ import annotations

import argparse
import statistics
from collections.abc import Callable
from time import perf_counter
from typing import Any

from sim import SIMULATED, WORLDS, bare_physics

from pytest_lasertest.model.geometry import Point2D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.nav.move_base import MoveBase
from pytest_lasertest.nav.nav2.nav2 import Nav2
from pytest_lasertest.nav.nav2.settings import Nav2Settings
from pytest_lasertest.sim.client import PhysicsClient
from pytest_lasertest.sim.scenario import run_scenario


class TimedMoveBase(MoveBase):
    """move_base, timing each costmap update and each DWA command it makes."""

    def __init__(self, robot: Robot, route: tuple[Point2D, ...]) -> None:
        super().__init__(robot, route)
        self.updates: list[float] = []  # s
        self.commands: list[float] = []  # s

    @property
    def controller_frequency(self) -> float:
        return self.settings.move_base.controller_frequency  # Hz

    def _start(self, pose: tuple[float, float, float], time: float) -> None:
        super()._start(pose, time)
        self.costmap.update = _timed(self.costmap.update, self.updates)  # type: ignore[method-assign]
        command = self.local_planner.command
        self.local_planner.command = _timed(command, self.commands)  # type: ignore[method-assign]


class TimedNav2(Nav2):
    """Nav2 with Jazzy's nav2_params.yaml (MPPI), timing each local costmap update and each
    MPPI command it makes."""

    def __init__(self, robot: Robot, route: tuple[Point2D, ...]) -> None:
        super().__init__(robot, route, Nav2Settings())
        self.updates: list[float] = []  # s
        self.commands: list[float] = []  # s
        self.local.update = _timed(self.local.update, self.updates)  # type: ignore[method-assign]
        self.controller.command = _timed(self.controller.command, self.commands)  # type: ignore[method-assign]

    @property
    def controller_frequency(self) -> float:
        return self.settings.controller_frequency  # Hz


Timed = TimedMoveBase | TimedNav2
TIMED: dict[str, type[TimedMoveBase] | type[TimedNav2]] = {
    "move_base": TimedMoveBase,
    "nav2": TimedNav2,
}


def _timed(function: Callable[..., Any], into: list[float]) -> Callable[..., Any]:
    """`function`, appending the wall time of each call to `into`."""

    def timed(*arguments: Any) -> Any:
        began = perf_counter()
        result = function(*arguments)
        into.append(perf_counter() - began)
        return result

    return timed


def _keeping(
    made: list[Timed], kind: type[TimedMoveBase] | type[TimedNav2]
) -> Callable[[Robot, tuple[Point2D, ...]], Timed]:
    """A factory of timed controllers of `kind` that appends each it makes to `made`."""

    def make(robot: Robot, route: tuple[Point2D, ...]) -> Timed:
        made.append(kind(robot, route))
        return made[-1]

    return make


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--controller", choices=list(TIMED), default="move_base")
    args = parser.parse_args()
    command_name = "DWA" if args.controller == "move_base" else "MPPI"
    cycles, ratios = [], []
    world = WORLDS["beside the route"]
    with PhysicsClient() as client:
        for _ in range(args.runs):
            made: list[Timed] = []
            scenario = world.scenario(SIMULATED)
            run = run_scenario(scenario, _keeping(made, TIMED[args.controller]), client)
            (controller,) = made
            period = 1.0 / controller.controller_frequency  # s
            steps = round(period / scenario.time_step)
            # The run's own wheel speeds, per step, as long as one control period.
            bare = bare_physics(scenario, run.driven, client) / len(run.driven) * steps
            update = statistics.median(controller.updates)
            command = statistics.median(controller.commands)
            print(
                f"{len(controller.updates)} costmap updates: {update * 1e3:.2f} ms; "
                f"{len(controller.commands)} {command_name} commands: {command * 1e3:.2f} ms; "
                f"physics of one {period * 1e3:.0f} ms control period: {bare * 1e3:.2f} ms"
            )
            cycles.append(update + command)
            ratios.append((update + command) / bare)
    print(
        f"planning cycle: {statistics.median(cycles) * 1e3:.2f} ms; "
        f"ratio to the physics of one control period: {statistics.median(ratios):.2f}"
    )


if __name__ == "__main__":
    main()
