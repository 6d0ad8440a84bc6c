"""Hostile artifacts directories and runs started elsewhere: a failing item's report survives any
artifact the operating system refuses (each such file gets one line beside it, with the fix),
`--laser-artifacts` that can never work stops the run at startup, long and odd names still get
their files, and the replay and rerun commands work from where pytest was started."""

from __future__ import annotations

import dataclasses
import errno
import importlib
import json
import math
import os
import shlex
from pathlib import Path

import pytest
import yaml

from pytest_lasertest.artifacts.files import NAME_LIMIT, artifact_path, write_best_effort
from pytest_lasertest.artifacts.repro import write_repro
from pytest_lasertest.model.verify import Placement, Scene, Verification, verify
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.pairsfile.placements import PinnedPlacement
from tests.helpers import EXAMPLES
from tests.helpers.model import RECORDED
from tests.helpers.runs import NO_PLACEMENTS
from tests.helpers.texts import SIZE_PAIR

COVERAGE_JSON = "out/gate.lasertest.yaml/to_lms111_coverage.json"
# The paper's pole that the 16-beam robot fails at: a placement item with all four artifacts.
PLACEMENT = ("-k", "size and candidate-misses-2", "--laser-seed=2", "--laser-profile=ci")
ROOT = os.geteuid() == 0
AS_ROOT = "root writes to any directory whatever its mode"


def command(result: pytest.RunResult, label: str) -> list[str]:
    """The arguments of the command the report prints after `label` (`replay` or `rerun`),
    as a shell would split them, without `pytest` itself."""
    line = next(text for text in result.stdout.lines if text.startswith(f"  {label:<10} "))
    words = shlex.split(line.removeprefix(f"  {label:<10} ").partition("  (")[0])
    assert words[0] == "pytest"
    return words[1:]


def assert_no_traceback(result: pytest.RunResult) -> None:
    output = result.stdout.str() + result.stderr.str()
    assert "Traceback" not in output
    assert "pytest_lasertest/" not in output


def test_a_folder_named_like_an_artifact_is_reported_beside_the_failure_not_instead_of_it(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    (pytester.path / COVERAGE_JSON).mkdir(parents=True)
    result = pytester.runpytest("--laser-artifacts=out", *NO_PLACEMENTS)
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(
        [
            "the candidate scans less than the baseline: 2 losses of coverage",
            "  replay     pytest 'gate.lasertest.yaml::to_lms111[[]coverage[]]' *",
            f"  unwritten  {COVERAGE_JSON}: Is a directory [[]EISDIR[]]; fix: a folder has this "
            "file's name: remove or rename it",
        ]
    )
    assert_no_traceback(result)


def test_a_file_where_the_pairs_file_s_folder_goes_is_named_in_the_fix(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    (pytester.path / "out").mkdir()
    (pytester.path / "out/gate.lasertest.yaml").write_text("a note, not a folder")
    # Named, so that pytest does not collect the note as a pairs file.
    result = pytester.runpytest("gate.lasertest.yaml", "--laser-artifacts=out", *NO_PLACEMENTS)
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(
        [
            "the candidate scans less than the baseline: 2 losses of coverage",
            f"  unwritten  {COVERAGE_JSON}: File exists [[]EEXIST[]]; fix: "
            "out/gate.lasertest.yaml is a file where a folder must go: remove or rename it",
        ]
    )
    assert_no_traceback(result)


@pytest.mark.skipif(ROOT, reason=AS_ROOT)
def test_a_folder_made_read_only_after_startup_is_reported_beside_the_failure(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    folder = pytester.path / "out/gate.lasertest.yaml"
    folder.mkdir(parents=True)
    folder.chmod(0o555)
    try:
        result = pytester.runpytest("--laser-artifacts=out", *NO_PLACEMENTS)
    finally:
        folder.chmod(0o755)
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(
        [
            f"  unwritten  {COVERAGE_JSON}: Permission denied [[]EACCES[]]; fix: let this user "
            "write to out/gate.lasertest.yaml, or give --laser-artifacts another directory"
        ]
    )
    assert_no_traceback(result)


@pytest.mark.skipif(ROOT, reason=AS_ROOT)
def test_an_artifacts_directory_this_user_cannot_write_stops_the_run_at_startup(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    locked = pytester.mkdir("locked")
    locked.chmod(0o555)
    try:
        result = pytester.runpytest("--laser-artifacts=locked/out", *NO_PLACEMENTS)
    finally:
        locked.chmod(0o755)
    assert result.ret == pytest.ExitCode.USAGE_ERROR
    result.stderr.fnmatch_lines(
        ["ERROR: --laser-artifacts='locked/out': this user cannot write to */locked: give a *"]
    )


@pytest.mark.parametrize(
    ("option", "problem"),
    [
        ("notes.txt/out", "*/notes.txt is a file, so no directory can be made below it"),
        ("gone/out", "*/gone is a link to nowhere, which does not exist"),
    ],
)
def test_an_artifacts_directory_below_a_file_or_a_dangling_link_stops_the_run_at_startup(
    pytester: pytest.Pytester, pairs_file: Path, option: str, problem: str
) -> None:
    (pytester.path / "notes.txt").write_text("")
    (pytester.path / "gone").symlink_to("nowhere")
    result = pytester.runpytest(f"--laser-artifacts={option}", *NO_PLACEMENTS)
    assert result.ret == pytest.ExitCode.USAGE_ERROR
    result.stderr.fnmatch_lines(
        [
            f"ERROR: --laser-artifacts={option!r}: {problem}: give a directory this user can "
            "write to (it is created if missing)"
        ]
    )
    assert_no_traceback(result)


def test_a_pipe_given_as_laser_pairs_is_refused_at_startup_rather_than_read_for_ever(
    pytester: pytest.Pytester,
) -> None:
    os.mkfifo(pytester.path / "gate.yaml")
    result = pytester.runpytest("--laser-pairs=gate.yaml")
    assert result.ret == pytest.ExitCode.USAGE_ERROR
    result.stderr.fnmatch_lines(
        ["ERROR: --laser-pairs: 'gate.yaml' is not a regular file (a pipe, socket or device)*"]
    )


def test_a_disk_that_fills_up_loses_only_the_repro_and_the_report_says_so(
    pytester: pytest.Pytester, paper: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # As the run will import it: an in-process run drops the modules it imported, and the
    # package keeps pointing at the dropped one.
    repro = importlib.import_module("pytest_lasertest.artifacts.repro")

    def full(path: Path, text: str) -> Path:
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(repro, "write_text", full)
    result = pytester.runpytest(*PLACEMENT, "--laser-artifacts=out")
    result.assert_outcomes(failed=1)
    stem = "out/paper.lasertest.yaml/size_candidate-misses-2"
    result.stdout.fnmatch_lines(
        [
            "the candidate fails (*) near witness candidate-misses-2: *",
            "  replay     pytest 'paper.lasertest.yaml::size[[]candidate-misses-2[]]' *",
            f"  artifact   {stem}.png",
            f"  artifact   {stem}.world",
            f"  artifact   {stem}.json",
            f"  artifact   {stem}",
            f"  unwritten  {stem}.lasertest.yaml: No space left on device [[]ENOSPC[]]; fix: free "
            "space on that disk, or give --laser-artifacts a directory on another one",
        ]
    )
    assert sorted(path.name for path in (pytester.path / stem).parent.iterdir()) == [
        "size_candidate-misses-2",  # the rosbag2's directory
        "size_candidate-misses-2.json",
        "size_candidate-misses-2.png",
        "size_candidate-misses-2.world",
    ]
    assert_no_traceback(result)


def test_a_hypothesis_database_that_cannot_be_written_is_not_promised_to_replay_the_case(
    pytester: pytest.Pytester, paper: Path
) -> None:
    # Hypothesis drops what it cannot save without a word.
    (pytester.path / ".hypothesis").write_text("")
    result = pytester.runpytest(*PLACEMENT)
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(
        [
            "  replay     pytest 'paper.lasertest.yaml::size[[]candidate-misses-2[]]' * (searches "
            "afresh: the example database cannot keep this case, as */.hypothesis is a file, so "
            "no directory can be made below it)"
        ]
    )
    result.stdout.no_fnmatch_line("*replays this case first*")


def test_a_300_character_pair_name_still_gets_its_files_each_told_apart(
    pytester: pytest.Pytester,
) -> None:
    # 7 s is within the check on the route's length, and too short for either robot to get there.
    text = SIZE_PAIR.replace("time_limit: 60.0", "time_limit: 7.0")
    first, second = "p" * 300, "p" * 299 + "q"
    sides = (
        "{baseline: {model: clearpath_lms1xx_gazebo, samples: 32}, "
        "candidate: {model: clearpath_lms1xx_gazebo, samples: 16}}"
    )
    pairs = "".join(f"  {name}: {sides}\n" for name in (first, second))
    pytester.makefile(".lasertest.yaml", gate=text.split("  size:")[0] + pairs)
    # Both robots fail: the candidate policy fails it.
    result = pytester.runpytest(
        "-m", "control", "--laser-artifacts=out", "--laser-policy=candidate"
    )
    result.assert_outcomes(failed=2)
    written = sorted((pytester.path / "out/gate.lasertest.yaml").iterdir())
    assert len(written) == 8  # a picture, a world, the numbers and a rosbag2 for each
    assert all(len(path.name) <= NAME_LIMIT + len(".world") for path in written)
    items = {json.loads(path.read_text())["item"] for path in written if path.suffix == ".json"}
    assert items == {f"gate.lasertest.yaml::{name}[no-obstacle]" for name in (first, second)}
    # The reports only: CI=true prints each failure's message untruncated in the summary too.
    reports = result.stdout.str().split("short test summary info")[0].splitlines()
    shown = [line for line in reports if line.startswith("  artifact   out/")]
    assert sorted(line.split()[1] for line in shown) == [
        str(path.relative_to(pytester.path)) for path in written
    ]
    assert_no_traceback(result)


def test_a_pairs_file_in_a_folder_with_spaces_unicode_and_dollars_gets_its_picture_and_replays(
    pytester: pytest.Pytester,
) -> None:
    folder = pytester.mkdir("$\\frac$ größe")
    text = SIZE_PAIR.replace("time_limit: 60.0", "time_limit: 7.0")
    (folder / "gate.lasertest.yaml").write_text(text)
    # Both robots fail: the candidate policy fails it.
    result = pytester.runpytest(
        "-m", "control", "--laser-artifacts=out", "--laser-policy=candidate"
    )
    result.assert_outcomes(failed=1)
    (picture,) = (pytester.path / "out").rglob("*.png")
    assert picture.read_bytes().startswith(b"\x89PNG\r\n\x1a\n")
    folders = picture.relative_to(pytester.path / "out").parts[:-1]
    assert all(folder.isascii() for folder in folders)
    assert not any(" " in folder or "$" in folder for folder in folders)
    result.stdout.fnmatch_lines([f"  artifact   {picture.relative_to(pytester.path)}"])
    assert_no_traceback(result)
    pytester.runpytest(*command(result, "replay")).assert_outcomes(failed=1)


@pytest.mark.parametrize(
    "nodeid",
    [
        "a b/gate.lasertest.yaml::size[coverage]",
        "größe/gate.lasertest.yaml::size[coverage]",
        "../../x/gate.lasertest.yaml::size[coverage]",
        "/abs/gate.lasertest.yaml::size[coverage]",
        f"{'d' * 250}/gate.lasertest.yaml::size[coverage]",
    ],
)
def test_artifact_paths_of_odd_ids_stay_inside_the_directory_in_short_safe_names(
    tmp_path: Path, nodeid: str
) -> None:
    path = artifact_path(tmp_path, nodeid, ".lasertest.yaml")
    parts = path.relative_to(tmp_path).parts
    assert path.resolve().is_relative_to(tmp_path.resolve())
    assert all(part not in ("", ".", "..") and part.isascii() and " " not in part for part in parts)
    assert all(len(part) <= NAME_LIMIT + len(".lasertest.yaml") for part in parts)
    assert parts[-1] == "size_coverage.lasertest.yaml"


def test_folders_whose_names_clean_to_the_same_text_stay_apart(tmp_path: Path) -> None:
    names = ["a b", "a_b", "a\tb", "a  b"]
    paths = {
        artifact_path(tmp_path, f"{name}/g.lasertest.yaml::p[coverage]", ".json") for name in names
    }
    assert len(paths) == len(names)


def test_the_rerun_line_works_from_a_subdirectory_of_the_rootdir(
    pytester: pytest.Pytester, pairs_file: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    pytester.makeini("[pytest]\n")
    monkeypatch.chdir(pytester.mkdir("sub"))
    result = pytester.runpytest("../gate.lasertest.yaml", *NO_PLACEMENTS, "--laser-seed=3")
    result.assert_outcomes(passed=1, failed=1)
    rerun = command(result, "replay")
    assert rerun[0] == "../gate.lasertest.yaml::to_lms111[coverage]"
    again = pytester.runpytest(*rerun)
    again.assert_outcomes(failed=1)
    again.stdout.fnmatch_lines(["FAILED ../gate.lasertest.yaml::to_lms111[[]coverage[]] - *"])


def test_the_rerun_line_works_for_a_pairs_file_given_by_an_absolute_path_from_elsewhere(
    pytester: pytest.Pytester, pairs_file: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(pytester.mkdir("elsewhere"))
    result = pytester.runpytest(str(pairs_file), *NO_PLACEMENTS)
    result.assert_outcomes(passed=1, failed=1)
    again = pytester.runpytest(*command(result, "replay"))
    again.assert_outcomes(failed=1)


def test_the_rerun_line_of_a_laser_pairs_file_of_another_name_collects_it_and_only_the_item(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    pairs_file.rename(pytester.path / "gate.yaml")
    result = pytester.runpytest("--laser-pairs=gate.yaml", *NO_PLACEMENTS)
    result.assert_outcomes(passed=1, failed=1)
    rerun = command(result, "replay")
    assert rerun[:2] == ["gate.yaml::to_lms111[coverage]", "--laser-pairs=gate.yaml"]
    pytester.runpytest(*rerun).assert_outcomes(failed=1)


def test_the_pinned_replay_and_the_rerun_work_from_a_subdirectory(
    pytester: pytest.Pytester, paper: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    pytester.makeini("[pytest]\n")
    monkeypatch.chdir(pytester.mkdir("sub"))
    result = pytester.runpytest("../paper.lasertest.yaml", *PLACEMENT, "--laser-artifacts=../out")
    result.assert_outcomes(failed=1)
    replay = command(result, "replay")
    repro = pytester.path / "out/paper.lasertest.yaml/size_candidate-misses-2.lasertest.yaml"
    assert replay == [str(repro.resolve())]
    pinned = pytester.runpytest(*replay)
    pinned.assert_outcomes(failed=1)
    pinned.stdout.fnmatch_lines(["the candidate fails at the pinned placement size[[]pinned-0[]]*"])
    rerun = pytester.runpytest(*command(result, "rerun"))
    rerun.assert_outcomes(failed=1)
    rerun.stdout.fnmatch_lines(["FAILED ../paper.lasertest.yaml::size[[]candidate-misses-2[]]*"])


def test_every_pair_of_the_examples_keeps_its_artifact_names_as_written(tmp_path: Path) -> None:
    for example in EXAMPLES.glob("*.lasertest.yaml"):
        for pair in yaml.safe_load(example.read_text())["pairs"]:
            nodeid = f"examples/{example.name}::{pair}[candidate-misses-2]"
            assert artifact_path(tmp_path, nodeid, ".png") == (
                tmp_path / "examples" / example.name / f"{pair}_candidate-misses-2.png"
            )


def test_the_numbers_file_is_standard_json_with_margins_that_do_not_apply_as_strings(
    pytester: pytest.Pytester, placement_pairs: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    placement = importlib.import_module("pytest_lasertest.plugin.items.placement")

    def rejecting(scene: Scene, witness: Placement) -> Verification:
        return dataclasses.replace(verify(scene, witness), concealment=-0.001)

    monkeypatch.setattr(placement, "verify", rejecting)
    result = pytester.runpytest("-k", "size and candidate", "--laser-artifacts=out")
    result.assert_outcomes(failed=1)
    text = (pytester.path / "out/gate.lasertest.yaml/size_candidate-misses-0.json").read_text()

    def refuse(constant: str) -> None:
        pytest.fail(f"{constant} is not JSON: jq and JavaScript refuse the file")

    evidence = json.loads(text, parse_constant=refuse)
    # Only a placement both scanners read is judged on being read too near.
    assert evidence["verification"]["too_near"] == "-inf"
    assert float(evidence["verification"]["too_near"]) == -math.inf


@pytest.mark.parametrize(
    ("edit", "problem"),
    [
        ("pairs: [", "the pairs file changed since it was read and is no longer a mapping"),
        ("candidate: {model: sick_lms111}", "the pair is gone from the file since it was read"),
    ],
)
def test_a_pairs_file_edited_during_the_run_leaves_the_repro_unwritten_not_a_traceback(
    tmp_path: Path, edit: str, problem: str
) -> None:
    path = tmp_path / "gate.lasertest.yaml"
    path.write_text(SIZE_PAIR)
    spec = load_pairs_file(path)
    (pair,) = spec.pairs
    text = SIZE_PAIR.split("  size:")[0] + "  size:\n    " + edit + "\n"
    path.write_text(edit if edit.startswith("pairs") else text)
    destination = tmp_path / "out" / "size.lasertest.yaml"
    pinned = PinnedPlacement(RECORDED, 1, "candidate-misses", pair.location)
    written = write_best_effort(
        ((destination, lambda: write_repro(destination, spec, pair, pinned, ())),)
    )
    assert written.written == ()
    (unwritten,) = written.unwritten
    assert problem in unwritten.reason
    assert unwritten.fix == "restore it, or run again"
    assert not destination.exists()
