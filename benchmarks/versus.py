"""The same drives timed in two checkouts side by side: how many times faster this one drives.

Each drive is a controller in a world for 30 s of simulated time (`--seconds`): the Husky with the
paper's 720-beam scanner under move_base, under Nav2 with Jazzy's nav2_params.yaml (MPPI), under
Nav2 with the Husky's own parameters (DWB) and under Nav2 with a team's MPPI parameters
(examples/nav2/cropped.nav2.yaml, which leaves regenerate_noises at Nav2's default), past one box
in its way, past two obstacles, and down the warehouse aisle of examples/worlds. Every round runs
all drives in one fresh process of each checkout in turn (the other checkout's package first on
the path, its own examples read), after one short drive that pays for imports and numba's
compiling; that start-up is timed apart.

Printed per drive: the median wall-clock seconds in each checkout and their ratio, then the same
for processor seconds (every thread's: what a busy machine, xdist's workers on every core, pays),
and whether the two trajectories hash alike (a speed-up that keeps the trajectories shows
`same`; the old checkout's own behaviour may differ where a later change meant it to). Then the
totals.

    python benchmarks/versus.py OLD_CHECKOUT [--rounds 3] [--seconds 30]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
WIDTH = 52  # characters: the drive column, wide enough for every drive's name

# Runs in each checkout's own process: only the API both checkouts share.
DRIVES = r"""
import json, sys, time
from pathlib import Path
from pytest_lasertest.model.geometry import Point2D, Pose2D
from pytest_lasertest.model.obstacles import Box, Cylinder
from pytest_lasertest.nav.move_base import MoveBase
from pytest_lasertest.nav.nav2.nav2 import Nav2
from pytest_lasertest.nav.nav2.settings import Nav2Settings
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.pairsfile.controller import default_controller
from pytest_lasertest.sim.client import PhysicsClient
from pytest_lasertest.sim.scenario import Scenario, run_scenario

started = time.perf_counter()
examples = Path(sys.argv[1]) / "examples"
paper = load_pairs_file(examples / "paper.lasertest.yaml")
aisle = load_pairs_file(examples / "worlds" / "aisle.lasertest.yaml").world
scanner = next(pair for pair in paper.pairs if pair.name == "distance").baseline.profile
nav2 = default_controller(examples / "x.lasertest.yaml").factory
team = load_pairs_file(examples / "nav2" / "cropped_range.lasertest.yaml").robot
controllers = {
    "move_base": MoveBase,
    "Nav2 MPPI": lambda robot, route: Nav2(robot, route, Nav2Settings()),
    "Nav2 DWB (Husky's)": nav2,
    "Nav2 MPPI (cropped.nav2.yaml)": lambda robot, route: nav2(team, route),
}
ahead = (Point2D(9.0, 0.0),)
worlds = {
    "one box in the way": dict(obstacles=(Box(4.0, 0.1, 0.3, 0.4, 0.4, 1.0),), route=ahead),
    "two in the way": dict(
        obstacles=(Cylinder(3.0, -0.2, 0.15, 1.0), Box(6.0, 0.3, 0.0, 0.3, 0.6, 1.0)),
        route=ahead,
    ),
    "the aisle": dict(obstacles=(), route=aisle.route, start=aisle.start, walls=aisle.walls),
}


def scenario(world, limit):
    start = world.get("start", Pose2D(0.0, 0.0, 0.0))
    extra = {"walls": world["walls"]} if "walls" in world else {}
    return Scenario(
        paper.robot, scanner, world["obstacles"], start, world["route"], limit, seed=0, **extra
    )


with PhysicsClient() as client:
    for make in controllers.values():
        run_scenario(scenario(worlds["one box in the way"], 2.0), make, client)
    print(json.dumps({"start-up": time.perf_counter() - started}), flush=True)
    for cname, make in controllers.items():
        for wname, world in worlds.items():
            began, cpu = time.perf_counter(), time.process_time()
            run = run_scenario(scenario(world, float(sys.argv[2])), make, client)
            seconds, cpu = time.perf_counter() - began, time.process_time() - cpu
            drive = f"{cname}, {wname}"
            record = {"drive": drive, "s": seconds, "cpu": cpu, "digest": run.digest()}
            print(json.dumps(record), flush=True)
"""


Timing = tuple[float, float, str]  # wall-clock s, processor s (every thread's), trajectory hash


def one_round(checkout: Path, simulated: float) -> dict[str, Timing]:
    """Every drive once, for `simulated` s at most, in a fresh process of `checkout`: wall and
    processor seconds and trajectory hash by drive, and the start-up under 'start-up'."""
    environment = {**os.environ, "PYTHONPATH": str(checkout)}
    with tempfile.TemporaryDirectory() as elsewhere:  # not this checkout's folder on the path
        done = subprocess.run(
            [sys.executable, "-c", DRIVES, str(checkout), str(simulated)],
            cwd=elsewhere,
            env=environment,
            capture_output=True,
            text=True,
            check=True,
        )
    found: dict[str, Timing] = {}
    for line in done.stdout.splitlines():
        record = json.loads(line)
        if "start-up" in record:
            found["start-up"] = (record["start-up"], 0.0, "")
        else:
            found[record["drive"]] = (record["s"], record["cpu"], record["digest"])
    return found


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("old", type=Path, help="the other checkout, e.g. a git worktree")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--seconds", type=float, default=30.0, help="simulated, per drive")
    args = parser.parse_args()
    checkouts = {"old": args.old.resolve(), "new": REPO}
    rounds: dict[str, list[dict[str, Timing]]] = {name: [] for name in checkouts}
    for _ in range(args.rounds):
        for name, checkout in checkouts.items():  # in turn, so that load drifts on both
            rounds[name].append(one_round(checkout, args.seconds))
    print(f"old: {checkouts['old']}; new: {checkouts['new']}; {args.rounds} rounds, medians")
    print(
        f"{'drive':{WIDTH}s} {'old s':>7s} {'new s':>7s} {'ratio':>6s} {'old cpu':>8s} "
        f"{'new cpu':>8s} {'ratio':>6s}  trajectory"
    )
    totals = {name: [0.0, 0.0] for name in checkouts}
    for drive in rounds["new"][0]:
        medians = {name: _medians(runs, drive) for name, runs in rounds.items()}
        if drive == "start-up":
            old, new = medians["old"][0], medians["new"][0]
            print(f"{drive:{WIDTH}s} {old:7.2f} {new:7.2f} {old / new:5.2f}x")
            continue
        same = "same" if rounds["old"][0][drive][2] == rounds["new"][0][drive][2] else "differs"
        print(f"{_row(drive, medians['old'], medians['new'])}  {same}")
        for name in checkouts:
            totals[name] = [sum(pair) for pair in zip(totals[name], medians[name], strict=True)]
    print(_row("all drives", totals["old"], totals["new"]))


def _medians(runs: list[dict[str, Timing]], drive: str) -> list[float]:
    """The median wall-clock and processor seconds of `drive` over the rounds."""
    return [statistics.median(run[drive][kind] for run in runs) for kind in (0, 1)]


def _row(drive: str, old: list[float], new: list[float]) -> str:
    """Wall-clock seconds old and new and their ratio, then processor seconds likewise:
    MPPI draws noise in a thread of its own, which costs processor time but, on an idle
    machine with a core to spare, no wall-clock time."""
    wall, cpu = old[0] / new[0], old[1] / new[1]
    return (
        f"{drive:{WIDTH}s} {old[0]:7.2f} {new[0]:7.2f} {wall:5.2f}x "
        f"{old[1]:8.2f} {new[1]:8.2f} {cpu:5.2f}x"
    )


if __name__ == "__main__":
    main()
