"""`lasertest profile FILE` prints the laser the gate reads from a robot description: the
PROFILE fields of `lasertest plan --json`, where they came from, and the mount it composed."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from pytest_lasertest.cli import main
from tests.helpers.git import commit_everything, git
from tests.helpers.texts import ROBOT, SIZE_PAIR, XACRO_LIDAR, XACRO_ROBOT

PROFILE_FIELDS = {
    "samples",
    "resolution",
    "min_angle",
    "max_angle",
    "range_min",
    "range_max",
    "range_resolution",
    "update_rate",
    "noise",
    "mount",
}


@pytest.fixture
def robot(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """robot.urdf in a repository whose last commit has 32 samples; the working tree has 16."""
    path = tmp_path / "robot.urdf"
    path.write_text(ROBOT)
    commit_everything(tmp_path)
    path.write_text(ROBOT.replace("<samples>32</samples>", "<samples>16</samples>"))
    monkeypatch.chdir(tmp_path)
    return path


def test_profile_prints_the_fields_and_the_mount_in_base_footprint(
    robot: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["profile", "robot.urdf"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines == [
        "sensor       front (ray) on link laser, robot.urdf:17",
        "file         robot.urdf",
        "samples      16 x resolution 1 = 16 beams",
        "angles       -1.57 to 1.57 rad (179.9 deg)",
        "range        0.1 to 10 m, resolution 0 m",
        "update_rate  20 Hz",
        "noise        none",
        "mount        xyz (0.3, 0, 0.3) m, rpy (0, 0, 0) rad in base_footprint",
        "laserscan    angle_min -1.57, angle_max 1.57, angle_increment 0.209333 rad, "
        "scan_time 0.05 s",
    ]


def test_profile_json_holds_the_plan_profile_fields_and_their_source(
    robot: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["profile", "robot.urdf", "--ref", "HEAD", "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert set(printed) == PROFILE_FIELDS | {
        "sensor",
        "link",
        "kind",
        "file",
        "ref",
        "commit",
        "base_frame",
    }
    assert printed["samples"] == 32  # as the commit has it, not the working tree
    assert printed["commit"] == git(robot.parent, "rev-parse", "HEAD")
    assert (printed["ref"], printed["base_frame"], printed["sensor"]) == (
        "HEAD",
        "base_footprint",
        "front",
    )
    assert printed["mount"] == {"xyz": [0.3, 0.0, 0.30000000000000004], "rpy": [0.0, 0.0, 0.0]}


def test_profile_expands_xacro_with_args_and_packages(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    (tmp_path / "pkg").mkdir()
    (tmp_path / "pkg" / "front.xacro").write_text(XACRO_LIDAR)
    (tmp_path / "robot.urdf.xacro").write_text(XACRO_ROBOT)
    monkeypatch.chdir(tmp_path)
    arguments = ["profile", "robot.urdf.xacro", "--package", "lidars=pkg", "--json"]
    assert main([*arguments, "--xacro-arg", "laser_enabled:=1"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert (printed["kind"], printed["samples"], printed["update_rate"]) == ("gpu_ray", 64, 10.0)
    assert printed["mount"]["rpy"][0] == pytest.approx(math.pi)
    # Without the arg, the laser stays off, and the error says which arg turns it on.
    assert main(arguments) == 2
    assert "laser_enabled (default '0')" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        (["--ref=--upload-pack=x"], "starts with '-', so git would read it as an option"),
        (["--ref", "no-such-branch"], "the ref 'no-such-branch' names no commit"),
        (["--sensor", "rear"], "robot.urdf has no laser sensor or link named 'rear'"),
    ],
)
def test_profile_errors_name_the_problem_and_exit_2(
    robot: Path, capsys: pytest.CaptureFixture[str], arguments: list[str], message: str
) -> None:
    assert main(["profile", "robot.urdf", *arguments]) == 2
    error = capsys.readouterr().err
    assert message in error
    assert "Traceback" not in error


@pytest.mark.parametrize("arguments", [["--xacro-arg", "laser_enabled=1"], ["--package", "lidars"]])
def test_profile_refuses_a_malformed_arg_or_package_as_a_usage_error(
    robot: Path, capsys: pytest.CaptureFixture[str], arguments: list[str]
) -> None:
    assert main(["profile", "robot.urdf", *arguments]) == 2
    assert "is not NAME" in capsys.readouterr().err


def test_plan_json_gives_each_scanner_the_same_profile_fields(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    pairs = tmp_path / "size.lasertest.yaml"
    pairs.write_text(SIZE_PAIR)
    assert main(["plan", str(pairs), "--json"]) == 0
    (pair,) = json.loads(capsys.readouterr().out)["pairs"]
    assert set(pair["baseline"]) == set(pair["candidate"]) == PROFILE_FIELDS
