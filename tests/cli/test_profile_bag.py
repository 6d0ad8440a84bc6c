"""`lasertest profile --bag PATH [--topic TOPIC]` prints the profile a recording of the scanner
shows as YAML a pairs file pastes, how it was read as comments; `--json` the same as JSON; a bag
that gives none, or options that mix a bag with a description, exit 2 with the problem and fix."""

from __future__ import annotations

import dataclasses
import json
import math
import textwrap
from pathlib import Path

import pytest

from pytest_lasertest.cli import main
from pytest_lasertest.inputs.inferred import LATENCY_NOTE, profile_from_bag
from pytest_lasertest.pairsfile import load_pairs_file
from tests.helpers.bags import RECORDED_PAIR, laser_scans, write_bag
from tests.helpers.model import HUSKY_MOUNT


@pytest.fixture
def bag(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """front, a rosbag2 MCAP recording of a driver with NaN no-returns and a per-scan
    range_max, in the working directory."""
    monkeypatch.chdir(tmp_path)
    return write_bag(tmp_path / "front", laser_scans(no_return=math.nan, per_scan=True))


def test_profile_bag_prints_the_profile_as_yaml_with_the_notes_as_comments(
    bag: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["profile", "--bag", "front", "--topic", "/scan"]) == 0
    printed = capsys.readouterr().out
    assert printed.splitlines()[:3] == [
        "# A scanner profile inferred from 30 LaserScan messages on /scan in front. Paste it below",
        "# `baseline:` or `candidate:` in a pairs file, or let the pairs file read the bag: "
        "`bag: {path:",
        "# front, topic: /scan}` (its path relative to the pairs file).",
    ]
    assert "# - latency cannot be measured from a recording" in printed
    assert printed.splitlines()[-6:] == [
        "samples: 181",
        "min_angle: -2.0",
        "max_angle: 2.0",
        "range: {min: 0.05, max: 11.0559}",
        "update_rate: 40.0",
        "driver: {no_return: nan, range_max: per_scan, stamp: end}",
    ]


def test_what_profile_bag_prints_pasted_into_a_pairs_file_gives_the_profile_it_inferred(
    bag: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["profile", "--bag", "front"]) == 0
    pasted = textwrap.indent(capsys.readouterr().out, " " * 6)
    (tmp_path / "gate.lasertest.yaml").write_text(RECORDED_PAIR + pasted)
    candidate = load_pairs_file(tmp_path / "gate.lasertest.yaml").pairs[0].candidate.profile
    inferred = profile_from_bag(bag).profile
    assert candidate == dataclasses.replace(inferred, pose=HUSKY_MOUNT)


def test_profile_bag_json_holds_the_fields_the_yaml_holds_and_the_notes(
    bag: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["profile", "--bag", "front", "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert set(printed) == {"bag", "topic", "messages", "arrival_age", "profile", "notes"}
    assert (printed["bag"], printed["topic"], printed["messages"]) == ("front", "/scan", 30)
    assert printed["arrival_age"] == 0.0
    assert printed["profile"] == {
        "samples": 181,
        "min_angle": -2.0,
        "max_angle": 2.0,
        "range": {"min": 0.05, "max": 11.0559},
        "update_rate": 40.0,
        "driver": {"no_return": "nan", "range_max": "per_scan", "stamp": "end"},
    }
    assert printed["notes"][-1] == LATENCY_NOTE


def test_a_bag_that_gives_no_profile_exits_2_naming_the_bag_the_problem_and_the_fix(
    bag: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["profile", "--bag", "front", "--topic", "/rear"]) == 2
    assert capsys.readouterr().err == (
        "lasertest: front: has no topic /rear; its LaserScan topics: /scan\n"
        "  fix: name one of its LaserScan topics: /scan\n"
    )
    assert main(["profile", "--bag", "missing.mcap", "--json"]) == 2
    error = json.loads(capsys.readouterr().out)["error"]
    assert (error["kind"], error["file"], error["problem"]) == (
        "input",
        "missing.mcap",
        "missing.mcap: does not exist",
    )


@pytest.mark.parametrize(
    ("arguments", "problem"),
    [
        ([], "give a description FILE, or a recording with --bag PATH"),
        (["robot.urdf", "--bag", "front"], "give a description FILE or --bag PATH, not both"),
        (
            ["robot.urdf", "--topic", "/scan"],
            "--topic names a topic of a bag, and no --bag was given",
        ),
        (
            ["--bag", "front", "--ref", "HEAD", "--sensor", "front"],
            "only a description FILE takes --sensor, --ref, not --bag",
        ),
    ],
)
def test_profile_options_that_mix_a_bag_and_a_description_are_usage_errors(
    bag: Path, capsys: pytest.CaptureFixture[str], arguments: list[str], problem: str
) -> None:
    assert main(["profile", *arguments, "--json"]) == 2
    error = json.loads(capsys.readouterr().out)["error"]
    assert (error["kind"], error["problem"]) == ("usage", problem)
    assert "lasertest profile --bag" in error["fix"]
