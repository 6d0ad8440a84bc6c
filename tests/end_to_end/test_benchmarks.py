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


FAULT_LINE = re.compile(
    r"mutants killed: gate \d+ of \d+, random \d+ of \d+; "
    r"killed cells per 1000 simulations: gate [\d.]+, random [\d.]+"
)


def test_the_fault_finding_benchmark_runs_and_never_kills_the_equivalent_mutant() -> None:
    lines = printed(
        "benchmarks/fault_finding.py",
        *("--seeds", "1", "--jobs", "1", "--mutants", "nan_guard", "--pairs", "slower"),
    )
    assert FAULT_LINE.fullmatch(lines[-1])
    # The equivalent mutant alone: nothing to kill, and no method kills it.
    assert lines[-1].startswith("mutants killed: gate 0 of 0, random 0 of 0")
    rows = [line.split() for line in lines if line.startswith("nan_guard")]
    assert [row[1] for row in rows] == ["gate", "random", "random"]
    assert all(row[-1] == "-" and row[-3].startswith("0/1") for row in rows)
