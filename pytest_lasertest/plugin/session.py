"""The plugin object of one run: the report header, pairs-file collection, and xdist seeding."""

from __future__ import annotations

from collections.abc import Generator
from pathlib import Path
from typing import Any

import pytest

from pytest_lasertest.plugin.options import OPTIONS_KEY, LaserOptions, is_pairs_file
from pytest_lasertest.reports.summary import Summary, Unchanged

# Where collection notes the pairs whose scanners read alike.
UNCHANGED_KEY = pytest.StashKey[Unchanged]()
# The pytest-xdist `workeroutput` entry that carries them from a worker to the controller.
UNCHANGED_OUTPUT = "lasertest_unchanged"


class LaserSession:
    """Collects pairs files, keeps a broken one from stopping the rest of the run, sums up what
    the placement items found, and names the pairs that needed no items."""

    def __init__(self, options: LaserOptions, unchanged: Unchanged) -> None:
        self.options = options
        self.named_files = frozenset(options.pairs)
        self.broken_files = 0
        self.summary = Summary()
        self.unchanged = unchanged

    def pytest_report_header(self, config: pytest.Config) -> str:
        artifacts = f", artifacts in {self.options.artifacts}" if self.options.artifacts else ""
        return f"lasertest: {self.options.replay_options()}{artifacts}"

    def pytest_collect_file(self, file_path: Path, parent: pytest.Collector) -> pytest.File | None:
        if not is_pairs_file(file_path, self.named_files):
            return None
        from pytest_lasertest.plugin.collect import PairFile

        pair_file: PairFile = PairFile.from_parent(parent, path=file_path)
        return pair_file

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
            "lasertest: pairs whose scanners read alike": self.unchanged.lines(),
        }
        for title, lines in sections.items():
            if lines:
                terminalreporter.section(title)
                for line in lines:
                    terminalreporter.write_line(line)


class XdistHooks:
    """Hooks registered only when pytest-xdist is active."""

    def __init__(self, seed_key: str, unchanged: Unchanged) -> None:
        self.seed_key = seed_key
        self.unchanged = unchanged

    def pytest_configure_node(self, node: Any) -> None:
        """Hand the controller's seed to each worker."""
        node.workerinput[self.seed_key] = node.config.stash[OPTIONS_KEY].seed

    def pytest_testnodedown(self, node: Any, error: object) -> None:
        """Take the pairs a worker collected to no items: the controller collects nothing."""
        self.unchanged.merge(getattr(node, "workeroutput", {}).get(UNCHANGED_OUTPUT, {}))
