"""The Nav2 parameters a params file sets that the imitation does not read are one warning per
params file in a run, naming it, however many pairs files drive with it; a pairs file that
collects no items warns of nothing."""

from __future__ import annotations

import shutil

import pytest

from tests.helpers import REPO

BRINGUP = REPO / "tests" / "data" / "nav2" / "nav2_params.yaml"  # sets amcl's, never read
WARNING = "UnreadParametersWarning: the Nav2 imitation does not read these parameters of "


def pairs_text(params: str | None, candidate: str = "hokuyo_ust_20lx") -> str:
    """A Nav2 pairs file driving with `params` (None: the bundled Husky's own)."""
    navigation = f"navigation: {{nav2: {params}}}\n" if params else ""
    return (
        "robot: husky\n"
        "controller: nav2\n"
        f"{navigation}"
        "world: {start: {x: 0, y: 0}, goal: {x: 3, y: 0}, time_limit: 30}\n"
        "pairs:\n"
        f"  longer: {{baseline: {{model: hokuyo_ust_10lx}}, candidate: {{model: {candidate}}}}}\n"
    )


def warnings_of(pytester: pytest.Pytester) -> list[str]:
    """The UnreadParametersWarning lines of collecting the pytester directory."""
    result = pytester.runpytest("--collect-only", "-q")
    return [line for line in result.outlines if WARNING in line]


def test_two_pairs_files_sharing_a_params_file_give_one_warning_naming_it(
    pytester: pytest.Pytester,
) -> None:
    shutil.copy(BRINGUP, pytester.path / "nav2_params.yaml")
    for name in ("one", "two"):
        (pytester.path / f"{name}.lasertest.yaml").write_text(pairs_text("nav2_params.yaml"))
    (line,) = warnings_of(pytester)
    assert line.endswith(
        f"{WARNING}the params file nav2_params.yaml "
        "(docs/explanation/navigation.md says what it imitates):"
    )


def test_each_params_file_gets_its_own_warning(pytester: pytest.Pytester) -> None:
    (pytester.path / "other").mkdir()
    shutil.copy(BRINGUP, pytester.path / "nav2_params.yaml")
    shutil.copy(BRINGUP, pytester.path / "other" / "nav2_params.yaml")
    (pytester.path / "one.lasertest.yaml").write_text(pairs_text("nav2_params.yaml"))
    (pytester.path / "two.lasertest.yaml").write_text(pairs_text("other/nav2_params.yaml"))
    lines = warnings_of(pytester)
    assert len(lines) == 2
    assert any(f"{WARNING}the params file nav2_params.yaml (" in line for line in lines)
    assert any(f"{WARNING}the params file other/nav2_params.yaml (" in line for line in lines)


def test_a_bundled_robot_s_params_file_is_named_from_the_package(
    pytester: pytest.Pytester,
) -> None:
    (pytester.path / "gate.lasertest.yaml").write_text(pairs_text(None))
    (line,) = warnings_of(pytester)
    assert f"{WARNING}the params file husky/nav2.yaml of the bundled robots (" in line


def test_a_pairs_file_whose_pairs_read_alike_warns_of_nothing(
    pytester: pytest.Pytester,
) -> None:
    shutil.copy(BRINGUP, pytester.path / "nav2_params.yaml")
    alike = pairs_text("nav2_params.yaml", candidate="hokuyo_ust_10lx")
    (pytester.path / "alike.lasertest.yaml").write_text(alike)
    assert warnings_of(pytester) == []
    # The same file with a pair that yields items does warn: the test can fail.
    (pytester.path / "alike.lasertest.yaml").write_text(pairs_text("nav2_params.yaml"))
    assert len(warnings_of(pytester)) == 1
