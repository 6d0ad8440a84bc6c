"""The control item of a pair, `PAIR[no-obstacle]`: both robots through the empty world. A
candidate that fails there fails it, and only it; a failure writes its artifacts; a run that
drives leaves no physics client connected."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from pytest_lasertest.sim.client import connected_clients
from tests.helpers.runs import ARTIFACTS, junit_cases, outcomes
from tests.helpers.texts import SIZE_PAIR


def test_a_candidate_that_fails_in_the_empty_world_fails_the_control_item_and_only_that(
    pytester: pytest.Pytester, placement_pairs: Path
) -> None:
    # 6 s cannot take either robot 6 m at move_base's 0.5 m/s: the failure is everywhere, not at
    # any placement (and the baseline's too, which the report says). The candidate policy fails
    # it, and the coverage item's loss.
    placement_pairs.write_text(SIZE_PAIR.replace("time_limit: 60.0", "time_limit: 6.0"))
    result = pytester.runpytest("-k", "size", "-rs", "--laser-seed=1", "--laser-policy=candidate")
    result.assert_outcomes(failed=2, skipped=3)
    result.stdout.fnmatch_lines(
        [
            "the baseline fails without any obstacle too: the world, its time limit or the "
            "controller is at fault*",
            "  candidate  clearpath_lms1xx_gazebo: FAILED: *goal not reached: * m away at best",
            "SKIPPED [[]3[]] gate.lasertest.yaml:10: the candidate already fails without any "
            "obstacle: see size[[]no-obstacle[]]",
        ]
    )


def test_a_run_that_drives_leaves_no_physics_client_connected(
    pytester: pytest.Pytester, placement_pairs: Path
) -> None:
    placement_pairs.write_text(SIZE_PAIR.replace("time_limit: 60.0", "time_limit: 6.0"))
    result = pytester.runpytest("-k", "size and no-obstacle", "--laser-policy=candidate")
    result.assert_outcomes(failed=1)
    assert connected_clients() == 0


def test_by_default_a_failure_the_baseline_shares_is_noted_as_pre_existing_not_failed(
    pytester: pytest.Pytester, placement_pairs: Path
) -> None:
    placement_pairs.write_text(SIZE_PAIR.replace("time_limit: 60.0", "time_limit: 6.0"))
    result = pytester.runpytest("-k", "size", "-rs", "--laser-seed=1", "--junitxml=out.xml")
    assert result.ret == pytest.ExitCode.OK
    # The placement items skip: a candidate that fails without obstacles fails everywhere.
    counts = outcomes(result)
    counts.pop("deselected", None)
    assert counts == {"skipped": 3, "coverage-loss": 1, "pre-existing": 1}
    result.stdout.fnmatch_lines(
        [
            "PRE-EXISTING   gate.lasertest.yaml::size[[]no-obstacle[]]: the baseline fails "
            "without any obstacle too: *",
        ]
    )
    cases = junit_cases(pytester.path / "out.xml")
    control = cases["gate.lasertest.yaml::size[no-obstacle]"]
    assert control.outcome == "xfail"
    assert control.message.startswith("the baseline fails without any obstacle too")


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
