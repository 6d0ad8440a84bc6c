"""examples/ci: the GitHub Actions workflow, and the gate it runs on a robot description. An
unrelated edit to the description collects no items and passes; a laser edit is judged."""

from __future__ import annotations

import json
import shlex
import shutil
from pathlib import Path
from typing import Any

import pytest
import yaml

from pytest_lasertest.cli import main
from tests.helpers import EXAMPLES
from tests.helpers.git import commit_everything
from tests.helpers.runs import outcomes

WORKFLOW = EXAMPLES / "ci" / "lasertest.yml"


def workflow() -> dict[Any, Any]:
    loaded: dict[Any, Any] = yaml.safe_load(WORKFLOW.read_text())
    return loaded


def gate_command(pairs: str) -> list[str]:
    """The workflow's pytest command, as its shell would run it, on `pairs` (minus `pytest`)."""
    (job,) = workflow()["jobs"].values()
    (step,) = [step for step in job["steps"] if step.get("name") == "Run the gate"]
    command = (
        step["run"]
        .replace('"$PAIRS"', pairs)
        .replace("${{ github.event.pull_request.number }}", "7")
        .replace('"$GITHUB_STEP_SUMMARY"', "step-summary.md")
    )
    words = shlex.split(command)
    assert words[0] == "pytest"
    return words[1:]


def test_the_workflow_runs_on_pull_requests_that_touch_a_description() -> None:
    # PyYAML reads the key `on` as True.
    paths = workflow()[True]["pull_request"]["paths"]
    assert {"**/*.urdf*", "**/*.xacro", "**/*.sdf"} <= set(paths)


def test_the_workflow_fetches_the_history_and_keeps_the_artifacts_and_junit_xml() -> None:
    (job,) = workflow()["jobs"].values()
    checkout, *_ = job["steps"]
    assert checkout["with"]["fetch-depth"] == 0
    (upload,) = [step for step in job["steps"] if "upload-artifact" in step.get("uses", "")]
    assert upload["if"] == "always()"
    command = gate_command("pairs.yaml")
    (artifacts,) = [word for word in command if word.startswith("--laser-artifacts=")]
    (junit,) = [word for word in command if word.startswith("--junitxml=")]
    assert upload["with"]["path"].rstrip("/") == artifacts.partition("=")[2]
    assert junit.partition("=")[2].startswith(artifacts.partition("=")[2] + "/")


def test_the_workflow_keeps_the_failures_found_and_sums_up_on_the_job_summary() -> None:
    (job,) = workflow()["jobs"].values()
    (cache,) = [step for step in job["steps"] if "actions/cache" in step.get("uses", "")]
    # Before the gate runs, so that it replays what an earlier run shrank.
    gate = [step.get("name") for step in job["steps"]].index("Run the gate")
    assert job["steps"].index(cache) < gate
    assert cache["with"]["path"] == ".hypothesis"
    assert cache["with"]["key"].endswith("${{ github.run_id }}")
    assert "lasertest-hypothesis-" in cache["with"]["restore-keys"].split()
    assert "--laser-summary=step-summary.md" in gate_command("pairs.yaml")


@pytest.fixture
def checkout(pytester: pytest.Pytester) -> Path:
    """A repository whose last commit holds examples/ci, as a pull request's checkout would."""
    shutil.copytree(EXAMPLES / "ci", pytester.path / "ci")
    commit_everything(pytester.path)
    return pytester.path / "ci"


def test_an_edit_that_changes_no_laser_field_collects_no_items_and_passes(
    pytester: pytest.Pytester, checkout: Path
) -> None:
    robot = checkout / "robot" / "robot.urdf.xacro"
    # A new link, joined to the robot (a link no joint joins is a second root, which urdfdom
    # refuses), that changes nothing the laser reads.
    camera = (
        "  <link name='camera'/>\n  <joint name='camera_joint' type='fixed'>"
        "<parent link='base_link'/><child link='camera'/></joint>\n</robot>"
    )
    robot.write_text(robot.read_text().replace("</robot>", camera))
    result = pytester.runpytest_subprocess(*gate_command("ci/gate.lasertest.yaml"))
    assert result.ret == pytest.ExitCode.OK
    result.stdout.fnmatch_lines(["ci/gate.lasertest.yaml::front_laser: no sensing change, *"])
    assert "passed" not in result.parseoutcomes()


def test_a_laser_edit_is_judged_and_leaves_junit_xml_and_evidence(
    pytester: pytest.Pytester, checkout: Path
) -> None:
    robot = checkout / "robot" / "robot.urdf.xacro"
    robot.write_text(robot.read_text().replace("<samples>720</samples>", "<samples>360</samples>"))
    result = pytester.runpytest_subprocess(
        *gate_command("ci/gate.lasertest.yaml"), "-m", "not placement"
    )
    # Half the beams scan less: a loss of coverage, in plain sight, that fails no run by default
    # (the robot may still drive as safely: the placement items judge that).
    assert result.ret == pytest.ExitCode.OK
    counts = outcomes(result)
    counts.pop("deselected", None)  # not counted where xdist runs it (-n auto)
    assert counts == {"passed": 1, "coverage-loss": 1}
    result.stdout.fnmatch_lines(
        ["COVERAGE-LOSS  ci/gate.lasertest.yaml::front_laser[[]coverage[]]: the candidate scans *"]
    )
    artifacts = pytester.path / "lasertest-artifacts"
    assert "front_laser[coverage]" in (artifacts / "junit.xml").read_text()
    assert (artifacts / "ci" / "gate.lasertest.yaml" / "front_laser_coverage.json").is_file()


def test_halving_the_beams_on_the_8_m_route_decides_both_directions(
    checkout: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    # On this route every direction of 720 against 360 beams was once undecided.
    robot = checkout / "robot" / "robot.urdf.xacro"
    robot.write_text(robot.read_text().replace("<samples>720</samples>", "<samples>360</samples>"))
    monkeypatch.chdir(checkout)
    assert main(["plan", "gate.lasertest.yaml", "--json"]) == 0
    (pair,) = json.loads(capsys.readouterr().out)["pairs"]
    assert pair["status"] == "sat"
    assert {witness["direction"] for witness in pair["witnesses"]} == {"candidate-misses"}
    # The other direction is proven: the 720-beam scanner misses nothing the 360-beam one reads.
    assert "no obstacle discriminates" in pair["explanation"]
    assert "could not decide" not in pair["explanation"]
