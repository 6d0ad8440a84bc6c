"""What every item of a pair shares: its pairs file and pair, its markers, the run's session and
options, a report location at the pair's line, and how its failures are shown.

An item fails by raising `ItemFailure` with its whole report, written by `reports/`. A
controller that breaks a drive (`ControllerError`: it raised, hung, or answered no command) fails
the item with a short report naming it and what it did; `--fulltrace` shows the traceback
instead. Any other exception is a bug in the plugin, and pytest shows its traceback.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

import pytest

from pytest_lasertest.pairsfile import Pair, PairsFile
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.plugin.options import LaserOptions
from pytest_lasertest.plugin.session import LaserSession
from pytest_lasertest.reports.drive import controller_error_report
from pytest_lasertest.reports.formats import Replay
from pytest_lasertest.sim.scenario import ControllerError

if TYPE_CHECKING:
    from _pytest._code.code import TerminalRepr, TracebackStyle


class ItemFailure(Exception):
    """An item's failure, with the report that explains it in full, and the files written
    below --laser-artifacts for it (pytest-html shows them: `plugin/html.py`)."""

    def __init__(self, report: str, artifacts: tuple[Path, ...] = ()) -> None:
        super().__init__(report.partition("\n")[0])
        self.report = report
        self.artifacts = artifacts


class PairItem(pytest.Item):
    """An item of one pair; `kind` is its marker besides `lasertest`."""

    kind: ClassVar[str]

    def __init__(self, *, spec: PairsFile, pair: Pair, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.spec = spec
        self.pair = pair
        self.add_marker("lasertest")
        self.add_marker(self.kind)

    @property
    def lasertest(self) -> LaserSession:
        """The run's session: its options, plans, drives and simulator."""
        return LaserSession.of(self.config)

    @property
    def options(self) -> LaserOptions:
        return self.lasertest.options

    @property
    def replay(self) -> Replay:
        """How to run this item again, as this run ran it, from where pytest was started."""
        return self.options.replay(self.nodeid, self.path, self.config.invocation_params.dir)

    def reportinfo(self) -> tuple[Path, int, str]:
        return self.path, self.pair.location.line - 1, self.name

    def repr_failure(
        self, excinfo: pytest.ExceptionInfo[BaseException], style: TracebackStyle | None = None
    ) -> str | TerminalRepr:
        error = excinfo.value
        if isinstance(error, ItemFailure):
            return error.report
        controller = getattr(self, "controller", None)  # the items that drive have one
        if (
            isinstance(error, ControllerError)
            and isinstance(controller, ControllerChoice)
            and not self.config.getoption("fulltrace", False)
        ):
            return controller_error_report(error, self.pair, controller, self.replay)
        return super().repr_failure(excinfo, style)
