"""The control item of a pair, `PAIR[no-obstacle]`: both robots through the empty world.

A candidate that fails there fails everywhere, so the pair's placement items then say so in one
line and leave the report to this item. The baseline's run also times the path the solver
places the pair's witnesses along (`LaserSession.plan`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from pytest_lasertest.inputs.errors import display_path
from pytest_lasertest.pairsfile import Pair
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.plugin.items.base import ItemFailure, PairItem
from pytest_lasertest.reports.drive import drive_properties, drive_report
from pytest_lasertest.search.drives import PairDrive

CONTROL = "no-obstacle"


class ControlItem(PairItem):
    """Both robots through the empty world: the candidate must still reach the goal there."""

    kind = "control"

    def __init__(self, *, controller: ControllerChoice, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.controller = controller

    @staticmethod
    def name_of(pair: Pair) -> str:
        """`PAIR[no-obstacle]`, which the pair's placement items name when they skip."""
        return f"{pair.name}[{CONTROL}]"

    def runtest(self) -> None:
        drives = self.lasertest.control_drive(self.spec, self.pair, self.controller)
        self.user_properties += [
            ("lasertest.seed", self.options.seed),
            ("lasertest.controller", self.controller.name),
            *drive_properties(drives),
        ]
        if drives.fails(self.options.policy):
            artifacts = [f"  artifact   {display_path(path)}" for path in self._write(drives)]
            raise ItemFailure(
                drive_report(
                    "the candidate fails without any obstacle: the change breaks the robot "
                    "everywhere, not only where the scanners differ",
                    self.pair,
                    self.controller,
                    drives,
                    artifacts,
                    self.options.policy,
                    self.replay,
                )
            )

    def _write(self, drives: PairDrive) -> tuple[Path, ...]:
        """The failure's picture, empty Gazebo world and numbers, if the run asked for them."""
        options = self.options
        if options.artifacts is None:
            return ()
        from pytest_lasertest.artifacts.evidence import write_control_evidence

        return write_control_evidence(
            options.artifacts, self.nodeid, self.spec, self.pair, drives, options.recorded()
        )
