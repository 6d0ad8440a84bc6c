"""The benchmark scripts stay runnable and keep the last line CI and readers track."""

from __future__ import annotations

import re
import subprocess
import sys

from tests.conftest import REPO

SOLVER_LINE = re.compile(
    r"ms per witness at 720 beams: [\d.]+; at 2880 beams: [\d.]+; "
    r"speed-up over rejection sampling: \d+"
)


def test_the_solver_benchmark_runs_and_ends_with_its_figures() -> None:
    result = subprocess.run(
        [sys.executable, "benchmarks/solver.py", "--catalogue-pairs", "1", "--budget", "0.2"],
        cwd=REPO,
        capture_output=True,
        text=True,
        check=True,
    )
    lines = result.stdout.strip().splitlines()
    assert SOLVER_LINE.fullmatch(lines[-1])
    checked = next(line for line in lines if line.startswith("verified again by ray casting"))
    verified, total = map(int, re.findall(r"\d+", checked))
    assert verified == total > 0
