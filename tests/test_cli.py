"""`lasertest plan` finds placements, `explain` shows their beams, `catalogue` lists the scanner
models, `doctor` checks the installation."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from pytest_lasertest import cli
from pytest_lasertest.cli import doctor, main
from pytest_lasertest.model.obstacles import Box
from pytest_lasertest.model.plan import Witness
from pytest_lasertest.model.route import nominal_path
from pytest_lasertest.model.verify import Placement, Scene, Verification
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.reports.explain import explain_scans, explain_text
from tests.conftest import SIZE_PAIR

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
    from pytest_lasertest.pairsfile.bundled import LIDARS_DIR

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
        doctor.Check(check.name, broken, check.fix) if check.name == "z3" else check
        for check in doctor.CHECKS
    )
    monkeypatch.setattr(doctor, "CHECKS", checks)
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
    margins = [float(m) for m in re.findall(r"margin (\d+\.\d) mm", out)]
    assert margins
    assert all(5.0 <= margin <= 20.0 for margin in margins)
    assert "the candidate misses it for " in out


def test_plan_of_a_broken_pairs_file_names_the_line_and_exits_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    pairs = tmp_path / "size.lasertest.yaml"
    pairs.write_text(SIZE_PAIR.replace("witnesses: 1", "witnesses: 0"))
    assert main(["plan", str(pairs)]) == 2
    assert "size.lasertest.yaml:8: settings.witnesses: 0 witnesses per direction" in (
        capsys.readouterr().err
    )


@pytest.fixture
def size_pairs(tmp_path: Path) -> Path:
    """The size pair (32 beams -> 16), one witness per direction."""
    pairs = tmp_path / "size.lasertest.yaml"
    pairs.write_text(SIZE_PAIR)
    return pairs


def explained(pairs: Path, pair: str, witness: str, capsys: pytest.CaptureFixture[str]) -> Any:
    assert main(["explain", str(pairs), pair, witness, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_explain_lists_the_detector_hits_and_no_misser_hits(
    size_pairs: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    detector, misser, later = explained(size_pairs, "size", "candidate-misses-0", capsys)["scans"]
    assert (detector["scanner"], detector["role"]) == ("baseline", "detector")
    assert (misser["scanner"], misser["role"]) == ("candidate", "misser")
    assert detector["hits"]
    assert misser["hits"] == []
    assert later["hits"] == []
    assert detector["time"] == misser["time"] <= later["time"]
    assert len(detector["hits"]) + len(detector["too_near"]) + detector["misses"] == 32
    assert misser["misses"] == 16
    assert misser["clearance"] >= 0.005
    assert later["clearance"] >= 0.005


def test_explain_prints_the_hits_as_runs_of_beams_and_says_the_misser_still_misses(
    size_pairs: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["explain", str(size_pairs), "size", "candidate-misses-0"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("size candidate-misses-0: box ")
    # The gate times the path by the baseline's obstacle-free run: move_base's first command,
    # at its first cycle, takes the robot off the start by 0.14 s.
    assert lines[2].startswith("  baseline (detector) at the anchor, t = 0.14 s, pose (")
    assert lines[2].endswith(": reads it")
    assert re.fullmatch(r"    beams? \d+(-\d+)? \(angles? [-.\d]+ rad\): [\d.]+ m", lines[3])
    assert lines[-2].startswith("  candidate (misser) last scan up to until, t = ")
    assert lines[-2].endswith(": still misses it")
    assert lines[-1].startswith("    16 of 16 beams miss; nearest beam clears it by ")


def test_explain_json_keeps_the_documented_keys(
    size_pairs: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    explanation = explained(size_pairs, "size", "baseline-misses-0", capsys)
    assert set(explanation) == {"pair", "witness", "obstacle", "scans"}
    assert (explanation["pair"], explanation["witness"]) == ("size", "baseline-misses-0")
    assert explanation["obstacle"]["shape"] in {"box", "cylinder"}
    assert [scan["scanner"] for scan in explanation["scans"]] == [
        "candidate",
        "baseline",
        "baseline",
    ]
    for scan in explanation["scans"]:
        assert set(scan) == {
            "scanner",
            "role",
            "time",
            "pose",
            "hits",
            "too_near",
            "misses",
            "clearance",
        }
        assert all(set(hit) == {"beam", "angle", "range"} for hit in scan["hits"])
    assert explanation["scans"][0]["clearance"] is None


def test_explain_of_an_unknown_pair_names_the_pairs_and_exits_2(
    size_pairs: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["explain", str(size_pairs), "sise", "candidate-misses-0"]) == 2
    captured = capsys.readouterr()
    assert captured.err == f"lasertest: no pair 'sise' in {size_pairs}; pairs: size\n"
    assert captured.out == ""


def test_explain_of_an_unknown_witness_names_the_witnesses_and_exits_2(
    size_pairs: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["explain", str(size_pairs), "size", "candidate-misses-1"]) == 2
    assert capsys.readouterr().err == (
        "lasertest: pair 'size' has no witness 'candidate-misses-1'; "
        "witnesses: candidate-misses-0, baseline-misses-0\n"
    )


NEAR_PAIR = SIZE_PAIR.replace("range: {max: 10.0}}", "range: {min: 0.5, max: 10.0}}", 1)


def test_beams_that_meet_the_obstacle_before_range_min_are_listed_as_too_near(
    tmp_path: Path,
) -> None:
    pairs = tmp_path / "near.lasertest.yaml"
    pairs.write_text(NEAR_PAIR)
    spec = load_pairs_file(pairs)
    (pair,) = spec.pairs
    robot, world = spec.robot, spec.world
    path = nominal_path(world.start, world.route, robot.nominal_speed, robot.nominal_turn_rate)
    scene = Scene(pair.baseline.profile, pair.candidate.profile, robot, path)
    box = Box(x=0.337 + 0.3, y=0.0, yaw=0.0, length=0.1, width=0.16, height=1.0)
    verification = Verification(0.0, 0.0, 0.0, 0.0, (), 0.0, late=False)
    witness = Witness(0, Placement(box, "baseline-misses", 0.0, 0.0), verification, (0, 0, 0))
    detector, misser, _ = explain_scans(scene, witness)
    assert detector.scanner == "candidate"
    assert [hit.beam for hit in detector.hits] == [7, 8]
    assert (misser.hits, misser.too_near, misser.misses) == ((), (14, 15, 16, 17), 28)
    text = explain_text("size", witness, (detector, misser))
    assert "    beams 7-8 (angles -0.157..0.157 rad): 0.25 m\n" in text
    assert "    nearer than range_min (-inf): beams 14-17\n" in text
