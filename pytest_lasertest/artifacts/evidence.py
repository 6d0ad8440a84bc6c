"""The artifacts of a failing item under `--laser-artifacts`: for a placement, a picture, a pairs
file that replays the case, a Gazebo world, a JSON file with every number and a rosbag2 of both
robots (`bag.py`), side by side; for a failure without an obstacle, the picture, the empty world,
the numbers and the rosbag2; for a lost coverage or a witness the ray cast rejects, the numbers.
Every JSON file starts with the same header. Each file is written on its own, best-effort
(`files.write_best_effort`): one the operating system refuses is reported beside the item's
failure, and the others are still written.

The picture shows the moment the candidate failed: its first collision, the instant it was
judged stuck, or (when it simply ran out of time) its last pose; both robots' trajectories and
both scanners' beams at that instant, each from its own robot, among the world's walls, over
the costmap the candidate's controller published then (the candidate is driven again for it,
keeping the costmap: a run is deterministic, so it is the same run). The Gazebo world holds the
walls too.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np

from pytest_lasertest.artifacts.bag import write_bag
from pytest_lasertest.artifacts.files import artifact_path, write_best_effort, write_json
from pytest_lasertest.artifacts.picture import BeamFan, FailureFigure, draw_failure
from pytest_lasertest.artifacts.repro import write_repro
from pytest_lasertest.artifacts.sdf import write_world
from pytest_lasertest.inputs.errors import Location
from pytest_lasertest.model.coverage import CoverageComparison
from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.obstacles import Obstacle, ray_distances
from pytest_lasertest.model.plan import Witness
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.model.verify import Verification
from pytest_lasertest.model.walls import NO_WALLS, Walls
from pytest_lasertest.pairsfile import Pair, PairsFile, Scanner
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.pairsfile.placements import PinnedPlacement
from pytest_lasertest.reports.failure import PlacementFailure
from pytest_lasertest.reports.formats import Artifacts, obstacle_json, witness_json
from pytest_lasertest.search.drives import PairDrive
from pytest_lasertest.sim.scenario import ControllerError, Run, run_scenario

# The picture, the repro, the Gazebo world, the numbers and the rosbag2's directory.
SUFFIXES = (".png", ".lasertest.yaml", ".world", ".json", "")


def write_evidence(directory: Path, failure: PlacementFailure) -> Artifacts:
    """Write the five artifacts of `failure` below `directory`, each best-effort."""
    png, repro, world, numbers, bag = (
        artifact_path(directory, failure.nodeid, suffix) for suffix in SUFFIXES
    )
    result = failure.result
    runs, note = driven_again((result.baseline, result.candidate), failure.controller)
    obstacle = result.placement.obstacle
    pinned = PinnedPlacement(obstacle, failure.seed, result.placement.direction, Location(repro, 1))
    header = [
        f"The minimal failure of {failure.nodeid}, pinned.",
        "Collect this file on its own to replay it; commit it (or copy its pair into your",
        "pairs file) to keep the case as a regression test.",
    ]
    walls = failure.spec.world.walls.boxes
    footprint = failure.spec.robot.footprint_array()
    return write_best_effort(
        (
            (png, lambda: draw_failure(failure_figure(failure, runs, note), png)),
            (repro, lambda: write_repro(repro, failure.spec, failure.pair, pinned, header)),
            (world, lambda: write_world(world, failure.pair.name, (obstacle,), walls)),
            (numbers, lambda: write_json(numbers, evidence_json(failure))),
            (bag, lambda: write_bag(bag, runs, footprint, (obstacle, *walls))),
        )
    )


def failure_moment(run: Run) -> tuple[float, str]:
    """When and how the run failed: its collision, its getting stuck, or its time running out."""
    verdicts = run.verdicts
    if verdicts.collision.time is not None:
        return verdicts.collision.time, f"collided at t = {verdicts.collision.time:.2f} s"
    if verdicts.stuck.time is not None:
        return verdicts.stuck.time, f"stuck at t = {verdicts.stuck.time:.2f} s"
    end = float(run.times[-1])
    return end, f"goal not reached by t = {end:.2f} s"


def failure_figure(failure: PlacementFailure, runs: dict[str, Run], note: str) -> FailureFigure:
    """The picture of the candidate's failure at the minimal placement, from its runs by role
    (the baseline's only where it was driven) and a note for the title."""
    result, candidate = failure.result, runs["candidate"]
    baseline = runs.get("baseline", candidate)
    title = f"{failure.nodeid}: {result.classification}{note}"
    obstacle = result.placement.obstacle
    return drive_figure(title, failure.spec, failure.pair, (baseline, candidate), obstacle)


def driven_again(
    runs: tuple[Run | None, Run], controller: ControllerChoice
) -> tuple[dict[str, Run], str]:
    """The baseline's run (if it was driven) and the candidate's, driven again recording what
    each robot published (the same runs: runs are deterministic), by role; and a note for the
    picture's title where the controller breaks on being asked what it publishes, whose runs
    are then kept as they were."""
    again: dict[str, Run] = {}
    try:
        for role, run in zip(("baseline", "candidate"), runs, strict=True):
            if run is not None:
                scenario = dataclasses.replace(run.scenario, record=True)
                again[role] = run_scenario(scenario, controller.factory)
    except ControllerError as error:
        kept = dict(zip(("baseline", "candidate"), runs, strict=True))
        note = f" (not recorded: {error.fault.describe()})"
        return {role: run for role, run in kept.items() if run is not None}, note
    return again, ""


def drive_figure(
    title: str, spec: PairsFile, pair: Pair, runs: tuple[Run, Run], obstacle: Obstacle | None
) -> FailureFigure:
    """The picture of the candidate's failure in one world, both robots' runs (baseline,
    candidate) drawn at the moment the candidate failed, among the world's walls, over the
    costmap the candidate's run kept, if it kept one."""
    baseline, candidate = runs
    time, label = failure_moment(candidate)
    candidate_pose, baseline_pose = _pose_at(candidate, time), _pose_at(baseline, time)
    world = spec.world
    walls = world.walls
    return FailureFigure(
        title=f"{title}, candidate {label}",
        obstacle=obstacle,
        baseline_path=baseline.poses[:, :2],
        candidate_path=candidate.poses[:, :2],
        footprint=spec.robot.footprint_array(),
        candidate_pose=_triple(candidate_pose),
        baseline_pose=_triple(baseline_pose),
        beams=(
            beam_fan(
                f"baseline {pair.baseline.label}",
                pair.baseline.profile,
                baseline_pose,
                obstacle,
                walls,
            ),
            beam_fan(
                f"candidate {pair.candidate.label}",
                pair.candidate.profile,
                candidate_pose,
                obstacle,
                walls,
            ),
        ),
        failure=_failure_point(candidate, candidate_pose, obstacle, walls),
        failure_label=label,
        goal=(world.goal.x, world.goal.y),
        start=(world.start.x, world.start.y),
        walls=walls.boxes,
        costmap=candidate.recording.last_costmap if candidate.recording else None,
    )


def write_control_evidence(
    directory: Path,
    nodeid: str,
    spec: PairsFile,
    pair: Pair,
    drives: PairDrive,
    run_options: dict[str, object],
    controller: ControllerChoice,
) -> Artifacts:
    """The artifacts of a failure in the world without an obstacle, each best-effort: the
    picture, the Gazebo world with only the walls, every number and the rosbag2; the item itself
    replays it."""
    png, _, world, numbers, bag = (artifact_path(directory, nodeid, suffix) for suffix in SUFFIXES)
    again, note = driven_again((drives.baseline, drives.candidate), controller)
    runs = (again["baseline"], again["candidate"])
    evidence = {
        **evidence_header(nodeid, spec, pair, run_options),
        "candidate": _run_json(drives.candidate),
        "baseline": _run_json(drives.baseline),
    }
    figure = drive_figure(f"{nodeid}: no obstacle{note}", spec, pair, runs, None)
    walls = spec.world.walls.boxes
    return write_best_effort(
        (
            (png, lambda: draw_failure(figure, png)),
            (world, lambda: write_world(world, pair.name, (), walls)),
            (numbers, lambda: write_json(numbers, evidence)),
            (bag, lambda: write_bag(bag, again, spec.robot.footprint_array(), walls)),
        )
    )


def write_coverage_evidence(
    directory: Path,
    nodeid: str,
    scanners: tuple[Scanner, Scanner],
    comparison: CoverageComparison,
    header: dict[str, object],
) -> Artifacts:
    """The numbers of a lost coverage, best-effort: both scanners' profiles and LaserScans, and
    every change."""
    baseline, candidate = scanners
    path = artifact_path(directory, nodeid, ".json")
    evidence = {
        **header,
        "baseline": _scanner_json(baseline),
        "candidate": _scanner_json(candidate),
        "coverage": dataclasses.asdict(comparison),
    }
    return write_best_effort(((path, lambda: write_json(path, evidence)),))


def write_rejection_evidence(
    directory: Path,
    nodeid: str,
    witness: Witness,
    verification: Verification,
    header: dict[str, object],
) -> Artifacts:
    """The numbers of a witness the exact ray cast rejects, best-effort: the witness and every
    margin."""
    path = artifact_path(directory, nodeid, ".json")
    evidence = {
        **header,
        "witness": witness_json(witness),
        "verification": dataclasses.asdict(verification),
    }
    return write_best_effort(((path, lambda: write_json(path, evidence)),))


def evidence_header(
    nodeid: str, spec: PairsFile, pair: Pair, run_options: dict[str, object]
) -> dict[str, object]:
    """What every JSON file of a failure starts with: the item, its pairs file and pair, and
    the run's seed, profile and policy."""
    return {"item": nodeid, "pairs_file": str(spec.path), "pair": pair.name, **run_options}


def _scanner_json(scanner: Scanner) -> dict[str, object]:
    profile = scanner.profile
    return {
        "model": scanner.model,
        **dataclasses.asdict(profile),
        "laserscan": dataclasses.asdict(profile.to_laserscan_meta()),
    }


def beam_fan(
    label: str,
    profile: LaserProfile,
    pose: FloatArray,
    obstacle: Obstacle | None,
    walls: Walls = NO_WALLS,
) -> BeamFan:
    """The scanner's beams at `pose`, each stopped where it enters the obstacle, at a wall, or
    at range_max; an obstacle behind a wall is not read (as `model/verify.py` has it)."""
    origins, directions = (array[0] for array in profile.rays(pose.reshape(1, 3)))
    hits = np.zeros(len(origins), dtype=bool)
    distances = np.full(len(origins), np.inf)
    reach = walls.reach(origins, directions)  # inf without walls
    if obstacle is not None:
        distances = ray_distances(origins, directions, obstacle)
        hits = (distances >= profile.range_min) & (distances <= profile.range_max)
        hits &= (distances < reach) & (obstacle.height > profile.scan_height)
    lengths = np.where(hits, distances, np.minimum(reach, profile.range_max))
    ends = origins + directions * lengths[:, np.newaxis]
    name = f"{label}: {profile.beam_count} beams, {profile.range_max:g} m"
    return BeamFan(name, origins, ends, hits)


def evidence_json(failure: PlacementFailure) -> dict[str, object]:
    """Every number of the failure."""
    result, trials = failure.result, failure.trials
    return {
        **evidence_header(failure.nodeid, failure.spec, failure.pair, failure.run_options),
        "witness": witness_json(failure.witness),
        "offset": dataclasses.asdict(result.offset),
        "minimal_obstacle": obstacle_json(result.placement.obstacle),
        "verification": dataclasses.asdict(result.verification),
        "classification": result.classification,
        "failed_oracles": result.oracles(),
        "candidate": _run_json(result.candidate),
        "baseline": _run_json(result.baseline) if result.baseline is not None else None,
        "box": {
            "low": dataclasses.asdict(failure.box.low),
            "high": dataclasses.asdict(failure.box.high),
        },
        "search": {
            "examples": trials.examples,
            "rejected": trials.rejected,
            "simulations": trials.simulations,
            "simulations_to_failure": trials.simulations_to_failure,
        },
    }


def _run_json(run: Run) -> dict[str, object]:
    verdicts = {
        name: {**dataclasses.asdict(verdict), "passed": verdict.passed, "margin": verdict.margin}
        for name, verdict in run.verdicts.named()
    }
    return {
        "passed": run.passed,
        "verdicts": verdicts,
        "trajectory_digest": run.digest(),
        "duration": float(run.times[-1]),
        "final_pose": run.poses[-1].tolist(),
    }


def _pose_at(run: Run, time: float) -> FloatArray:
    """The run's pose at `time`, or its last if it ended before."""
    index = min(int(np.searchsorted(run.times, time)), len(run.times) - 1)
    pose: FloatArray = run.poses[index]
    return pose


def _failure_point(
    run: Run, pose: FloatArray, obstacle: Obstacle | None, walls: Walls = NO_WALLS
) -> tuple[float, float]:
    """Where the obstacle or a wall was touched (the point of either nearest the robot), else
    where the robot was."""
    x, y = float(pose[0]), float(pose[1])
    solids = (*([] if obstacle is None else [obstacle]), *walls.boxes)
    if run.verdicts.collision.time is None or not solids:
        return x, y
    touched = (solid.nearest_point(x, y) for solid in solids)
    return min(touched, key=lambda point: math.hypot(point[0] - x, point[1] - y))


def _triple(pose: FloatArray) -> tuple[float, float, float]:
    x, y, yaw = pose.tolist()
    return x, y, yaw
