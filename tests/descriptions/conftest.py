"""The corpus tests' fixtures: the robot environment cleared, the ROS packages assembled from
the corpus and the stubs, and the descriptions read from them.

The `module`-scoped ones are built once per test module. `no_robot_environment` is not autouse:
the corpus test modules ask for it through `pytestmark`. The paths, tables and helpers are in
corpus.py, next to this file.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from tests.descriptions.corpus import (
    HUSKY_KINETIC,
    HUSKY_NOETIC,
    ROBOT_ENVIRONMENT,
    STUBS,
    TURTLEBOT3,
    Description,
    husky_packages,
)


@pytest.fixture
def no_robot_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    """No robot setup variable that xacro's $(optenv) reads (ROBOT_ENVIRONMENT) is set."""
    for name in list(os.environ):
        if name.startswith(ROBOT_ENVIRONMENT):
            monkeypatch.delenv(name, raising=False)


@pytest.fixture(scope="module")
def packages(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """Each ROS package whose corpus files need stand-ins, as one directory: the corpus files
    and the stubs copied together, as a checkout of the package would hold them."""
    root = tmp_path_factory.mktemp("packages")
    assembled = {}
    for key, corpus, stub in (
        ("husky_noetic", HUSKY_NOETIC, "husky_description"),
        ("husky_kinetic", HUSKY_KINETIC, "husky_description"),
        ("turtlebot3_description", TURTLEBOT3, "turtlebot3_description"),
    ):
        directory = root / key / corpus.name
        for source in (corpus, STUBS / stub):
            shutil.copytree(source, directory, dirs_exist_ok=True, copy_function=shutil.copyfile)
        assembled[key] = directory
    return assembled


@pytest.fixture(scope="module")
def husky(packages: dict[str, Path]) -> Description:
    """F01 in its assembled husky_description (noetic-devel)."""
    package = packages["husky_noetic"]
    return Description(package / "urdf/husky.urdf.xacro", husky_packages(package))


@pytest.fixture(scope="module")
def husky_kinetic(packages: dict[str, Path]) -> Description:
    """F04 in its assembled husky_description (kinetic-devel)."""
    package = packages["husky_kinetic"]
    return Description(package / "urdf/husky.urdf.xacro", husky_packages(package))


@pytest.fixture(scope="module")
def turtlebot3_burger(packages: dict[str, Path]) -> Description:
    """F15 in its assembled turtlebot3_description."""
    package = packages["turtlebot3_description"]
    return Description(
        package / "urdf/turtlebot3_burger.urdf.xacro", {"turtlebot3_description": package}
    )
