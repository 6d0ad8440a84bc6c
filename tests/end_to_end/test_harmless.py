"""Harmless scanner changes pass the gate (tests/data/harmless/): the same scanner twice, a
same-family swap that reads at least as much, a strict upgrade and a re-mount by 1 cm, on the
Husky under move_base and under Nav2, as CI runs them: `CI` set, default options, so each file's
seed is the one its path gives. Each item runs alone, with a short search (`--laser-examples`),
so that no test runs long; benchmarks/verdicts.py runs the whole files under seeds 0-7."""

from __future__ import annotations

import shutil

import pytest

from tests.helpers import DATA
from tests.helpers.runs import outcomes

HARMLESS = DATA / "harmless"
STACKS = ("move_base", "nav2")
# The pairs that collect items; `identical` collects none (see the last test).
PAIRS = ("same_family", "strict_upgrade", "remount_1cm")
# Items that drive an obstacle both scanners read. The misses items skip: neither scanner of a
# harmless change misses what the other reads, or the baseline misses what a better one reads.
AVOID = ("avoid-0", "avoid-1", "avoid-2")


def gate(pytester: pytest.Pytester, monkeypatch: pytest.MonkeyPatch, stack: str) -> str:
    """The stack's harmless pairs file at the path it has in this repository, whose path fixes
    its seed on CI; its node id's file part."""
    relative = f"tests/data/harmless/{stack}.lasertest.yaml"
    target = pytester.path / relative
    target.parent.mkdir(parents=True)
    shutil.copy(HARMLESS / f"{stack}.lasertest.yaml", target)
    monkeypatch.setenv("CI", "true")
    return relative


@pytest.mark.parametrize("item", AVOID)
@pytest.mark.parametrize("pair", PAIRS)
@pytest.mark.parametrize("stack", STACKS)
def test_a_harmless_change_fails_no_placement_item_on_ci(
    pytester: pytest.Pytester, monkeypatch: pytest.MonkeyPatch, stack: str, pair: str, item: str
) -> None:
    path = gate(pytester, monkeypatch, stack)
    result = pytester.runpytest_subprocess(f"{path}::{pair}[{item}]", "--laser-examples=4")
    assert result.ret == pytest.ExitCode.OK, result.stdout.str()
    assert "failed" not in outcomes(result)


@pytest.mark.parametrize("stack", STACKS)
def test_a_harmless_change_loses_no_coverage_and_drives_the_empty_world_on_ci(
    pytester: pytest.Pytester, monkeypatch: pytest.MonkeyPatch, stack: str
) -> None:
    path = gate(pytester, monkeypatch, stack)
    result = pytester.runpytest_subprocess(path, "-k", "coverage or no-obstacle", "-rA")
    assert result.ret == pytest.ExitCode.OK, result.stdout.str()
    assert outcomes(result) == {"passed": 2 * len(PAIRS), "deselected": 9 * len(PAIRS)}
    result.stdout.fnmatch_lines([f"{path}::identical: no sensing change, no items: *"])
