"""Pinned placements: `PAIR[pinned-K]`, one item per entry of a pair's `placements:` list.

A pinned placement is a recorded case (typically a failure's repro file, committed): both robots
drive past that very obstacle with the scan noise it was recorded with, and the policy judges
the runs as it judges any placement. A pair that pins placements is a regression test and
yields nothing else: no coverage check, no solving, no search.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from _pytest._code.code import TerminalRepr, TracebackStyle

from pytest_lasertest.plugin.items.control import DriveFailed, drive_report, physics_client, run_cache
from pytest_lasertest.search.drives import drive_pair
from pytest_lasertest.reports.failure import MEANINGS
from pytest_lasertest.plugin.items.base import PairItem
from pytest_lasertest.reports.plan import DETECTED_BY, describe_obstacle
from pytest_lasertest.pairsfile import Pair, PairsFile
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.pairsfile.placements import PinnedPlacement
from pytest_lasertest.search.trials import classify


class PinnedItem(PairItem):
    """Both robots past one pinned obstacle."""

    kind = "pinned"

    def __init__(
        self, *, controller: ControllerChoice, pinned: PinnedPlacement, **kwargs: Any
    ) -> None:
        super().__init__(**kwargs)
        self.controller = controller
        self.pinned = pinned

    def runtest(self) -> None:
        pinned = self.pinned
        drives = drive_pair(
            self.spec,
            self.pair,
            (pinned.obstacle,),
            pinned.seed,
            self.controller,
            physics_client(self.config),
            run_cache(self.config),
        )
        classification = classify(drives.baseline.passed, drives.candidate.passed)
        self.user_properties += [
            ("lasertest.seed", pinned.seed),
            ("lasertest.controller", self.controller.name),
            ("lasertest.obstacle", describe_obstacle(pinned.obstacle)),
            ("lasertest.classification", classification),
            *drives.properties(),
        ]
        if drives.fails(self.options.policy):
            raise DriveFailed(
                f"the candidate fails at the pinned placement {self.name}: "
                f"{MEANINGS[classification]}",
                drives,
                self._details(),
            )

    def _details(self) -> list[str]:
        pinned = self.pinned
        lines = [f"  obstacle   {describe_obstacle(pinned.obstacle)} ({pinned.location})"]
        if pinned.direction is not None:
            lines.append(f"  recorded   where the {DETECTED_BY[pinned.direction]} read it")
        lines.append(f"  noise seed {pinned.seed} (pinned; --laser-seed does not change it)")
        return lines

    def repr_failure(
        self, excinfo: pytest.ExceptionInfo[BaseException], style: TracebackStyle | None = None
    ) -> str | TerminalRepr:
        if isinstance(excinfo.value, DriveFailed):
            return drive_report(self, self.pair, self.controller, excinfo.value)
        return super().repr_failure(excinfo, style)

    def reportinfo(self) -> tuple[Path, int, str]:
        return self.path, self.pinned.location.line - 1, self.name


def pinned_items(
    parent: pytest.File, spec: PairsFile, pair: Pair, controller: ControllerChoice
) -> list[pytest.Item]:
    """The pair's pinned items, `PAIR[pinned-K]` in the order the file lists them."""
    return [
        PinnedItem.from_parent(
            parent,
            name=f"{pair.name}[pinned-{index}]",
            spec=spec,
            pair=pair,
            controller=controller,
            pinned=pinned,
        )
        for index, pinned in enumerate(pair.placements)
    ]
