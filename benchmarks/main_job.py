"""The README's main job, `pytest examples/`, timed side by side with another checkout's, beside
the physics its drives cannot do without.

Runs `python -m pytest examples/ --laser-seed=SEED -p no:cacheprovider` with CI unset (the dev
profile, as on a user's machine) in this checkout and, with `--against CHECKOUT`, in that one (a
worktree of an older commit, its code first on PYTHONPATH, its own examples), one after the
other, each from a cold start as on a fresh clone: numba's cached machine code under
pytest_lasertest/ and the example database (.hypothesis/examples) are deleted first (kept with
`--warm`). For each run it prints the wall time, the peak resident memory of the largest process,
and how many items had each outcome (verdicts.py's letters: . passed, F failed, p pre-existing, m
marginal, c coverage-loss, s skipped). Every drive this checkout's run makes is added up (the
plugin simulated.py): the simulated seconds, and what PyBullet alone costs to step that long,
bare (sim.py's `bare_physics`, on the run of a placement item's world, timed right after the
job). That is the floor a job of these drives cannot beat, with every scan, controller, solver
and search free. The last line reads

    main job: S s here (peak M MB), O s against CHECKOUT (ratio R); T simulated s in D drives,
    bare physics alone F s

on one line, R being the other checkout's time over this one's (above 1, this one is faster);
`against` and its ratio only with `--against`.

    python benchmarks/main_job.py [--against CHECKOUT] [--workers N] [--examples N] [--seed 1]
                                  [--warm] [-- PYTEST_ARGUMENT ...]

Arguments after `--` go to pytest in place of `examples/` (a file, `-k` ...), in both checkouts.
"""

from __future__ import annotations

import argparse
import collections
import os
import shutil
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass
from pathlib import Path

from sim import WORLDS, bare_physics
from verdicts import letter

from pytest_lasertest.nav.move_base import MoveBase
from pytest_lasertest.sim.client import PhysicsClient
from pytest_lasertest.sim.scenario import run_scenario

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
# Prints the largest child's peak resident memory (kB on Linux) after running the command.
PEAK = (
    "import resource, subprocess, sys; code = subprocess.call(sys.argv[1:]); "
    "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss, file=sys.stderr); "
    "sys.exit(code)"
)


@dataclass(frozen=True)
class Job:
    """One run of the main job: what it took and what it found."""

    wall: float  # s
    peak: float  # MB, the largest process's
    outcomes: str  # letter counts, as `. 70, F 15, ...`
    simulated: float  # s of simulated time over every drive (0 where not counted)
    drives: int


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--against", type=Path, default=None, help="another checkout to time")
    parser.add_argument("--workers", type=int, default=0, help="xdist workers (-n); 0 serial")
    parser.add_argument("--examples", type=int, default=None, help="--laser-examples, if given")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument(
        "--warm", action="store_true", help="keep numba's cache and the example database"
    )
    parser.add_argument("pytest", nargs="*", default=["examples/"], help="after --: for pytest")
    args = parser.parse_args()
    options = [*args.pytest, f"--laser-seed={args.seed}"]
    options += [] if args.examples is None else [f"--laser-examples={args.examples}"]
    options += [] if args.workers == 0 else ["-n", str(args.workers)]
    here = job(REPO, options, counted=True, cold=not args.warm)
    print(f"this checkout: {describe(here)}", flush=True)
    floor = here.simulated * physics_per_second()
    line = f"main job: {here.wall:.0f} s here (peak {here.peak:.0f} MB)"
    if args.against is not None:
        there = job(args.against.resolve(), options, counted=False, cold=not args.warm)
        print(f"{args.against}: {describe(there)}")
        line += f", {there.wall:.0f} s against {args.against} (ratio {there.wall / here.wall:.2f})"
    print(
        f"{line}; {here.simulated:.0f} simulated s in {here.drives} drives, "
        f"bare physics alone {floor:.1f} s"
    )


def job(checkout: Path, options: list[str], counted: bool, cold: bool) -> Job:
    """The main job in `checkout`, timed, from a cold start if `cold`; its drives counted if
    `counted`."""
    if cold:
        cold_start(checkout)
    with tempfile.TemporaryDirectory() as scratch:
        junit, tally = Path(scratch) / "job.xml", Path(scratch) / "simulated.txt"
        command = [sys.executable, "-m", "pytest", *options, "-q", "-p", "no:cacheprovider"]
        command += [f"--junitxml={junit}", *(["-p", "simulated"] if counted else [])]
        path = os.pathsep.join([str(checkout), *([str(HERE)] if counted else [])])
        environment = {**os.environ, "PYTHONPATH": path, "LASERTEST_SIMULATED": str(tally)}
        environment.pop("CI", None)
        began = time.perf_counter()
        done = subprocess.run(
            [sys.executable, "-c", PEAK, *command],
            cwd=checkout,
            env=environment,
            capture_output=True,
            text=True,
            check=False,
        )
        wall = time.perf_counter() - began
        if done.returncode not in (0, 1) or not junit.exists():
            sys.exit(
                f"the main job in {checkout} ended with status {done.returncode}:\n{done.stdout}"
            )
        peak = int(done.stderr.strip().splitlines()[-1]) / 1024.0
        seconds, drives = _tally(tally) if counted else (0.0, 0)
        return Job(wall, peak, _outcomes(junit), seconds, drives)


def cold_start(checkout: Path) -> None:
    """Delete numba's cached machine code and the example database, as a fresh clone has
    neither: compiling counts, and a replayed failure would try fewer examples."""
    for pattern in ("*.nbi", "*.nbc"):
        for cached in (checkout / "pytest_lasertest").rglob(pattern):
            cached.unlink()
    shutil.rmtree(checkout / ".hypothesis" / "examples", ignore_errors=True)


def _tally(tally: Path) -> tuple[float, int]:
    """Simulated seconds and drives over the processes' lines of simulated.py."""
    lines = [line.split() for line in tally.read_text().splitlines()] if tally.exists() else []
    return sum(float(line[1]) for line in lines), sum(int(line[2]) for line in lines)


def _outcomes(junit: Path) -> str:
    """Counts of each outcome letter (verdicts.py's) of the JUnit XML's test cases."""
    counts = collections.Counter(letter(case) for case in ElementTree.parse(junit).iter("testcase"))
    return ", ".join(f"{mark} {count}" for mark, count in sorted(counts.items()))


def describe(job: Job) -> str:
    return f"{job.wall:.1f} s, peak {job.peak:.0f} MB; {job.outcomes}"


def physics_per_second(runs: int = 3) -> float:
    """Wall seconds PyBullet takes to step one simulated second bare (the least of `runs`
    timings), on a robot run past one obstacle beside its route, as a placement item drives."""
    world = WORLDS["one beside the route"]
    scenario = world.scenario(30.0)
    with PhysicsClient() as client:
        run = run_scenario(scenario, MoveBase, client)
        simulated = float(run.times[-1])
        return min(bare_physics(scenario, run.driven, client) for _ in range(runs)) / simulated


if __name__ == "__main__":
    main()
