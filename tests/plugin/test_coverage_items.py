"""The coverage item of a pair: a candidate that scans less than its baseline fails, and its
report points at the pair in the pairs file."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.helpers.runs import NO_PLACEMENTS


def test_a_failure_points_at_the_pair_in_the_pairs_file(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    result = pytester.runpytest("-q", "--laser-seed=11", *NO_PLACEMENTS)
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(
        [
            "*_ gate.lasertest.yaml::to_lms111[[]coverage[]] _*",
            "the candidate scans less than the baseline: 2 losses of coverage",
            "  pair       to_lms111 (gate.lasertest.yaml:11)",
            "  baseline   inline profile: 720 beams over [[]-1.570, 1.570[]] rad, *",
            "  candidate  sick_lms111: 541 beams *",
            "  lost:",
            "    range.min: 0.1 -> 0.5 m; *",
            "    beam spacing: *",
            "  other changes:",
            "*",
            "  replay     pytest 'gate.lasertest.yaml::to_lms111[[]coverage[]]' --laser-seed=11 *",
        ]
    )
