"""What a pytest run of a pairs file must show: one clean collection error, the cases of its
JUnit XML, the controllers that drove its items."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple, Protocol

import pytest

from pytest_lasertest.inputs.errors import SpecError

# Runs that test the plumbing run the coverage items alone: no solver, no simulator; under the
# candidate policy, so that a loss of coverage fails its item as any failure would.
NO_PLACEMENTS = ("-m", "coverage", "--laser-policy=candidate")

# Where --laser-artifacts=out writes the artifacts of the paper's pairs file.
ARTIFACTS = Path("out/paper.lasertest.yaml")


class Expected(Protocol):
    """What an error must say."""

    @property
    def problem(self) -> str: ...

    @property
    def fix(self) -> str: ...


@dataclass(frozen=True)
class Case:
    """One way to break a pairs file (VALID_PAIRS, unless the test says which), and the error it
    must produce."""

    old: str
    new: str
    line: int
    field: str
    problem: str
    fix: str


def assert_one_clean_error(
    result: pytest.RunResult,
    line: int,
    field: str,
    case: Expected,
    file: str = "gate.lasertest.yaml",
) -> None:
    """The run failed with exactly this error in `file`, and nothing of our code's insides
    leaked."""
    assert result.ret == pytest.ExitCode.TESTS_FAILED
    result.assert_outcomes(errors=1)
    output = result.stdout.lines
    head = f"{file}:{line}: {field}: " if field else f"{file}:{line}: "
    index = next((i for i, text in enumerate(output) if text.startswith(head)), None)
    assert index is not None, f"no line starts with {head!r}"
    assert case.problem in output[index]
    assert output[index + 1].startswith("  fix: ")
    assert case.fix in output[index + 1]
    result.stdout.no_fnmatch_line("*Traceback*")
    result.stdout.no_re_match_line(r".*\.py:\d+")
    result.stdout.no_fnmatch_line("*CollectError*")


def assert_spec_error(error: SpecError, file: str, case: Case) -> None:
    """The error, raised while reading, names `file`, the case's line and field, its problem
    and its fix, in one line and a fix line."""
    assert error.location.path.name == file
    assert (error.location.line, error.field) == (case.line, case.field)
    assert case.problem in error.problem
    assert case.fix in error.fix
    where = f":{case.line}: {case.field}: " if case.field else f":{case.line}: "
    assert where in str(error)
    assert str(error).count("\n") == 1
    assert "\n  fix: " in str(error)


class JunitCase(NamedTuple):
    """One test case of a JUnit XML report."""

    outcome: str  # passed, failure, error, skipped, or xfail (a failure the policy notes)
    message: str  # the failure's or the skip's message
    properties: dict[str, str]


def outcomes(result: pytest.RunResult) -> dict[str, int]:
    """The counts of a run's closing line, lasertest's own outcomes included (`2 pre-existing`,
    `1 coverage-loss`), which pytester's parseoutcomes cuts at the hyphen."""
    closing = next(line for line in reversed(result.stdout.lines) if " in " in line)
    counts = re.findall(r"(\d+) ([\w-]+)", closing.partition(" in ")[0])
    # Warnings are no outcome of an item.
    return {word: int(count) for count, word in counts if not word.startswith("warning")}


def junit_cases(path: Path) -> dict[str, JunitCase]:
    """The test cases of a JUnit XML report, by item id."""
    cases = {}
    for case in ET.parse(path).iter("testcase"):
        ending = next((child for child in case if child.tag != "properties"), None)
        properties = {prop.get("name", ""): prop.get("value", "") for prop in case.iter("property")}
        outcome = "passed" if ending is None else ending.tag
        if ending is not None and ending.get("type") == "pytest.xfail":
            outcome = "xfail"
        cases[f"{case.get('classname')}::{case.get('name')}"] = JunitCase(
            outcome,
            ending.get("message", "") if ending is not None else "",
            properties,
        )
    return cases


def controllers(pytester: pytest.Pytester) -> dict[str, str]:
    """Each item's `lasertest.controller` property in out.xml, by its file and name."""
    tree = ET.parse(pytester.path / "out.xml")
    return {
        f"{case.get('classname')}::{case.get('name')}": prop.get("value", "")
        for case in tree.iter("testcase")
        for prop in case.iter("property")
        if prop.get("name") == "lasertest.controller"
    }
