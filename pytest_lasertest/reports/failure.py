"""What a placement item tells its reader when it fails, and what every placement item records.

A failure report names the oracle that fired and its margin, the minimal failing placement and
its change from the witness, which beams of each scanner read the obstacle, whether the baseline
fails there too, the search's figures, the seed and how to replay the case. A witness the exact
ray cast rejects is reported as the bug in the solver it is. The same numbers go on
`item.user_properties` as plain values, so they reach JUnit XML and cross to the pytest-xdist
controller, where the run's summary is made from them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pytest_lasertest.model.obstacles import Obstacle
from pytest_lasertest.model.plan import Witness
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.model.verify import (
    REQUIRED_MARGIN,
    Scene,
    Verification,
    hit_margins,
    read_too_near,
    readings,
)
from pytest_lasertest.pairsfile import Pair, PairsFile
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.reports.drive import (
    MEANINGS,
    controller_line,
    redrive_lines,
    robot_line,
    run_properties,
)
from pytest_lasertest.reports.formats import Artifacts, Replay, pose_text, run_line, shell_word
from pytest_lasertest.search.blame import ChainTried, TraitTried, blame_lines
from pytest_lasertest.search.offsets import AXES, OffsetBox
from pytest_lasertest.search.trials import TrialResult, Trials

REPRO_SUFFIX = ".lasertest.yaml"


@dataclass(frozen=True)
class PlacementFailure:
    """A placement item's minimal failure, and the search that found it."""

    nodeid: str  # the item's
    spec: PairsFile
    pair: Pair
    controller: ControllerChoice
    witness: Witness
    result: TrialResult  # the minimal failing trial
    trials: Trials
    box: OffsetBox
    notes: tuple[str, ...]  # Hypothesis's own: the falsifying example, what explain found
    seed: int  # of the run, and of its scan noise
    run_options: dict[str, object]  # the run's seed, profile and policy, as artifacts record
    unstored: str | None = None  # why Hypothesis's example database cannot keep the failure
    # The candidate again with each driver trait the pair differs in set to the baseline's.
    driver_tried: tuple[TraitTried, ...] = ()
    # The candidate again with the pair's scan filter chain taken out, where it has one.
    chain_tried: ChainTried | None = None


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


def failure_report(failure: PlacementFailure, replay: Replay, artifacts: Artifacts) -> str:
    """The report of a placement item's minimal failure."""
    pair, result, trials = failure.pair, failure.result, failure.trials
    lines = [
        f"the candidate fails ({' and '.join(result.oracles())}) near witness "
        f"{failure.witness.id}: {MEANINGS[result.classification]}",
        f"  pair       {pair.name} ({pair.location})",
        controller_line(failure.controller),
        robot_line(result.candidate.scenario.robot),
        *oracle_lines(result),
        f"  witness    {failure.witness.placement.obstacle.describe()}",
        f"  minimal    {result.placement.obstacle.describe()}",
        f"  change     {result.offset.describe()} ({_which_change(result, trials)})",
        f"  margins    {margins_text(result.verification)}",
        *beam_lines(trials.scene, result),
        run_line("baseline", pair.baseline.label, result.baseline),
        run_line("candidate", pair.candidate.label, result.candidate),
        *(redrive_lines(result.drive) if result.drive is not None else []),
        *blame_lines(failure.driver_tried, failure.chain_tried),
        search_line(trials, failure.box),
        *(f"  hypothesis {note}" for note in failure.notes),
        f"  policy     {trials.policy}",
        f"  seed       {failure.seed}",
        *_replay_lines(replay, artifacts, _stored(failure)),
    ]
    return "\n".join(lines)


def _which_change(result: TrialResult, trials: Trials) -> str:
    """Whether the change shown is the search's smallest failure, or one it only noted."""
    if result.fails(trials.policy):
        return "the smallest the search found that fails"
    return f"the first the search found; the {trials.policy} policy does not fail the run on it"


def _stored(failure: PlacementFailure) -> str:
    """What a rerun of the item does: replay the failure from the example database, where the
    search failed on it and could store it; else search again, as this run did."""
    if not failure.result.fails(failure.trials.policy):
        return "(searches again as this run did: the same seed tries the same examples)"
    if failure.unstored is not None:
        return (
            f"(searches afresh: the example database cannot keep this case, as {failure.unstored})"
        )
    return "(replays this case first, from .hypothesis/)"


def _replay_lines(replay: Replay, artifacts: Artifacts, stored: str) -> list[str]:
    """How to run the case again: the item, and the pinned repro if one was written; then where
    the artifacts are, and any that could not be written."""
    repro = [path for path in artifacts.written if path.name.endswith(REPRO_SUFFIX)]
    lines = artifacts.lines("artifact", replay.here)
    if not repro:
        return [f"{replay.line()}  {stored}", *lines]
    return [
        f"  replay     pytest {shell_word(replay.shown(repro[0]))}  (this case alone, pinned)",
        f"  rerun      {replay.command()}  {stored}",
        *lines,
    ]


def rejection_report(
    pair: Pair, witness: Witness, verification: Verification, replay: Replay, artifacts: Artifacts
) -> str:
    """The report of a witness the exact ray cast rejects: a bug in the solver."""
    placement = witness.placement
    lines = [
        f"the exact ray cast rejects witness {witness.id}, which the solver returned as "
        "verified: this is a bug in pytest-lasertest's solver, please report it with this "
        "pairs file",
        f"  pair       {pair.name} ({pair.location})",
        f"  baseline   {pair.baseline.label}: {pair.baseline.profile.describe()}",
        f"  candidate  {pair.candidate.label}: {pair.candidate.profile.describe()}",
        f"  obstacle   {placement.obstacle.describe()}",
        f"  read by    the {placement.read_by()} at t = "
        f"{placement.anchor:.2f} s, robot at {pose_text(*witness.pose)}",
        f"  margins    {margins_text(verification)}; each must reach "
        f"{REQUIRED_MARGIN * 1000:.1f} mm",
    ]
    if verification.seen_by_misser_at:
        times = ", ".join(f"{time:.2f}" for time in verification.seen_by_misser_at)
        lines.append(f"  misser     reads it at t = {times} s")
    lines.append(replay.line())
    lines += artifacts.lines("evidence", replay.here)
    return "\n".join(lines)


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
    lines = [f"  beams      at t = {placement.anchor:.2f} s, robot at {pose_text(*pose.tolist())}:"]
    for side in placement.scanners:
        profile = getattr(scene, side)
        reading = beam_reading(profile, pose, placement.obstacle)
        lines.append(f"    {side:<9} {reading.describe()}")
    if math.isfinite(result.verification.too_near):
        lines += too_near_lines(scene, placement.obstacle)
    return lines


def too_near_lines(scene: Scene, obstacle: Obstacle) -> list[str]:
    """Where the candidate reads a placement both read nearer than its range_min, beam by beam."""
    depth, time = read_too_near(scene, obstacle)
    if not depth > 0.0:
        return []
    pose = scene.path.poses_at(np.array([time]))
    near = np.flatnonzero(np.isneginf(readings(scene.candidate, pose, obstacle)[0]))
    beams = ", ".join(map(str, near[:8])) + (" ..." if len(near) > 8 else "")
    return [
        f"  too near   at t = {time:.2f} s, robot at {pose_text(*pose[0].tolist())}: candidate "
        f"beams {beams} read it nearer than range_min {scene.candidate.range_min} m (-inf), "
        f"the baseline in range"
    ]


def margins_text(verification: Verification) -> str:
    """`detection 15.2 mm, concealment ...`: each of the ray cast's margins."""
    parts = {
        "detection": verification.detection,
        "concealment": verification.concealment,
        "clearance": verification.clearance,
        "obstruction": verification.obstruction,
    }
    # Only a placement both scanners read is judged on being read too near (else it is -inf), and
    # it has no misser to conceal it: its concealment is infinite.
    if math.isfinite(verification.too_near):
        parts["read too near"] = verification.too_near
    return ", ".join(
        f"{name} {value * 1000:.1f} mm" for name, value in parts.items() if value != math.inf
    )


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
        # The search looks for what the policy fails: under `regression`, regressions only.
        else f"no {'regression' if trials.policy == 'regression' else 'failure'}"
    )
    return (
        f"  search     {trials.examples} examples, {trials.rejected} rejected "
        f"({trials.rejection_rate:.0%}), {trials.simulations} simulations; {found}; "
        f"offsets up to {_reach(box)}"
    )


def witness_properties(witness: Witness, verification: Verification) -> list[tuple[str, object]]:
    """The witness an item searches around, and its ray-cast margins."""
    return [
        ("lasertest.obstacle", witness.placement.obstacle.describe()),
        ("lasertest.margin", verification.margin),
        ("lasertest.lead", verification.lead),
        ("lasertest.late", verification.late),
        ("lasertest.detected_by", witness.placement.read_by()),
    ]


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
        ("lasertest.marginal", trials.count("marginal")),
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
        ("lasertest.minimal_obstacle", result.placement.obstacle.describe()),
    ]


def _reach(box: OffsetBox) -> str:
    units = {"yaw": "rad"}
    parts = []
    for name in AXES:
        low, high = box.bounds(name)
        if low or high:
            parts.append(f"{name} {low:+.3f}..{high:+.3f} {units.get(name, 'm')}")
    return ", ".join(parts) or "none (the witness alone)"
