"""Collection nodes: a pairs file, and the items it yields for each pair.

Each pair yields `PAIR[coverage]`, its control item `PAIR[no-obstacle]` (`drive_item.py`) and
its placement items (`placement_item.py`); a pair that pins placements yields only its pinned
items (`pinned_item.py`). The pairs file chooses the controller its items drive
with: its own `controller:`, else a conftest's `pytest_lasertest_make_controller`, else the
default.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import cast

import pytest
from _pytest._code.code import TerminalRepr, TracebackStyle

from pytest_lasertest.artifacts.files import artifact_path, write_json
from pytest_lasertest.model.coverage import CoverageChange, CoverageComparison, compare_coverage
from pytest_lasertest.plugin.items.control import CONTROL, ControlItem
from pytest_lasertest.nav.protocol import ControllerFactory
from pytest_lasertest.plugin.items.base import PairItem
from pytest_lasertest.plugin.items.pinned import pinned_items
from pytest_lasertest.plugin.items.placement import placement_items
from pytest_lasertest.model.sensor import LaserProfile, same_sensing
from pytest_lasertest.plugin.session import UNCHANGED_KEY
from pytest_lasertest.pairsfile import Location, PairsFile, SpecError, load_pairs_file
from pytest_lasertest.pairsfile.controller import ControllerChoice, default_controller
from pytest_lasertest.inputs.errors import display_path

HOOK = "pytest_lasertest_make_controller"


class PairFile(pytest.File):
    """A pairs file; a file that cannot be used is one collection error naming file and line."""

    spares_the_run = True  # a broken pairs file does not stop the other files (LaserSession)

    def collect(self) -> list[pytest.Item]:
        try:
            spec = load_pairs_file(self.path)
            controller = self._controller(spec)
        except SpecError as error:
            raise self.CollectError(str(error)) from None
        items: list[pytest.Item] = []
        for pair in spec.pairs:
            if same_sensing(pair.baseline.profile, pair.candidate.profile):
                # An edit that changes nothing the scanner reads (the usual URDF change) costs
                # the gate nothing; the summary says so.
                self.config.stash[UNCHANGED_KEY].add(
                    f"{self.nodeid}::{pair.name}",
                    f"baseline {pair.baseline.label} and candidate {pair.candidate.label} "
                    f"both read {pair.candidate.profile.describe()}",
                )
                continue
            if pair.placements:
                items += pinned_items(self, spec, pair, controller)
                continue
            items.append(
                CoverageItem.from_parent(self, name=f"{pair.name}[coverage]", spec=spec, pair=pair)
            )
            items.append(
                ControlItem.from_parent(
                    self,
                    name=f"{pair.name}[{CONTROL}]",
                    spec=spec,
                    pair=pair,
                    controller=controller,
                )
            )
            items += placement_items(self, spec, pair, controller)
        return items

    def _controller(self, spec: PairsFile) -> ControllerChoice:
        """The pairs file's `controller:`, else the first factory a conftest (or plugin) returns
        from the hook, else the default. Collection chooses, so every pytest-xdist worker,
        collecting the same file under the same conftests, chooses the same."""
        if spec.controller is not None:
            return spec.controller
        # The file's own hook proxy: only conftests at or above the pairs file take part.
        factory: object = self.ihook.pytest_lasertest_make_controller(config=self.config, spec=spec)
        if factory is None:
            return default_controller(self.path)
        if not callable(factory):
            raise SpecError(
                Location(self.path, 1),
                "controller",
                f"the {HOOK} hook (in a conftest.py or plugin) returned {factory!r:.60}, not a "
                "controller factory",
                "return a callable that takes (robot, route) and returns a controller, or None "
                "for the default",
            )
        return ControllerChoice(
            _qualified_name(factory), f"from the {HOOK} hook", cast(ControllerFactory, factory)
        )


class CoverageLost(Exception):
    """The candidate scanner is blind somewhere the baseline scanner saw."""

    def __init__(self, comparison: CoverageComparison, artifact: Path | None) -> None:
        super().__init__(comparison)
        self.comparison = comparison
        self.artifact = artifact


class CoverageItem(PairItem):
    """Checks that the candidate scans everything its baseline scanned, on the same robot."""

    kind = "coverage"

    def runtest(self) -> None:
        comparison = compare_coverage(
            self.pair.baseline.profile,
            self.pair.candidate.profile,
            min_obstacle_size=self.spec.settings.min_obstacle_size,
            max_speed=self.spec.robot.max_linear_velocity,
        )
        self.user_properties.append(("lasertest.seed", self.options.seed))
        self.user_properties.append(("lasertest.coverage_losses", len(comparison.losses)))
        for change in comparison.changes:
            self.user_properties.append(
                (
                    f"lasertest.{change.attribute}",
                    f"{change.baseline:g} -> {change.candidate:g} {change.unit}",
                )
            )
        if comparison.losses:
            raise CoverageLost(comparison, self._write_artifact(comparison))

    def _write_artifact(self, comparison: CoverageComparison) -> Path | None:
        if self.options.artifacts is None:
            return None
        path = artifact_path(self.options.artifacts, self.nodeid, ".json")
        return write_json(path, self._evidence(comparison))

    def _evidence(self, comparison: CoverageComparison) -> dict[str, object]:
        return {
            "item": self.nodeid,
            "pairs_file": str(self.spec.path),
            "pair": self.pair.name,
            "seed": self.options.seed,
            "policy": self.options.policy,
            "baseline": {
                "model": self.pair.baseline.model,
                **_profile_dict(self.pair.baseline.profile),
            },
            "candidate": {
                "model": self.pair.candidate.model,
                **_profile_dict(self.pair.candidate.profile),
            },
            "coverage": dataclasses.asdict(comparison),
        }

    def repr_failure(
        self, excinfo: pytest.ExceptionInfo[BaseException], style: TracebackStyle | None = None
    ) -> str | TerminalRepr:
        if isinstance(excinfo.value, CoverageLost):
            return self._coverage_report(excinfo.value)
        return super().repr_failure(excinfo, style)

    def _coverage_report(self, lost: CoverageLost) -> str:
        pair, losses = self.pair, lost.comparison.losses
        lines = [
            f"the candidate scans less than the baseline: {len(losses)} "
            f"loss{'es' if len(losses) > 1 else ''} of coverage",
            f"  pair       {pair.name} ({pair.location})",
            f"  baseline   {pair.baseline.label}: {pair.baseline.profile.describe()}",
            f"  candidate  {pair.candidate.label}: {pair.candidate.profile.describe()}",
            "  lost:",
            *(_change_line(change) for change in losses),
        ]
        others = [change for change in lost.comparison.changes if not change.worse]
        if others:
            lines += ["  other changes:", *(_change_line(change) for change in others)]
        lines.append(f"  replay     pytest '{self.nodeid}' {self.options.replay_options()}")
        if lost.artifact is not None:
            lines.append(f"  evidence   {display_path(lost.artifact)}")
        return "\n".join(lines)


def _qualified_name(factory: object) -> str:
    """`module:qualname` of a hook's factory, for reports."""
    module = getattr(factory, "__module__", None)
    name = getattr(factory, "__qualname__", None)
    return f"{module}:{name}" if module and name else repr(factory)


def _change_line(change: CoverageChange) -> str:
    return (
        f"    {change.attribute}: {change.baseline:g} -> {change.candidate:g} {change.unit}; "
        f"{change.detail}"
    )


def _profile_dict(profile: LaserProfile) -> dict[str, object]:
    return {
        **dataclasses.asdict(profile),
        "laserscan": dataclasses.asdict(profile.to_laserscan_meta()),
    }
