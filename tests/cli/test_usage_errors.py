"""A command line the `lasertest` command cannot parse (none at all, an unknown command, a missing
argument, a bad option value, a word no command takes) gets argparse's usage and error, then a
`fix:` line saying what to run, exit status 2 and no traceback; with --json the same fix."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from pytest_lasertest.cli import main

EXAMPLE = "lasertest plan robots/husky/gate.lasertest.yaml"


def refused(arguments: list[str], capsys: pytest.CaptureFixture[str]) -> list[str]:
    """stderr's lines for a command line argparse refuses, checked to be a clean usage error."""
    assert main(arguments) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert "Traceback" not in captured.err
    lines = captured.err.splitlines()
    assert lines[0].startswith("usage: lasertest")
    return lines


def test_bare_lasertest_ends_with_a_fix_line_naming_the_help_and_an_example(
    capsys: pytest.CaptureFixture[str],
) -> None:
    lines = refused([], capsys)
    assert lines[-2] == "lasertest: error: the following arguments are required: command"
    assert lines[-1] == (
        f"  fix: run `lasertest --help` for the commands, or e.g. `{EXAMPLE}` to find the "
        "placements that tell each pair apart"
    )


def test_the_installed_command_run_bare_ends_with_a_fix_line_and_exits_2() -> None:
    command = [sys.executable, "-m", "pytest_lasertest.cli"]
    done = subprocess.run(command, capture_output=True, text=True, timeout=60, check=False)
    assert done.returncode == 2
    assert done.stdout == ""
    assert done.stderr.splitlines()[-1].startswith("  fix: run `lasertest --help` for the ")


def test_a_misspelt_command_gets_the_command_it_resembles(
    capsys: pytest.CaptureFixture[str],
) -> None:
    lines = refused(["plna", "gate.lasertest.yaml"], capsys)
    assert "invalid choice: 'plna'" in lines[-2]
    assert lines[-1] == (
        "  fix: did you mean `lasertest plan`? give one of the commands plan, explain, profile, "
        "catalogue, schema, doctor; `lasertest --help` says what each does"
    )


def test_an_unknown_command_like_none_gets_the_list_of_commands(
    capsys: pytest.CaptureFixture[str],
) -> None:
    lines = refused(["frobnicate"], capsys)
    assert lines[-1] == (
        "  fix: give one of the commands plan, explain, profile, catalogue, schema, doctor; "
        "`lasertest --help` says what each does"
    )


@pytest.mark.parametrize(
    ("arguments", "error", "example"),
    [
        (
            ["explain", "gate.lasertest.yaml"],
            "lasertest explain: error: the following arguments are required: PAIR, WITNESS",
            "lasertest explain robots/husky/gate.lasertest.yaml size candidate-misses-0",
        ),
        (
            ["plan"],
            "lasertest plan: error: the following arguments are required: PAIRS.yaml",
            EXAMPLE,
        ),
        (
            ["explain", "gate.lasertest.yaml", "size", "avoid-0", "--seed", "minus one"],
            "lasertest explain: error: argument --seed: 'minus one' is not a seed: give a whole "
            "number from 0 to 4294967295, as the run's report header prints it "
            "(lasertest: --laser-seed=N ...)",
            "lasertest explain robots/husky/gate.lasertest.yaml size candidate-misses-0",
        ),
        (
            ["profile", "robot.urdf", "--xacro-arg", "laser_enabled"],
            "lasertest profile: error: argument --xacro-arg: 'laser_enabled' is not "
            "NAME:=VALUE, e.g. laser_enabled:=1",
            "lasertest profile robots/mybot/robot.urdf.xacro",
        ),
        (
            ["catalogue", "--jsn"],
            "lasertest catalogue: error: unrecognized arguments: --jsn",
            "lasertest catalogue --json",
        ),
    ],
)
def test_a_command_s_bad_arguments_end_with_its_usage_an_example_and_its_help(
    arguments: list[str], error: str, example: str, capsys: pytest.CaptureFixture[str]
) -> None:
    lines = refused(arguments, capsys)
    command = error.split(":")[0]
    assert lines[0].startswith(f"usage: {command} ")
    assert lines[-2] == error
    assert lines[-1] == (
        f"  fix: run e.g. `{example}`; `{command} --help` says what each argument takes"
    )


@pytest.mark.parametrize("arguments", [[], ["plna"], ["plan"], ["catalogue", "--jsn"]])
def test_with_json_a_usage_error_s_fix_is_the_one_on_stderr(
    arguments: list[str], capsys: pytest.CaptureFixture[str]
) -> None:
    assert main([*arguments, "--json"]) == 2
    captured = capsys.readouterr()
    error = json.loads(captured.out)["error"]
    assert error["kind"] == "usage"
    assert captured.err.splitlines()[-1] == f"  fix: {error['fix']}"
