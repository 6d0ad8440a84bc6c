"""Scanners a pairs file reads from a recording (`pairsfile/recorded.py`): `bag: {path, topic}`,
the path relative to the pairs file, with profile fields and `pose:` that override what the bag
shows; a bag that gives no profile is an error at its line."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import pytest

from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.inputs.inferred import profile_from_bag
from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.pairsfile import load_pairs_file
from tests.helpers.bags import RECORDED_PAIR, laser_scans, write_bag
from tests.helpers.model import HUSKY_MOUNT

# Line numbers matter: the candidate's `bag:` is on line 7.
RECORDED = RECORDED_PAIR + "      bag: {path: recordings/front, topic: /scan}\n"


@pytest.fixture
def bag(tmp_path: Path) -> Path:
    """recordings/front, a rosbag2 MCAP recording whose driver publishes no-returns as NaN."""
    (tmp_path / "recordings").mkdir()
    return write_bag(tmp_path / "recordings" / "front", laser_scans(no_return=math.nan))


def refusal(tmp_path: Path, text: str) -> SpecError:
    path = tmp_path / "gate.lasertest.yaml"
    path.write_text(text)
    with pytest.raises(SpecError) as caught:
        load_pairs_file(path)
    return caught.value


def test_a_scanner_read_from_a_bag_gives_the_profile_its_scans_show_on_the_robot_s_mount(
    tmp_path: Path, bag: Path
) -> None:
    path = tmp_path / "gate.lasertest.yaml"
    path.write_text(RECORDED)
    candidate = load_pairs_file(path).pairs[0].candidate
    shown = profile_from_bag(bag, "/scan").profile
    assert candidate.profile == dataclasses.replace(shown, pose=HUSKY_MOUNT)
    assert candidate.profile.driver.no_return == "nan"
    assert candidate.label == "bag recordings/front /scan"


def test_profile_fields_and_pose_beside_bag_override_what_the_bag_shows(
    tmp_path: Path, bag: Path
) -> None:
    path = tmp_path / "gate.lasertest.yaml"
    path.write_text(
        RECORDED
        + "      range: {max: 8.0}\n"
        + "      driver: {latency: 0.02}\n"
        + "      pose: {xyz: [0.3, 0.0, 0.5]}\n"
    )
    profile = load_pairs_file(path).pairs[0].candidate.profile
    shown = profile_from_bag(bag, "/scan").profile
    assert (profile.range_min, profile.range_max) == (shown.range_min, 8.0)
    assert profile.driver == dataclasses.replace(shown.driver, latency=0.02)
    assert profile.pose == Pose3D((0.3, 0.0, 0.5), HUSKY_MOUNT.rpy)


def test_a_topic_the_bag_lacks_is_an_error_at_the_pairs_file_line_that_names_it(
    tmp_path: Path, bag: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    text = RECORDED.replace(
        "      bag: {path: recordings/front, topic: /scan}",
        "      bag:\n        path: recordings/front\n        topic: /scna",
    )
    error = refusal(tmp_path, text)
    assert (error.location.line, error.field) == (9, "pairs.recorded.candidate.bag.topic")
    assert str(error) == (
        "gate.lasertest.yaml:9: pairs.recorded.candidate.bag.topic: recordings/front: has no "
        "topic /scna; its LaserScan topics: /scan\n"
        "  fix: did you mean /scan? name one of its LaserScan topics: /scan"
    )


def test_a_bag_that_does_not_exist_is_an_error_at_the_bag_line(tmp_path: Path) -> None:
    error = refusal(tmp_path, RECORDED)
    assert (error.location.line, error.field) == (7, "pairs.recorded.candidate.bag")
    assert error.problem == "recordings/front: does not exist"


def test_a_damaged_bag_is_an_error_at_the_bag_line(tmp_path: Path) -> None:
    (tmp_path / "recordings").mkdir()
    (tmp_path / "recordings" / "front.mcap").write_bytes(b"\x89MCAP0\r\n" + bytes(100))
    error = refusal(tmp_path, RECORDED.replace("recordings/front", "recordings/front.mcap"))
    assert (error.location.line, error.field) == (7, "pairs.recorded.candidate.bag")
    assert error.problem.startswith("recordings/front.mcap: is damaged or cut short")


@pytest.mark.parametrize(
    ("bag_line", "line", "field", "problem"),
    [
        (
            "bag: {path: recordings/front, topic: /scan}\n      model: sick_lms111",
            8,
            "pairs.recorded.candidate.model",
            "a scanner read from a `bag:` takes no `model:`",
        ),
        (
            "bag: {topic: /scan}",
            7,
            "pairs.recorded.candidate.bag.path",
            "path is missing",
        ),
        (
            "bag: recordings/front",
            7,
            "pairs.recorded.candidate.bag",
            "`bag:` takes the bag's path and its topic",
        ),
        (
            "bag: {path: recordings/front, name: /scan}",
            7,
            "pairs.recorded.candidate.bag.name",
            "unknown key 'name'",
        ),
    ],
)
def test_a_bag_written_wrong_is_an_error_at_its_line(
    tmp_path: Path, bag: Path, bag_line: str, line: int, field: str, problem: str
) -> None:
    text = RECORDED.replace("bag: {path: recordings/front, topic: /scan}", bag_line)
    error = refusal(tmp_path, text)
    assert (error.location.line, error.field, error.problem) == (line, field, problem)
