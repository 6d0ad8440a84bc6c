"""`--laser-artifacts DIR` keeps the evidence of every failing item as JSON."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.helpers.runs import NO_PLACEMENTS


def test_a_failing_item_writes_every_number_of_its_comparison(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    result = pytester.runpytest("--laser-artifacts=out", "--laser-seed=5", *NO_PLACEMENTS)
    result.assert_outcomes(passed=1, failed=1)
    written = sorted(path.relative_to(pytester.path) for path in (pytester.path / "out").rglob("*"))
    evidence = Path("out/gate.lasertest.yaml/to_lms111_coverage.json")
    assert written == [evidence.parent, evidence]
    result.stdout.fnmatch_lines([f"  evidence   {evidence}"])
    data = json.loads((pytester.path / evidence).read_text())
    assert data["item"] == "gate.lasertest.yaml::to_lms111[coverage]"
    assert data["seed"] == 5
    assert data["candidate"]["model"] == "sick_lms111"
    assert data["candidate"]["laserscan"]["angle_increment"] == pytest.approx(0.00872665, abs=1e-8)
    losses = [change["attribute"] for change in data["coverage"]["changes"] if change["worse"]]
    assert losses == ["range.min", "beam spacing"]


def test_passing_items_and_runs_without_the_option_write_nothing(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    # The placements to steer round are left out: whether they pass depends on the seed.
    result = pytester.runpytest("-k", "same and not avoid", "--laser-artifacts=out")
    result.assert_outcomes(passed=2, skipped=6)
    pytester.runpytest(*NO_PLACEMENTS).assert_outcomes(passed=1, failed=1)
    assert not (pytester.path / "out").exists()
    assert not list(pytester.path.rglob("*.json"))
