"""The same drives timed in two checkouts side by side: how many times faster this one drives.

Each drive is a controller in a world for 30 s of simulated time (`--seconds`): the Husky with the
paper's 720-beam scanner under move_base, under Nav2 with Jazzy's nav2_params.yaml (MPPI) and under
Nav2 with the Husky's own parameters (DWB), past one box in its way, past two obstacles, and down
the warehouse aisle of examples/worlds. Every round runs all drives in one fresh process of each
checkout in turn (the other checkout's package first on the path, its own examples read), after one
short drive that pays for imports and numba's compiling; that start-up is timed apart.

Printed per drive: the median seconds in each checkout, their ratio, and whether the two
trajectories hash alike (a speed-up that keeps the trajectories shows `same`; the old checkout's
own behaviour may differ where a later change meant it to). Then the totals.

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
controllers = {
    "move_base": MoveBase,
    "Nav2 MPPI": lambda robot, route: Nav2(robot, route, Nav2Settings()),
    "Nav2 DWB (Husky's)": default_controller(examples / "x.lasertest.yaml").factory,
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
            began = time.perf_counter()
            run = run_scenario(scenario(world, float(sys.argv[2])), make, client)
            seconds = time.perf_counter() - began
            drive = f"{cname}, {wname}"
            print(json.dumps({"drive": drive, "s": seconds, "digest": run.digest()}), flush=True)
"""


def one_round(checkout: Path, simulated: float) -> dict[str, tuple[float, str]]:
    """Every drive once, for `simulated` s at most, in a fresh process of `checkout`: seconds
    and trajectory hash by drive, and the start-up under 'start-up'."""
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
    found: dict[str, tuple[float, str]] = {}
    for line in done.stdout.splitlines():
        record = json.loads(line)
        if "start-up" in record:
            found["start-up"] = (record["start-up"], "")
        else:
            found[record["drive"]] = (record["s"], record["digest"])
    return found


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("old", type=Path, help="the other checkout, e.g. a git worktree")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--seconds", type=float, default=30.0, help="simulated, per drive")
    args = parser.parse_args()
    checkouts = {"old": args.old.resolve(), "new": REPO}
    rounds: dict[str, list[dict[str, tuple[float, str]]]] = {name: [] for name in checkouts}
    for _ in range(args.rounds):
        for name, checkout in checkouts.items():  # in turn, so that load drifts on both
            rounds[name].append(one_round(checkout, args.seconds))
    print(f"old: {checkouts['old']}; new: {checkouts['new']}; {args.rounds} rounds, medians")
    print(f"{'drive':40s} {'old s':>7s} {'new s':>7s} {'ratio':>6s}  trajectory")
    totals = dict.fromkeys(checkouts, 0.0)
    for drive in rounds["new"][0]:
        old, new = (statistics.median(r[drive][0] for r in rounds[name]) for name in checkouts)
        same = "same" if rounds["old"][0][drive][1] == rounds["new"][0][drive][1] else "differs"
        if drive == "start-up":
            print(f"{drive:40s} {old:7.2f} {new:7.2f} {old / new:5.2f}x")
            continue
        print(f"{drive:40s} {old:7.2f} {new:7.2f} {old / new:5.2f}x  {same}")
        totals["old"] += old
        totals["new"] += new
    ratio = totals["old"] / totals["new"]
    print(f"{'all drives':40s} {totals['old']:7.2f} {totals['new']:7.2f} {ratio:5.2f}x")


if __name__ == "__main__":
    main()
