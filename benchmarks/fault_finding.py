"""Does the gate find the bugs a scanner change exposes? A mutation analysis, side by side.

Faults in the software that reads the scanner (mutants.py: filters and settings tuned for the old
scanner) are put one at a time into the Husky's navigation stack, the one each names (move_base
or Nav2, built as the plugin builds it: mutation.py). For each fault, each scanner change of
fault_finding_pairs.yaml (a cell) and each seed, three methods look for a placement that exposes
it, at the same number of simulated runs:
- the gate: what `pytest --laser-policy=regression` does with the pair, its control drive and its
  placement items, each searching around its witness with the `ci` budget;
- random corridor: obstacles drawn uniformly within 1 m of the route, as many runs as the gate;
- random world: obstacles drawn uniformly in the route's box widened by 2 m, as many runs.
Every simulated run is counted, baseline runs and the checks below included. A placement kills
the cell when the candidate fails under the fault, the baseline passes under it, and the
candidate passes without it: the fault, not the new scanner alone, is what fails the robot; and
all three hold again under a second, independent draw of the scan noise, so that a kill is the
fault's doing and not one draw of 1 mm noise on a run that passes or fails by millimetres. A
method stops at its first kill: for the gate, at the trial of the item that would have failed
there (the runs the item would go on to spend shrinking it are not counted); each check without
the fault is counted for both. The equivalent mutant must never be killed.

It prints a row per mutant and method (cells killed of those tried, per seed), then
`mutants killed: gate G of M, random R of M; killed cells per 1000 simulations: gate g, random r`
(summed over seeds; random is random corridor).

    python benchmarks/fault_finding.py [--seeds 1 2 3] [--jobs 2] [--mutants ...] [--pairs ...]
                                       [--cells MUTANT:PAIR ...] [--without-world]
"""

from __future__ import annotations

import argparse
import functools
import hashlib
import math
import multiprocessing
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from mutants import MUTANTS
from mutation import bare

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.obstacles import Box, Cylinder, Obstacle
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.pairsfile import PairsFile, load_pairs_file
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.search.budgets import BUDGETS
from pytest_lasertest.search.drives import RunCache, scenario
from pytest_lasertest.search.plans import avoid_for, pair_scene, plan_scene, route_path
from pytest_lasertest.search.trials import Setting, TrialResult
from pytest_lasertest.search.witness import passed_by_baseline, search_witness
from pytest_lasertest.sim.client import PhysicsClient
from pytest_lasertest.sim.scenario import Run, Scenario
from pytest_lasertest.solver.search import MIN_HEIGHT, SearchSettings

PAIRS = Path(__file__).resolve().parent / "fault_finding_pairs.yaml"
METHODS = ("gate", "random corridor", "random world")
CORRIDOR = 1.0  # m either side of the route
WORLD_MARGIN = 2.0  # m around the route's box


@dataclass(frozen=True)
class Cell:
    """One fault, one scanner change, one seed."""

    mutant: str
    pair: str
    seed: int


@dataclass(frozen=True)
class Outcome:
    """What one method did in one cell."""

    cell: Cell
    method: str
    killed: bool
    simulations: int
    killer: str  # the placement that killed it, described


class Counter(RunCache):
    """A run cache of its own per method and cell, counting the runs it simulates and
    remembering how many had been simulated when each run was."""

    def __init__(self) -> None:
        super().__init__(size=100_000)
        self.simulations = 0
        self.made: dict[int, int] = {}  # id of a run: simulations up to and including it

    def run(self, scenario: Scenario, controller: ControllerChoice, client: PhysicsClient) -> Run:
        fresh = not self.knows(scenario, controller)
        run = super().run(scenario, controller, client)
        if fresh:
            self.simulations += 1
            self.made[id(run)] = self.simulations
        return run


class Bench:
    """The pairs file and one process's physics client."""

    def __init__(self) -> None:
        self.spec = load_pairs_file(PAIRS)
        self.client = PhysicsClient()
        self.polyline = np.array(route_path(self.spec).polyline())  # (V, 2) m


class Search:
    """One method's search in one cell: the pair, the mutant's stack with the fault and without
    it, and the runs it simulates."""

    def __init__(self, bench: Bench, cell: Cell, method: str) -> None:
        self.bench, self.cell, self.method = bench, cell, method
        self.pair = next(pair for pair in bench.spec.pairs if pair.name == cell.pair)
        mutant = next(mutant for mutant in MUTANTS if mutant.name == cell.mutant)
        baseline, stack = self.pair.baseline.profile, mutant.stack
        self.fault = ControllerChoice(
            f"{stack}+{mutant.name}", "mutants.py", mutant.factory(baseline)
        )
        self.clean = ControllerChoice(stack, "mutants.py", bare(stack))
        self.cache = Counter()

    def drive(
        self,
        profile: LaserProfile,
        obstacles: tuple[Obstacle, ...],
        controller: ControllerChoice,
        seed: int | None = None,
    ) -> Run:
        """A run under the cell's scan noise, or under `seed`'s."""
        noise = self.cell.seed if seed is None else seed
        world = scenario(self.bench.spec, profile, obstacles, noise)
        return self.cache.run(world, controller, self.bench.client)

    def kills(self, obstacles: tuple[Obstacle, ...], candidate: Run, baseline: Run | None) -> bool:
        """Whether the faulty runs (the baseline's only if the candidate failed) kill: the
        candidate fails, the baseline passes, and without the fault the candidate passes; and
        so again under a second draw of the scan noise."""
        if candidate.passed or baseline is None or not baseline.passed:
            return False
        return self.drive(self.pair.candidate.profile, obstacles, self.clean).passed and (
            self.kills_again(obstacles)
        )

    def kills_again(self, obstacles: tuple[Obstacle, ...]) -> bool:
        """Whether the three checks of a kill hold under a second, independent noise draw."""
        seed, pair = _seed(self.cell, "again"), self.pair
        return (
            not self.drive(pair.candidate.profile, obstacles, self.fault, seed).passed
            and self.drive(pair.baseline.profile, obstacles, self.fault, seed).passed
            and self.drive(pair.candidate.profile, obstacles, self.clean, seed).passed
        )

    def outcome(
        self, obstacles: tuple[Obstacle, ...] | None, simulations: int | None = None
    ) -> Outcome:
        """The search's outcome: killed by `obstacles` (() for none), or not killed (None),
        after `simulations` (all the cache simulated, unless given)."""
        killer = "" if obstacles is None else "; ".join(o.describe() for o in obstacles)
        spent = self.cache.simulations if simulations is None else simulations
        return Outcome(self.cell, self.method, obstacles is not None, spent, killer)


def gate(bench: Bench, cell: Cell) -> Outcome:
    """The gate's items for the pair in collection order, under the regression policy: the
    control drive, the placements to steer round, then each direction's witnesses."""
    search, spec = Search(bench, cell, "gate"), bench.spec
    pair = search.pair
    baseline = search.drive(pair.baseline.profile, (), search.fault)
    candidate = search.drive(pair.candidate.profile, (), search.fault)
    if search.kills((), candidate, baseline):
        return search.outcome(())
    if baseline.passed and not candidate.passed:
        return search.outcome(None)  # the placement items skip: the control item failed
    scene = pair_scene(spec, pair, baseline)
    setting = Setting(spec, pair, search.fault, cell.seed, bench.client, search.cache)
    avoid = passed_by_baseline(setting, avoid_for(spec, scene), spec.settings.witnesses)
    for witness in (*avoid, *plan_scene(spec, pair, scene).witnesses()):
        key = f"{cell.pair}[{witness.id}]"
        before = search.cache.simulations
        found = search_witness(
            setting,
            scene,
            witness,
            spec.settings.obstacle_sizes,
            "regression",
            BUDGETS["ci"],
            key=key,
            seed=_seed(cell, key),
            database=None,
        )
        searched = search.cache.simulations
        for result in found.trials.results.values():  # in the order they were tried
            obstacles = (result.placement.obstacle,)
            if search.kills(obstacles, result.candidate, result.baseline):
                checks = search.cache.simulations - searched  # the checks' runs
                return search.outcome(obstacles, _tried_by(search.cache, result, before) + checks)
    return search.outcome(None)


def _tried_by(cache: Counter, result: TrialResult, before: int) -> int:
    """Simulations up to the trial `result` of an item that began after `before`: the item
    would have failed there, and what it simulated after (the shrinking) is not counted, as
    random placement stops at its kill."""
    runs = (result.candidate, result.baseline)
    return max(before, *(cache.made.get(id(run), 0) for run in runs if run is not None))


def random_placements(bench: Bench, cell: Cell, method: str, budget: int) -> Outcome:
    """Random obstacles, one at a time, until a kill or `budget` simulations."""
    search, spec = Search(bench, cell, method), bench.spec
    pair = search.pair
    rng = np.random.default_rng(_seed(cell, method))
    draw = _corridor_point if method == "random corridor" else _world_point
    while search.cache.simulations < budget:
        obstacles = (_obstacle(rng, draw(bench.polyline, rng), spec),)
        candidate = search.drive(pair.candidate.profile, obstacles, search.fault)
        if candidate.passed or search.cache.simulations >= budget:
            continue
        baseline = search.drive(pair.baseline.profile, obstacles, search.fault)
        if search.kills(obstacles, candidate, baseline):
            return search.outcome(obstacles)
    return search.outcome(None)


def _corridor_point(polyline: FloatArray, rng: np.random.Generator) -> tuple[float, float]:
    """A point drawn uniformly within CORRIDOR of the route's `polyline` (V, 2) m."""
    low, high = polyline.min(axis=0) - CORRIDOR, polyline.max(axis=0) + CORRIDOR
    while True:
        point = rng.uniform(low, high)
        if _distance_to(polyline, point) <= CORRIDOR:
            return float(point[0]), float(point[1])


def _world_point(polyline: FloatArray, rng: np.random.Generator) -> tuple[float, float]:
    """A point drawn uniformly in the box of the route's `polyline` widened by WORLD_MARGIN."""
    point = rng.uniform(polyline.min(axis=0) - WORLD_MARGIN, polyline.max(axis=0) + WORLD_MARGIN)
    return float(point[0]), float(point[1])


def _distance_to(polyline: FloatArray, point: FloatArray) -> float:
    starts, ends = polyline[:-1], polyline[1:]
    edges = ends - starts
    along = np.clip(
        np.einsum("ij,ij->i", point - starts, edges) / np.einsum("ij,ij->i", edges, edges), 0, 1
    )
    nearest = starts + along[:, None] * edges
    return float(np.min(np.hypot(*(point - nearest).T)))


def _obstacle(rng: np.random.Generator, point: tuple[float, float], spec: PairsFile) -> Obstacle:
    """A box or a cylinder at `point`, its sides and height drawn within the pairs file's."""
    smallest, largest = spec.settings.obstacle_sizes
    height = float(rng.uniform(MIN_HEIGHT, SearchSettings().max_height))
    x, y = point
    if rng.random() < 0.5:
        return Cylinder(x, y, float(rng.uniform(smallest, largest)) / 2.0, height)
    length, width = (float(value) for value in rng.uniform(smallest, largest, 2))
    return Box(x, y, float(rng.uniform(-math.pi, math.pi)), length, width, height)


def _seed(cell: Cell, name: str) -> int:
    text = f"{cell.seed}:{cell.mutant}:{cell.pair}:{name}"
    return int.from_bytes(hashlib.sha256(text.encode()).digest()[:4], "big")


_BENCH: Bench | None = None


def _work(cell: Cell, methods: tuple[str, ...] = METHODS) -> list[Outcome]:
    """The gate on one cell, then each random method of `methods` at the gate's budget."""
    global _BENCH
    if _BENCH is None:
        _BENCH = Bench()
    found = gate(_BENCH, cell)
    budget = max(found.simulations, 1)
    others = (method for method in methods if method != "gate")
    return [found, *(random_placements(_BENCH, cell, method, budget) for method in others)]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--mutants", nargs="+", default=[mutant.name for mutant in MUTANTS])
    parser.add_argument("--pairs", nargs="+", default=None)
    parser.add_argument(
        "--cells", nargs="+", default=None, help="MUTANT:PAIR cells only, instead of every one"
    )
    alone = parser.add_mutually_exclusive_group()
    alone.add_argument(
        "--without-world", action="store_true", help="leave random world placement out (faster)"
    )
    alone.add_argument(
        "--random",
        choices=METHODS[1:],
        default=None,
        help="this random method alone beside the gate (the gate sets its budget)",
    )
    args = parser.parse_args()
    methods = METHODS[:2] if args.without_world else METHODS
    if args.random:
        methods = ("gate", args.random)
    pairs = args.pairs or [pair.name for pair in load_pairs_file(PAIRS).pairs]
    chosen = [tuple(cell.split(":")) for cell in args.cells or ()]
    if chosen:
        args.mutants = list(dict.fromkeys(mutant for mutant, _ in chosen))
    every = [(m, p) for m in args.mutants for p in pairs]
    cells = [Cell(m, p, s) for s in args.seeds for m, p in every if not chosen or (m, p) in chosen]
    began = time.perf_counter()
    outcomes: list[Outcome] = []
    with multiprocessing.get_context("spawn").Pool(args.jobs) as pool:
        for done in pool.imap_unordered(functools.partial(_work, methods=methods), cells):
            outcomes += done
            print(
                f"  {done[0].cell}: {', '.join(map(_progress, done))}", file=sys.stderr, flush=True
            )
    print(_table(outcomes, args.mutants, args.seeds, methods))
    print(f"({time.perf_counter() - began:.0f} s)")
    print(_last_line(outcomes, args.mutants, args.seeds))


def _progress(outcome: Outcome) -> str:
    """What one method did in one cell, and what killed it."""
    killed = f"KILL by {outcome.killer or 'no obstacle'}" if outcome.killed else "-"
    return f"{outcome.method} {killed} ({outcome.simulations})"


def _table(
    outcomes: list[Outcome], mutants: list[str], seeds: list[int], methods: tuple[str, ...]
) -> str:
    """A row per mutant and method: cells killed of those tried, and simulations, per seed; then
    the pairs whose cells any seed killed."""
    header = ["mutant", "method", *(f"seed {seed}" for seed in seeds), "killed on"]
    rows = [header]
    for mutant in mutants:
        for method in methods:
            mine = [o for o in outcomes if o.cell.mutant == mutant and o.method == method]
            per_seed = [[o for o in mine if o.cell.seed == seed] for seed in seeds]
            figures = [
                f"{sum(o.killed for o in cells)}/{len(cells)} ({sum(o.simulations for o in cells)})"
                for cells in per_seed
            ]
            killed_on = ", ".join(sorted({o.cell.pair for o in mine if o.killed})) or "-"
            rows.append([mutant, method, *figures, killed_on])
    widths = [max(len(row[column]) for row in rows) for column in range(len(header) - 1)]
    return "\n".join(
        "  ".join(cell.ljust(width) for cell, width in zip(row, widths, strict=False))
        + "  "
        + row[-1]
        for row in rows
    )


def _figures(outcomes: list[Outcome], method: str, real: list[str], seeds: list[int]) -> Figures:
    """Mutants killed (a mutant once per seed) and killed cells per 1000 simulations."""
    mine = [o for o in outcomes if o.method == method]
    killed = sum(
        any(o.killed for o in mine if o.cell.mutant == mutant and o.cell.seed == seed)
        for mutant in real
        for seed in seeds
    )
    cells = sum(o.killed for o in mine if o.cell.mutant in real)
    simulations = sum(o.simulations for o in mine)
    return Figures(killed, 1000.0 * cells / max(simulations, 1))


@dataclass(frozen=True)
class Figures:
    """What one method achieved over every cell and seed."""

    mutants: int  # killed, counted once per mutant and seed
    per_thousand: float  # killed cells per 1000 simulations


def _last_line(outcomes: list[Outcome], mutants: list[str], seeds: list[int]) -> str:
    real = [m.name for m in MUTANTS if m.name in mutants and not m.equivalent]
    gate = _figures(outcomes, "gate", real, seeds)
    random = _figures(outcomes, "random corridor", real, seeds)
    total = len(real) * len(seeds)
    return (
        f"mutants killed: gate {gate.mutants} of {total}, random {random.mutants} of {total}; "
        f"killed cells per 1000 simulations: gate {gate.per_thousand:.1f}, "
        f"random {random.per_thousand:.1f}"
    )


if __name__ == "__main__":
    main()
