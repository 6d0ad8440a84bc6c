"""Hostile input to the `lasertest` command: every verb given a missing file, a directory, a pipe,
an unreadable file or one that is neither YAML nor XML, and bad option values, says what is
wrong and what to give instead on stderr, exits with status 2 and shows no traceback; with
--json, stdout holds the same error as a JSON object."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from pytest_lasertest.cli import main
from tests.helpers.texts import ROBOT, SIZE_PAIR

# Each file-reading verb: the words before its file, the words after it, what the file must be.
VERBS = {
    "plan": (["plan"], [], "a pairs file"),
    "explain": (["explain"], ["size", "candidate-misses-0"], "a pairs file"),
    "profile": (["profile"], [], "a URDF, xacro or SDF file"),
}
ERROR_KEYS = {"kind", "message", "file", "line", "field", "problem", "fix"}


@pytest.fixture
def here(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A working directory holding a valid pairs file and a robot description."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "gate.lasertest.yaml").write_text(SIZE_PAIR)
    (tmp_path / "robot.urdf").write_text(ROBOT)
    return tmp_path


def run(verb: str, file: str, *extra: str) -> list[str]:
    before, after, _ = VERBS[verb]
    return [*before, file, *after, *extra]


def assert_clean_error(code: int, capsys: pytest.CaptureFixture[str], problem: str) -> str:
    """Exit status 2, the problem on stderr with a fix below it, nothing on stdout, no
    traceback; returns stderr."""
    captured = capsys.readouterr()
    assert code == 2
    assert captured.out == ""
    first, _, rest = captured.err.partition("\n")
    assert first.startswith("lasertest: ")
    assert problem in first
    assert rest.startswith("  fix: ")
    assert "Traceback" not in captured.err
    return captured.err


@pytest.mark.parametrize("verb", VERBS)
def test_a_missing_file_says_it_does_not_exist(
    here: Path, verb: str, capsys: pytest.CaptureFixture[str]
) -> None:
    code = main(run(verb, "gone.yaml"))
    assert_clean_error(code, capsys, "'gone.yaml' does not exist")


@pytest.mark.parametrize("verb", VERBS)
def test_a_directory_says_it_is_one_and_what_the_verb_takes_instead(
    here: Path, verb: str, capsys: pytest.CaptureFixture[str]
) -> None:
    code = main(run(verb, "."))
    what = VERBS[verb][2]
    error = assert_clean_error(code, capsys, f"'.' is a directory, not {what}")
    assert f"  fix: give {what}: lasertest {verb} " in error


@pytest.mark.parametrize("verb", VERBS)
def test_a_pipe_is_refused_rather_than_waited_on(here: Path, verb: str) -> None:
    os.mkfifo(here / "pipe.yaml")
    command = [sys.executable, "-m", "pytest_lasertest.cli", *run(verb, "pipe.yaml")]
    done = subprocess.run(command, capture_output=True, text=True, timeout=60, check=False)
    assert done.returncode == 2
    assert done.stderr.startswith(
        "lasertest: 'pipe.yaml' is not a regular file (a pipe, socket or device)\n  fix: "
    )


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads any file whatever its mode")
@pytest.mark.parametrize("verb", VERBS)
def test_an_unreadable_file_says_so(
    here: Path, verb: str, capsys: pytest.CaptureFixture[str]
) -> None:
    locked = here / "locked.yaml"
    locked.write_text(SIZE_PAIR)
    locked.chmod(0)
    code = main(run(verb, "locked.yaml"))
    assert_clean_error(code, capsys, "'locked.yaml' cannot be read: Permission denied")


@pytest.mark.parametrize(
    ("verb", "content", "problem"),
    [
        ("plan", "just some words\n", "notes.txt:1: "),
        ("explain", "just some words\n", "notes.txt:1: "),
        ("profile", "just some words\n", "notes.txt:1: this is not well-formed XML"),
        ("plan", "\x00\xff\xfe binary", "notes.txt:1: the file is not UTF-8 text"),
        ("profile", "\x00\xff\xfe binary", "notes.txt:1: "),
    ],
)
def test_a_file_of_the_wrong_kind_names_its_line(
    here: Path, verb: str, content: str, problem: str, capsys: pytest.CaptureFixture[str]
) -> None:
    (here / "notes.txt").write_bytes(content.encode("latin-1"))
    code = main(run(verb, "notes.txt"))
    assert_clean_error(code, capsys, problem)


@pytest.mark.parametrize(
    ("arguments", "kind", "problem"),
    [
        (["plan", "gone.yaml"], "usage", "'gone.yaml' does not exist"),
        (["profile", "."], "usage", "'.' is a directory, not a URDF, xacro or SDF file"),
        (["plan", "robot.urdf"], "input", "expected a mapping"),
        (["explain", "gate.lasertest.yaml", "sise", "x"], "usage", "no pair 'sise'"),
        (["profile", "robot.urdf", "--sensor", "rear"], "input", "no laser sensor or link"),
        (["profile", "robot.urdf", "--ref=-x"], "git", "starts with '-'"),
        (["profile", "robot.urdf", "--xacro-arg", "x"], "usage", "'x' is not NAME:=VALUE"),
        (["plan"], "usage", "the following arguments are required: PAIRS.yaml"),
        (["catalogue", "--jsn"], "usage", "unrecognized arguments: --jsn"),
    ],
)
def test_with_json_every_error_is_a_json_object_on_stdout_as_well_as_text_on_stderr(
    here: Path,
    arguments: list[str],
    kind: str,
    problem: str,
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main([*arguments, "--json"]) == 2
    captured = capsys.readouterr()
    error = json.loads(captured.out)["error"]
    assert set(error) == ERROR_KEYS
    assert error["kind"] == kind
    assert problem in error["problem"]
    assert error["fix"]
    assert error["problem"] in captured.err
    assert "Traceback" not in captured.err


def test_a_json_error_in_a_file_gives_its_file_line_and_field(
    here: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (here / "gate.lasertest.yaml").write_text(SIZE_PAIR.replace("witnesses: 1", "witnesses: 0"))
    assert main(["plan", "gate.lasertest.yaml", "--json"]) == 2
    error = json.loads(capsys.readouterr().out)["error"]
    assert (error["file"], error["line"], error["field"]) == (
        "gate.lasertest.yaml",
        8,
        "settings.witnesses",
    )
    assert error["message"].startswith("gate.lasertest.yaml:8: settings.witnesses: ")


@pytest.mark.parametrize(
    ("package", "problem"),
    [
        ("lidars=absent", "'lidars=absent': 'absent' is missing; DIR is the directory"),
        ("lidars=robot.urdf", "'lidars=robot.urdf': 'robot.urdf' is a file; DIR is the directory"),
    ],
)
def test_a_package_that_is_no_directory_is_a_usage_error(
    here: Path, package: str, problem: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["profile", "robot.urdf", "--package", package]) == 2
    captured = capsys.readouterr()
    assert captured.err.startswith("usage: lasertest profile ")
    assert problem in captured.err
    assert captured.out == ""


def test_a_reader_that_stops_early_ends_the_command_quietly(here: Path) -> None:
    command = [sys.executable, "-m", "pytest_lasertest.cli", "catalogue", "--json"]
    with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE) as process:
        assert process.stdout is not None
        assert process.stderr is not None
        process.stdout.close()  # before the command has written a byte
        error = process.stderr.read().decode()
        code = process.wait(timeout=60)
    assert code == 1
    assert error == ""


@pytest.mark.parametrize("verb", ["plan", "explain"])
def test_a_controller_that_raises_names_its_line_and_is_a_json_error(
    here: Path, verb: str, capsys: pytest.CaptureFixture[str]
) -> None:
    (here / "kaput_controller.py").write_text(
        "def make(robot, route):\n    raise RuntimeError('kaput')\n"
    )
    pairs = SIZE_PAIR.replace("pairs:", "controller: kaput_controller:make\npairs:")
    (here / "gate.lasertest.yaml").write_text(pairs)
    try:
        code = main(run(verb, "gate.lasertest.yaml", "--json"))
    finally:
        sys.modules.pop("kaput_controller", None)
    assert code == 2
    captured = capsys.readouterr()
    error = json.loads(captured.out)["error"]
    assert (error["kind"], error["file"], error["line"]) == ("controller", "kaput_controller.py", 2)
    assert error["problem"] == (
        "the controller kaput_controller:make broke the obstacle-free drive that times pair "
        "'size': the factory raised RuntimeError: kaput (at kaput_controller.py:2 in make)"
    )
    assert captured.err.startswith(f"lasertest: {error['problem']}\n  fix: ")
    assert "Traceback" not in captured.err
