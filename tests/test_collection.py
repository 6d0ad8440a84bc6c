"""Pairs files become items with ids from YAML names; every run prints how to replay it."""

from __future__ import annotations

import dataclasses
import json
import re
import shutil
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import NamedTuple

import pytest

from pytest_lasertest.model.verify import Placement, Scene, Verification, verify
from pytest_lasertest.sim.client import connected_clients
from tests.conftest import EXAMPLES, SIZE_PAIR


def pair_items(file: str, pair: str, witnesses: int = 3) -> list[str]:
    """The ids a pair collects: its coverage and control items, then one per direction and
    witness index."""
    return [f"{file}::{pair}[coverage]", f"{file}::{pair}[no-obstacle]"] + [
        f"{file}::{pair}[{direction}-{index}]"
        for direction in ("candidate-misses", "baseline-misses")
        for index in range(witnesses)
    ]


def gate_items(file: str) -> list[str]:
    """The ids of VALID_PAIRS (tests/conftest.py) written to `file`."""
    return pair_items(file, "to_lms111") + pair_items(file, "same")


PAPER_ITEMS = [
    item
    for pair in ("blind_spot", "distance", "size")
    for item in pair_items("examples/paper.lasertest.yaml", pair)
]


@pytest.fixture
def examples(pytester: pytest.Pytester) -> Path:
    """A copy of the repository's examples in the pytester directory."""
    return Path(shutil.copytree(EXAMPLES, pytester.path / "examples"))


# Runs that test the plumbing run the coverage items alone: no solver, no simulator.
NO_PLACEMENTS = ("-m", "coverage")
# The same, with the project's own unmarked tests.
PLUMBING = ("-m", "not placement and not control")


def collected(result: pytest.RunResult) -> list[str]:
    """The item ids of a `--collect-only -q` run."""
    return [line for line in result.stdout.lines if "::" in line]


def test_the_paper_example_collects_seven_items_per_pair_of_table_iv_b(
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


def test_files_named_lasertest_yaml_are_collected_and_other_yaml_is_not(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    shutil.copy(pairs_file, pytester.path / "gate.lasertest.yml")
    shutil.copy(pairs_file, pytester.path / "settings.yaml")
    result = pytester.runpytest("--collect-only", "-q")
    assert collected(result) == gate_items("gate.lasertest.yaml") + gate_items("gate.lasertest.yml")


def test_laser_pairs_alone_runs_that_file_and_not_the_test_suite(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    pairs_file.rename(pytester.path / "robot-pairs.yaml")
    pytester.makepyfile(test_unit="def test_unit(): pass")
    result = pytester.runpytest("--laser-pairs", "robot-pairs.yaml", "--collect-only", "-q")
    assert collected(result) == gate_items("robot-pairs.yaml")


def test_laser_pairs_with_arguments_runs_both(pytester: pytest.Pytester, pairs_file: Path) -> None:
    pairs_file.rename(pytester.path / "robot-pairs.yaml")
    pytester.makepyfile(test_unit="def test_unit(): pass")
    result = pytester.runpytest(
        "test_unit.py", "--laser-pairs", "robot-pairs.yaml", "-q", *PLUMBING
    )
    result.assert_outcomes(passed=2, failed=1)


def test_ini_laser_pairs_are_collected_alongside_the_test_suite(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    pairs_file.rename(pytester.path / "robot-pairs.yaml")
    pytester.makeini("[pytest]\nlaser_pairs = robot-pairs.yaml\n")
    pytester.makepyfile(test_unit="def test_unit(): pass")
    result = pytester.runpytest("-q", *PLUMBING)
    result.assert_outcomes(passed=2, failed=1)


def test_a_relative_laser_pairs_path_works_from_a_subdirectory_under_xdist(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    pytester.makeini("[pytest]\n")
    subdirectory = pytester.mkdir("robots")
    pairs_file.rename(subdirectory / "gate.yaml")
    with pytest.MonkeyPatch.context() as patch:
        patch.chdir(subdirectory)
        result = pytester.runpytest_subprocess(
            "--laser-pairs", "gate.yaml", "-n", "2", *NO_PLACEMENTS
        )
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
    result = pytester.runpytest_subprocess("-n", "2", "--junitxml=report.xml", *NO_PLACEMENTS)
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
    assert collected(selected) == gate_items("gate.lasertest.yaml")
    assert collected(others) == ["test_unit.py::test_unit"]


def test_a_failure_points_at_the_pair_in_the_pairs_file(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    result = pytester.runpytest("-q", "--laser-seed=11", *NO_PLACEMENTS)
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


# A pair that differs only in samples, and one that does not differ at all; one witness each.
PLACEMENT_PAIRS = (
    SIZE_PAIR
    + """\
  same:
    baseline: {model: clearpath_lms1xx_gazebo, samples: 32}
    candidate: {model: clearpath_lms1xx_gazebo, samples: 32, noise: {stddev: 0.02}}
"""
)

# Records whether z3 is loaded once collection is done, and again once the items have run.
Z3_PROBE = """\
import sys

loaded = []

def pytest_collection_finish(session):
    loaded.append("z3" in sys.modules)

def pytest_sessionfinish(session):
    loaded.append("z3" in sys.modules)
    with open("z3.txt", "w") as probe:
        probe.write(" ".join(map(str, loaded)))
"""


@pytest.fixture
def placement_pairs(pytester: pytest.Pytester) -> Path:
    """PLACEMENT_PAIRS as `gate.lasertest.yaml` in the pytester directory."""
    path = pytester.path / "gate.lasertest.yaml"
    path.write_text(PLACEMENT_PAIRS)
    return path


class JunitCase(NamedTuple):
    """One test case of a JUnit XML report."""

    outcome: str  # passed, failure, error or skipped
    message: str  # the failure's or the skip's message
    properties: dict[str, str]


def junit_cases(path: Path) -> dict[str, JunitCase]:
    """The test cases of a JUnit XML report, by item id."""
    cases = {}
    for case in ET.parse(path).iter("testcase"):
        ending = next((child for child in case if child.tag != "properties"), None)
        properties = {prop.get("name", ""): prop.get("value", "") for prop in case.iter("property")}
        cases[f"{case.get('classname')}::{case.get('name')}"] = JunitCase(
            ending.tag if ending is not None else "passed",
            ending.get("message", "") if ending is not None else "",
            properties,
        )
    return cases


def test_each_pair_collects_a_coverage_item_and_one_item_per_direction_and_witness(
    pytester: pytest.Pytester, placement_pairs: Path
) -> None:
    placement_pairs.write_text(PLACEMENT_PAIRS.replace("witnesses: 1", "witnesses: 2"))
    result = pytester.runpytest("--collect-only", "-q")
    assert collected(result) == [
        "gate.lasertest.yaml::size[coverage]",
        "gate.lasertest.yaml::size[no-obstacle]",
        "gate.lasertest.yaml::size[candidate-misses-0]",
        "gate.lasertest.yaml::size[candidate-misses-1]",
        "gate.lasertest.yaml::size[baseline-misses-0]",
        "gate.lasertest.yaml::size[baseline-misses-1]",
        "gate.lasertest.yaml::same[coverage]",
        "gate.lasertest.yaml::same[no-obstacle]",
        "gate.lasertest.yaml::same[candidate-misses-0]",
        "gate.lasertest.yaml::same[candidate-misses-1]",
        "gate.lasertest.yaml::same[baseline-misses-0]",
        "gate.lasertest.yaml::same[baseline-misses-1]",
    ]


def test_collection_does_not_load_z3_and_running_a_placement_item_does(
    pytester: pytest.Pytester, placement_pairs: Path
) -> None:
    pytester.makeconftest(Z3_PROBE)
    outcomes = pytester.runpytest_subprocess("-k", "size and candidate").parseoutcomes()
    assert outcomes.get("passed", 0) + outcomes.get("failed", 0) == 1
    assert (pytester.path / "z3.txt").read_text() == "False True"


@pytest.fixture
def paper_pairs(pytester: pytest.Pytester) -> Path:
    """The paper's pairs file, whose size pair puts the thin pole in the 16-beam robot's way."""
    path = pytester.path / "paper.lasertest.yaml"
    shutil.copy(EXAMPLES / "paper.lasertest.yaml", path)
    return path


def test_the_sparser_scanner_drives_into_its_witness_and_the_denser_one_stops_short_stuck(
    pytester: pytest.Pytester, paper_pairs: Path
) -> None:
    result = pytester.runpytest(
        "-k", "size and misses-1", "--junitxml=report.xml", "--laser-seed=1", "--laser-profile=ci"
    )
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(
        [
            "the candidate fails (collision and goal) near witness candidate-misses-1: "
            "pre-existing: the baseline fails here too",
            "  pair       size (paper.lasertest.yaml:40)",
            "  controller move_base (the default)",
            "  oracle     collision: collided at t = * s (margin *-* mm)",
            "  oracle     goal: goal not reached: * m away at best (margin -* mm)",
            "  witness    cylinder of radius 0.025 m at * m high",
            "  minimal    cylinder of radius 0.025 m at * m high",
            "  change     none (the smallest the search found that fails)",
            "  margins    detection * mm, concealment * mm, clearance * mm, obstruction * mm",
            "  beams      at t = 1.14 s, robot at (0.51, 0.00, 0.00):",
            "    baseline  beam 15 read it, 15 mm deep",
            "    candidate no beam reads it; beam 7 comes nearest, 260 mm clear",
            # The paper's finding: the 32-beam robot stops short of the pole and never gets past.
            "  baseline   clearpath_lms1xx_gazebo: FAILED: no collision, least clearance * mm; "
            "stuck at t = * s: *; goal not reached: *",
            "  candidate  clearpath_lms1xx_gazebo: FAILED: collided at t = * s; *",
            "  search     1 examples, 0 rejected (0%), 2 simulations; the first failure at "
            "simulation 1, then 1 more to classify and shrink it; offsets up to x *",
            "  policy     candidate",
            "  seed       1",
            "  replay     pytest 'paper.lasertest.yaml::size[[]candidate-misses-1[]]' "
            "--laser-seed=1 --laser-profile=ci --laser-policy=candidate  (replays this case "
            "first, from .hypothesis/)",
        ]
    )
    cases = junit_cases(pytester.path / "report.xml")
    for direction, detector in [("candidate-misses", "baseline"), ("baseline-misses", "candidate")]:
        _, _, properties = cases[f"paper.lasertest.yaml::size[{direction}-1]"]
        assert properties["lasertest.detected_by"] == detector
        assert float(properties["lasertest.margin"]) >= 0.005
        assert float(properties["lasertest.lead"]) >= 0.0
        assert properties["lasertest.late"] in {"True", "False"}
        assert re.fullmatch(r"(box|cylinder) .* m high", properties["lasertest.obstacle"])
        assert properties["lasertest.candidate.collision"] in {"pass", "fail"}
    dense = cases["paper.lasertest.yaml::size[baseline-misses-1]"].properties
    assert int(dense["lasertest.examples"]) == 16
    sparse = cases["paper.lasertest.yaml::size[candidate-misses-1]"].properties
    assert sparse["lasertest.candidate.collision"] == "fail"
    assert float(sparse["lasertest.candidate.collision_margin"]) <= 0.0
    assert sparse["lasertest.baseline.stuck"] == "fail"
    assert sparse["lasertest.classification"] == "pre-existing"
    assert sparse["lasertest.failed_oracles"] == "collision,goal"


def test_placement_items_of_identical_scanners_are_skipped_because_they_cast_the_same_beams(
    pytester: pytest.Pytester, placement_pairs: Path
) -> None:
    result = pytester.runpytest("-k", "same", "-rs")
    result.assert_outcomes(passed=2, skipped=2)
    result.stdout.fnmatch_lines(
        ["SKIPPED [[]2[]] gate.lasertest.yaml:13: unsat: the two scanners cast the same beams *"]
    )


def test_not_placement_deselects_the_placement_items_and_not_coverage_the_coverage_items(
    pytester: pytest.Pytester, placement_pairs: Path
) -> None:
    without_placements = pytester.runpytest("-m", "not placement", "--co", "-q")
    without_coverage = pytester.runpytest("-m", "not coverage", "--co", "-q")
    assert collected(without_placements) == [
        "gate.lasertest.yaml::size[coverage]",
        "gate.lasertest.yaml::size[no-obstacle]",
        "gate.lasertest.yaml::same[coverage]",
        "gate.lasertest.yaml::same[no-obstacle]",
    ]
    assert collected(without_coverage) == [
        "gate.lasertest.yaml::size[no-obstacle]",
        "gate.lasertest.yaml::size[candidate-misses-0]",
        "gate.lasertest.yaml::size[baseline-misses-0]",
        "gate.lasertest.yaml::same[no-obstacle]",
        "gate.lasertest.yaml::same[candidate-misses-0]",
        "gate.lasertest.yaml::same[baseline-misses-0]",
    ]


def test_items_run_and_sum_up_the_same_under_xdist_as_serially(
    pytester: pytest.Pytester, paper_pairs: Path
) -> None:
    selection = ("-k", "size", "--laser-seed=1", "--laser-profile=ci")
    serial = pytester.runpytest(*selection, "--junitxml=serial.xml")
    # Each run starts from an empty example database, or the second would replay the first's
    # failures and try fewer examples.
    shutil.rmtree(pytester.path / ".hypothesis")
    distributed = pytester.runpytest_subprocess(*selection, "--junitxml=xdist.xml", "-n", "2")
    assert junit_cases(pytester.path / "serial.xml") == junit_cases(pytester.path / "xdist.xml")
    assert summary(serial.stdout.lines) == summary(distributed.stdout.lines)
    assert summary(serial.stdout.lines)[1].split() == [
        # witnesses, examples, rejected, failed, by oracle, regressions, pre-existing
        *("paper.lasertest.yaml::size", "6", "55", "0", "(0%)", "3", "2", "1", "3", "1", "2"),
    ]
    assert {
        name: case.outcome for name, case in junit_cases(pytester.path / "serial.xml").items()
    } == {
        "paper.lasertest.yaml::size[coverage]": "failure",
        "paper.lasertest.yaml::size[no-obstacle]": "passed",
        **{f"paper.lasertest.yaml::size[baseline-misses-{index}]": "passed" for index in range(2)},
        "paper.lasertest.yaml::size[baseline-misses-2]": "failure",
        "paper.lasertest.yaml::size[candidate-misses-0]": "passed",
        "paper.lasertest.yaml::size[candidate-misses-1]": "failure",
        # Found by perturbing the witness, which both robots pass: see the next test.
        "paper.lasertest.yaml::size[candidate-misses-2]": "failure",
    }


def summary(lines: list[str]) -> list[str]:
    """The lasertest summary table of a run's output."""
    start = next(index for index, line in enumerate(lines) if "lasertest: placements" in line)
    table = []
    for line in lines[start + 1 :]:
        if line.startswith(("=", "FAILED", "ERROR")):
            break
        table.append(line)
    return table


def test_a_witness_the_ray_cast_rejects_fails_as_a_bug_in_the_solver(
    pytester: pytest.Pytester, placement_pairs: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from pytest_lasertest.plugin.items import placement as placement_item

    def rejecting(scene: Scene, placement: Placement) -> Verification:
        return dataclasses.replace(verify(scene, placement), concealment=-0.001)

    monkeypatch.setattr(placement_item, "verify", rejecting)
    result = pytester.runpytest(
        "-k", "size and candidate", "--laser-seed=2", "--laser-artifacts=out"
    )
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(
        [
            "*_ size[[]candidate-misses-0[]] _*",
            "the exact ray cast rejects witness candidate-misses-0, which the solver returned as "
            "verified: this is a bug in pytest-lasertest's solver*",
            "  pair       size (gate.lasertest.yaml:10)",
            "  baseline   clearpath_lms1xx_gazebo: 32 beams *",
            "  candidate  clearpath_lms1xx_gazebo: 16 beams *",
            "  obstacle   * m high",
            "  read by    the baseline at t = * s, robot at (*)",
            "  margins    detection * mm, concealment -1.0 mm, clearance * mm, obstruction * mm; "
            "each must reach 5.0 mm",
            "  replay     pytest 'gate.lasertest.yaml::size[[]candidate-misses-0[]]' *",
            "  evidence   out/gate.lasertest.yaml/size_candidate-misses-0.json",
        ]
    )
    evidence = json.loads(
        (pytester.path / "out/gate.lasertest.yaml/size_candidate-misses-0.json").read_text()
    )
    assert evidence["witness"]["id"] == "candidate-misses-0"
    assert evidence["verification"]["concealment"] == -0.001


def test_a_candidate_that_fails_in_the_empty_world_fails_the_control_item_and_only_that(
    pytester: pytest.Pytester, placement_pairs: Path
) -> None:
    # 2 s cannot take either robot 6 m: the failure is everywhere, not at any placement.
    placement_pairs.write_text(SIZE_PAIR.replace("time_limit: 60.0", "time_limit: 2.0"))
    result = pytester.runpytest("-k", "size", "-rs", "--laser-seed=1")
    result.assert_outcomes(failed=2, skipped=2)
    result.stdout.fnmatch_lines(
        [
            "the candidate fails without any obstacle: the change breaks the robot everywhere*",
            "  candidate  clearpath_lms1xx_gazebo: FAILED: *goal not reached: * m away at best",
            "SKIPPED [[]2[]] gate.lasertest.yaml:10: the candidate already fails without any "
            "obstacle: see size[[]no-obstacle[]]",
        ]
    )


def test_a_run_that_drives_leaves_no_physics_client_connected(
    pytester: pytest.Pytester, placement_pairs: Path
) -> None:
    placement_pairs.write_text(SIZE_PAIR.replace("time_limit: 60.0", "time_limit: 2.0"))
    result = pytester.runpytest("-k", "size and no-obstacle")
    result.assert_outcomes(failed=1)
    assert connected_clients() == 0


def test_under_the_regression_policy_a_failure_the_baseline_shares_passes(
    pytester: pytest.Pytester, placement_pairs: Path
) -> None:
    placement_pairs.write_text(SIZE_PAIR.replace("time_limit: 60.0", "time_limit: 2.0"))
    result = pytester.runpytest("-k", "size and no-obstacle", "--laser-policy=regression")
    result.assert_outcomes(passed=1)
