"""The conformance ledger: each test's `upstream` mark and outcome, each module's `NOT_PORTED`,
and, with `--conformance-table=FILE` (a serial run of tests/conformance), the table of
tests.helpers.upstream written from them, which docs/explanation/conformance.md shows."""

from __future__ import annotations

from collections.abc import Generator
from pathlib import Path

import pytest

from tests.helpers.upstream import NotPorted, Ported, Source, markdown

LEDGER = pytest.StashKey[tuple[list[Ported], list[NotPorted]]]()


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption(
        "--conformance-table",
        metavar="FILE",
        help="write the conformance table (Markdown) of this run of tests/conformance to FILE",
    )


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers", "upstream(source, test, assertions): the upstream test a conformance test ports"
    )
    config.stash[LEDGER] = ([], [])
    if _table_path(config) and getattr(config.option, "numprocesses", None):
        raise pytest.UsageError("--conformance-table: run tests/conformance serially (-n 0)")


@pytest.hookimpl(wrapper=True)
def pytest_make_collect_report(
    collector: pytest.Collector,
) -> Generator[None, pytest.CollectReport, pytest.CollectReport]:
    """Each module's NOT_PORTED, a module of nothing else (an upstream file of which nothing
    could be set up) included."""
    report = yield
    if isinstance(collector, pytest.Module) and report.passed:
        collector.config.stash[LEDGER][1].extend(getattr(collector.obj, "NOT_PORTED", ()))
    return report


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(
    item: pytest.Item, call: pytest.CallInfo[None]
) -> Generator[None, pytest.TestReport, pytest.TestReport]:
    report = yield
    mark = item.get_closest_marker("upstream")
    if mark is not None and (call.when == "call" or (call.when == "setup" and not report.passed)):
        item.config.stash[LEDGER][0].append(_ported(mark, report))
    return report


def _ported(mark: pytest.Mark, report: pytest.TestReport) -> Ported:
    source: Source = mark.kwargs["source"]
    test, assertions = mark.kwargs["test"], mark.kwargs["assertions"]
    if report.passed:
        return Ported(source, test, assertions, "reproduced", "")
    if hasattr(report, "wasxfail"):
        return Ported(source, test, assertions, "differs", report.wasxfail.removeprefix("reason: "))
    return Ported(source, test, assertions, "failed", "the conformance test failed")


def pytest_sessionfinish(session: pytest.Session) -> None:
    path = _table_path(session.config)
    if path:
        ported, not_ported = session.config.stash[LEDGER]
        Path(path).write_text(markdown(ported, not_ported))


def _table_path(config: pytest.Config) -> str | None:
    path: str | None = config.getoption("conformance_table", default=None)
    return path
