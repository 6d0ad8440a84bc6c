"""`lasertest catalogue` lists the scanner models; `lasertest doctor` checks the installation."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from pytest_lasertest import cli
from pytest_lasertest.cli import main

REQUIRED_MODELS = {
    "sick_lms111",
    "sick_tim571",
    "hokuyo_utm_30lx",
    "hokuyo_ust_10lx",
    "hokuyo_urg_04lx",
    "rplidar_a1",
    "rplidar_a2",
    "rplidar_a3",
    "robotis_lds_01",
    "ydlidar_x4",
}


def test_the_catalogue_lists_the_real_scanners_with_their_figures(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert cli.main(["catalogue"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].split()[:4] == ["model", "FOV", "deg", "beams"]
    rows = {line.split()[0]: line for line in lines[1:]}
    assert rows.keys() >= REQUIRED_MODELS
    assert rows["sick_lms111"].split()[1:6] == ["270", "541", "0.500", "0.5-20", "50"]


def test_the_catalogue_as_json_gives_every_number(capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["catalogue", "--json"]) == 0
    rows = {row["model"]: row for row in json.loads(capsys.readouterr().out)}
    assert len(rows) >= 10
    assert rows["robotis_lds_01"] == {
        "model": "robotis_lds_01",
        "name": "ROBOTIS LDS-01",
        "fov_deg": 359.0,
        "beams": 360,
        "step_deg": 1.0,
        "range_min_m": 0.12,
        "range_max_m": 3.5,
        "update_rate_hz": 5.0,
        "noise_stddev_m": None,
    }


def test_every_catalogue_file_names_its_source() -> None:
    from pytest_lasertest.spec.bundled import LIDARS_DIR

    for path in sorted(LIDARS_DIR.glob("*.yaml")):
        assert "# Source:" in path.read_text(), f"{path.name} does not name its datasheet"


def test_the_doctor_passes_on_this_installation(capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["doctor"]) == 0
    output = capsys.readouterr().out
    for check in ("python", "packages", "z3", "pybullet", "bundled robots", "pytest plugin"):
        assert f"ok    {check}: " in output
    assert output.rstrip().endswith("all checks passed")


def test_the_doctor_says_what_to_fix_when_a_check_fails(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    def broken() -> str:
        raise ImportError("libz3.so: cannot open shared object file")

    checks = tuple(
        cli.Check(check.name, broken, check.fix) if check.name == "z3" else check
        for check in cli.CHECKS
    )
    monkeypatch.setattr(cli, "CHECKS", checks)
    assert cli.main(["doctor"]) == 1
    output = capsys.readouterr().out
    assert "FAIL  z3: ImportError: libz3.so: cannot open shared object file" in output
    assert "      fix: pip install --force-reinstall z3-solver" in output
    assert output.rstrip().endswith("1 check(s) failed")


def test_the_console_script_runs_and_prints_no_pybullet_banner() -> None:
    result = subprocess.run(
        [sys.executable, "-m", "pytest_lasertest.cli", "doctor"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert "build time" not in result.stdout + result.stderr


SIZE_PAIR = """\
robot: husky
world:
  start: {x: 0.0, y: 0.0, yaw: 0.0}
  goal: {x: 6.0, y: 0.0}
  time_limit: 60.0
settings:
  min_obstacle_size: 0.0507
  witnesses: 1
pairs:
  size:
    baseline: {model: clearpath_lms1xx_gazebo, samples: 32, range: {max: 10.0}}
    candidate: {model: clearpath_lms1xx_gazebo, samples: 16, range: {max: 10.0}}
"""


def test_plan_json_keeps_the_documented_contract_and_is_the_same_every_run(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    pairs = tmp_path / "size.lasertest.yaml"
    pairs.write_text(SIZE_PAIR)
    assert main(["plan", str(pairs), "--json"]) == 0
    first = capsys.readouterr().out
    assert main(["plan", str(pairs), "--json"]) == 0
    assert capsys.readouterr().out == first
    (pair,) = json.loads(first)["pairs"]
    assert set(pair) == {
        "name",
        "status",
        "explanation",
        "baseline",
        "candidate",
        "start",
        "goal",
        "path",
        "witnesses",
    }
    assert pair["status"] == "sat"
    assert pair["path"] == [[0.0, 0.0], [6.0, 0.0]]
    assert pair["candidate"]["samples"] == 16
    assert set(pair["candidate"]) >= {"range_min", "range_max", "update_rate", "mount"}
    assert [w["id"] for w in pair["witnesses"]] == ["candidate-misses-0", "baseline-misses-0"]
    witness = pair["witnesses"][0]
    assert witness["detected_by"] == "baseline"
    assert witness["margin"] >= 0.005
    assert witness["obstacle"]["shape"] in {"box", "cylinder"}
    assert len(witness["pose"]) == 3


def test_plan_prints_each_witness_with_its_margin(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    pairs = tmp_path / "size.lasertest.yaml"
    pairs.write_text(SIZE_PAIR)
    assert main(["plan", str(pairs)]) == 0
    out = capsys.readouterr().out
    assert "candidate-misses-0: " in out
    assert "read by the baseline" in out
    assert "margin 20.0 mm" in out


def test_plan_of_a_broken_pairs_file_names_the_line_and_exits_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    pairs = tmp_path / "size.lasertest.yaml"
    pairs.write_text(SIZE_PAIR.replace("witnesses: 1", "witnesses: 0"))
    assert main(["plan", str(pairs)]) == 2
    assert "size.lasertest.yaml:8: settings.witnesses: 0 witnesses per direction" in (
        capsys.readouterr().err
    )
