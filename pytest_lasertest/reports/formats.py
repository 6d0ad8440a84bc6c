"""The shared formats of what reports show: obstacles, scanner profiles, witnesses and runs.

The JSON forms are stable contracts (documented in the README): `lasertest plan --json`,
`lasertest profile --json` and the artifacts' JSON files all write obstacles, profiles and
witnesses this way.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from pytest_lasertest.model.obstacles import Box, Obstacle
from pytest_lasertest.model.plan import Witness
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.sim.scenario import Run


def obstacle_json(obstacle: Obstacle) -> dict[str, object]:
    """A box's side lengths or a cylinder's radius, with its centre, yaw and height."""
    if isinstance(obstacle, Box):
        shape: dict[str, object] = {"shape": "box", "yaw": obstacle.yaw}
        shape["size"] = [obstacle.length, obstacle.width]
    else:
        shape = {"shape": "cylinder", "yaw": 0.0, "radius": obstacle.radius}
    return {"x": obstacle.x, "y": obstacle.y, **shape, "height": obstacle.height}


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
        "detected_by": witness.placement.read_by(),
        "margin": witness.verification.margin,
        "lead": witness.verification.lead,
        "late": witness.verification.late,
    }


def run_line(side: str, label: str, run: Run | None) -> str:
    """`  candidate  sick_lms111: FAILED: collided at ...; ...`: one robot's run in a report, or
    that it was not driven because the candidate passed."""
    if run is None:
        return f"  {side:<10} {label}: not driven (the candidate passed)"
    outcome = "; ".join(verdict.describe() for _, verdict in run.verdicts.named())
    return f"  {side:<10} {label}: {'passed' if run.passed else 'FAILED'}: {outcome}"


def pose_text(x: float, y: float, yaw: float) -> str:
    """`(4.52, -0.31, 0.00)`: a robot pose, m, m, rad."""
    return f"({x:.2f}, {y:.2f}, {yaw:.2f})"


@dataclass(frozen=True)
class Replay:
    """How to run an item again: its node id and the options of the run it failed in."""

    nodeid: str
    options: str  # `--laser-seed=... --laser-profile=... --laser-policy=...`

    def command(self) -> str:
        """`pytest 'NODEID' --laser-seed=...`."""
        return f"pytest '{self.nodeid}' {self.options}"

    def line(self) -> str:
        """`  replay     pytest 'NODEID' --laser-seed=...`, as every failure report ends."""
        return f"  replay     {self.command()}"
