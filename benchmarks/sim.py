"""How fast a robot run simulates, against bare PyBullet stepping, measured side by side.

Each robot run drives the Husky with the paper's 720-beam, 50 Hz scanner and a controller (the
Husky's move_base by default, Nav2 with Jazzy's nav2_params.yaml, or the reactive reference)
for 30 s of simulated time, in an empty world, past one obstacle beside its route (as a
placement item drives) or past four; and down the warehouse aisle of examples/worlds (a
map_server map: two racks of shelving either side of a 1.6 m aisle, ending at the bay's wall),
beside the same route in an empty world, to the aisle's far end.
Right after each run, the same world (robot, ground, obstacles) is stepped bare through the
wheel speeds the run drove: the same physics, with no scans, no controller and no oracles. That
is the floor a run cannot beat. (Stepping wheels held at one speed instead costs PyBullet about
15 % more, which would flatter the ratio.) Then many short runs in one process check that memory
and physics clients are released. Every world is built in one physics client, reset for it, as
the plugin does. A line then compares the aisle with its route without walls: the real-time
factor of each (medians), and how many times as much a simulated second costs with the map. The
last line reads `real-time factor: R; ratio to bare physics: Q` (medians over the first three
worlds, as before the aisle was added).

    python benchmarks/sim.py [--runs 15] [--memory-runs 1000] [--controller move_base|nav2|reactive]
"""

from __future__ import annotations

import argparse
import statistics
import time
from dataclasses import dataclass
from pathlib import Path

from pytest_lasertest.model.geometry import FloatArray, Point2D, Pose2D
from pytest_lasertest.model.obstacles import Box, Cylinder, Obstacle
from pytest_lasertest.model.walls import NO_WALLS, Walls
from pytest_lasertest.nav.move_base import MoveBase
from pytest_lasertest.nav.nav2.nav2 import Nav2
from pytest_lasertest.nav.nav2.settings import Nav2Settings
from pytest_lasertest.nav.protocol import ControllerFactory
from pytest_lasertest.nav.reactive import ReactiveController
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.sim.client import PhysicsClient, PhysicsWorld, connected_clients
from pytest_lasertest.sim.scenario import Scenario, run_scenario

REPO = Path(__file__).resolve().parent.parent
PAPER = load_pairs_file(REPO / "examples" / "paper.lasertest.yaml")
AISLE = load_pairs_file(REPO / "examples" / "worlds" / "aisle.lasertest.yaml").world
SCANNER = next(pair for pair in PAPER.pairs if pair.name == "distance").baseline.profile
SIMULATED = 30.0  # s per run
CONTROLLERS: dict[str, ControllerFactory] = {
    "move_base": MoveBase,
    # Jazzy's nav2_params.yaml (MPPI), whatever the robot's own Nav2 file says.
    "nav2": lambda robot, route: Nav2(robot, route, Nav2Settings()),
    "reactive": ReactiveController,
}
START = Pose2D(0.0, 0.0, 0.0)
ROUTE = (Point2D(30.0, 0.0),)  # beyond what 30 s at 0.5 m/s reaches: the run lasts 30 s


@dataclass(frozen=True)
class World:
    """Where a run drives: what stands there, and the route from the start."""

    obstacles: tuple[Obstacle, ...] = ()
    walls: Walls = NO_WALLS
    start: Pose2D = START
    route: tuple[Point2D, ...] = ROUTE

    def scenario(self, time_limit: float) -> Scenario:
        """The Husky with the paper's scanner, driving here for at most `time_limit` s."""
        return Scenario(
            PAPER.robot,
            SCANNER,
            self.obstacles,
            self.start,
            self.route,
            time_limit,
            seed=0,
            walls=self.walls,
        )


# Beside the route, inside the scanner's range for most of the run.
BESIDE = (
    Box(4.0, 1.6, 0.3, 0.6, 0.4, 1.0),
    Cylinder(7.0, -1.5, 0.1, 1.0),
    Box(10.0, 2.0, 0.0, 1.0, 0.3, 1.0),
    Cylinder(13.0, 1.4, 0.05, 1.0),
)
WORLDS: dict[str, World] = {
    "empty": World(),
    # What a placement item drives past: one obstacle near the route.
    "one beside the route": World((Box(6.0, 0.8, 0.3, 0.4, 0.4, 1.0),)),
    "beside the route": World(BESIDE),
    # The aisle, and its route in an empty world: what the map costs, side by side.
    "aisle": World(walls=AISLE.walls, start=AISLE.start, route=AISLE.route),
    "aisle's route, no walls": World(start=AISLE.start, route=AISLE.route),
}
WITH_MAP, WITHOUT_MAP = "aisle", "aisle's route, no walls"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=15, help="robot runs, taking turns by world")
    parser.add_argument("--memory-runs", type=int, default=1000)
    parser.add_argument("--controller", choices=list(CONTROLLERS), default="move_base")
    args = parser.parse_args()
    controller = CONTROLLERS[args.controller]
    measured: dict[str, list[tuple[float, float]]] = {name: [] for name in WORLDS}
    names = list(WORLDS)
    # One client for every world, as the plugin keeps one per process.
    with PhysicsClient() as client:
        for index in range(args.runs):
            name = names[index % len(names)]
            measured[name].append(one_run(name, WORLDS[name], controller, client))
        memory(args.memory_runs, controller, client)
    print(f"{connected_clients()} physics clients left connected")
    print(map_cost(measured))
    aisle = {WITH_MAP, WITHOUT_MAP}
    first = [run for name, runs in measured.items() if name not in aisle for run in runs]
    print(
        f"real-time factor: {statistics.median(f for f, _ in first):.0f}; "
        f"ratio to bare physics: {statistics.median(r for _, r in first):.2f}"
    )


def map_cost(measured: dict[str, list[tuple[float, float]]]) -> str:
    """The aisle against its route without walls, by real-time factor (medians)."""
    with_map, without = measured[WITH_MAP], measured[WITHOUT_MAP]
    if not with_map or not without:
        return f"map: not measured (fewer than {len(WORLDS)} runs)"
    walled = statistics.median(f for f, _ in with_map)
    empty = statistics.median(f for f, _ in without)
    return (
        f"map: real-time factor {walled:.0f} in the aisle, {empty:.0f} on its route without "
        f"walls; a simulated second costs {empty / walled:.2f} times as much with the map"
    )


def one_run(
    name: str, world: World, controller: ControllerFactory, client: PhysicsClient
) -> tuple[float, float]:
    """A robot run in the world, then a bare stepping of it: (real-time factor, ratio)."""
    scenario = world.scenario(SIMULATED)
    began = time.perf_counter()
    run = run_scenario(scenario, controller, client)
    wall = time.perf_counter() - began
    bare = bare_physics(scenario, run.driven, client)
    simulated = float(run.times[-1])
    factor, ratio = simulated / wall, wall / bare
    print(
        f"{name}: {simulated:.1f} s simulated in {wall:.3f} s, real-time factor {factor:.0f}; "
        f"bare physics {bare:.3f} s; ratio {ratio:.2f}; {run.scans} scans; "
        f"{'passed' if run.passed else '; '.join(run.verdicts.failures())}"
    )
    return factor, ratio


def bare_physics(scenario: Scenario, wheels: FloatArray, client: PhysicsClient) -> float:
    """Wall time (s) of stepping the scenario's world (its obstacles and walls) through the
    wheel speeds (T, 2) rad/s of a run of it: the same physics, without the scans, the
    controller or the oracles."""
    with PhysicsWorld(scenario.start, scenario.solids, scenario.time_step, client) as world:
        began = time.perf_counter()
        for left, right in wheels.tolist():
            world.step(left, right)
        return time.perf_counter() - began


def memory(runs: int, controller: ControllerFactory, client: PhysicsClient) -> None:
    """Resident memory growth over `runs` one-second robot runs, after ten to warm up."""
    scenario = WORLDS["beside the route"].scenario(1.0)
    for _ in range(10):
        run_scenario(scenario, controller, client)
    before = resident_bytes()
    for _ in range(runs):
        run_scenario(scenario, controller, client)
    grown = (resident_bytes() - before) / 2**20
    print(f"{runs} runs in one process: resident memory grew {grown:.1f} MB")


def resident_bytes() -> int:
    return int(Path("/proc/self/statm").read_text().split()[1]) * 4096


if __name__ == "__main__":
    main()
