"""Pinned placements: `PAIR[pinned-K]`, one item per entry of a pair's `placements:` list.

A pinned placement is a recorded case (typically a failure's repro file, committed): both robots
drive past that very obstacle with the scan noise it was recorded with, and the policy judges
the runs as it judges any placement. A pair that pins placements is a regression test and
yields nothing else: no coverage check, no solving, no search.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import pytest

from pytest_lasertest.model.policy import CANDIDATE_FAILED, Classification
from pytest_lasertest.model.verify import DETECTED_BY
from pytest_lasertest.pairsfile import Pair, PairsFile
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.pairsfile.placements import PinnedPlacement
from pytest_lasertest.plugin.items.base import PairItem
from pytest_lasertest.reports.drive import MEANINGS, drive_properties, drive_report
from pytest_lasertest.reports.formats import Artifacts
from pytest_lasertest.search.blame import blame, blame_lines
from pytest_lasertest.search.drives import drive_pair


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
        pinned, session = self.pinned, self.lasertest
        client, cache = session.physics_client(), session.run_cache()
        drives = drive_pair(
            self.spec, self.pair, (pinned.obstacle,), pinned.seed, self.controller, client, cache
        )
        classification = drives.classification
        self.user_properties += [
            ("lasertest.seed", pinned.seed),
            ("lasertest.controller", self.controller.name),
            ("lasertest.obstacle", pinned.obstacle.describe()),
            ("lasertest.classification", classification),
            *drive_properties(drives),
        ]
        if classification in CANDIDATE_FAILED:
            report = drive_report(
                f"the candidate fails at the pinned placement {self.name}: "
                f"{MEANINGS[classification]}",
                self.pair,
                self.controller,
                drives,
                self._details(),
                self.options.policy,
                self.replay,
                self._blame(classification),
            )
            raise self.failure(classification, report, Artifacts())

    def _blame(self, classification: Classification) -> list[str]:
        """A regression's `driver` and `filters` lines: the candidate driven again past the
        pinned obstacle, with its pinned noise, one driver trait or the chain changed back."""
        if classification != "regression":
            return []
        setting = self.lasertest.setting(self.spec, self.pair, self.controller)
        setting = dataclasses.replace(setting, seed=self.pinned.seed)
        return blame_lines(*blame(setting, self.pinned.obstacle))

    def _details(self) -> list[str]:
        pinned = self.pinned
        lines = [f"  obstacle   {pinned.obstacle.describe()} ({pinned.location})"]
        if pinned.direction is not None:
            lines.append(f"  recorded   where the {DETECTED_BY[pinned.direction]} read it")
        lines.append(f"  noise seed {pinned.seed} (pinned; --laser-seed does not change it)")
        return lines

    def reportinfo(self) -> tuple[Path, int, str]:
        return self.path, self.pinned.location.line - 1, self.nodeid


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
