"""The run's summaries: the placement items' table, the same under xdist as serially, and the
pairs whose scanners read alike, which collect to no items and get one line each."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from tests.helpers.git import git
from tests.helpers.runs import junit_cases, outcomes
from tests.helpers.texts import PAIRS, ROBOT

# The outcome of each item of the paper's size pair at seed 1, here, where its node ids (and so
# its items' seeds) are not those of examples/.
OUTCOMES = {
    # The 16-beam scanner scans less: noted, not failed (an expected failure in JUnit).
    "coverage": "xfail",
    "no-obstacle": "passed",
    "avoid-0": "passed",
    # A pole beside the route, which the 16-beam scanner reads with one beam: its robot is held
    # going round it (stuck by a millimetre of progress, under every draw); the 32-beam robot
    # passes. Under examples/, seeded by another node id, the item passes at seed 1.
    "avoid-1": "failure",
    # The baseline robot passes only two of the placements to steer round.
    "avoid-2": "skipped",
    **{f"baseline-misses-{index}": "passed" for index in range(2)},
    # Both robots fail at these: pre-existing, noted.
    "baseline-misses-2": "xfail",
    "candidate-misses-0": "passed",
    "candidate-misses-1": "xfail",
    # Found by perturbing the witness: the 16-beam robot collides with the moved box and the
    # 32-beam robot passes, under every further draw (the box moved within 1 cm).
    "candidate-misses-2": "failure",
}
# The pair's items in six runs, so that xdist spreads them, and the summary row of each run:
# witnesses, examples, rejected, failed, by oracle (collision, stuck, goal), regressions,
# marginal, pre-existing. Together the pair searched 8 witnesses and 127 examples.
ROWS = {
    ("coverage", "no-obstacle", "avoid-0"): (
        ("1", "16", "0", "(0%)", "0", "0", "0", "0", "0", "0", "0")
    ),
    ("avoid-1", "avoid-2"): ("1", "19", "0", "(0%)", "1", "0", "1", "1", "1", "0", "0"),
    ("candidate-misses-2",): ("1", "12", "0", "(0%)", "1", "1", "0", "1", "1", "1", "0"),
    ("candidate-misses-0", "candidate-misses-1"): (
        ("2", "32", "0", "(0%)", "0", "0", "0", "0", "0", "0", "1")
    ),
    ("baseline-misses-0", "baseline-misses-1"): (
        ("2", "32", "0", "(0%)", "0", "0", "0", "0", "0", "0", "0")
    ),
    ("baseline-misses-2",): ("1", "16", "0", "(0%)", "0", "0", "0", "0", "0", "0", "1"),
}


@pytest.mark.parametrize("items", ROWS, ids=[items[0] for items in ROWS])
def test_items_run_and_sum_up_the_same_under_xdist_as_serially(
    pytester: pytest.Pytester, paper: Path, items: tuple[str, ...]
) -> None:
    nodes = [f"{paper.name}::size[{item}]" for item in items]
    selection = (*nodes, "--laser-seed=1", "--laser-profile=ci")
    serial = pytester.runpytest(*selection, "--junitxml=serial.xml")
    # Each run starts from an empty example database, or the second would replay the first's
    # failures and try fewer examples.
    shutil.rmtree(pytester.path / ".hypothesis", ignore_errors=True)
    distributed = pytester.runpytest_subprocess(*selection, "--junitxml=xdist.xml", "-n", "2")
    cases = junit_cases(pytester.path / "serial.xml")
    assert cases == junit_cases(pytester.path / "xdist.xml")
    assert summary(serial.stdout.lines) == summary(distributed.stdout.lines)
    assert summary(serial.stdout.lines)[1].split() == [f"{paper.name}::size", *ROWS[items]]
    assert {name: case.outcome for name, case in cases.items()} == {
        f"{paper.name}::size[{item}]": OUTCOMES[item] for item in items
    }


def test_the_runs_above_hold_each_item_of_the_pair_once() -> None:
    assert sorted(item for items in ROWS for item in items) == sorted(OUTCOMES)


def summary(lines: list[str]) -> list[str]:
    """The lasertest summary table of a run's output."""
    start = next(index for index, line in enumerate(lines) if "lasertest: placements" in line)
    table = []
    for line in lines[start + 1 :]:
        if line.startswith(("=", "FAILED", "ERROR")):
            break
        table.append(line)
    return table


def test_a_pair_whose_scanners_read_alike_yields_no_items_and_one_summary_line(
    pytester: pytest.Pytester, repository: Path
) -> None:
    # An edit that changes nothing the laser reads: a comment and a new link.
    edited = ROBOT.replace(
        "</robot>",
        "  <!-- a camera, soon -->\n  <link name='camera'/>\n  <joint name='camera_joint' "
        "type='fixed'><parent link='base_link'/><child link='camera'/></joint>\n</robot>",
    )
    (repository / "robot.urdf").write_text(edited)
    result = pytester.runpytest("--laser-seed=1")
    assert result.ret == pytest.ExitCode.OK
    result.assert_outcomes()
    result.stdout.fnmatch_lines(
        [
            "*= lasertest: pairs whose scanners read alike =*",
            "gate.lasertest.yaml::swap: no sensing change, no items: baseline front in "
            "robot.urdf at HEAD (*) and candidate front in robot.urdf both read 32 beams *",
        ]
    )


def test_no_sensing_change_is_summed_up_alike_on_pytest_xdist_workers(
    pytester: pytest.Pytester, repository: Path
) -> None:
    result = pytester.runpytest_subprocess("-n", "2", "--laser-seed=1")
    assert result.ret == pytest.ExitCode.OK
    summary = [line for line in result.stdout.lines if "no sensing change" in line]
    assert summary == [
        "gate.lasertest.yaml::swap: no sensing change, no items: baseline front in robot.urdf "
        f"at HEAD ({git(repository, 'rev-parse', '--short=7', 'HEAD')}) and candidate front in "
        "robot.urdf both read 32 beams over [-1.570, 1.570] rad, range 0.10-10.00 m, 20 Hz, "
        "scan plane 0.300 m"
    ]


def test_a_changed_pair_beside_an_unchanged_one_runs_and_the_run_fails_as_usual(
    pytester: pytest.Pytester, repository: Path
) -> None:
    (repository / "gate.lasertest.yaml").write_text(
        PAIRS + "  narrower:\n    baseline: {urdf: robot.urdf}\n"
        "    candidate: {urdf: robot.urdf, max_angle: 1.0}\n"
    )
    result = pytester.runpytest("-k", "coverage", "--laser-seed=1", "--laser-policy=candidate")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["*narrower[[]coverage[]]*", "*swap: no sensing change*"])


def test_the_markdown_summary_is_appended_with_the_picture_of_each_failing_item(
    pytester: pytest.Pytester, paper: Path
) -> None:
    # As a GitHub job summary: a file the workflow's earlier steps may have written to.
    summary = pytester.path / "step-summary.md"
    summary.write_text("earlier step\n")
    run = ("-k", "size and baseline-misses-2", "--laser-seed=1", "--laser-examples=2")
    policy = "--laser-policy=candidate"  # the failure is pre-existing: fail it
    result = pytester.runpytest(
        *run, policy, "--laser-artifacts=out", "--laser-summary=step-summary.md"
    )
    result.assert_outcomes(failed=1)
    lines = summary.read_text().splitlines()
    assert lines[:3] == ["earlier step", "### lasertest: placements searched, per pair", ""]
    assert lines[5].startswith("| paper.lasertest.yaml::size | 1 | ")
    picture = "out/paper.lasertest.yaml/size_baseline-misses-2.png"
    assert lines[-1] == f"- `paper.lasertest.yaml::size[baseline-misses-2]`: picture `{picture}`"
    assert (pytester.path / picture).is_file()


def test_a_noted_failure_is_listed_in_the_job_summary_and_its_picture_is_drawn(
    pytester: pytest.Pytester, paper: Path
) -> None:
    summary = pytester.path / "step-summary.md"
    run = ("-k", "size and baseline-misses-2", "--laser-seed=1", "--laser-examples=2")
    result = pytester.runpytest(*run, "--laser-artifacts=out", "--laser-summary=step-summary.md")
    assert result.ret == pytest.ExitCode.OK
    assert outcomes(result) == {"deselected": 32, "pre-existing": 1}
    result.stdout.fnmatch_lines(
        [
            "*= lasertest: failures that do not fail the run (--laser-policy=candidate fails *",
            "PRE-EXISTING  paper.lasertest.yaml::size[[]baseline-misses-2[]]: the candidate "
            "fails * near witness baseline-misses-2: pre-existing: the baseline fails here too",
        ]
    )
    assert summary.read_text().splitlines()[-1] == (
        "- pre-existing: `paper.lasertest.yaml::size[baseline-misses-2]`: the candidate fails "
        "(stuck and goal) near witness baseline-misses-2: pre-existing: the baseline fails here too"
    )
    # Its artifacts are written as a failure's are.
    assert (pytester.path / "out/paper.lasertest.yaml/size_baseline-misses-2.png").is_file()
