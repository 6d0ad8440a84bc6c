"""The one object that owns a run's state, and the hooks that use it.

`LaserSession` holds the run's options and everything the run keeps between items: the plans of
its pairs, their obstacle-free drives, the runs already simulated, the physics client they are
simulated in, the pairs that needed no items, and the summary of what the placement items found.
The entry point registers it as a plugin and keeps it in the config's stash, where items find it
(`LaserSession.of`). Nothing heavy is imported here: the solver, the simulator and numpy load
when an item first needs them.
"""

from __future__ import annotations

from collections.abc import Generator
from pathlib import Path
from typing import TYPE_CHECKING, Any

import pytest

from pytest_lasertest.plugin.options import LaserOptions, is_pairs_file
from pytest_lasertest.reports.summary import Summary, Unchanged

if TYPE_CHECKING:
    from pytest_lasertest.model.plan import PairPlan, Witness
    from pytest_lasertest.model.verify import Scene
    from pytest_lasertest.pairsfile import Pair, PairsFile
    from pytest_lasertest.pairsfile.controller import ControllerChoice
    from pytest_lasertest.search.drives import PairDrive, RunCache
    from pytest_lasertest.search.trials import Setting
    from pytest_lasertest.sim.client import PhysicsClient
    from pytest_lasertest.sim.scenario import ControllerError

# The pytest-xdist `workerinput` entry that hands the controller's seed to each worker.
SEED_INPUT = "lasertest_seed"
# The progress letter of each failure the policy notes without failing the run on it.
NOTED_LETTERS = {"pre-existing": "p", "marginal": "m", "coverage-loss": "c"}
NOTED_SECTION = "failures that do not fail the run (--laser-policy=candidate fails them)"
# The pytest-xdist `workeroutput` entry that carries a worker's unchanged pairs to the controller.
UNCHANGED_OUTPUT = "lasertest_unchanged"


class LaserSession:
    """The run's options and state: collects pairs files, keeps a broken one from stopping the
    rest of the run, plans and drives each pair once, sums up what the placement items found,
    and names the pairs that needed no items."""

    key = pytest.StashKey["LaserSession"]()

    def __init__(self, options: LaserOptions) -> None:
        self.options = options
        self.named_files = frozenset(options.pairs)
        self.broken_files = 0
        self.summary = Summary()
        self.unchanged = Unchanged()
        # The Nav2 params files whose unread parameters collection has warned of: once each.
        self.unread_warned: set[str] = set()
        # Keyed by (pairs file path, pair name): every item of a pairs file drives with the
        # same controller, so the file and the pair name a plan and a control drive.
        self._scenes: dict[tuple[Path, str], Scene] = {}
        self._plans: dict[tuple[Path, str], PairPlan] = {}
        self._avoid: dict[tuple[Path, str], tuple[Witness, ...]] = {}
        self._controls: dict[tuple[Path, str], PairDrive] = {}
        # The control drives a controller broke: every item of the pair reports it, none drives
        # it again (a controller that hangs would make each of them wait its time out).
        self._broken: dict[tuple[Path, str], ControllerError] = {}
        self._client: PhysicsClient | None = None
        self._cache: RunCache | None = None

    @classmethod
    def of(cls, config: pytest.Config) -> LaserSession:
        """The session of the run `config` configures."""
        return config.stash[cls.key]

    def collects(self, path: Path) -> bool:
        """Whether pytest should collect `path` (any file it visits) as a pairs file."""
        return is_pairs_file(path, self.named_files)

    def physics_client(self) -> PhysicsClient:
        """The process's physics client, which every drive resets and builds its world in (see
        `PhysicsClient` for what a client of its own would cost each run)."""
        if self._client is None:
            from pytest_lasertest.sim.client import PhysicsClient

            self._client = PhysicsClient()
        return self._client

    def run_cache(self) -> RunCache:
        """The process's runs, by scenario: no scenario is simulated twice in a session."""
        if self._cache is None:
            from pytest_lasertest.search.drives import RunCache

            self._cache = RunCache()
        return self._cache

    def control_drive(self, spec: PairsFile, pair: Pair, controller: ControllerChoice) -> PairDrive:
        """The pair's obstacle-free runs, driven once per process; they are deterministic, so
        pytest-xdist workers that drive the same pair get the same runs. A controller that
        breaks them raises `ControllerError`, again for every later item, without driving."""
        key = (spec.path, pair.name)
        if key in self._broken:
            broken = self._broken[key]
            again = type(broken)(broken.fault, broken.scenario, broken.controller)
            raise again from broken.__cause__
        if key not in self._controls:
            from pytest_lasertest.search.drives import drive_pair
            from pytest_lasertest.sim.scenario import ControllerError

            client, cache = self.physics_client(), self.run_cache()
            try:
                self._controls[key] = drive_pair(
                    spec, pair, (), self.options.seed_of(spec.path), controller, client, cache
                )
            except ControllerError as error:
                self._broken[key] = error
                raise
        return self._controls[key]

    def scene(self, spec: PairsFile, pair: Pair, controller: ControllerChoice) -> Scene:
        """The pair's scanners on its robot, along the path its baseline drove without an
        obstacle: what its witnesses are placed in and judged against."""
        key = (spec.path, pair.name)
        if key not in self._scenes:
            from pytest_lasertest.search.plans import pair_scene

            control = self.control_drive(spec, pair, controller)
            self._scenes[key] = pair_scene(spec, pair, control.baseline)
        return self._scenes[key]

    def plan(self, spec: PairsFile, pair: Pair, controller: ControllerChoice) -> PairPlan:
        """The pair's witnesses, planned once per process; planning is deterministic, so workers
        that plan the same pair find the same."""
        key = (spec.path, pair.name)
        if key not in self._plans:
            from pytest_lasertest.search.plans import plan_scene

            self._plans[key] = plan_scene(spec, pair, self.scene(spec, pair, controller))
        return self._plans[key]

    def avoid(
        self, spec: PairsFile, pair: Pair, controller: ControllerChoice
    ) -> tuple[Witness, ...]:
        """The placements the pair's robots must act on and the baseline robot passes, as
        many as the pairs file asks witnesses per direction, found once per process."""
        key = (spec.path, pair.name)
        if key not in self._avoid:
            from pytest_lasertest.search.plans import avoid_for
            from pytest_lasertest.search.witness import passed_by_baseline

            found = avoid_for(spec, self.scene(spec, pair, controller))
            setting = self.setting(spec, pair, controller)
            self._avoid[key] = passed_by_baseline(setting, found, spec.settings.witnesses)
        return self._avoid[key]

    def setting(self, spec: PairsFile, pair: Pair, controller: ControllerChoice) -> Setting:
        """Where the pair's trials drive: its controller, the run's seed, this process's
        simulator and runs."""
        from pytest_lasertest.search.trials import Setting

        client, cache = self.physics_client(), self.run_cache()
        seed = self.options.seed_of(spec.path)
        return Setting(spec, pair, controller, seed, client, cache)

    def pytest_report_header(self, config: pytest.Config) -> str:
        artifacts = f", artifacts in {self.options.artifacts}" if self.options.artifacts else ""
        options = self.options
        seed = "" if options.seed is not None else f"{options.seed_line()}; "
        return f"lasertest: {seed}{options.replay_options(options.seed)}{artifacts}"

    @pytest.hookimpl(wrapper=True)
    def pytest_make_collect_report(
        self, collector: pytest.Collector
    ) -> Generator[None, pytest.CollectReport, pytest.CollectReport]:
        report = yield
        if report.failed and getattr(collector, "spares_the_run", False):
            self.broken_files += 1
        return report

    @pytest.hookimpl(wrapper=True)
    def pytest_runtestloop(self, session: pytest.Session) -> Generator[None, object, object]:
        # pytest stops the run at any collection error; a broken pairs file must not stop the
        # other files, but it still fails the run.
        session.testsfailed -= self.broken_files
        try:
            return (yield)
        finally:
            session.testsfailed += self.broken_files

    def pytest_runtest_logreport(self, report: pytest.TestReport) -> None:
        if report.when == "call":
            self.summary.add(report.nodeid, report.failed, report.user_properties)
            category = getattr(report, "lasertest_category", None)
            if category is not None:
                self.summary.note(report.nodeid, category, getattr(report, "wasxfail", ""))

    @pytest.hookimpl(tryfirst=True)
    def pytest_report_teststatus(
        self, report: pytest.TestReport, config: pytest.Config
    ) -> tuple[str, str, str] | None:
        """A failure the policy notes without failing the run on it: its own outcome, counted
        in the closing line (`3 pre-existing`), before pytest's xfail would claim it."""
        category = getattr(report, "lasertest_category", None)
        if category is None or report.when != "call":
            return None
        return category, NOTED_LETTERS.get(category, "x"), category.upper()

    @pytest.hookimpl(tryfirst=True)
    def pytest_sessionfinish(self, session: pytest.Session, exitstatus: int) -> None:
        workeroutput = getattr(session.config, "workeroutput", None)
        if workeroutput is not None:
            workeroutput[UNCHANGED_OUTPUT] = dict(self.unchanged.pairs)
        if exitstatus == pytest.ExitCode.NO_TESTS_COLLECTED and self.unchanged.pairs:
            # The gate ran and found nothing to test: an unrelated edit must pass CI.
            session.exitstatus = pytest.ExitCode.OK

    def pytest_terminal_summary(self, terminalreporter: pytest.TerminalReporter) -> None:
        artifacts = str(self.options.artifacts) if self.options.artifacts else None
        sections = {
            "lasertest: placements searched, per pair": self.summary.lines(artifacts),
            f"lasertest: {NOTED_SECTION}": self.summary.noted_lines(),
            "lasertest: pairs whose scanners read alike": self.unchanged.lines(),
        }
        for title, lines in sections.items():
            if lines:
                terminalreporter.section(title)
                for line in lines:
                    terminalreporter.write_line(line)
        if terminalreporter.hasopt("x"):
            self._noted_reports(terminalreporter)
        if self.options.summary is not None:
            problem = self._append_summary(self.options.summary)
            if problem is not None:
                terminalreporter.write_line(f"lasertest: --laser-summary: {problem}", red=True)

    def _noted_reports(self, terminalreporter: pytest.TerminalReporter) -> None:
        """Under `-rx` (or `-rA`), where pytest would list its expected failures, the whole
        report of each failure the policy noted, headed like a failure's."""
        reports = [
            report
            for category in NOTED_LETTERS
            for report in terminalreporter.stats.get(category, [])
            if isinstance(report, pytest.TestReport)
        ]
        if not reports:
            return
        terminalreporter.section(f"lasertest: reports of the {NOTED_SECTION}")
        # In the order of the one-line list above: by category, then node id.
        for report in sorted(
            reports, key=lambda report: (report.lasertest_category, report.nodeid)
        ):
            terminalreporter.write_sep("_", f"{report.head_line or report.nodeid}")
            terminalreporter.write_line(report.longreprtext)

    def _append_summary(self, path: Path) -> str | None:
        """Append the Markdown table to `path`; why it could not be, if it could not."""
        from pytest_lasertest.artifacts.files import artifact_path
        from pytest_lasertest.inputs.errors import display_path

        pictures: dict[str, str] = {}
        artifacts = self.options.artifacts
        # Only pictures the run drew: none without --laser-artifacts, or where writing failed.
        if artifacts is not None:
            drawn = {
                nodeid: artifact_path(artifacts, nodeid, ".png") for nodeid in self.summary.failing
            }
            pictures = {
                nodeid: display_path(picture)
                for nodeid, picture in drawn.items()
                if picture.is_file()
            }
        text = self.summary.markdown(pictures)
        if not text:
            return None
        try:
            with path.open("a", encoding="utf-8") as handle:
                handle.write(text)
        except OSError as error:
            return f"{display_path(path)} could not be written: {error.strerror or error}"
        return None

    def pytest_unconfigure(self, config: pytest.Config) -> None:
        if self._client is not None:
            self._client.close()


class XdistHooks:
    """Hooks registered only when pytest-xdist is active."""

    def __init__(self, session: LaserSession) -> None:
        self.session = session

    def pytest_configure_node(self, node: Any) -> None:
        """Hand the controller's seed to each worker (none where each pairs file has its own)."""
        if self.session.options.seed is not None:
            node.workerinput[SEED_INPUT] = self.session.options.seed

    def pytest_testnodedown(self, node: Any, error: object) -> None:
        """Take the pairs a worker collected to no items: the controller collects nothing."""
        output = getattr(node, "workeroutput", {}).get(UNCHANGED_OUTPUT, {})
        self.session.unchanged.merge(output)
