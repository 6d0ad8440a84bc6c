"""`lasertest plan` finds placements (timing the path with the pairs file's controller), `explain`
shows their beams, `catalogue` lists the scanner models."""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path
from typing import Any

import pytest

from pytest_lasertest import cli
from pytest_lasertest.cli import main
from tests.helpers.texts import SIZE_PAIR

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
    assert rows["hokuyo_ust_10lx"].split()[7:11] == ["nan", "end", "+3.1", "ms"]


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
        # hls_lfcd_lds_driver: 0.0 for no return, stamped once the whole turn is read.
        "no_return": "zero",
        "stamp": "end",
    }


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
    # The gate times the path by the baseline's obstacle-free run: Nav2 (the default) takes
    # the robot off the start by 1.16 s (its first plan, MPPI from a sequence of zeros, the
    # smoother's ramp).
    assert lines[2].startswith("  baseline (detector) at the anchor, t = 1.16 s, pose (")
    assert lines[2].endswith(": reads it")
    assert re.fullmatch(r"    beams? \d+(-\d+)? \(angles? [-.\d]+ rad\): [\d.]+ m", lines[3])
    assert lines[-2].startswith("  candidate (misser) last scan up to until, t = ")
    assert lines[-2].endswith(": still misses it")
    assert lines[-1].startswith("    16 of 16 beams miss; nearest beam clears it by ")


def test_explain_json_keeps_the_documented_keys(
    size_pairs: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    explanation = explained(size_pairs, "size", "baseline-misses-0", capsys)
    assert set(explanation) == {"pair", "witness", "obstacle", "margins", "scans"}
    assert set(explanation["margins"]) == {
        "detection",
        "concealment",
        "clearance",
        "obstruction",
        "too_near",
        "walls",
    }
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
    assert captured.err == (
        f"lasertest: no pair 'sise' in {size_pairs}\n  fix: give one of its pairs: size\n"
    )
    assert captured.out == ""


def test_explain_of_an_unknown_witness_names_the_witnesses_and_exits_2(
    size_pairs: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["explain", str(size_pairs), "size", "candidate-misses-1"]) == 2
    assert capsys.readouterr().err == (
        "lasertest: pair 'size' has no witness 'candidate-misses-1'\n"
        "  fix: give one of the witnesses `lasertest plan` prints for it (candidate-misses-0, "
        "baseline-misses-0), or avoid-0 for its placement both scanners read\n"
    )


def test_lasertest_plan_times_the_path_with_the_pairs_file_s_controller(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # A factory that leaves a mark, then drives as the default does.
    (tmp_path / "marking_controller.py").write_text(
        "from pathlib import Path\n"
        "from pytest_lasertest.nav.reactive import ReactiveController\n\n\n"
        "def make(robot, route):\n"
        "    with (Path(__file__).parent / 'marks').open('a') as marks:\n"
        "        marks.write('made\\n')\n"
        "    return ReactiveController(robot, route)\n"
    )
    pairs = tmp_path / "gate.lasertest.yaml"
    pairs.write_text(SIZE_PAIR.replace("pairs:", "controller: marking_controller:make\npairs:"))
    try:
        assert main(["plan", str(pairs)]) == 0
    finally:
        sys.modules.pop("marking_controller", None)
    assert "size" in capsys.readouterr().out
    assert (tmp_path / "marks").read_text() == "made\n"  # the baseline's obstacle-free run


# Placements both scanners read, which the robot must act on: the items PAIR[avoid-K].

# The size pair with a candidate whose range_min (0.9 m) is the larger: near, it reads -inf.
NEAR_PAIR = SIZE_PAIR.replace(
    "samples: 16, range: {max: 10.0}}", "samples: 16, range: {min: 0.9, max: 10.0}}"
)
# A controller that drives as the default reactive one does, and stops for good once any beam
# reads anything: it passes the obstacle-free world and fails past every placement.
TIMID_CONTROLLER = """\
import numpy as np

from pytest_lasertest.nav.reactive import ReactiveController


class Timid:
    def __init__(self, robot, route):
        self.inner = ReactiveController(robot, route)
        self.frozen = False

    def observe(self, scan, odometry, time):
        self.frozen = self.frozen or bool(np.isfinite(scan.ranges).any())
        return (0.0, 0.0) if self.frozen else self.inner.observe(scan, odometry, time)


def make(robot, route):
    return Timid(robot, route)
"""


def test_explain_of_an_avoid_witness_says_what_the_robot_must_do_and_what_both_scanners_read(
    size_pairs: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["explain", str(size_pairs), "size", "avoid-0"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("size avoid-0: cylinder of radius ")
    assert lines[1].startswith(
        "  a placement both scanners read, which the robot must act on: it reaches "
    )
    assert lines[1].endswith(
        " mm into what the robot sweeps along its path, so the robot must steer round it"
    )
    assert re.fullmatch(r"  anchor t = [\d.]+ s: both read it there, .*", lines[2])
    assert re.fullmatch(
        r"  margins detection [\d.]+ mm, clearance [\d.]+ mm, obstruction [\d.]+ mm", lines[3]
    )
    baseline = lines.index(next(line for line in lines if line.startswith("  baseline ")))
    candidate = lines.index(next(line for line in lines if line.startswith("  candidate ")))
    for heading in (lines[baseline], lines[candidate]):
        assert " at the anchor, t = " in heading
        assert heading.endswith(": reads it")
    assert re.fullmatch(
        r"    beams? \d+(-\d+)? \(angles? [-.\d]+ rad\): [\d.]+ m", lines[baseline + 1]
    )
    assert lines[candidate - 1].startswith("    31 of 32 beams miss")
    assert lines[-1].startswith("    15 of 16 beams miss")


def test_explain_json_of_an_avoid_witness_gives_both_scanners_hits_and_its_margins(
    size_pairs: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    explanation = explained(size_pairs, "size", "avoid-0", capsys)
    assert explanation["witness"] == "avoid-0"
    baseline, candidate = explanation["scans"]
    assert (baseline["scanner"], candidate["scanner"]) == ("baseline", "candidate")
    assert baseline["time"] == candidate["time"]
    assert baseline["hits"]
    assert candidate["hits"]
    assert baseline["clearance"] is None
    margins = explanation["margins"]
    assert margins["concealment"] == "inf"  # no scanner misses it
    assert margins["detection"] >= 0.005
    assert margins["obstruction"] >= 0.005


def test_explain_of_an_avoid_witness_read_too_near_lists_the_candidate_s_minus_inf_beams(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    pairs = tmp_path / "near.lasertest.yaml"
    pairs.write_text(NEAR_PAIR)
    assert main(["explain", str(pairs), "size", "avoid-0"]) == 0
    out = capsys.readouterr().out
    assert "the candidate reads it nearer than its range_min (-inf, which a costmap drops)" in out
    assert re.search(r", read too near [\d.]+ mm\n", out)
    assert re.search(
        r"\n  too near   at t = [\d.]+ s, robot at \(.*\): candidate beams [\d, ]+ read it nearer "
        r"than range_min 0\.9 m \(-inf\), the baseline in range$",
        out,
    )


def test_explain_of_an_avoid_witness_beyond_the_pair_s_items_names_them_and_exits_2(
    size_pairs: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["explain", str(size_pairs), "size", "avoid-1"]) == 2
    assert capsys.readouterr().err == (
        "lasertest: pair 'size' has no witness 'avoid-1': its placement both scanners read is "
        "avoid-0, as many as settings.witnesses asks\n"
        "  fix: give avoid-0, or a witness `lasertest plan` prints for it\n"
    )


def test_explain_of_an_avoid_witness_the_baseline_fails_says_its_item_skips_and_exits_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "timid_controller.py").write_text(TIMID_CONTROLLER)
    pairs = tmp_path / "timid.lasertest.yaml"
    pairs.write_text(SIZE_PAIR.replace("pairs:", "controller: timid_controller:make\npairs:"))
    try:
        assert main(["explain", str(pairs), "size", "avoid-0", "--seed", "7"]) == 2
    finally:
        sys.modules.pop("timid_controller", None)
    assert capsys.readouterr().err == (
        "lasertest: pair 'size' has no witness 'avoid-0': with seed 7 the baseline robot passes "
        "0 of its placements both scanners read, and its item size[avoid-0] is skipped\n"
        "  fix: give a witness `lasertest plan` prints, or give the seed of the run (its "
        "--laser-seed) with --seed\n"
    )
