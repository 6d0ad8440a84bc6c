"""The driver examples under Nav2 (Clearpath's A200 parameters without a map), as their README
says: a no-return published as NaN or range_max, a per-scan range_max and a reversed beam order
each fail as a regression, for their trait; a no-return published as 0.0 fails as a marginal
failure; and their fixed variants fail nothing (both robots stop at the pole: pre-existing).
Under move_base they run in the main job (test_examples.py)."""

from __future__ import annotations

import shutil

import pytest

from tests.helpers import EXAMPLES

CASES = {
    "no_return_nan.lasertest.yaml": ("nan", "no_return"),
    "no_return_range_max.lasertest.yaml": ("range_max", "no_return"),
    "range_max_per_scan.lasertest.yaml": ("range_max_per_scan", "range_max"),
    "reversed_beams.lasertest.yaml": ("reversed_beams", "beam_order"),
}
# Held beside the pole by 8.5 mm of progress in 30 s; with the pole moved within 1 cm it passes.
MARGINAL = {"no_return_zero.lasertest.yaml": "zero"}
# Each case's fixed variant (`PAIR_fixed`), which fails nothing.
FIXED = {name: pair for name, (pair, _) in CASES.items()} | MARGINAL
UNDER_NAV2 = "controller: nav2\nnavigation:\n  nav2: a200_no_map.nav2.yaml"


def under_nav2(pytester: pytest.Pytester, name: str, pair: str) -> pytest.RunResult:
    """The avoid item of `pair` in driver example `name` under Nav2 without a map, as the
    README ran it: seed 1, the ci profile, the regression policy. Each item runs alone, so that
    xdist spreads them."""
    drivers = EXAMPLES / "drivers"
    shutil.copy(drivers / "a200_no_map.nav2.yaml", pytester.path)
    text = (drivers / name).read_text()
    assert text.count("controller: move_base") == 1
    (pytester.path / name).write_text(text.replace("controller: move_base", UNDER_NAV2))
    return pytester.runpytest_subprocess(
        f"{name}::{pair}[avoid-0]", "-rA", "--laser-seed=1", "--laser-profile=ci",
        "--laser-policy=regression", "-n", "0",
    )  # fmt: skip


@pytest.mark.parametrize(("name", "case"), CASES.items(), ids=CASES)
def test_each_driver_case_fails_under_nav2_without_a_map(
    pytester: pytest.Pytester, name: str, case: tuple[str, str]
) -> None:
    pair, trait = case
    result = under_nav2(pytester, name, pair)
    failed = {line.split()[1] for line in result.stdout.lines if line.startswith("FAILED ")}
    assert failed == {f"{name}::{pair}[avoid-0]"}
    result.stdout.fnmatch_lines(
        [
            f"*::{pair}[[]avoid-0[]] _*",
            "*: a regression: the baseline passes where the candidate fails",
            "  controller nav2 *",
            f"  driver     passes with the baseline's {trait} (*): the failure comes from *",
        ]
    )


@pytest.mark.parametrize(("name", "pair"), MARGINAL.items(), ids=MARGINAL)
def test_the_zero_no_return_fails_under_nav2_only_marginally(
    pytester: pytest.Pytester, name: str, pair: str
) -> None:
    result = under_nav2(pytester, name, pair)
    assert result.ret == pytest.ExitCode.OK
    result.stdout.fnmatch_lines([f"MARGINAL *{name}::{pair}[[]avoid-0[]]: *"])


@pytest.mark.parametrize(("name", "pair"), FIXED.items(), ids=FIXED)
def test_each_driver_fix_fails_nothing_under_nav2_without_a_map(
    pytester: pytest.Pytester, name: str, pair: str
) -> None:
    result = under_nav2(pytester, name, f"{pair}_fixed")
    assert result.ret == pytest.ExitCode.OK
    assert f"{name}::{pair}_fixed[avoid-0]" in not_failing(result)


def not_failing(result: pytest.RunResult) -> set[str]:
    """The items that passed, or failed without failing the run (`PRE-EXISTING  ITEM: ...`)."""
    passed = {line.split()[1] for line in result.stdout.lines if line.startswith("PASSED ")}
    noted = {
        line.split()[1].rstrip(":")
        for line in result.stdout.lines
        if line.startswith(("PRE-EXISTING ", "MARGINAL "))
    }
    return passed | noted
