"""A pytest plugin of main_job.py (`-p simulated`, this folder on PYTHONPATH): it adds up the
simulated seconds of every drive the run makes, the items' and their failures' evidence, and
appends `<pid> <seconds> <drives>` to the file $LASERTEST_SIMULATED when the process ends its
session (each xdist worker its own line)."""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

_TOTAL = {"seconds": 0.0, "drives": 0}


def pytest_configure(config: pytest.Config) -> None:
    # The simulator's entry point, before the modules that drive import it by name (the plugin
    # imports them only when it needs them); any of them already imported is counted too.
    # Nothing else is imported here, so that the run's memory stays its own.
    from pytest_lasertest.sim import scenario

    counted = _counted(scenario.run_scenario)
    scenario.run_scenario = counted
    for name in ("pytest_lasertest.search.drives", "pytest_lasertest.artifacts.evidence"):
        module = sys.modules.get(name)
        if module is not None:
            module.run_scenario = counted


def _counted(run_scenario: Callable[..., Any]) -> Callable[..., Any]:
    """`run_scenario`, adding each run's simulated time to the total."""

    def counted(*arguments: Any, **keywords: Any) -> Any:
        run = run_scenario(*arguments, **keywords)
        _TOTAL["seconds"] += float(run.times[-1]) if len(run.times) else 0.0
        _TOTAL["drives"] += 1
        return run

    return counted


def pytest_unconfigure(config: pytest.Config) -> None:
    target = os.environ.get("LASERTEST_SIMULATED")
    if target:
        with Path(target).open("a") as file:
            file.write(f"{os.getpid()} {_TOTAL['seconds']:.3f} {_TOTAL['drives']}\n")
