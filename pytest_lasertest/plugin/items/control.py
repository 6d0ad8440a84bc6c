"""The control item of a pair, `PAIR[no-obstacle]`: both robots through the empty world.

A candidate that fails there fails everywhere, so the pair's placement items then say so in one
line and leave the report to this item. The baseline's run also times the path the solver
places the pair's witnesses along (`LaserSession.plan`).
"""

from __future__ import annotations

from typing import Any

from pytest_lasertest.model.policy import CANDIDATE_FAILED
from pytest_lasertest.pairsfile import Pair
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.plugin.items.base import PairItem
from pytest_lasertest.reports.drive import drive_properties, drive_report
from pytest_lasertest.reports.formats import Artifacts
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
            ("lasertest.seed", self.seed),
            ("lasertest.controller", self.controller.name),
            *drive_properties(drives),
        ]
        found = drives.classification
        if found in CANDIDATE_FAILED:
            written = self._write(drives)
            headline, details = _verdict(drives)
            report = drive_report(
                headline,
                self.pair,
                self.controller,
                drives,
                [*details, *written.lines("artifact", self.replay.here)],
                self.options.policy,
                self.replay,
            )
            raise self.failure(found, report, written)

    def _write(self, drives: PairDrive) -> Artifacts:
        """The failure's picture, empty Gazebo world and numbers, if the run asked for them."""
        options = self.options
        if options.artifacts is None:
            return Artifacts()
        from pytest_lasertest.artifacts.evidence import write_control_evidence

        return write_control_evidence(
            options.artifacts,
            self.nodeid,
            self.spec,
            self.pair,
            drives,
            options.recorded(self.path),
            self.controller,
        )


def _verdict(drives: PairDrive) -> tuple[str, list[str]]:
    """The headline of a failing control item, and a fix when the baseline fails as well: then
    the world, its time limit or the controller is at fault, not the scanner change."""
    baseline = drives.baseline
    if drives.classification == "marginal":
        return (
            "marginal: the candidate fails without any obstacle and the baseline passes, but "
            "not under every draw of the scan noise: the change is not shown to break the robot",
            [],
        )
    if baseline.passed:
        return (
            "the candidate fails without any obstacle: the change breaks the robot everywhere, "
            "not only where the scanners differ",
            [],
        )
    headline = (
        "the baseline fails without any obstacle too: the world, its time limit or the "
        "controller is at fault, not the scanner change"
    )
    verdicts, limit = baseline.verdicts, baseline.scenario.time_limit
    if verdicts.stuck.passed and verdicts.collision.passed:
        fix = (
            f"the baseline robot was still on its way when world.time_limit ({limit:g} s) ran "
            f"out, {verdicts.goal.nearest:.2f} m from the goal: raise time_limit"
        )
    else:
        fix = (
            "the baseline robot cannot drive the route in the empty world: check the route, "
            "the robot's navigation parameters and the controller with the baseline scanner"
        )
    return headline, [f"  fix        {fix}"]
