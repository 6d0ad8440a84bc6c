"""What `lasertest plan` prints: the witnesses of every pair, as text or as the JSON contract.

The JSON is a stable contract (documented in the README):
`{"pairs": [{"name", "status", "explanation", "baseline", "candidate", "start", "goal", "path",
"witnesses": [{"id", "direction", "obstacle", "pose", "detected_by", "margin", "lead",
"late"}]}]}`.
"""

from __future__ import annotations

import dataclasses

from pytest_lasertest.model.geometry import Box, Obstacle
from pytest_lasertest.model.verify import ROLES, PairPlan, Status, Witness
from pytest_lasertest.model.sensor import LaserProfile

DETECTED_BY = {direction: detector for direction, (detector, _) in ROLES.items()}


def pair_status(plan: PairPlan) -> Status:
    """sat when either direction has a witness; unknown when Z3 could not decide; else unsat."""
    statuses = {direction.status for direction in plan.directions}
    if "sat" in statuses:
        return "sat"
    return "unknown" if "unknown" in statuses else "unsat"


def plan_json(plan: PairPlan) -> dict[str, object]:
    """One pair of the JSON contract."""
    scene = plan.scene
    start = scene.path.start
    return {
        "name": plan.name,
        "status": pair_status(plan),
        "explanation": _explanation(plan),
        "baseline": profile_json(scene.baseline),
        "candidate": profile_json(scene.candidate),
        "start": [start.x, start.y, start.yaw],
        "goal": list(scene.path.polyline()[-1]),
        "path": [list(point) for point in scene.path.polyline()],
        "witnesses": [
            witness_json(witness)
            for direction in plan.directions
            for witness in direction.witnesses
        ],
    }


def profile_json(profile: LaserProfile) -> dict[str, object]:
    """A profile's Gazebo fields and its mount relative to base_footprint."""
    return {
        "samples": profile.samples,
        "resolution": profile.resolution,
        "min_angle": profile.min_angle,
        "max_angle": profile.max_angle,
        "range_min": profile.range_min,
        "range_max": profile.range_max,
        "range_resolution": profile.range_resolution,
        "update_rate": profile.update_rate,
        "noise": None if profile.noise is None else dataclasses.asdict(profile.noise),
        "mount": {"xyz": list(profile.pose.xyz), "rpy": list(profile.pose.rpy)},
    }


def witness_json(witness: Witness) -> dict[str, object]:
    """One witness: the obstacle, the robot pose where only one scanner reads it, the margin."""
    return {
        "id": witness.id,
        "direction": witness.placement.direction,
        "obstacle": obstacle_json(witness.placement.obstacle),
        "pose": list(witness.pose),
        "detected_by": DETECTED_BY[witness.placement.direction],
        "margin": witness.verification.margin,
        "lead": witness.verification.lead,
        "late": witness.verification.late,
    }


def obstacle_json(obstacle: Obstacle) -> dict[str, object]:
    """A box's side lengths or a cylinder's radius, with its centre, yaw and height."""
    if isinstance(obstacle, Box):
        shape: dict[str, object] = {"shape": "box", "yaw": obstacle.yaw}
        shape["size"] = [obstacle.length, obstacle.width]
    else:
        shape = {"shape": "cylinder", "yaw": 0.0, "radius": obstacle.radius}
    return {"x": obstacle.x, "y": obstacle.y, **shape, "height": obstacle.height}


def plan_text(plan: PairPlan) -> str:
    """A few lines per pair for people."""
    lines = [f"{plan.name}: {pair_status(plan)}"]
    for direction in plan.directions:
        lines.append(f"  {direction.direction}: {direction.status}")
        for witness in direction.witnesses:
            x, y, yaw = witness.pose
            lines.append(
                f"    {witness.id}: {describe_obstacle(witness.placement.obstacle)}; "
                f"read by the {DETECTED_BY[direction.direction]} from ({x:.2f}, {y:.2f}, "
                f"{yaw:.2f}) at t = {witness.placement.anchor:.2f} s; "
                f"margin {witness.verification.margin * 1000:.1f} mm; {_lead(witness)}"
            )
        if direction.explanation:
            lines.append(f"    {direction.explanation}")
    return "\n".join(lines)


def _lead(witness: Witness) -> str:
    """How long the difference lasts on the approach."""
    lead = witness.verification.lead
    _, misser = ROLES[witness.placement.direction]
    if witness.verification.late:
        return f"the {misser} misses it for {lead:.2f} m, until too late to stop"
    return f"the {misser} misses it for {lead:.2f} m more"


def describe_obstacle(obstacle: Obstacle) -> str:
    """`box 0.051 x 0.051 m, yaw 0.000 rad, at (4.524, -0.312) m, 0.327 m high`."""
    where = f"at ({obstacle.x:.3f}, {obstacle.y:.3f}) m, {obstacle.height:.3f} m high"
    if isinstance(obstacle, Box):
        sides = f"{obstacle.length:.3f} x {obstacle.width:.3f} m"
        return f"box {sides}, yaw {obstacle.yaw:.3f} rad, {where}"
    return f"cylinder of radius {obstacle.radius:.3f} m {where}"


def _explanation(plan: PairPlan) -> str:
    return "; ".join(
        f"{direction.direction}: {direction.explanation}"
        for direction in plan.directions
        if direction.explanation
    )
