"""examples/ci/nightly.yml: the gate split across a CI matrix with pytest-split. Each shard runs
its share of the same items, and the shards' outcomes together are those of one run."""

from __future__ import annotations

import shlex
import shutil
from typing import Any

import pytest
import yaml

from tests.helpers import EXAMPLES
from tests.helpers.runs import junit_cases

NIGHTLY = EXAMPLES / "ci" / "nightly.yml"
# Six of the paper's size pair's items, passes and failures that do not fail the run (a loss of
# coverage, pre-existing failures) among them, searching little.
ITEMS = "coverage or no-obstacle or candidate-misses-0 or candidate-misses-1 or baseline-misses-"
SELECTION = ("-k", f"size and ({ITEMS})", "--laser-examples=2", "-p", "no:randomly")


def nightly() -> dict[Any, Any]:
    loaded: dict[Any, Any] = yaml.safe_load(NIGHTLY.read_text())
    return loaded


def shard_command(group: int) -> list[str]:
    """The workflow's pytest command for matrix group `group` on the paper's pairs file, as
    its shell would run it (minus `pytest`), on one worker."""
    (job,) = nightly()["jobs"].values()
    (step,) = [step for step in job["steps"] if step.get("name") == "Run the gate's share"]
    command = (
        step["run"]
        .replace('"$PAIRS"', "paper.lasertest.yaml")
        .replace("${{ matrix.group }}", str(group))
        .replace("${{ github.run_number }}", "7")
        .replace('"$GITHUB_STEP_SUMMARY"', "summary.md")
        .replace("-n auto", "-n 0")
        .replace("--junitxml=lasertest-artifacts/junit.xml", f"--junitxml=shard-{group}.xml")
        .replace("--laser-profile=nightly", "--laser-profile=ci")
    )
    words = shlex.split(command)
    assert words[0] == "pytest"
    return words[1:]


def test_the_matrix_splits_four_ways_with_one_seed_and_keeps_each_shard_s_failures() -> None:
    (job,) = nightly()["jobs"].values()
    assert job["strategy"]["matrix"]["group"] == [1, 2, 3, 4]
    command = shard_command(1)
    assert command[command.index("--splits") + 1] == "4"
    assert command[command.index("--group") + 1] == "1"
    (cache,) = [step for step in job["steps"] if "actions/cache" in step.get("uses", "")]
    assert cache["with"]["path"] == ".hypothesis"
    assert "${{ matrix.group }}" in cache["with"]["key"]


def test_the_shards_outcomes_together_are_one_run_s(pytester: pytest.Pytester) -> None:
    shutil.copy(EXAMPLES / "paper.lasertest.yaml", pytester.path)
    shards: dict[str, str] = {}
    for group in range(1, 5):
        pytester.runpytest(*shard_command(group), *SELECTION)
        found = junit_cases(pytester.path / f"shard-{group}.xml")
        assert not set(found) & set(shards)  # each item runs in one shard only
        shards |= {name: case.outcome for name, case in found.items()}
    whole = [word for word in shard_command(1) if word not in ("--splits", "4", "--group", "1")]
    whole = [word.replace("shard-1.xml", "whole.xml") for word in whole]
    # From an empty example database, as each shard's was: a stored failure would be tried first.
    shutil.rmtree(pytester.path / ".hypothesis", ignore_errors=True)
    pytester.runpytest(*whole, *SELECTION)
    one_run = junit_cases(pytester.path / "whole.xml")
    assert shards == {name: case.outcome for name, case in one_run.items()}
    assert {"xfail", "passed"} <= set(shards.values())
