"""`lasertest doctor`: checks that the plugin's dependencies, solver, simulator, bundled robots,
scanner catalogue and pytest entry point work, each with what to do when it does not."""

from __future__ import annotations

import importlib.metadata
import importlib.util
import sys
from collections.abc import Callable
from dataclasses import dataclass

from pytest_lasertest.pairsfile.bundled import bundled_robots
from pytest_lasertest.pairsfile.catalogue import load_catalogue
from pytest_lasertest.pairsfile.robot import load_robot_file

# Distribution name -> module name, for the packages the plugin runs on.
DEPENDENCIES = {
    "pytest": "pytest",
    "numpy": "numpy",
    "pyyaml": "yaml",
    "hypothesis": "hypothesis",
    "z3-solver": "z3",
    "pybullet": "pybullet",
    "xacro": "xacro",
}


@dataclass(frozen=True)
class Check:
    """One thing the plugin needs, how to test it, and what to do when it is broken."""

    name: str
    run: Callable[[], str]
    fix: str


def run_doctor() -> int:
    """Run every check, print one line each, and return 1 if any failed."""
    failures = 0
    for check in CHECKS:
        try:
            print(f"ok    {check.name}: {check.run()}")
        except Exception as error:  # noqa: BLE001  (the doctor reports every failure as text)
            failures += 1
            print(f"FAIL  {check.name}: {type(error).__name__}: {error}\n      fix: {check.fix}")
    print("all checks passed" if not failures else f"{failures} check(s) failed")
    return 1 if failures else 0


def _python() -> str:
    return f"{sys.implementation.name} {sys.version.split()[0]} at {sys.executable}"


def _packages() -> str:
    found, missing = [], []
    for distribution, module in DEPENDENCIES.items():
        try:
            version = importlib.metadata.version(distribution)
        except importlib.metadata.PackageNotFoundError:
            version = None
        if version is None or importlib.util.find_spec(module) is None:
            missing.append(distribution)
        else:
            found.append(f"{distribution} {version}")
    if missing:
        raise RuntimeError(f"not installed: {', '.join(missing)}")
    return ", ".join(found)


def _z3() -> str:
    from pytest_lasertest.solver import self_test

    return self_test()


def _pybullet() -> str:
    from pytest_lasertest.sim import self_test

    return self_test()


def _robots() -> str:
    robots = bundled_robots()
    if not robots:
        raise RuntimeError("no bundled robot found")
    return ", ".join(f"{name} ({load_robot_file(path).name})" for name, path in robots.items())


def _catalogue() -> str:
    entries = load_catalogue().entries
    if not entries:
        raise RuntimeError("the scanner catalogue is empty")
    return f"{len(entries)} models load and validate"


def _entry_point() -> str:
    for entry_point in importlib.metadata.entry_points(group="pytest11"):
        if entry_point.value == "pytest_lasertest.plugin":
            return f"pytest loads it as {entry_point.name!r}"
    raise RuntimeError("no pytest11 entry point names pytest_lasertest.plugin")


CHECKS = (
    Check("python", _python, "install Python 3.11 or newer"),
    Check("packages", _packages, "pip install pytest-lasertest, which brings its dependencies"),
    Check("z3", _z3, "pip install --force-reinstall z3-solver"),
    Check("pybullet", _pybullet, "pip install --force-reinstall pybullet"),
    Check("bundled robots", _robots, "reinstall pytest-lasertest: its package data is incomplete"),
    Check("scanner catalogue", _catalogue, "reinstall pytest-lasertest: its catalogue is damaged"),
    Check(
        "pytest plugin", _entry_point, "reinstall pytest-lasertest so pytest finds its entry point"
    ),
)
