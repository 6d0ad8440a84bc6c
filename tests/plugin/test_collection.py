"""Collection: pairs files become items with ids from YAML names, found by name, by
`--laser-pairs` or the `laser_pairs` ini option, the same on every run and every xdist worker,
marked for `-m`; collecting loads no solver."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from tests.helpers import EXAMPLES
from tests.helpers.runs import NO_PLACEMENTS, outcomes
from tests.helpers.texts import PLACEMENT_PAIRS


def pair_items(file: str, pair: str, witnesses: int = 3) -> list[str]:
    """The ids a pair collects: its coverage and control items, one per placement to steer
    round, then one per direction and witness index."""
    return [
        f"{file}::{pair}[{kind}-{index}]" if index is not None else f"{file}::{pair}[{kind}]"
        for kind, index in [
            ("coverage", None),
            ("no-obstacle", None),
            *(("avoid", index) for index in range(witnesses)),
            *(
                (direction, index)
                for direction in ("candidate-misses", "baseline-misses")
                for index in range(witnesses)
            ),
        ]
    ]


def gate_items(file: str) -> list[str]:
    """The ids of VALID_PAIRS (tests/helpers/texts.py) written to `file`."""
    return pair_items(file, "to_lms111") + pair_items(file, "same")


PAPER_ITEMS = [
    item
    for pair in ("blind_spot", "distance", "size")
    for item in pair_items("examples/paper.lasertest.yaml", pair)
]


# Runs that test the plumbing with the project's own unmarked tests: no solver, no simulator.
PLUMBING = ("-m", "not placement and not control", "--laser-policy=candidate")


@pytest.fixture
def examples(pytester: pytest.Pytester) -> Path:
    """A copy of the repository's examples in the pytester directory."""
    return Path(shutil.copytree(EXAMPLES, pytester.path / "examples"))


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


def test_items_carry_the_lasertest_marker(pytester: pytest.Pytester, pairs_file: Path) -> None:
    pytester.makepyfile(test_unit="def test_unit(): pass")
    selected = pytester.runpytest("-m", "lasertest", "--co", "-q")
    others = pytester.runpytest("-m", "not lasertest", "--co", "-q")
    assert collected(selected) == gate_items("gate.lasertest.yaml")
    assert collected(others) == ["test_unit.py::test_unit"]


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


def test_each_pair_collects_a_coverage_item_and_one_item_per_direction_and_witness(
    pytester: pytest.Pytester, placement_pairs: Path
) -> None:
    placement_pairs.write_text(PLACEMENT_PAIRS.replace("witnesses: 1", "witnesses: 2"))
    result = pytester.runpytest("--collect-only", "-q")
    assert collected(result) == [
        "gate.lasertest.yaml::size[coverage]",
        "gate.lasertest.yaml::size[no-obstacle]",
        "gate.lasertest.yaml::size[avoid-0]",
        "gate.lasertest.yaml::size[avoid-1]",
        "gate.lasertest.yaml::size[candidate-misses-0]",
        "gate.lasertest.yaml::size[candidate-misses-1]",
        "gate.lasertest.yaml::size[baseline-misses-0]",
        "gate.lasertest.yaml::size[baseline-misses-1]",
        "gate.lasertest.yaml::same[coverage]",
        "gate.lasertest.yaml::same[no-obstacle]",
        "gate.lasertest.yaml::same[avoid-0]",
        "gate.lasertest.yaml::same[avoid-1]",
        "gate.lasertest.yaml::same[candidate-misses-0]",
        "gate.lasertest.yaml::same[candidate-misses-1]",
        "gate.lasertest.yaml::same[baseline-misses-0]",
        "gate.lasertest.yaml::same[baseline-misses-1]",
    ]


def test_collection_does_not_load_z3_and_running_a_placement_item_does(
    pytester: pytest.Pytester, placement_pairs: Path
) -> None:
    pytester.makeconftest(Z3_PROBE)
    counts = outcomes(pytester.runpytest_subprocess("-k", "size and candidate"))
    # It ran, whatever it found (passed, failed, pre-existing or marginal).
    ran = ("passed", "failed", "pre-existing", "marginal")
    assert sum(counts.get(outcome, 0) for outcome in ran) == 1
    assert (pytester.path / "z3.txt").read_text() == "False True"


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
        "gate.lasertest.yaml::size[avoid-0]",
        "gate.lasertest.yaml::size[candidate-misses-0]",
        "gate.lasertest.yaml::size[baseline-misses-0]",
        "gate.lasertest.yaml::same[no-obstacle]",
        "gate.lasertest.yaml::same[avoid-0]",
        "gate.lasertest.yaml::same[candidate-misses-0]",
        "gate.lasertest.yaml::same[baseline-misses-0]",
    ]


def test_the_avoid_marker_selects_the_placements_to_steer_round(
    pytester: pytest.Pytester, placement_pairs: Path
) -> None:
    result = pytester.runpytest("-m", "avoid", "--co", "-q")
    assert collected(result) == [
        "gate.lasertest.yaml::size[avoid-0]",
        "gate.lasertest.yaml::same[avoid-0]",
    ]
