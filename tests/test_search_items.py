"""Placement items search around their witness: failures shrink, replay first on the next run,
come with artifacts that replay them, and sum up per pair."""

from __future__ import annotations

import json
import shutil
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES
from tests.test_collection import junit_cases

# The pole-like box of the size pair's third witness: both robots pass the witness itself, and
# the search finds that moving it 6 cm further on makes the 16-beam robot drive into it.
ITEM = "paper.lasertest.yaml::size[candidate-misses-2]"
RUN = ("-k", "size and candidate-misses-2", "--laser-seed=1", "--laser-profile=ci")
ARTIFACTS = Path("out/paper.lasertest.yaml")


@pytest.fixture
def paper(pytester: pytest.Pytester) -> Path:
    path = pytester.path / "paper.lasertest.yaml"
    shutil.copy(EXAMPLES / "paper.lasertest.yaml", path)
    return path


def properties(pytester: pytest.Pytester, report: str, item: str = ITEM) -> dict[str, str]:
    return junit_cases(pytester.path / report)[item].properties


def test_a_failure_found_by_perturbing_the_witness_is_shrunk_and_reported(
    pytester: pytest.Pytester, paper: Path
) -> None:
    result = pytester.runpytest(*RUN, "--junitxml=report.xml")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(
        [
            "the candidate fails (collision and goal) near witness candidate-misses-2: a "
            "regression: the baseline passes where the candidate fails",
            "  oracle     collision: collided at t = * s (margin -* mm)",
            "  witness    box 0.051 x 0.051 m, yaw 0.393 rad, at (7.584, 0.306) m, 0.458 m high",
            "  minimal    box * m high",
            "  change     x +0.0* m (the smallest the search found that fails)",
            "    baseline  beam * read it, * mm deep",
            "    candidate no beam reads it; beam * comes nearest, * mm clear",
            "  baseline   clearpath_lms1xx_gazebo: passed: *",
            "  candidate  clearpath_lms1xx_gazebo: FAILED: collided at t = * s; *",
        ]
    )
    found = properties(pytester, "report.xml")
    assert found["lasertest.classification"] == "regression"
    assert found["lasertest.offset"].startswith("x +0.0")
    # The witness itself passes, so the failure needs at least a second simulation.
    assert found["lasertest.candidate.collision"] == "pass"
    assert int(found["lasertest.simulations_to_failure"]) >= 2


def test_the_next_run_replays_the_stored_failure_first_and_needs_fewer_simulations(
    pytester: pytest.Pytester, paper: Path
) -> None:
    pytester.runpytest(*RUN, "--junitxml=first.xml").assert_outcomes(failed=1)
    pytester.runpytest(*RUN, "--junitxml=second.xml").assert_outcomes(failed=1)
    first, second = properties(pytester, "first.xml"), properties(pytester, "second.xml")
    assert int(second["lasertest.simulations_to_failure"]) == 1
    assert int(second["lasertest.simulations_to_failure"]) < int(
        first["lasertest.simulations_to_failure"]
    )
    assert second["lasertest.minimal_obstacle"] == first["lasertest.minimal_obstacle"]


def test_the_repro_file_collected_alone_fails_the_same_way(
    pytester: pytest.Pytester, paper: Path
) -> None:
    pytester.runpytest(*RUN, "--laser-artifacts=out").assert_outcomes(failed=1)
    evidence = json.loads((ARTIFACTS / "size_candidate-misses-2.json").read_text())
    repro = ARTIFACTS / "size_candidate-misses-2.lasertest.yaml"
    replay = pytester.runpytest(str(repro), "--junitxml=repro.xml", "--laser-seed=99")
    replay.assert_outcomes(failed=1)
    replay.stdout.fnmatch_lines(
        ["the candidate fails at the pinned placement size[[]pinned-0[]]: a regression: *"]
    )
    (pinned,) = (
        case.properties
        for name, case in junit_cases(pytester.path / "repro.xml").items()
        if name.endswith("::size[pinned-0]")
    )
    assert evidence["candidate"]["trajectory_digest"].startswith(
        pinned["lasertest.candidate.trajectory"]
    )
    assert pinned["lasertest.classification"] == evidence["classification"] == "regression"


def test_a_failing_item_writes_a_picture_a_repro_a_gazebo_world_and_every_number(
    pytester: pytest.Pytester, paper: Path
) -> None:
    result = pytester.runpytest(*RUN, "--laser-artifacts=out")
    written = sorted(path.name for path in ARTIFACTS.iterdir())
    stem = "size_candidate-misses-2"
    assert written == [f"{stem}.json", f"{stem}.lasertest.yaml", f"{stem}.png", f"{stem}.world"]
    assert (ARTIFACTS / f"{stem}.png").read_bytes().startswith(b"\x89PNG\r\n\x1a\n")
    world = ET.parse(ARTIFACTS / f"{stem}.world").getroot()
    assert world.get("version") == "1.6"
    assert len(world.findall("./world/model")) == 2  # the ground and the obstacle
    evidence = json.loads((ARTIFACTS / f"{stem}.json").read_text())
    assert evidence["classification"] == "regression"
    assert evidence["offset"]["x"] > 0.0
    assert evidence["baseline"]["passed"] is True
    assert evidence["candidate"]["verdicts"]["collision"]["passed"] is False
    assert evidence["seed"] == 1
    result.stdout.fnmatch_lines(
        [
            f"  replay     pytest '{ARTIFACTS}/{stem}.lasertest.yaml'  (this case alone, pinned)",
            f"  artifact   {ARTIFACTS}/{stem}.png",
        ]
    )


def test_laser_examples_sets_how_many_perturbations_each_item_tries(
    pytester: pytest.Pytester, paper: Path
) -> None:
    run = ("-k", "size and baseline-misses-0", "--laser-seed=1", "--junitxml=report.xml")
    pytester.runpytest(*run, "--laser-examples=3").assert_outcomes(passed=1)
    item = "paper.lasertest.yaml::size[baseline-misses-0]"
    assert properties(pytester, "report.xml", item)["lasertest.examples"] == "3"


@pytest.mark.parametrize("value", ["0", "many", "-3", "10001"])
def test_a_bad_number_of_examples_is_a_usage_error_naming_it(
    pytester: pytest.Pytester, value: str
) -> None:
    result = pytester.runpytest(f"--laser-examples={value}")
    assert result.ret == pytest.ExitCode.USAGE_ERROR
    result.stderr.fnmatch_lines(
        [f"ERROR: --laser-examples='{value}' is not a number of examples: give a whole number *"]
    )


def test_hypothesis_statistics_count_each_items_outcomes(
    pytester: pytest.Pytester, paper: Path
) -> None:
    result = pytester.runpytest(
        "-k",
        "size and baseline-misses-0",
        "--laser-seed=1",
        "--laser-examples=3",
        "--hypothesis-show-statistics",
    )
    result.stdout.fnmatch_lines(
        [
            "*Hypothesis Statistics*",
            "paper.lasertest.yaml::size[[]baseline-misses-0[]]:",
            "*- 3 passing, 0 failing, and 0 invalid test cases",
            "*Events:",
            "*100.00%, candidate passed",
        ]
    )


PINNED = """\
robot: husky
world:
  start: {{x: 0.0, y: 0.0, yaw: 0.0}}
  goal: {{x: 6.0, y: 0.0}}
  time_limit: 40.0
pairs:
  size:
    baseline: {{model: clearpath_lms1xx_gazebo, samples: 32, range: {{max: 10.0}}}}
    candidate: {{model: clearpath_lms1xx_gazebo, samples: 16, range: {{max: 10.0}}}}
    placements:
      - obstacle: {obstacle}
        seed: 3
"""
# Far off the route: neither robot comes near it.
ASIDE = "{shape: cylinder, x: 3.0, y: 4.0, radius: 0.2, height: 0.5}"
# A wall across the route that both scanners read: both robots stop before it, stuck.
WALL = "{shape: box, x: 3.0, y: 0.0, yaw: 0.0, length: 0.2, width: 6.0, height: 0.5}"


def test_a_pair_that_pins_placements_yields_only_its_pinned_items(
    pytester: pytest.Pytester,
) -> None:
    pytester.makefile(".lasertest.yaml", gate=PINNED.format(obstacle=ASIDE))
    result = pytester.runpytest("--co", "-q")
    assert [line for line in result.stdout.lines if "::" in line] == [
        "gate.lasertest.yaml::size[pinned-0]"
    ]


def test_a_pinned_placement_both_robots_pass_passes(pytester: pytest.Pytester) -> None:
    pytester.makefile(".lasertest.yaml", gate=PINNED.format(obstacle=ASIDE))
    pytester.runpytest().assert_outcomes(passed=1)


def test_a_pinned_failure_both_robots_share_fails_only_under_the_candidate_policy(
    pytester: pytest.Pytester,
) -> None:
    pytester.makefile(".lasertest.yaml", gate=PINNED.format(obstacle=WALL))
    failed = pytester.runpytest("--laser-policy=candidate")
    failed.assert_outcomes(failed=1)
    failed.stdout.fnmatch_lines(
        [
            "the candidate fails at the pinned placement size[[]pinned-0[]]: pre-existing: the "
            "baseline fails here too",
            "  obstacle   box 0.200 x 6.000 m, yaw 0.000 rad, at (3.000, 0.000) m, 0.500 m high "
            "(gate.lasertest.yaml:11)",
            "  noise seed 3 (pinned; --laser-seed does not change it)",
        ]
    )
    pytester.runpytest("--laser-policy=regression").assert_outcomes(passed=1)


def test_a_control_item_that_fails_writes_its_picture_world_and_numbers(
    pytester: pytest.Pytester, paper: Path
) -> None:
    result = pytester.runpytest(
        "-k", "distance and no-obstacle", "--laser-seed=1", "--laser-artifacts=out"
    )
    result.assert_outcomes(failed=1)
    stem = ARTIFACTS / "distance_no-obstacle"
    result.stdout.fnmatch_lines([f"  artifact   {stem}.png", f"  artifact   {stem}.world"])
    assert Path(f"{stem}.png").read_bytes().startswith(b"\x89PNG\r\n\x1a\n")
    world = ET.parse(f"{stem}.world").getroot()
    assert [model.get("name") for model in world.iter("model")] == ["ground_plane"]
    evidence = json.loads(Path(f"{stem}.json").read_text())
    assert evidence["candidate"]["verdicts"]["stuck"]["passed"] is False
    assert evidence["baseline"]["passed"] is True


def test_under_the_regression_policy_a_failure_the_baseline_shares_passes_and_is_counted(
    pytester: pytest.Pytester, paper: Path
) -> None:
    # Both robots get stuck at this witness, a 5 cm box beside the route.
    item = "paper.lasertest.yaml::size[baseline-misses-2]"
    run = ("-k", "size and baseline-misses-2", "--laser-seed=1", "--laser-examples=2")
    result = pytester.runpytest(*run, "--laser-policy=regression", "--junitxml=report.xml")
    result.assert_outcomes(passed=1)
    found = properties(pytester, "report.xml", item)
    assert found["lasertest.candidate.stuck"] == found["lasertest.baseline.stuck"] == "fail"
    assert int(found["lasertest.pre_existing"]) >= 1
    assert found["lasertest.regressions"] == "0"
    pytester.runpytest(*run, "--laser-policy=candidate").assert_outcomes(failed=1)
