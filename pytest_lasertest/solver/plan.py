"""Witnesses for both directions of a pair: diverse, verified, or a reason why there are none."""

from __future__ import annotations

import numpy as np

from pytest_lasertest.path import nominal_path
from pytest_lasertest.placement import (
    DIRECTIONS,
    Direction,
    DirectionPlan,
    PairPlan,
    Scene,
    Status,
    Witness,
)
from pytest_lasertest.solver.backend import Solution
from pytest_lasertest.solver.search import Found, Query, SearchSettings, anchor_times, shapes_for
from pytest_lasertest.spec.pairs import Pair, PairsFile

SIDE = {"candidate-misses": ("baseline", "candidate"), "baseline-misses": ("candidate", "baseline")}


def plan_direction(scene: Scene, direction: Direction, settings: SearchSettings) -> DirectionPlan:
    """Up to `settings.witnesses` witnesses, each from the next anchor that yields one."""
    anchors = anchor_times(scene, direction, settings.anchor_spacing)
    witnesses: list[Witness] = []
    answers: list[Solution] = []
    cursor = 0
    for index in range(settings.witnesses):
        for step in range(len(anchors)):
            anchor = anchors[(cursor + step) % len(anchors)]
            found = _at_anchor(scene, direction, anchor, index, settings, witnesses, answers)
            if found is not None:
                witnesses.append(found)
                cursor = (cursor + step + 1) % len(anchors)
                break
        else:
            break
    if witnesses:
        missing = settings.witnesses - len(witnesses)
        note = f"only {len(witnesses)} diverse witnesses found" if missing else ""
        return DirectionPlan(direction, "sat", tuple(witnesses), note)
    return _without_witness(scene, direction, settings, anchors, answers)


def _at_anchor(
    scene: Scene,
    direction: Direction,
    anchor: float,
    index: int,
    settings: SearchSettings,
    witnesses: list[Witness],
    answers: list[Solution],
) -> Witness | None:
    pose = _pose(scene, anchor)
    apart = tuple(witness.placement.obstacle for witness in witnesses)
    for shape in shapes_for(index, pose[2]):
        result = Query(scene, direction, anchor, shape, settings, apart).run()
        if isinstance(result, Found):
            return Witness(index, result.placement, result.verification, pose)
        answers.append(result)
    return None


def _pose(scene: Scene, time: float) -> tuple[float, float, float]:
    """The robot's pose [x, y, yaw] on the nominal path at `time`."""
    x, y, yaw = (float(value) for value in scene.path.poses_at(np.array([time]))[0])
    return x, y, yaw


def _without_witness(
    scene: Scene,
    direction: Direction,
    settings: SearchSettings,
    anchors: list[float],
    answers: list[Solution],
) -> DirectionPlan:
    if not anchors:
        return DirectionPlan(
            direction, "unsat", (), "the path leaves no room to brake before the goal"
        )
    # The searches offered Z3 a few promising beams; a proof needs every beam of the scan.
    pose = _pose(scene, anchors[0])
    proofs = [
        Query(scene, direction, anchors[0], shape, settings, beam_limit=None).run()
        for shape in shapes_for(0, pose[2])
    ]
    for proof in proofs:
        if isinstance(proof, Found):
            witness = Witness(0, proof.placement, proof.verification, pose)
            return DirectionPlan(direction, "sat", (witness,), "")
    solutions = [proof for proof in proofs if isinstance(proof, Solution)]
    undecided = any(answer.verdict == "unknown" for answer in [*solutions, *answers])
    status: Status = "unknown" if undecided else "unsat"
    searched = f"; no witness at the other {len(anchors) - 1} anchors searched along the path"
    return DirectionPlan(
        direction, status, (), explain(scene, direction, settings, solutions) + searched
    )


def explain(
    scene: Scene, direction: Direction, settings: SearchSettings, solutions: list[Solution]
) -> str:
    """Why no placement discriminates at the start pose, from the unsat cores, in words."""
    unknown = [s.reason for s in solutions if s.verdict == "unknown"]
    if unknown:
        return f"Z3 could not decide at the start pose ({unknown[0]})"
    detector_side, misser_side = SIDE[direction]
    labels = sorted({label for solution in solutions for label in solution.core})
    reasons = [_reason(label, scene, direction, settings) for label in labels]
    return (
        f"no obstacle discriminates at the start pose: the {detector_side} cannot read one "
        f"that the {misser_side} misses under these conditions together: "
        + "; ".join(reason for reason in reasons if reason)
    )


def _reason(label: str, scene: Scene, direction: Direction, settings: SearchSettings) -> str:
    detector_side, misser_side = SIDE[direction]
    if label == "bounds":
        return f"obstacle size {settings.min_size:g}-{settings.max_size:g} m"
    if label == "robot":
        return f"clear of the robot until it stands ({scene.robot.braking_distance:.2f} m braking)"
    if label == "path":
        return "in the robot's way after it could stop"
    if label == "detector":
        return f"read by the {detector_side} ({scene.detector(direction).describe()})"
    if label.startswith("misser@"):
        return f"missed by the {misser_side} ({scene.misser(direction).describe()})"
    if label.startswith("constraint "):
        constraint = settings.constraints[int(label.split()[1])]
        return f"your constraint {constraint.text!r} ({constraint.location})"
    return ""


def plan_pair(spec: PairsFile, pair: Pair) -> PairPlan:
    """Both directions of one pair of a pairs file."""
    robot = spec.robot
    path = nominal_path(
        spec.world.start, spec.world.route, robot.nominal_speed, robot.nominal_turn_rate
    )
    scene = Scene(pair.baseline.profile, pair.candidate.profile, robot, path)
    settings = SearchSettings(
        witnesses=spec.settings.witnesses,
        min_size=spec.settings.min_obstacle_size,
        max_size=spec.settings.max_obstacle_size,
        constraints=spec.constraints,
    )
    plans = tuple(plan_direction(scene, direction, settings) for direction in DIRECTIONS)
    return PairPlan(pair.name, scene, plans)
