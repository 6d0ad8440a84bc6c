"""The run's summary: per pair, what its placement items searched and found; and every failure
the run's policy noted without failing the run on it (pre-existing, marginal, a loss of
coverage), each in plain sight with its headline.

It is made from the reports alone (their outcome and `user_properties`), which pytest-xdist
carries from the workers to the controller, so a distributed run sums up as a serial one.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

ORACLES = ("collision", "stuck", "goal")
NOTED_TITLE = (
    "Failures that do not fail the run (the change did not cause them, or they did not hold "
    "under every draw of the scan noise and the obstacles' positions; --laser-policy=candidate "
    "fails them)"
)
COLUMNS = (
    "witnesses",
    "examples",
    "rejected",
    "failed",
    *ORACLES,
    "regressions",
    "marginal",
    "pre-existing",
)


@dataclass
class PairTally:
    """The searches of one pair's placement items, summed."""

    witnesses: int = 0  # items that searched around a witness
    examples: int = 0
    rejected: int = 0
    failed: int = 0  # items the policy failed
    oracles: dict[str, int] = field(default_factory=lambda: dict.fromkeys(ORACLES, 0))
    regressions: int = 0  # items whose search found a regression, failed or not
    marginal: int = 0  # items whose search found a failure that some further draw undid
    pre_existing: int = 0  # items whose search found a failure the baseline shares

    def add(self, failed: bool, properties: Mapping[str, object]) -> None:
        """Count one placement item's report."""
        self.witnesses += 1
        self.examples += _whole(properties.get("lasertest.examples"))
        self.rejected += _whole(properties.get("lasertest.rejected"))
        self.regressions += _whole(properties.get("lasertest.regressions")) > 0
        self.marginal += _whole(properties.get("lasertest.marginal")) > 0
        self.pre_existing += _whole(properties.get("lasertest.pre_existing")) > 0
        if not failed:
            return
        self.failed += 1
        for oracle in str(properties.get("lasertest.failed_oracles", "")).split(","):
            if oracle in self.oracles:
                self.oracles[oracle] += 1

    def row(self) -> tuple[str, ...]:
        drawn = self.examples + self.rejected
        share = f" ({self.rejected / drawn:.0%})" if drawn else ""
        return (
            str(self.witnesses),
            str(self.examples),
            f"{self.rejected}{share}",
            str(self.failed),
            *(str(self.oracles[oracle]) for oracle in ORACLES),
            str(self.regressions),
            str(self.marginal),
            str(self.pre_existing),
        )


@dataclass
class Summary:
    """Every pair's tally, keyed by `pairs file::pair`."""

    pairs: dict[str, PairTally] = field(default_factory=dict)
    failing: list[str] = field(default_factory=list)  # the failing placement items' node ids
    # node id -> (category, headline) of each failure the policy noted without failing on it
    noted: dict[str, tuple[str, str]] = field(default_factory=dict)

    def note(self, nodeid: str, category: str, headline: str) -> None:
        """Keep a failure the run's policy does not fail the run on."""
        self.noted[nodeid] = (category, headline)

    def noted_lines(self) -> list[str]:
        """`CATEGORY  NODEID: HEADLINE`, by category, then node id."""
        entries = sorted(self.noted.items(), key=lambda entry: (entry[1][0], entry[0]))
        width = max((len(category) for category, _ in self.noted.values()), default=0)
        return [
            f"{category.upper():<{width}}  {nodeid}: {headline}"
            for nodeid, (category, headline) in entries
        ]

    def add(self, nodeid: str, failed: bool, properties: Iterable[tuple[str, object]]) -> None:
        """Count a placement item's call report; other reports leave no trace."""
        named = dict(properties)
        if "lasertest.examples" not in named:
            return
        pair = nodeid.rpartition("[")[0]
        self.pairs.setdefault(pair, PairTally()).add(failed, named)
        if failed:
            self.failing.append(nodeid)

    def markdown(self, pictures: Mapping[str, str]) -> str:
        """The table as GitHub-flavoured Markdown, each failing placement item with the path of
        its picture (`pictures`, by node id, when the run wrote artifacts), and the failures
        that do not fail the run."""
        if not self.pairs and not self.noted:
            return ""
        lines = ["### lasertest: placements searched, per pair"]
        if self.pairs:
            header, *rows = self._rows()
            lines += ["", _markdown_row(header), "| --- |" + " ---: |" * len(COLUMNS)]
            lines += [_markdown_row(row) for row in rows]
        if self.failing:
            lines += ["", "Failing placement items:", ""]
            lines += [_failing(nodeid, pictures.get(nodeid)) for nodeid in sorted(self.failing)]
        if self.noted:
            lines += ["", f"{NOTED_TITLE}:", ""]
            lines += [
                f"- {category}: `{nodeid}`: {headline}"
                for nodeid, (category, headline) in sorted(self.noted.items())
            ]
        return "\n".join(lines) + "\n"

    def _rows(self) -> list[tuple[str, ...]]:
        """The header, then one row per pair in node-id order."""
        names = sorted(self.pairs)
        return [("pair", *COLUMNS)] + [(name, *self.pairs[name].row()) for name in names]

    def lines(self, artifacts: str | None) -> list[str]:
        """The table, one row per pair in node-id order, and where the artifacts went."""
        if not self.pairs:
            return []
        rows = self._rows()
        widths = [max(len(row[column]) for row in rows) for column in range(len(rows[0]))]
        lines = [
            "  ".join(
                cell.ljust(width) if column == 0 else cell.rjust(width)
                for column, (cell, width) in enumerate(zip(row, widths, strict=True))
            )
            for row in rows
        ]
        if artifacts is not None and (self.failing or self.noted):
            lines.append(f"artifacts of the failures above and below: {artifacts}")
        return lines


@dataclass
class Unchanged:
    """The pairs whose two scanners read alike, which collect to no items: pair id -> what both
    scanners are."""

    pairs: dict[str, str] = field(default_factory=dict)

    def add(self, pair: str, scanners: str) -> None:
        """Note one pair."""
        self.pairs[pair] = scanners

    def merge(self, other: Mapping[str, str]) -> None:
        """Take the pairs a pytest-xdist worker noted (every worker notes the same)."""
        self.pairs.update(other)

    def lines(self) -> list[str]:
        """One line per pair, in node-id order."""
        return [
            f"{pair}: no sensing change, no items: {self.pairs[pair]}"
            for pair in sorted(self.pairs)
        ]


def _markdown_row(cells: tuple[str, ...]) -> str:
    """A Markdown table row, pipes in a cell escaped (a pair's name is the user's)."""
    return "| " + " | ".join(cell.replace("|", "\\|") for cell in cells) + " |"


def _failing(nodeid: str, picture: str | None) -> str:
    """One failing item's list entry, with its picture's path if it has one."""
    shown = f"`{nodeid}`"
    return f"- {shown}: picture `{picture}`" if picture else f"- {shown}"


def _whole(value: object) -> int:
    return value if isinstance(value, int) else 0
