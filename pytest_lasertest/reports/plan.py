"""What `lasertest plan` prints: the witnesses of every pair, as text or as the JSON contract.

The JSON is a stable contract (documented in docs/reference/cli.md):
`{"pairs": [{"name", "status", "explanation", "baseline", "candidate", "start", "goal", "path",
"witnesses": [{"id", "direction", "obstacle", "pose", "detected_by", "margin", "lead",
"late"}]}]}`.
"""

from __future__ import annotations

from pytest_lasertest.model.plan import PairPlan, Witness
from pytest_lasertest.model.verify import DETECTED_BY, ROLES, Direction
from pytest_lasertest.reports.formats import pose_text, profile_json, witness_json


def plan_json(plan: PairPlan) -> dict[str, object]:
    """One pair of the JSON contract."""
    scene = plan.scene
    start = scene.path.start
    return {
        "name": plan.name,
        "status": plan.status,
        "explanation": _explanation(plan),
        "baseline": profile_json(scene.baseline),
        "candidate": profile_json(scene.candidate),
        "start": [start.x, start.y, start.yaw],
        "goal": list(scene.path.polyline()[-1]),
        "path": [list(point) for point in scene.path.polyline()],
        "witnesses": [witness_json(witness) for witness in plan.witnesses()],
    }


def plan_text(plan: PairPlan) -> str:
    """A few lines per pair for people."""
    lines = [f"{plan.name}: {plan.status}"]
    for direction in plan.directions:
        lines.append(f"  {direction.direction}: {direction.status}")
        for witness in direction.witnesses:
            lines.append(
                f"    {witness.id}: {witness.placement.obstacle.describe()}; "
                f"read by the {DETECTED_BY[direction.direction]} from {pose_text(*witness.pose)} "
                f"at t = {witness.placement.anchor:.2f} s; "
                f"margin {witness.verification.margin * 1000:.1f} mm; "
                f"{_lead(witness, direction.direction)}"
            )
        if direction.explanation:
            lines.append(f"    {direction.explanation}")
    return "\n".join(lines)


def _lead(witness: Witness, direction: Direction) -> str:
    """How long the difference lasts on the approach."""
    lead = witness.verification.lead
    _, misser = ROLES[direction]
    if witness.verification.late:
        return f"the {misser} misses it for {lead:.2f} m, until too late to stop"
    return f"the {misser} misses it for {lead:.2f} m more"


def _explanation(plan: PairPlan) -> str:
    return "; ".join(
        f"{direction.direction}: {direction.explanation}"
        for direction in plan.directions
        if direction.explanation
    )
