"""Each option is parsed by a pure function; a bad value is a usage error naming it and why; the
header prints the options that replay the run, and xdist workers use its seed."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from pytest_lasertest.plugin import collection_args
from pytest_lasertest.plugin.options import (
    default_profile,
    derived_seed,
    parse_artifacts,
    parse_pairs,
    parse_policy,
    parse_profile,
    parse_seed,
)
from tests.helpers.runs import NO_PLACEMENTS


@pytest.mark.parametrize(("text", "seed"), [("0", 0), ("42", 42), ("4294967295", 4294967295)])
def test_a_seed_is_a_whole_number_up_to_2_to_the_32(text: str, seed: int) -> None:
    assert parse_seed(text) == seed


def test_random_asks_for_a_fresh_seed() -> None:
    assert parse_seed("random") is None


@pytest.mark.parametrize("text", ["-1", "4294967296", "1.5", "abc", "", "0x10"])
def test_a_bad_seed_is_a_usage_error_naming_it_and_the_accepted_values(text: str) -> None:
    with pytest.raises(
        pytest.UsageError, match=r"--laser-seed='.*' is not a seed.*0 to 4294967295"
    ):
        parse_seed(text)


@pytest.mark.parametrize("name", ["dev", "ci", "nightly", "triage"])
def test_the_four_budget_profiles_are_accepted(name: str) -> None:
    assert parse_profile(name) == name


def test_an_unknown_profile_names_the_four_profiles() -> None:
    with pytest.raises(pytest.UsageError, match=r"'fast' is not.*dev, ci, nightly, triage"):
        parse_profile("fast")


@pytest.mark.parametrize(
    ("environ", "profile"),
    [({}, "dev"), ({"CI": "true"}, "ci"), ({"CI": "1"}, "ci"), ({"CI": "false"}, "dev")],
)
def test_the_default_profile_is_ci_on_a_ci_service(environ: dict[str, str], profile: str) -> None:
    assert default_profile(environ) == profile


def test_an_unknown_policy_names_both_policies_and_what_they_mean() -> None:
    with pytest.raises(
        pytest.UsageError,
        match=r"'strict' is not a policy.*'regression' \(the default.*'candidate'",
    ):
        parse_policy("strict")


def test_the_artifacts_directory_may_not_exist_yet(tmp_path: Path) -> None:
    assert parse_artifacts("out/laser", tmp_path) == tmp_path / "out" / "laser"


def test_an_artifacts_path_that_is_a_file_is_refused(tmp_path: Path) -> None:
    (tmp_path / "report.txt").write_text("")
    with pytest.raises(pytest.UsageError, match=r"'report.txt' is not a directory"):
        parse_artifacts("report.txt", tmp_path)


def test_a_missing_pairs_file_is_a_usage_error_naming_it(tmp_path: Path) -> None:
    with pytest.raises(pytest.UsageError, match=r"--laser-pairs: 'gone.yaml' is missing"):
        parse_pairs(["gone.yaml"], tmp_path, "--laser-pairs")


def test_a_directory_given_as_pairs_file_says_to_pass_it_to_pytest(tmp_path: Path) -> None:
    with pytest.raises(pytest.UsageError, match=r"is a directory.*pass the directory to pytest"):
        parse_pairs(["."], tmp_path, "--laser-pairs")


def test_named_pairs_files_alone_replace_the_default_test_paths(tmp_path: Path) -> None:
    named = (tmp_path / "gate.yaml",)
    assert collection_args(["tests"], False, named, (), tmp_path) == [str(named[0])]


def test_named_pairs_files_join_explicit_arguments_once(tmp_path: Path) -> None:
    named = (tmp_path / "gate.yaml",)
    args = collection_args(["tests", "gate.yaml"], True, named, (), tmp_path)
    assert args == ["tests", "gate.yaml"]


def test_pairs_files_from_the_ini_file_join_the_default_test_paths(tmp_path: Path) -> None:
    always = (tmp_path / "ci.yaml",)
    assert collection_args(["tests"], False, (), always, tmp_path) == ["tests", str(always[0])]


@pytest.mark.parametrize(
    ("option", "message"),
    [
        ("--laser-seed=abc", "ERROR: --laser-seed='abc' is not a seed*"),
        ("--laser-profile=fast", "ERROR: --laser-profile='fast' is not a budget profile*"),
        ("--laser-policy=strict", "ERROR: --laser-policy='strict' is not a policy*"),
        ("--laser-artifacts=conftest.py", "ERROR: --laser-artifacts='conftest.py' is not a dir*"),
        ("--laser-summary=.", "ERROR: --laser-summary='.' is not a file*GITHUB_STEP_SUMMARY*"),
        (
            "--laser-summary=conftest.py/summary.md",
            "ERROR: --laser-summary='conftest.py/summary.md': * is a file, so no directory*",
        ),
        ("--laser-pairs=gone.yaml", "ERROR: --laser-pairs: 'gone.yaml' is missing*"),
    ],
)
def test_a_bad_option_stops_the_run_with_a_usage_error_and_no_traceback(
    pytester: pytest.Pytester, option: str, message: str
) -> None:
    pytester.makeconftest("")
    result = pytester.runpytest(option)
    assert result.ret == pytest.ExitCode.USAGE_ERROR
    result.stderr.fnmatch_lines([message])
    assert "Traceback" not in result.stderr.str() + result.stdout.str()


def test_a_bad_ini_pairs_path_is_a_usage_error_naming_the_ini_option(
    pytester: pytest.Pytester,
) -> None:
    pytester.makeini("[pytest]\nlaser_pairs = gone.lasertest.yaml\n")
    result = pytester.runpytest()
    assert result.ret == pytest.ExitCode.USAGE_ERROR
    result.stderr.fnmatch_lines(["ERROR: laser_pairs (ini): '*gone.lasertest.yaml' is missing*"])


def test_the_header_prints_the_options_that_replay_the_run(
    pytester: pytest.Pytester, pairs_file: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    result = pytester.runpytest("--laser-seed=7", "--co")
    result.stdout.fnmatch_lines(
        ["lasertest: --laser-seed=7 --laser-profile=dev --laser-policy=regression"]
    )


def test_the_profile_defaults_to_ci_and_the_seed_to_the_pairs_file_s_own_on_a_ci_service(
    pytester: pytest.Pytester, pairs_file: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("CI", "true")
    result = pytester.runpytest("--co", "--laser-policy=candidate")
    result.stdout.fnmatch_lines(
        [
            "lasertest: seed fixed per pairs file, from its path (on CI; --laser-seed=random "
            "explores); --laser-profile=ci --laser-policy=candidate"
        ]
    )


@pytest.mark.parametrize("given", [["--laser-seed=random"], ["--laser-profile=nightly"]])
def test_on_a_ci_service_a_random_seed_or_the_nightly_profile_still_explores(
    pytester: pytest.Pytester, pairs_file: Path, monkeypatch: pytest.MonkeyPatch, given: list[str]
) -> None:
    monkeypatch.setenv("CI", "true")
    result = pytester.runpytest("--co", *given)
    result.stdout.fnmatch_lines(["lasertest: --laser-seed=* --laser-profile=*"])


def test_a_random_seed_is_fresh_each_run(pytester: pytest.Pytester, pairs_file: Path) -> None:
    def seed() -> str:
        match = re.search(r"--laser-seed=(\d+)", pytester.runpytest("--co").stdout.str())
        assert match is not None
        return match.group(1)

    assert seed() != seed()


def junit_seeds(report: Path) -> dict[str, str]:
    """Each test case's `lasertest.seed` property in a JUnit XML report, by class and name."""
    seeds = {}
    for case in ET.parse(report).iter("testcase"):
        for prop in case.iter("property"):
            if prop.get("name") == "lasertest.seed":
                seeds[f"{case.get('classname')}::{case.get('name')}"] = str(prop.get("value"))
    return seeds


def test_on_a_ci_service_each_pairs_file_s_seed_is_fixed_by_its_path_on_every_worker(
    pytester: pytest.Pytester, pairs_file: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("CI", "true")
    other = pytester.path / "other"
    other.mkdir()
    (other / "gate.lasertest.yaml").write_text(pairs_file.read_text())
    runs = [
        pytester.runpytest_subprocess(*options, f"--junitxml={name}.xml", *NO_PLACEMENTS)
        for name, options in (("serial", []), ("workers", ["-n", "2"]))
    ]
    serial, workers = (junit_seeds(pytester.path / f"{name}.xml") for name in ("serial", "workers"))
    # The same on every run and worker, and each file's the seed derived_seed gives its path:
    # a commit's verdict does not change between reruns.
    assert serial == workers
    assert {(name.startswith("other."), seed) for name, seed in serial.items()} == {
        (False, str(derived_seed("gate.lasertest.yaml"))),
        (True, str(derived_seed("other/gate.lasertest.yaml"))),
    }
    for run in runs:
        run.stdout.fnmatch_lines(["lasertest: seed fixed per pairs file, from its path *"])


def test_xdist_workers_use_the_seed_the_header_prints(
    pytester: pytest.Pytester, pairs_file: Path
) -> None:
    result = pytester.runpytest_subprocess("-n", "2", "--junitxml=report.xml", *NO_PLACEMENTS)
    match = re.search(r"--laser-seed=(\d+)", result.stdout.str())
    assert match is not None
    seeds = {
        prop.get("value")
        for prop in ET.parse(pytester.path / "report.xml").iter("property")
        if prop.get("name") == "lasertest.seed"
    }
    assert seeds == {match.group(1)}


@pytest.mark.parametrize("value", ["0", "many", "-3", "10001"])
def test_a_bad_number_of_examples_is_a_usage_error_naming_it(
    pytester: pytest.Pytester, value: str
) -> None:
    result = pytester.runpytest(f"--laser-examples={value}")
    assert result.ret == pytest.ExitCode.USAGE_ERROR
    result.stderr.fnmatch_lines(
        [f"ERROR: --laser-examples='{value}' is not a number of examples: give a whole number *"]
    )


def test_a_file_where_the_html_reports_artifacts_go_is_refused_naming_html_not_our_option(
    tmp_path: Path,
) -> None:
    # The user gave --html alone: the error names it, and --laser-artifacts as the way out.
    (tmp_path / ".lasertest-artifacts").write_text("")
    with pytest.raises(pytest.UsageError) as refused:
        parse_artifacts(".lasertest-artifacts", tmp_path, beside_report=True)
    assert str(refused.value) == (
        "--html puts the failure artifacts beside its report, in '.lasertest-artifacts', which "
        "is not a directory: move what is there, or give --laser-artifacts=DIR to put them "
        "elsewhere"
    )
