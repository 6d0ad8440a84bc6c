"""Pairs files become items with ids from YAML names; every run prints how to replay it."""

from __future__ import annotations

import re
import shutil
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES

PAPER_ITEMS = [
    "examples/paper.lasertest.yaml::blind_spot[coverage]",
    "examples/paper.lasertest.yaml::distance[coverage]",
    "examples/paper.lasertest.yaml::size[coverage]",
]


@pytest.fixture
def examples(pytester: pytest.Pytester) -> Path:
    """A copy of the repository's examples in the pytester directory."""
    return Path(shutil.copytree(EXAMPLES, pytester.path / "examples"))


def collected(result: pytest.RunResult) -> list[str]:
    """The item ids of a `--collect-only -q` run."""
    return [line for line in result.stdout.lines if "::" in line]


def test_the_paper_example_collects_one_item_per_pair_of_table_iv_b(
    pytester: pytest.Pytester, examples: Path
) -> None:
    result = pytester.runpytest(
        "--laser-pairs", "examples/paper.lasertest.yaml", "--collect-only", "-q"
    )
    assert collected(result) == PAPER_ITEMS


def test_collection_is_identical_across_runs_and_under_xdist(
    pytester: pytest.Pytester, examples: Path
) -> None:
    command = ["--laser-pairs", "examples/paper.lasertest.yaml", "--collect-only", "-q"]
    first = collected(pytester.runpytest_subprocess(*command))
    second = collected(pytester.runpytest_subprocess(*command))
    distributed = collected(pytester.runpytest_subprocess(*command, "-n", "2"))
    assert first == second == distributed == PAPER_ITEMS


def test_items_run_the_same_under_xdist_as_serially(
    pytester: pytest.Pytester, examples: Path
) -> None:
    serial = pytester.runpytest_subprocess("examples", "-rA", "--laser-seed=3")
    distributed = pytester.runpytest_subprocess("examples", "-rA", "--laser-seed=3", "-n", "2")

    def outcomes(result: pytest.RunResult) -> list[str]:
        return sorted(re.findall(r"^(PASSED|FAILED) (\S+)", result.stdout.str(), re.MULTILINE))

    assert outcomes(serial) == outcomes(distributed)
    assert len(outcomes(serial)) == 5


def test_files_named_lasertest_yaml_are_collected_and_other_yaml_is_not(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    shutil.copy(pairs_file, pytester.path / "gate.lasertest.yml")
    shutil.copy(pairs_file, pytester.path / "settings.yaml")
    result = pytester.runpytest("--collect-only", "-q")
    assert collected(result) == [
        "gate.lasertest.yaml::to_lms111[coverage]",
        "gate.lasertest.yaml::same[coverage]",
        "gate.lasertest.yml::to_lms111[coverage]",
        "gate.lasertest.yml::same[coverage]",
    ]


def test_laser_pairs_alone_runs_that_file_and_not_the_test_suite(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    pairs_file.rename(pytester.path / "robot-pairs.yaml")
    pytester.makepyfile(test_unit="def test_unit(): pass")
    result = pytester.runpytest("--laser-pairs", "robot-pairs.yaml", "--collect-only", "-q")
    assert collected(result) == [
        "robot-pairs.yaml::to_lms111[coverage]",
        "robot-pairs.yaml::same[coverage]",
    ]


def test_laser_pairs_with_arguments_runs_both(pytester: pytest.Pytester, pairs_file: Path) -> None:
    pairs_file.rename(pytester.path / "robot-pairs.yaml")
    pytester.makepyfile(test_unit="def test_unit(): pass")
    result = pytester.runpytest("test_unit.py", "--laser-pairs", "robot-pairs.yaml", "-q")
    result.assert_outcomes(passed=2, failed=1)


def test_ini_laser_pairs_are_collected_alongside_the_test_suite(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    pairs_file.rename(pytester.path / "robot-pairs.yaml")
    pytester.makeini("[pytest]\nlaser_pairs = robot-pairs.yaml\n")
    pytester.makepyfile(test_unit="def test_unit(): pass")
    result = pytester.runpytest("-q")
    result.assert_outcomes(passed=2, failed=1)


def test_a_relative_laser_pairs_path_works_from_a_subdirectory_under_xdist(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    pytester.makeini("[pytest]\n")
    subdirectory = pytester.mkdir("robots")
    pairs_file.rename(subdirectory / "gate.yaml")
    with pytest.MonkeyPatch.context() as patch:
        patch.chdir(subdirectory)
        result = pytester.runpytest_subprocess("--laser-pairs", "gate.yaml", "-n", "2")
    result.assert_outcomes(passed=1, failed=1)


def test_the_header_prints_the_options_that_replay_the_run(
    pytester: pytest.Pytester, pairs_file: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("CI", raising=False)
    result = pytester.runpytest("--laser-seed=7", "--co")
    result.stdout.fnmatch_lines(
        ["lasertest: --laser-seed=7 --laser-profile=dev --laser-policy=candidate"]
    )


def test_the_profile_defaults_to_ci_on_a_ci_service(
    pytester: pytest.Pytester, pairs_file: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("CI", "true")
    result = pytester.runpytest("--co", "--laser-policy=regression")
    result.stdout.fnmatch_lines(
        ["lasertest: --laser-seed=* --laser-profile=ci --laser-policy=regression"]
    )


def test_a_random_seed_is_fresh_each_run(pytester: pytest.Pytester, pairs_file: Path) -> None:
    def seed() -> str:
        match = re.search(r"--laser-seed=(\d+)", pytester.runpytest("--co").stdout.str())
        assert match is not None
        return match.group(1)

    assert seed() != seed()


def test_xdist_workers_use_the_seed_the_header_prints(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    result = pytester.runpytest_subprocess("-n", "2", "--junitxml=report.xml")
    match = re.search(r"--laser-seed=(\d+)", result.stdout.str())
    assert match is not None
    seeds = {
        prop.get("value")
        for prop in ET.parse(pytester.path / "report.xml").iter("property")
        if prop.get("name") == "lasertest.seed"
    }
    assert seeds == {match.group(1)}


def test_items_carry_the_lasertest_marker(pytester: pytest.Pytester, pairs_file: Path) -> None:
    pytester.makepyfile(test_unit="def test_unit(): pass")
    selected = pytester.runpytest("-m", "lasertest", "--co", "-q")
    others = pytester.runpytest("-m", "not lasertest", "--co", "-q")
    assert collected(selected) == [
        "gate.lasertest.yaml::to_lms111[coverage]",
        "gate.lasertest.yaml::same[coverage]",
    ]
    assert collected(others) == ["test_unit.py::test_unit"]


def test_a_failure_points_at_the_pair_in_the_pairs_file(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    result = pytester.runpytest("-q", "--laser-seed=11")
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(
        [
            "*_ to_lms111[[]coverage[]] _*",
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
