"""The installed plugin: light at import, its lower layers and `lasertest plan` free of pytest,
complete as a wheel, found by pytest."""

from __future__ import annotations

import json
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from tests.helpers import REPO


def test_importing_the_entry_point_loads_no_heavy_module() -> None:
    script = (
        "import pytest_lasertest.plugin, sys; print(sorted(m for m in "
        "('z3', 'pybullet', 'hypothesis', 'numpy', 'numba', 'yaml') if m in sys.modules))"
    )
    result = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True
    )
    assert result.stdout.strip() == "[]"


# Every layer but the plugin runs without pytest; import-linter forbids the import statically,
# these tests catch it at run time, wherever it comes from.
PYTEST_FREE_LAYERS = (
    "model",
    "nav",
    "sim",
    "inputs",
    "descriptions",
    "pairsfile",
    "solver",
    "search",
    "reports",
    "artifacts",
    "cli",
)
# What a fresh interpreter prints last: the pytest modules it has loaded.
LOADED_PYTEST = (
    "print(json.dumps(sorted(name for name in sys.modules "
    "if name.partition('.')[0] in ('pytest', '_pytest'))))"
)


def test_importing_every_module_of_the_layers_below_the_plugin_loads_no_pytest() -> None:
    script = "\n".join(
        [
            "import importlib, json, pkgutil, sys",
            f"for layer in {PYTEST_FREE_LAYERS!r}:",
            "    package = importlib.import_module('pytest_lasertest.' + layer)",
            "    for module in pkgutil.walk_packages(package.__path__, package.__name__ + '.'):",
            # `python -m pytest_lasertest.cli` runs the command: importing it would too.
            "        if not module.name.endswith('.__main__'):",
            "            importlib.import_module(module.name)",
            "print(json.dumps(sorted(name for name in sys.modules if name.startswith('pytest_'))))",
            LOADED_PYTEST,
        ]
    )
    result = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True
    )
    *_, imported, loaded = result.stdout.splitlines()
    assert {
        "pytest_lasertest.model.geometry",
        "pytest_lasertest.nav.move_base.costmap",
        "pytest_lasertest.reports.summary",
        "pytest_lasertest.search.perturb",
        "pytest_lasertest.sim.client",
        "pytest_lasertest.solver.backend",
    } <= set(json.loads(imported))
    assert json.loads(loaded) == []


def test_lasertest_plan_runs_without_loading_pytest() -> None:
    script = "\n".join(
        [
            "import contextlib, io, json, sys",
            "from pytest_lasertest.cli import main",
            "with contextlib.redirect_stdout(io.StringIO()) as printed:",
            "    status = main(['plan', 'examples/paper.lasertest.yaml', '--json'])",
            "print(status, len(json.loads(printed.getvalue())['pairs']))",
            LOADED_PYTEST,
        ]
    )
    result = subprocess.run(
        [sys.executable, "-c", script], cwd=REPO, capture_output=True, text=True, check=True
    )
    *_, planned, loaded = result.stdout.splitlines()
    assert planned == "0 3"
    assert json.loads(loaded) == []


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


def test_the_wheel_ships_the_robots_the_catalogue_the_schema_and_the_entry_points(
    tmp_path: Path,
) -> None:
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
    for robot in ("husky", "jackal", "turtlebot3_burger", "turtlebot3_waffle"):
        for part in ("robot", "navigation", "nav2"):
            assert f"pytest_lasertest/robots/{robot}/{part}.yaml" in names
    assert "pytest_lasertest/py.typed" in names
    assert "pytest_lasertest/pairsfile/schema/pairs-file.schema.json" in names
    assert len([n for n in names if n.startswith("pytest_lasertest/robots/lidars/")]) >= 10
    (entry_points,) = [n for n in names if n.endswith(".dist-info/entry_points.txt")]
    text = zipfile.ZipFile(wheel).read(entry_points).decode()
    assert "[pytest11]\nlasertest = pytest_lasertest.plugin" in text
    assert "lasertest = pytest_lasertest.cli:main" in text
    assert (
        "[lasertest.controllers]\nmove_base = pytest_lasertest.nav.move_base:MoveBase\n"
        "nav2 = pytest_lasertest.nav.nav2.nav2:Nav2\n"
        "reactive = pytest_lasertest.nav.reactive:ReactiveController"
    ) in text
