"""How fast the solver finds verified witnesses, all measured side by side in one run.

Prints the median time per verified witness on 720-beam and 2880-beam pairs that differ in each
sensing attribute; the time to prove that identical scanners have no witness; verified witnesses
per second against a rejection sampler (uniform placements, the same verifier, the same time
budget) on the paper's size pair; and checks again, by ray casting, every witness of the examples
and of a random sample of catalogue pairs. Then the matrix: every ordered pair of distinct
catalogue scanners, each on the Husky's mount, planned in both directions on the paper's 10 m
straight route and on the route that turns; one line per direction left undecided (neither sat
nor unsat: route, baseline -> candidate, direction, the first 200 characters of the plan's
explanation), then `undecided: U of N directions; median plan: M ms; p95 plan: P ms`, the times
being those of the pair plans (both directions of one scene). The last line reads
`ms per witness at 720 beams: A; at 2880 beams: B; speed-up over rejection sampling: S`.

    python benchmarks/solver.py [--catalogue-pairs 200] [--budget 20] [--seed 0]
                                [--matrix-models 13]
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import statistics
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from pytest_lasertest.model.geometry import Point2D, Pose2D, Pose3D
from pytest_lasertest.model.obstacles import Box, Cylinder, Obstacle
from pytest_lasertest.model.plan import DirectionPlan, Witness
from pytest_lasertest.model.route import nominal_path, scan_times
from pytest_lasertest.model.verify import DIRECTIONS, Direction, Placement, Scene, readings, verify
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.pairsfile.catalogue import load_catalogue
from pytest_lasertest.search.plans import plan_for
from pytest_lasertest.solver.plan import DirectionSearch, plan_direction
from pytest_lasertest.solver.search import MIN_HEIGHT, SearchSettings, anchor_times

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
ROBOT = PAPER.robot
SETTINGS = SearchSettings(witnesses=3, min_size=PAPER.settings.min_obstacle_size)
STRAIGHT = nominal_path(PAPER.world.start, PAPER.world.route, 0.5, 1.0)  # 10 m, straight ahead
TURNING = nominal_path(Pose2D(0.0, 0.0, 0.0), (Point2D(2.0, 0.0), Point2D(2.0, 6.0)), 0.5, 1.0)
HUSKY_MOUNT = Pose3D((0.337, 0.0, 0.308), (math.pi, 0.0, 0.0))
ROUTES = {"straight": STRAIGHT, "turning": TURNING}  # the matrix's routes, by the name it prints
EXPLANATION_CHARS = 200  # how much of an undecided direction's explanation the matrix prints


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--catalogue-pairs", type=int, default=200)
    parser.add_argument("--budget", type=float, default=20.0, help="s per side, sampler race")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument(
        "--matrix-models",
        type=int,
        default=None,
        help="how many catalogue models (the first, by key) enter the matrix; all by default",
    )
    args = parser.parse_args()
    if args.matrix_models is not None and args.matrix_models < 2:
        parser.error("--matrix-models needs at least 2 models to make a pair")
    per_witness = {beams: median_ms_per_witness(beams) for beams in (720, 2880)}
    identical_proof()
    speed_up = sampler_race(args.budget, np.random.default_rng(args.seed))
    verified, total = verify_examples()
    more_verified, more_total = verify_catalogue(args.catalogue_pairs, args.seed)
    checked = verified + more_verified
    print(f"verified again by ray casting: {checked} of {total + more_total} witnesses")
    if checked != total + more_total:
        raise SystemExit("some witness failed the exact verification")
    print_matrix(matrix(args.matrix_models))
    print(
        f"ms per witness at 720 beams: {per_witness[720]:.1f}; "
        f"at 2880 beams: {per_witness[2880]:.1f}; speed-up over rejection sampling: {speed_up:.0f}"
    )


def variants(beams: int) -> Iterator[tuple[str, Scene]]:
    """Pairs of the Husky's LMS1xx at `beams` beams that differ in one sensing attribute each."""
    base = dataclasses.replace(PAPER.pairs[1].baseline.profile, samples=beams)
    (x, y, z), rpy = base.pose.xyz, base.pose.rpy
    changed = {
        "range 10 -> 5 m": dataclasses.replace(base, range_max=5.0),
        "samples halved": dataclasses.replace(base, samples=beams // 2),
        "minimum range 0.1 -> 0.8 m": dataclasses.replace(base, range_min=0.8),
        "update rate 50 -> 10 Hz": dataclasses.replace(base, update_rate=10.0),
        "mounted 0.1 m higher": dataclasses.replace(base, pose=Pose3D((x, y, z + 0.1), rpy)),
        "mounted 0.15 m further back": dataclasses.replace(
            base, pose=Pose3D((x - 0.15, y, z), rpy)
        ),
    }
    for name, candidate in changed.items():
        yield name, Scene(base, candidate, ROBOT, STRAIGHT)
    narrow = dataclasses.replace(base, min_angle=-1.0, max_angle=1.0)
    yield "field of view +-1.57 -> +-1 rad, turning route", Scene(base, narrow, ROBOT, TURNING)


def median_ms_per_witness(beams: int) -> float:
    """How long each verified witness took to find (from the one before it), median over the
    variants' witnesses; each direction's whole planning time, with the search that finds no
    more witnesses and any proof, is printed beside it."""
    samples: list[float] = []
    for name, scene in variants(beams):
        for direction in DIRECTIONS:
            times = witness_times(scene, direction)
            start = time.perf_counter()
            plan = plan_direction(scene, direction, SETTINGS)
            whole = (time.perf_counter() - start) * 1000
            print(
                f"{beams} beams, {name}, {direction}: {plan.status}, {len(times)} witnesses in "
                f"{', '.join(f'{t:.0f}' for t in times) or '-'} ms; whole plan {whole:.0f} ms"
            )
            samples += times
    median = statistics.median(samples)
    print(f"{beams} beams: median {median:.1f} ms per verified witness of {len(samples)}")
    return median


def witness_times(scene: Scene, direction: Direction) -> list[float]:
    """Milliseconds from the start, or from the witness before, to each verified witness."""
    search = DirectionSearch(scene, direction, SETTINGS)
    anchors = anchor_times(scene, direction, SETTINGS.anchor_spacing)
    times, start = [], time.perf_counter()
    for _ in search.found(anchors):
        now = time.perf_counter()
        times.append((now - start) * 1000)
        start = now
    return times


def identical_proof() -> None:
    """How long proving that a scanner and its copy have no witness takes."""
    profile = PAPER.pairs[1].baseline.profile
    scene = Scene(profile, profile, ROBOT, STRAIGHT)
    start = time.perf_counter()
    plans = [plan_direction(scene, direction, SETTINGS) for direction in DIRECTIONS]
    elapsed = time.perf_counter() - start
    statuses = ", ".join(plan.status for plan in plans)
    print(f"identical profiles: {statuses} for both directions in {elapsed * 1000:.1f} ms")


def sampler_race(budget: float, rng: np.random.Generator) -> float:
    """Verified witnesses per second, solver against rejection sampler, on the size pair."""
    size = next(pair for pair in PAPER.pairs if pair.name == "size")
    scene = Scene(size.baseline.profile, size.candidate.profile, ROBOT, STRAIGHT)
    settings = dataclasses.replace(SETTINGS, witnesses=20)
    found, start = 0, time.perf_counter()
    while time.perf_counter() - start < budget:
        found += sum(len(plan_direction(scene, d, settings).witnesses) for d in DIRECTIONS)
    solver_seconds = time.perf_counter() - start
    sampled, tried, sampler_seconds = rejection_sample(scene, settings, budget, rng)
    solver_rate = found / solver_seconds
    sampler_rate = max(sampled, 1) / sampler_seconds
    bound = "" if sampled else " (none found: taking one, so the speed-up is a lower bound)"
    print(
        f"size pair: solver {solver_rate:.1f} verified witnesses/s; rejection sampler "
        f"{sampled} of {tried} placements verified in {sampler_seconds:.1f} s{bound}"
    )
    return solver_rate / sampler_rate


def rejection_sample(
    scene: Scene, settings: SearchSettings, budget: float, rng: np.random.Generator
) -> tuple[int, int, float]:
    """Uniform placements in the world, kept when the verifier accepts them at an anchor."""
    polyline = np.array(scene.path.polyline())
    # The world: every place either scanner can read from some pose on the path.
    reach = max(scene.baseline.range_max, scene.candidate.range_max)
    low, high = polyline.min(axis=0) - reach, polyline.max(axis=0) + reach
    anchors = {d: anchor_times(scene, d, settings.anchor_spacing) for d in DIRECTIONS}
    found = tried = 0
    start = time.perf_counter()
    while time.perf_counter() - start < budget:
        direction: Direction = DIRECTIONS[int(rng.integers(2))]
        anchor = float(rng.choice(anchors[direction]))
        obstacle = random_obstacle(rng, low, high, settings)
        placement = Placement(obstacle, direction, anchor, anchor)
        found += verify(scene, placement).holds()
        tried += 1
    return found, tried, time.perf_counter() - start


def random_obstacle(
    rng: np.random.Generator, low: np.ndarray, high: np.ndarray, settings: SearchSettings
) -> Obstacle:
    x, y = rng.uniform(low, high)
    size = float(rng.uniform(settings.min_size, settings.max_size))
    height = float(rng.uniform(MIN_HEIGHT, settings.max_height))
    if rng.integers(2):
        return Cylinder(float(x), float(y), size / 2.0, height)
    return Box(float(x), float(y), float(rng.uniform(0.0, math.pi / 2.0)), size, size, height)


def verify_examples() -> tuple[int, int]:
    """Every witness of every pair in examples/, checked again."""
    verified = total = 0
    for path in sorted(EXAMPLES.glob("*.lasertest.yaml")):
        spec = load_pairs_file(path)
        for pair in spec.pairs:
            plan = plan_for(spec, pair)
            for direction in plan.directions:
                for witness in direction.witnesses:
                    verified += checked(plan.scene, witness)
                    total += 1
    print(f"examples: {verified} of {total} witnesses verified again")
    return verified, total


def verify_catalogue(count: int, seed: int) -> tuple[int, int]:
    """Witnesses of `count` random catalogue pairs, on random mounts and routes, checked again."""
    rng = np.random.default_rng(seed)
    catalogue = load_catalogue()
    models = sorted(catalogue.entries)
    mounts = [
        HUSKY_MOUNT,
        Pose3D((0.337, 0.0, 0.408), (math.pi, 0.0, 0.0)),
        Pose3D((0.2, 0.0, 0.25), (0.0, 0.0, 0.0)),
        Pose3D((0.337, 0.05, 0.308), (math.pi, 0.0, 0.2)),
    ]
    settings = dataclasses.replace(SETTINGS, witnesses=1, min_size=0.05)
    verified = total = sat = 0
    start = time.perf_counter()
    for _ in range(count):
        first, second = (catalogue.entries[str(m)] for m in rng.choice(models, 2))
        baseline = first.profile(mounts[int(rng.integers(len(mounts)))])
        candidate = second.profile(mounts[int(rng.integers(len(mounts)))])
        path = (STRAIGHT, TURNING)[int(rng.integers(2))]
        scene = Scene(baseline, candidate, ROBOT, path)
        plans = [plan_direction(scene, direction, settings) for direction in DIRECTIONS]
        witnesses = [w for plan in plans for w in plan.witnesses]
        sat += any(plan.status == "sat" for plan in plans)
        verified += sum(checked(scene, witness) for witness in witnesses)
        total += len(witnesses)
    elapsed = time.perf_counter() - start
    print(
        f"catalogue: {count} random pairs ({sat} with a witness) in {elapsed:.1f} s; "
        f"{verified} of {total} witnesses verified again"
    )
    return verified, total


@dataclass(frozen=True)
class PairTiming:
    """One pair plan of the matrix: both directions of one scene, and how long they took."""

    route: str  # a key of ROUTES
    baseline: str  # catalogue key
    candidate: str  # catalogue key
    ms: float  # both directions together
    plans: tuple[DirectionPlan, ...]


def matrix(models: int | None = None) -> list[PairTiming]:
    """Every ordered pair of distinct catalogue scanners (the first `models` by key, or all),
    both on the Husky's mount, planned in both directions on each route of ROUTES."""
    catalogue = load_catalogue()
    keys = sorted(catalogue.entries)[:models]
    profiles = {key: catalogue.entries[key].profile(HUSKY_MOUNT) for key in keys}
    timings = []
    for route, path in ROUTES.items():
        for baseline in keys:
            for candidate in keys:
                if baseline == candidate:
                    continue
                scene = Scene(profiles[baseline], profiles[candidate], ROBOT, path)
                start = time.perf_counter()
                plans = tuple(plan_direction(scene, d, SETTINGS) for d in DIRECTIONS)
                ms = (time.perf_counter() - start) * 1000
                timings.append(PairTiming(route, baseline, candidate, ms, plans))
    return timings


def print_matrix(timings: list[PairTiming]) -> None:
    """A line per undecided direction, then how many there are and how long pair plans took:
    the median, and the 95th percentile as `statistics.quantiles(times, n=20)[-1]` (its
    default, exclusive method)."""
    undecided = total = 0
    for timing in timings:
        for plan in timing.plans:
            total += 1
            if plan.status in ("sat", "unsat"):
                continue
            undecided += 1
            print(
                f"undecided, {timing.route}, {timing.baseline} -> {timing.candidate}, "
                f"{plan.direction}: {plan.explanation[:EXPLANATION_CHARS]}"
            )
    times = [timing.ms for timing in timings]
    median, p95 = statistics.median(times), statistics.quantiles(times, n=20)[-1]
    print(
        f"undecided: {undecided} of {total} directions; "
        f"median plan: {median:.0f} ms; p95 plan: {p95:.0f} ms"
    )


def checked(scene: Scene, witness: Witness) -> bool:
    """The verifier's verdict, and the readings themselves: the detector reads the obstacle at
    the anchor, the misser reads nothing of it in range at any scan up to `until`."""
    placement = witness.placement
    # Only placements both scanners read lack a direction, and no plan's witness is one.
    assert placement.direction is not None
    detector, misser = scene.detector(placement.direction), scene.misser(placement.direction)
    anchor = scene.path.poses_at(np.array([placement.anchor]))
    seen = np.isfinite(readings(detector, anchor, placement.obstacle)).any()
    times = scan_times(misser.update_rate, placement.until)
    missed = not np.isfinite(readings(misser, scene.path.poses_at(times), placement.obstacle)).any()
    return bool(verify(scene, placement).holds() and seen and missed)


if __name__ == "__main__":
    main()
