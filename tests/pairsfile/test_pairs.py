"""Loading pairs files: catalogue models with overrides, the robot's mount, anchors, routes, and
the paper's example."""

from __future__ import annotations

from pathlib import Path

import pytest

from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.model.geometry import Point2D, Pose2D, Pose3D
from pytest_lasertest.pairsfile import load_pairs_file
from tests.helpers import EXAMPLES
from tests.helpers.model import HUSKY_MOUNT
from tests.helpers.texts import VALID_PAIRS


def write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "gate.lasertest.yaml"
    path.write_text(text)
    return path


def test_a_catalogue_model_gives_its_datasheet_figures_on_the_robot_s_mount(
    tmp_path: Path,
) -> None:
    spec = load_pairs_file(write(tmp_path, VALID_PAIRS))
    candidate = spec.pairs[0].candidate
    assert candidate.model == "sick_lms111"
    assert candidate.profile.beam_count == 541
    assert (candidate.profile.range_min, candidate.profile.range_max) == (0.5, 20.0)
    assert candidate.profile.pose == HUSKY_MOUNT


def test_overrides_replace_single_fields_of_a_model_and_keep_the_rest(tmp_path: Path) -> None:
    text = VALID_PAIRS.replace(
        "      model: sick_lms111",
        "      model: sick_lms111\n      range: {max: 8.0}\n      pose: {xyz: [0.3, 0.0, 0.5]}",
    )
    candidate = load_pairs_file(write(tmp_path, text)).pairs[0].candidate.profile
    assert (candidate.range_min, candidate.range_max) == (0.5, 8.0)
    assert candidate.pose == Pose3D((0.3, 0.0, 0.5), HUSKY_MOUNT.rpy)
    assert candidate.update_rate == 50.0


def test_yaml_anchors_and_merge_keys_let_pairs_share_a_profile(tmp_path: Path) -> None:
    text = VALID_PAIRS.replace(
        "    baseline:\n      samples: 720",
        "    baseline: &paper\n      samples: 720",
    ).replace(
        "    candidate:\n      model: sick_lms111",
        "    candidate:\n      <<: *paper\n      samples: 16",
    )
    pair = load_pairs_file(write(tmp_path, text)).pairs[0]
    assert pair.baseline.profile.beam_count == 720
    assert pair.candidate.profile.beam_count == 16
    assert pair.candidate.profile.max_angle == pair.baseline.profile.max_angle


def test_a_route_ends_at_its_goal(tmp_path: Path) -> None:
    text = VALID_PAIRS.replace(
        "  goal: {x: 9.0, y: 0.0}", "  route:\n    - {x: 6.0, y: 0.0}\n    - {x: 6.0, y: 4.0}"
    )
    world = load_pairs_file(write(tmp_path, text)).world
    assert world.start == Pose2D(0.0, 0.0, 0.0)
    assert world.route == (Point2D(6.0, 0.0), Point2D(6.0, 4.0))
    assert world.goal == Point2D(6.0, 4.0)
    assert world.time_limit == 60.0


def test_pairs_keep_their_order_and_the_line_they_start_on(tmp_path: Path) -> None:
    spec = load_pairs_file(write(tmp_path, VALID_PAIRS))
    assert [(pair.name, pair.location.line) for pair in spec.pairs] == [
        ("to_lms111", 11),
        ("same", 20),
    ]
    assert spec.settings.min_obstacle_size == 0.05
    assert [constraint.text for constraint in spec.constraints] == ["x > 1"]


def test_the_paper_example_holds_table_iv_b(tmp_path: Path) -> None:
    spec = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
    pairs = {pair.name: pair for pair in spec.pairs}
    assert list(pairs) == ["blind_spot", "distance", "size"]
    for pair in pairs.values():
        for side in (pair.baseline.profile, pair.candidate.profile):
            assert side.update_rate == 50.0
            assert side.range_min == 0.1
            assert side.pose == HUSKY_MOUNT
    blind, distance, size = pairs["blind_spot"], pairs["distance"], pairs["size"]
    assert (blind.baseline.profile.max_angle, blind.candidate.profile.max_angle) == (1.57, 1.0)
    assert (distance.baseline.profile.range_max, distance.candidate.profile.range_max) == (
        10.0,
        5.0,
    )
    assert (size.baseline.profile.beam_count, size.candidate.profile.beam_count) == (32, 16)
    assert blind.baseline.profile.beam_count == distance.candidate.profile.beam_count == 720


def test_a_scanners_driver_is_read_with_yamls_own_spellings_of_inf_nan_and_zero(
    tmp_path: Path,
) -> None:
    text = VALID_PAIRS.replace(
        "      model: sick_lms111",
        "      model: sick_lms111\n"
        "      driver: {no_return: .nan, too_near: 0, range_max: per_scan, latency: 0.02}",
    )
    driver = load_pairs_file(write(tmp_path, text)).pairs[0].candidate.profile.driver
    assert (driver.no_return, driver.too_near, driver.range_max) == ("nan", "zero", "per_scan")
    assert driver.latency == 0.02


@pytest.mark.parametrize(
    ("driver", "problem", "fix"),
    [
        ("{no_return: -.inf}", "'-inf' is not a choice here", "inf, nan, zero, range_max"),
        ("{beam_order: cw}", "'cw' is not a choice here", "counter-clockwise, clockwise"),
        ("{latency: -0.5}", "-0.5 s is not a stamp delay", "0 to 10"),
        ("{latency: fast}", "expected a number in s", "write a number in s"),
        ("{no_retrun: nan}", "unknown key 'no_retrun'", "did you mean 'no_return'?"),
    ],
)
def test_a_driver_no_scanner_has_is_an_error_at_its_line_with_the_fix(
    tmp_path: Path, driver: str, problem: str, fix: str
) -> None:
    text = VALID_PAIRS.replace(
        "      model: sick_lms111", f"      model: sick_lms111\n      driver: {driver}"
    )
    with pytest.raises(SpecError) as refused:
        load_pairs_file(write(tmp_path, text))
    line = 1 + text.splitlines().index(f"      driver: {driver}")
    assert refused.value.location.line == line
    assert problem in refused.value.problem
    assert fix in refused.value.fix
