"""How fast a robot run simulates, against bare PyBullet stepping, measured side by side.

Each robot run drives the Husky with the paper's 720-beam, 50 Hz scanner and a controller (the
Husky's move_base by default, Nav2 with Jazzy's nav2_params.yaml, or the reactive reference)
for 30 s of simulated time, in an empty world, past one obstacle beside its route (as a
placement item drives) or past four.
Right after each run, the same world (robot, ground, obstacles) is stepped bare through the
wheel speeds the run drove: the same physics, with no scans, no controller and no oracles. That
is the floor a run cannot beat. (Stepping wheels held at one speed instead costs PyBullet about
15 % more, which would flatter the ratio.) Then many short runs in one process check that memory
and physics clients are released. Every world is built in one physics client, reset for it, as
the plugin does. The last line reads `real-time factor: R; ratio to bare physics: Q` (medians).

    python benchmarks/sim.py [--runs 9] [--memory-runs 1000] [--controller move_base|nav2|reactive]
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

from pytest_lasertest.model.geometry import FloatArray, Point2D, Pose2D
from pytest_lasertest.model.obstacles import Box, Cylinder, Obstacle
from pytest_lasertest.nav.move_base import MoveBase
from pytest_lasertest.nav.nav2.nav2 import Nav2
from pytest_lasertest.nav.nav2.settings import Nav2Settings
from pytest_lasertest.nav.protocol import ControllerFactory
from pytest_lasertest.nav.reactive import ReactiveController
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.sim.client import PhysicsClient, PhysicsWorld, connected_clients
from pytest_lasertest.sim.scenario import Scenario, run_scenario

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
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
# Beside the route, inside the scanner's range for most of the run.
SCENES: dict[str, tuple[Obstacle, ...]] = {
    "empty": (),
    # What a placement item drives past: one obstacle near the route.
    "one beside the route": (Box(6.0, 0.8, 0.3, 0.4, 0.4, 1.0),),
    "beside the route": (
        Box(4.0, 1.6, 0.3, 0.6, 0.4, 1.0),
        Cylinder(7.0, -1.5, 0.1, 1.0),
        Box(10.0, 2.0, 0.0, 1.0, 0.3, 1.0),
        Cylinder(13.0, 1.4, 0.05, 1.0),
    ),
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=9, help="robot runs, taking turns by scene")
    parser.add_argument("--memory-runs", type=int, default=1000)
    parser.add_argument("--controller", choices=list(CONTROLLERS), default="move_base")
    args = parser.parse_args()
    controller = CONTROLLERS[args.controller]
    factors, ratios = [], []
    names = list(SCENES)
    # One client for every world, as the plugin keeps one per process.
    with PhysicsClient() as client:
        for index in range(args.runs):
            name = names[index % len(names)]
            factor, ratio = one_run(name, SCENES[name], controller, client)
            factors.append(factor)
            ratios.append(ratio)
        memory(args.memory_runs, controller, client)
    print(f"{connected_clients()} physics clients left connected")
    print(
        f"real-time factor: {statistics.median(factors):.0f}; "
        f"ratio to bare physics: {statistics.median(ratios):.2f}"
    )


def one_run(
    name: str,
    obstacles: tuple[Obstacle, ...],
    controller: ControllerFactory,
    client: PhysicsClient,
) -> tuple[float, float]:
    """A robot run in the world, then a bare stepping of it: (real-time factor, ratio)."""
    scenario = Scenario(PAPER.robot, SCANNER, obstacles, START, ROUTE, SIMULATED, seed=0)
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
    """Wall time (s) of stepping the scenario's world through the wheel speeds (T, 2) rad/s of a
    run of it: the same physics, without the scans, the controller or the oracles."""
    with PhysicsWorld(scenario.start, scenario.obstacles, scenario.time_step, client) as world:
        began = time.perf_counter()
        for left, right in wheels.tolist():
            world.step(left, right)
        return time.perf_counter() - began


def memory(runs: int, controller: ControllerFactory, client: PhysicsClient) -> None:
    """Resident memory growth over `runs` one-second robot runs, after ten to warm up."""
    scenario = Scenario(PAPER.robot, SCANNER, SCENES["beside the route"], START, ROUTE, 1.0, seed=0)
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
