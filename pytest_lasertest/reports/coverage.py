"""What a failing coverage item tells its reader: each attribute the candidate scans less of,
and the other changes of the pair."""

from __future__ import annotations

from pytest_lasertest.model.coverage import CoverageChange, CoverageComparison
from pytest_lasertest.pairsfile import Pair
from pytest_lasertest.reports.formats import Artifacts, Replay


def coverage_report(
    pair: Pair, comparison: CoverageComparison, replay: Replay, artifacts: Artifacts
) -> str:
    """The losses of coverage, then the changes that lose nothing."""
    losses = comparison.losses
    lines = [
        f"the candidate scans less than the baseline: {len(losses)} "
        f"loss{'es' if len(losses) > 1 else ''} of coverage",
        f"  pair       {pair.name} ({pair.location})",
        f"  baseline   {pair.baseline.label}: {pair.baseline.profile.describe()}",
        f"  candidate  {pair.candidate.label}: {pair.candidate.profile.describe()}",
        "  lost:",
        *(_change_line(change) for change in losses),
    ]
    others = [change for change in comparison.changes if not change.worse]
    if others:
        lines += ["  other changes:", *(_change_line(change) for change in others)]
    lines.append(replay.line())
    lines += artifacts.lines("evidence", replay.here)
    return "\n".join(lines)


def coverage_properties(comparison: CoverageComparison) -> list[tuple[str, object]]:
    """How many losses, and each change as `baseline -> candidate unit`."""
    return [
        ("lasertest.coverage_losses", len(comparison.losses)),
        *(
            (
                f"lasertest.{change.attribute}",
                _values(change),
            )
            for change in comparison.changes
        ),
    ]


def _change_line(change: CoverageChange) -> str:
    return f"    {change.attribute}: {_values(change)}; {change.detail}"


def _values(change: CoverageChange) -> str:
    """`baseline -> candidate unit`: figures as %g, a driver's choices as they are written."""
    before, after = (
        value if isinstance(value, str) else f"{value:g}"
        for value in (change.baseline, change.candidate)
    )
    return f"{before} -> {after} {change.unit}".rstrip()
