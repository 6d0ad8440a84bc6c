"""The benchmark scripts stay runnable and keep the last line CI and readers track."""

from __future__ import annotations

import re
import subprocess
import sys

from tests.helpers import REPO

SOLVER_LINE = re.compile(
    r"ms per witness at 720 beams: [\d.]+; at 2880 beams: [\d.]+; "
    r"speed-up over rejection sampling: \d+"
)


def printed(*arguments: str) -> list[str]:
    """The lines a benchmark script prints, run with `arguments` from the repository."""
    result = subprocess.run(
        [sys.executable, *arguments], cwd=REPO, capture_output=True, text=True, check=True
    )
    return result.stdout.strip().splitlines()


def test_the_solver_benchmark_runs_and_ends_with_its_figures() -> None:
    lines = printed("benchmarks/solver.py", "--catalogue-pairs", "1", "--budget", "0.2")
    assert SOLVER_LINE.fullmatch(lines[-1])
    checked = next(line for line in lines if line.startswith("verified again by ray casting"))
    verified, total = map(int, re.findall(r"\d+", checked))
    assert verified == total > 0


SIM_LINE = re.compile(r"real-time factor: \d+; ratio to bare physics: [\d.]+")


def test_the_simulator_benchmark_runs_and_ends_with_its_figures() -> None:
    lines = printed("benchmarks/sim.py", "--runs", "2", "--memory-runs", "5")
    assert SIM_LINE.fullmatch(lines[-1])
    assert "0 physics clients left connected" in lines[-2]


NAV_LINE = re.compile(
    r"planning cycle: [\d.]+ ms; ratio to the physics of one control period: [\d.]+"
)


def test_the_navigation_benchmark_runs_and_ends_with_its_figures() -> None:
    lines = printed("benchmarks/nav.py", "--runs", "1")
    assert NAV_LINE.fullmatch(lines[-1])
    assert re.match(r"\d+ costmap updates: [\d.]+ ms; \d+ DWA commands: ", lines[0])
