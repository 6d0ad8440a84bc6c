"""The benchmarks' own modules, imported as fault_finding.py imports them (from benchmarks/)."""

from __future__ import annotations

import importlib
from pathlib import Path
from types import ModuleType

import pytest

from tests.helpers import REPO


@pytest.fixture
def benchmarks_dir(monkeypatch: pytest.MonkeyPatch) -> Path:
    """benchmarks/, on the import path for the test."""
    monkeypatch.syspath_prepend(str(REPO / "benchmarks"))
    return REPO / "benchmarks"


@pytest.fixture
def mutation(benchmarks_dir: Path) -> ModuleType:
    """benchmarks/mutation.py: how a fault goes into a stack."""
    return importlib.import_module("mutation")


@pytest.fixture
def mutants(benchmarks_dir: Path) -> ModuleType:
    """benchmarks/mutants.py: the faults, move_base's and Nav2's."""
    return importlib.import_module("mutants")


@pytest.fixture
def faults(benchmarks_dir: Path) -> ModuleType:
    """benchmarks/nav2_faults.py: the faults put into Nav2."""
    return importlib.import_module("nav2_faults")
