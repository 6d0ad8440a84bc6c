"""The upstream unit tests the conformance tests (tests/conformance) port: which file of which
commit of which repository, and how the ported assertions add up into the conformance table.

A conformance test ports one upstream test, or the part of it about one behaviour:

    INFLATION = Source("Nav2 costmap: inflation layer", NAVIGATION2_JAZZY,
                       "nav2_costmap_2d/test/integration/inflation_tests.cpp")

    @INFLATION.test("TestNode.testCostFunctionCorrectness", assertions=12)
    def test_cost_function_correctness() -> None: ...

`assertions` counts the upstream EXPECT_/ASSERT_ statements the test reproduces: each once (a
statement in a loop too), those of an upstream helper once per call of the helper. The mark
counts once per collected item: a parametrised test carries each case's count on its
`pytest.param(..., marks=...)`. One that our imitation departs from is its own test, marked
`pytest.mark.xfail(strict=True, reason=...)` with the reason: the table lists it as differing.
Upstream assertions that cannot be set up with our classes are listed in the module's
`NOT_PORTED`, each with its reason.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Literal

import pytest

# The upstream commits ported from (the branches' commits that our imitations cite).
NAVIGATION2_JAZZY = ("ros-navigation/navigation2", "f4108e5b")
NAVIGATION2_HUMBLE = ("ros-navigation/navigation2", "3c3db59d")
NAVIGATION_NOETIC = ("ros-planning/navigation", "9ad64419")
# laser_filters' ros2 branch (ROS 2) and noetic-devel (ROS 1), as nav/laser_filters cites them.
LASER_FILTERS_ROS2 = ("ros-perception/laser_filters", "905f5e9a")
LASER_FILTERS_NOETIC = ("ros-perception/laser_filters", "75913d51")

Verdict = Literal["reproduced", "differs", "failed"]


@dataclass(frozen=True)
class Source:
    """One upstream test file, and the row of the table its assertions count in."""

    component: str  # e.g. "Nav2 costmap: inflation layer"
    release: tuple[str, str]  # (repository, commit)
    path: str  # the test file, in the repository

    def test(self, name: str, assertions: int) -> pytest.MarkDecorator:
        """The mark of a test porting `assertions` assertions of the upstream test `name`."""
        if assertions < 1:
            raise ValueError(f"{name}: a conformance test ports at least one assertion")
        return pytest.mark.upstream(source=self, test=name, assertions=assertions)

    def cite(self) -> str:
        repository, commit = self.release
        return f"{repository}@{commit}:{self.path}"


@dataclass(frozen=True)
class NotPorted:
    """Upstream assertions no conformance test reproduces, and why."""

    source: Source
    test: str
    assertions: int
    reason: str


@dataclass(frozen=True)
class Ported:
    """One conformance test's upstream assertions, and what the run made of them."""

    source: Source
    test: str
    assertions: int
    verdict: Verdict
    reason: str  # why it differs; "" where it reproduces


@dataclass
class Row:
    """One component's counts of upstream assertions."""

    applicable: int = 0
    ported: int = 0
    reproduced: int = 0


def rows(ported: Iterable[Ported], not_ported: Iterable[NotPorted]) -> dict[str, Row]:
    """Each component's counts, in the order components first appear."""
    table: dict[str, Row] = defaultdict(Row)
    for port in ported:
        row = table[port.source.component]
        row.applicable += port.assertions
        row.ported += port.assertions
        row.reproduced += port.assertions if port.verdict == "reproduced" else 0
    for gap in not_ported:
        table[gap.source.component].applicable += gap.assertions
    return dict(table)


def markdown(ported: list[Ported], not_ported: list[NotPorted]) -> str:
    """The conformance table and, below it, every assertion that is not reproduced."""
    table = rows(ported, not_ported)
    total = Row(*(sum(getattr(row, field) for row in table.values()) for field in vars(Row())))
    lines = [
        "| component | applicable | ported | reproduced |",
        "|---|---:|---:|---:|",
        *(
            f"| {name} | {r.applicable} | {r.ported} | {r.reproduced} |"
            for name, r in table.items()
        ),
        f"| **all** | **{total.applicable}** | **{total.ported}** | **{total.reproduced}** |",
        "",
        "Not reproduced:",
        "",
    ]
    for port in ported:
        if port.verdict != "reproduced":
            why = f"{port.verdict}: {port.reason}"
            lines.append(_gap(port.source, port.test, port.assertions, why))
    lines.extend(
        _gap(g.source, g.test, g.assertions, f"not ported: {g.reason}") for g in not_ported
    )
    return "\n".join(lines) + "\n"


def _gap(source: Source, test: str, assertions: int, why: str) -> str:
    return f"- `{source.path}` `{test}` ({assertions}): {why}"
