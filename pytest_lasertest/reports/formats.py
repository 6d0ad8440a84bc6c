"""The shared formats of what reports show: obstacles, scanner profiles, witnesses and runs;
how to run an item again; which artifacts a failure wrote and which it could not.

The JSON forms are stable contracts (documented in docs/reference/cli.md): `lasertest plan --json`,
`lasertest profile --json` and the artifacts' JSON files all write obstacles, profiles and
witnesses this way, as standard JSON (`json_text`).
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass
from pathlib import Path

from pytest_lasertest.model.obstacles import Box, Obstacle
from pytest_lasertest.model.plan import Witness
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.sim.scenario import Run


def json_text(data: object, *, sort_keys: bool = False) -> str:
    """`data` as standard JSON, indented: an infinite or NaN number (a margin that does not
    apply, say) as the string "inf", "-inf" or "nan", which Python's float() reads back. Python
    would write `Infinity`, which is no JSON: jq, JavaScript and most parsers refuse the file."""
    return json.dumps(_finite(data), indent=2, sort_keys=sort_keys, allow_nan=False)


def _finite(value: object) -> object:
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    if isinstance(value, dict):
        return {key: _finite(item) for key, item in value.items()}
    if isinstance(value, list | tuple):
        return [_finite(item) for item in value]
    return value


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
    line = f"  {side:<10} {label}: {'passed' if run.passed else 'FAILED'}: {outcome}"
    return line + "".join(f"\n  {'':<10} {text}" for text in activity_lines(run.activity))


# How many of a run's events a report shows; the rest are counted.
SHOWN_EVENTS = 8


def activity_lines(activity: tuple[tuple[float, str], ...]) -> list[str]:
    """`stack did: Spin at t = 12.10 s, Wait at t = 22.10 s`: what the controller said it did
    in a run, if anything."""
    if not activity:
        return []
    runs: list[list[tuple[float, str]]] = []
    for event in activity:  # the same event again and again is one entry
        if runs and runs[-1][0][1] == event[1]:
            runs[-1].append(event)
        else:
            runs.append([event])
    shown = [_run_text(run) for run in runs[:SHOWN_EVENTS]]
    more = len(runs) - SHOWN_EVENTS
    return ["stack did: " + ", ".join(shown) + (f", and {more} more" if more > 0 else "")]


def _run_text(run: list[tuple[float, str]]) -> str:
    (first, what), last = run[0], run[-1][0]
    if len(run) == 1:
        return f"{what} at t = {first:.2f} s"
    return f"{what} {len(run)} times from t = {first:.2f} s to {last:.2f} s"


def pose_text(x: float, y: float, yaw: float) -> str:
    """`(4.52, -0.31, 0.00)`: a robot pose, m, m, rad."""
    return f"({x:.2f}, {y:.2f}, {yaw:.2f})"


@dataclass(frozen=True)
class Replay:
    """How to run an item again from the directory pytest was started in: the item as pytest
    takes it there, and the options of the run it failed in."""

    item: str  # `PATH::NAME`, PATH relative to `here` (with `..` if need be)
    options: str  # `--laser-seed=... --laser-profile=... --laser-policy=...`
    here: Path  # where pytest was started: the commands work from there

    def command(self) -> str:
        """`pytest 'PATH::NAME' --laser-seed=...`."""
        return f"pytest {shell_word(self.item)} {self.options}"

    def line(self) -> str:
        """`  replay     pytest 'PATH::NAME' --laser-seed=...`, as every failure report ends."""
        return f"  replay     {self.command()}"

    def shown(self, path: Path) -> str:
        """A file as the commands name it: relative below `here`, else absolute."""
        return shown_path(path, self.here)


@dataclass(frozen=True)
class Unwritten:
    """An artifact a failing item could not write (the operating system refused it, or the
    pairs file changed under the repro), and why."""

    path: Path  # where it was to go
    reason: str  # e.g. "No space left on device [ENOSPC]"
    fix: str

    def line(self, here: Path) -> str:
        """`  unwritten  PATH: REASON; fix: FIX`: one line beside the failure it belongs to."""
        return f"  unwritten  {shown_path(self.path, here)}: {self.reason}; fix: {self.fix}"


@dataclass(frozen=True)
class Artifacts:
    """What a failing item wrote below `--laser-artifacts`, and what it could not."""

    written: tuple[Path, ...] = ()
    unwritten: tuple[Unwritten, ...] = ()

    def lines(self, label: str, here: Path) -> list[str]:
        """`  LABEL   PATH` for each file written, then an `unwritten` line for each not."""
        return [f"  {label:<10} {shown_path(path, here)}" for path in self.written] + [
            problem.line(here) for problem in self.unwritten
        ]


def shell_word(text: str) -> str:
    """`text` in single quotes, as a POSIX shell reads it back whatever it holds."""
    return "'" + text.replace("'", "'\"'\"'") + "'"


def shown_path(path: Path, here: Path) -> str:
    """`path` as a command started in `here` names it: relative below `here`, else absolute."""
    resolved = path.resolve()
    try:
        return str(resolved.relative_to(here.resolve()))
    except ValueError:
        return str(resolved)
