"""What a failing placement item tells its reader, and what every placement item records.

The report names the oracle that fired and its margin, the minimal failing placement and its
change from the witness, which beams of each scanner read the obstacle, whether the baseline
fails there too, the search's figures, the seed and how to replay the case. The same numbers go
on `item.user_properties` as plain values, so they reach JUnit XML and cross to the pytest-xdist
controller, where the run's summary is made from them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pytest_lasertest.search.drives import run_properties
from pytest_lasertest.model.geometry import Obstacle
from pytest_lasertest.search.offsets import AXES, OffsetBox
from pytest_lasertest.model.verify import ROLES, Scene, Verification, hit_margins
from pytest_lasertest.reports.plan import describe_obstacle
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.pairsfile import Pair
from pytest_lasertest.search.trials import TrialResult, Trials

# What each class of failure means for the change.
MEANINGS = {
    "regression": "a regression: the baseline passes where the candidate fails",
    "pre-existing": "pre-existing: the baseline fails here too",
    "improvement": "an improvement: the candidate passes where the baseline fails",
    "unchanged": "unchanged: both pass",
}


@dataclass(frozen=True)
class BeamReading:
    """Which beams of one scan read an obstacle, or how near the nearest came."""

    hits: tuple[int, ...]  # beam indices, in the LaserScan's order
    depth: float  # m, how deep the deepest beam passes inside; negative: the nearest's clearance
    nearest: int  # the beam passing deepest, or nearest

    def describe(self) -> str:
        if not self.hits:
            clear = -self.depth * 1000  # mm
            return f"no beam reads it; beam {self.nearest} comes nearest, {clear:.0f} mm clear"
        beams = ", ".join(map(str, self.hits[:8])) + (" ..." if len(self.hits) > 8 else "")
        plural = "s" if len(self.hits) > 1 else ""
        return f"beam{plural} {beams} read it, {self.depth * 1000:.0f} mm deep"


def beam_reading(profile: LaserProfile, pose: np.ndarray, obstacle: Obstacle) -> BeamReading:
    """The beams of the scan `profile` takes at `pose` [x, y, yaw] that read `obstacle`."""
    margins = hit_margins(profile, pose.reshape(1, 3), obstacle)[0]
    nearest = int(np.argmax(margins))
    hits = tuple(int(index) for index in np.flatnonzero(margins > 0.0))
    return BeamReading(hits, float(margins[nearest]), nearest)


def beam_lines(scene: Scene, result: TrialResult) -> list[str]:
    """Each scanner's reading of the minimal placement, at the instant the detector must see it."""
    placement = result.placement
    pose = scene.path.poses_at(np.array([placement.anchor]))[0]
    lines = [f"  beams      at t = {placement.anchor:.2f} s, robot at {_pose(pose)}:"]
    for side in ROLES[placement.direction]:
        profile = getattr(scene, side)
        reading = beam_reading(profile, pose, placement.obstacle)
        lines.append(f"    {side:<9} {reading.describe()}")
    return lines


def margin_line(verification: Verification) -> str:
    """The minimal placement's ray-cast margins."""
    return f"  margins    {margins_text(verification)}"


def margins_text(verification: Verification) -> str:
    """`detection 15.2 mm, concealment ...`: each of the ray cast's margins."""
    parts = {
        "detection": verification.detection,
        "concealment": verification.concealment,
        "clearance": verification.clearance,
        "obstruction": verification.obstruction,
    }
    return ", ".join(f"{name} {value * 1000:.1f} mm" for name, value in parts.items())


def oracle_lines(result: TrialResult) -> list[str]:
    """The candidate's failing oracles, each with its margin."""
    return [
        f"  oracle     {name}: {verdict.describe()} (margin {verdict.margin * 1000:.1f} mm)"
        for name, verdict in result.candidate.verdicts.named()
        if not verdict.passed
    ]


def search_line(trials: Trials, box: OffsetBox) -> str:
    """What the search cost and found."""
    found = (
        f"the first failure at simulation {trials.simulations_to_failure}, then "
        f"{trials.shrink_simulations} more to classify and shrink it"
        if trials.simulations_to_failure is not None
        else "no failure"
    )
    return (
        f"  search     {trials.examples} examples, {trials.rejected} rejected "
        f"({trials.rejection_rate:.0%}), {trials.simulations} simulations; {found}; "
        f"offsets up to {_reach(box)}"
    )


def search_properties(box: OffsetBox, trials: Trials) -> list[tuple[str, object]]:
    """The search's figures, for JUnit XML and the run's summary."""
    witness = trials.witness_result
    rows: list[tuple[str, object]] = [
        ("lasertest.examples", trials.examples),
        ("lasertest.rejected", trials.rejected),
        ("lasertest.simulations", trials.simulations),
        ("lasertest.failures", trials.failures),
        # Found whether or not the policy fails the item on them.
        ("lasertest.regressions", trials.count("regression")),
        ("lasertest.pre_existing", trials.count("pre-existing")),
    ]
    if trials.simulations_to_failure is not None:
        rows.append(("lasertest.simulations_to_failure", trials.simulations_to_failure))
    for name in AXES:
        low, high = box.bounds(name)
        rows.append((f"lasertest.box.{name}", f"{low:+.4f} .. {high:+.4f}"))
    if witness is not None:
        # At the witness itself, as each robot drove it (the baseline only if the candidate failed).
        rows += run_properties("candidate", witness.candidate)
        if witness.baseline is not None:
            rows += run_properties("baseline", witness.baseline)
    return rows


def failure_properties(result: TrialResult) -> list[tuple[str, object]]:
    """The minimal failure: its oracles, its class and its change from the witness."""
    return [
        ("lasertest.failed_oracles", ",".join(result.oracles())),
        ("lasertest.classification", result.classification),
        ("lasertest.offset", result.offset.describe()),
        ("lasertest.minimal_obstacle", describe_obstacle(result.placement.obstacle)),
    ]


def _reach(box: OffsetBox) -> str:
    units = {"yaw": "rad"}
    parts = []
    for name in AXES:
        low, high = box.bounds(name)
        if low or high:
            parts.append(f"{name} {low:+.3f}..{high:+.3f} {units.get(name, 'm')}")
    return ", ".join(parts) or "none (the witness alone)"


def _pose(pose: np.ndarray) -> str:
    x, y, yaw = pose.tolist()
    return f"({x:.2f}, {y:.2f}, {yaw:.2f})"


def trial_lines(result: TrialResult, pair: Pair) -> list[str]:
    """What each robot did at the minimal placement."""
    lines = []
    for side, run in (("baseline", result.baseline), ("candidate", result.candidate)):
        label = getattr(pair, side).label
        if run is None:
            lines.append(f"  {side:<10} {label}: not driven (the candidate passed)")
            continue
        outcome = "; ".join(verdict.describe() for _, verdict in run.verdicts.named())
        lines.append(f"  {side:<10} {label}: {'passed' if run.passed else 'FAILED'}: {outcome}")
    return lines
