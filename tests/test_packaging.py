"""The installed plugin: light at import, complete as a wheel, found by pytest."""

from __future__ import annotations

import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from tests.conftest import REPO


def test_importing_the_entry_point_loads_no_heavy_module() -> None:
    script = (
        "import pytest_lasertest.plugin, sys; print(sorted(m for m in "
        "('z3', 'pybullet', 'hypothesis', 'numpy', 'yaml') if m in sys.modules))"
    )
    result = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True
    )
    assert result.stdout.strip() == "[]"


def test_a_pytest_run_without_pairs_files_loads_no_solver_or_simulator(
    pytester: pytest.Pytester,
) -> None:
    pytester.makepyfile(
        test_unit="""
        import sys

        def test_heavy_modules_are_not_loaded():
            assert not {"z3", "pybullet", "pytest_lasertest.plugin.collect"} & set(sys.modules)
        """
    )
    pytester.runpytest_subprocess("-p", "no:hypothesispytest").assert_outcomes(passed=1)


def test_the_wheel_ships_the_robots_the_catalogue_and_the_entry_points(tmp_path: Path) -> None:
    subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "wheel",
            "--no-deps",
            "--no-build-isolation",
            "-q",
            "-w",
            str(tmp_path),
            str(REPO),
        ],
        check=True,
        capture_output=True,
    )
    (wheel,) = tmp_path.glob("pytest_lasertest-*.whl")
    names = set(zipfile.ZipFile(wheel).namelist())
    assert "pytest_lasertest/robots/husky/robot.yaml" in names
    assert "pytest_lasertest/py.typed" in names
    assert len([n for n in names if n.startswith("pytest_lasertest/robots/lidars/")]) >= 10
    (entry_points,) = [n for n in names if n.endswith(".dist-info/entry_points.txt")]
    text = zipfile.ZipFile(wheel).read(entry_points).decode()
    assert "[pytest11]\nlasertest = pytest_lasertest.plugin" in text
    assert "lasertest = pytest_lasertest.cli:main" in text
    assert (
        "[lasertest.controllers]\nmove_base = pytest_lasertest.nav.move_base:MoveBase\n"
        "reactive = pytest_lasertest.nav.reactive:ReactiveController"
    ) in text
