"""What a drive tells its reader: each robot's scanner and what its run did, the controller, the
policy and how to replay it; what a controller that broke a drive did; and the figures JUnit XML
and the run's summary take from it, as plain values that cross to the pytest-xdist controller."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from pytest_lasertest.inputs.errors import display_path
from pytest_lasertest.model.draws import Draw
from pytest_lasertest.model.policy import JITTER, NEAR_MISS, Classification, Policy
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.pairsfile import Pair
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.reports.formats import Replay, run_line
from pytest_lasertest.search.drives import PairDrive, near_misses
from pytest_lasertest.sim.faults import Frame
from pytest_lasertest.sim.scenario import ControllerError, Run

# What each class of failure means for the change.
MEANINGS: dict[Classification, str] = {
    "regression": "a regression: the baseline passes where the candidate fails",
    "marginal": "marginal: the candidate fails where the baseline passes, but not under every "
    "further draw of the scan noise and the obstacles' positions",
    "pre-existing": "pre-existing: the baseline fails here too",
    "improvement": "an improvement: the candidate passes where the baseline fails",
    "unchanged": "unchanged: both pass",
}


def drive_report(
    headline: str,
    pair: Pair,
    controller: ControllerChoice,
    drives: PairDrive,
    details: list[str],
    policy: Policy,
    replay: Replay,
    blame: Sequence[str] = (),
) -> str:
    """A failing drive: what failed, the controller, what happened to each robot (and, for a
    regression, what it comes from: `blame`), and how to replay it."""
    lines = [
        headline,
        f"  pair       {pair.name} ({pair.location})",
        controller_line(controller),
        robot_line(drives.candidate.scenario.robot),
        *details,
        run_line("baseline", pair.baseline.label, drives.baseline),
        run_line("candidate", pair.candidate.label, drives.candidate),
        *redrive_lines(drives),
        *blame,
        f"  policy     {policy}",
        replay.line(),
    ]
    return "\n".join(lines)


def controller_error_report(
    error: ControllerError, pair: Pair, controller: ControllerChoice, replay: Replay
) -> str:
    """A drive the controller broke: what it was called for and what it did, in which drive,
    the lines of its code that did it, and the fix. No traceback: `--fulltrace` shows one."""
    fault, scenario = error.fault, error.scenario
    side = "candidate" if scenario.profile == pair.candidate.profile else "baseline"
    scanner = getattr(pair, side).label
    obstacles = "; ".join(obstacle.describe() for obstacle in scenario.obstacles)
    lines = [
        f"the controller broke the drive: {fault.describe()}",
        f"  pair       {pair.name} ({pair.location})",
        controller_line(controller),
        f"  drive      the {side} robot ({scanner}), "
        + (f"past {obstacles}" if obstacles else "without any obstacle"),
        *_frame_lines(fault.frames),
        f"  fix        {fault.fix}",
        replay.line(),
    ]
    return "\n".join(lines)


def _frame_lines(frames: tuple[Frame, ...]) -> list[str]:
    """`  at         my_controller.py:12 in observe`, then the line deeper down that raised, if
    it is another; paths relative to the working directory."""
    labels = ("at", "inside")[: len(frames)]
    return [
        f"  {label:<10} {display_path(Path(frame.path))}:{frame.line} in {frame.function}"
        for label, frame in zip(labels, frames, strict=True)
    ]


def redrive_lines(drive: PairDrive) -> list[str]:
    """Why a failure of the candidate alone is, or is not, a regression: a near miss of the
    baseline's, and how it held under further draws (each draw's noise seed, how far it moved
    the obstacles, and both robots' outcomes with their margins)."""
    lines = [
        f"  near miss  draw {draw}: the baseline passed {name} by only {margin * 1000:.1f} mm "
        f"(under {NEAR_MISS * 1000:.0f} mm): it came that near failing too"
        for draw, again in enumerate(drive.draws)
        for name, margin in near_misses(again.baseline, again.candidate)
    ]
    redrives, classification = drive.redrives, drive.classification
    if not redrives:
        return lines
    held = "held under all" if classification == "regression" else "did not hold under all"
    lines.append(
        f"  re-driven  under {_draws(len(redrives))} (fresh scan noise, each obstacle moved "
        f"within {JITTER * 1000:.0f} mm); the failure {held} of them:"
    )
    for number, again in enumerate(redrives, start=1):
        assert again.draw is not None  # `drives.redrawn` records every re-drive's draw
        lines.append(
            f"    draw {number}   {_drawn(again.draw)}: baseline {_brief(again.baseline)}; "
            f"candidate {_brief(again.candidate)}"
        )
    return lines


def _draws(count: int) -> str:
    """`1 further draw`, `2 further draws`."""
    return f"{count} further draw" if count == 1 else f"{count} further draws"


def _drawn(draw: Draw) -> str:
    """`seed 2230207094, obstacle moved (+2.7, -4.6) mm`."""
    moves = ", ".join(f"({dx * 1000:+.1f}, {dy * 1000:+.1f})" for dx, dy in draw.shifts)
    moved = f"obstacle moved {moves} mm" if len(draw.shifts) == 1 else f"obstacles moved {moves} mm"
    return f"seed {draw.noise}, {moved}" if draw.shifts else f"seed {draw.noise}"


def _brief(run: Run) -> str:
    """`passed` or `FAILED (stuck)`, and every oracle's margin: `margins collision 212.0, ...`."""
    failed = [name for name, verdict in run.verdicts.named() if not verdict.passed]
    outcome = "passed" if not failed else f"FAILED ({', '.join(failed)})"
    margins = ", ".join(
        f"{name} {verdict.margin * 1000:.1f}" for name, verdict in run.verdicts.named()
    )
    return f"{outcome}, margins {margins} mm"


def controller_line(controller: ControllerChoice) -> str:
    """`  controller move_base (the default)`, and what the stack runs where we know it:
    `  controller nav2 (from gate.lasertest.yaml:3): Nav2 jazzy: NavFn, MPPI, ...`, the scan
    filter chain in front of it last."""
    chain = controller.scan_filters
    said = [controller.stack, chain.describe() if chain is not None else ""]
    stack = ", ".join(part for part in said if part)
    return f"  controller {controller.name} ({controller.source}){': ' if stack else ''}{stack}"


def robot_line(robot: Robot) -> str:
    """`  robot      Clearpath Husky A200: pybullet_data's Husky, driven through its wheels`."""
    return f"  robot      {robot.name}: {robot.body.describe()}"


def drive_properties(drives: PairDrive) -> list[tuple[str, object]]:
    """Each oracle's margin and outcome for both robots."""
    return run_properties("baseline", drives.baseline) + run_properties(
        "candidate", drives.candidate
    )


def run_properties(side: str, run: Run) -> list[tuple[str, object]]:
    """Each oracle's outcome and margin in one robot's run, and its trajectory's digest."""
    rows: list[tuple[str, object]] = []
    for oracle, verdict in run.verdicts.named():
        rows.append((f"lasertest.{side}.{oracle}", "pass" if verdict.passed else "fail"))
        margin = round(float(verdict.margin), 4)  # m; a plain float crosses to xdist
        rows.append((f"lasertest.{side}.{oracle}_margin", margin))
    rows.append((f"lasertest.{side}.trajectory", run.digest()[:16]))
    return rows
