"""What every item of a pair shares: its pairs file and pair, its markers, the run's session and
options, a report location at the pair's line, and how its failures are shown.

An item fails by raising `ItemFailure` with its whole report, written by `reports/`. A failure
the run's policy does not fail the run on (pre-existing, marginal, a loss of coverage, under the
default `regression` policy) is raised as a `NotedFailure`, which the entry point reports as an
expected failure of its own category (`LaserSession.pytest_report_teststatus`). A
controller that breaks a drive (`ControllerError`: it raised, hung, or answered no command) fails
the item with a short report naming it and what it did; `--fulltrace` shows the traceback
instead. Any other exception is a bug in the plugin, and pytest shows its traceback.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, Literal, cast

import pytest

from pytest_lasertest.model.policy import Classification, Policy, fails
from pytest_lasertest.pairsfile import Pair, PairsFile
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.plugin.options import LaserOptions
from pytest_lasertest.plugin.session import LaserSession
from pytest_lasertest.reports.drive import controller_error_report
from pytest_lasertest.reports.formats import Artifacts, Replay
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


# The failures that fail the run only under the `candidate` policy: each its own outcome.
Noted = Literal["pre-existing", "marginal", "coverage-loss"]


def _noted(policy: Policy, found: Classification | Literal["coverage-loss"]) -> Noted | None:
    """The category a failure is noted under where `policy` does not fail the run on it; None
    where it does (see `policy.fails`; a loss of coverage fails only under `candidate`)."""
    if found == "coverage-loss":
        return None if policy == "candidate" else found
    if fails(policy, found) or found not in ("pre-existing", "marginal"):
        return None
    return cast(Noted, found)


class NotedFailure(ItemFailure):
    """A failure in plain sight that does not fail the run under the run's policy: reported as
    an expected failure (pytest's xfail: JUnit's `skipped type="pytest.xfail"`) of its own
    category, with its report kept for the run's summary."""

    def __init__(self, category: Noted, report: str, artifacts: tuple[Path, ...] = ()) -> None:
        super().__init__(report, artifacts)
        self.category: Noted = category


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

    @property
    def seed(self) -> int:
        """The scan noise's and the search's seed for this item's pairs file."""
        return self.options.seed_of(self.path)

    def failure(
        self, found: Classification | Literal["coverage-loss"], report: str, artifacts: Artifacts
    ) -> ItemFailure:
        """The exception to fail with for what the item `found`: a plain `ItemFailure` where the
        run's policy fails the run on it, else a `NotedFailure` of its category. Either way the
        item's `lasertest.outcome` property, in JUnit XML, says which."""
        category = _noted(self.options.policy, found)
        self.user_properties.append(("lasertest.outcome", category or "failed"))
        if category is None:
            return ItemFailure(report, artifacts.written)
        return NotedFailure(category, report, artifacts.written)

    def reportinfo(self) -> tuple[Path, int, str]:
        # The domain heads the failure's section: the node id, so that two files' `size[coverage]`
        # are told apart there.
        return self.path, self.pair.location.line - 1, self.nodeid

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
