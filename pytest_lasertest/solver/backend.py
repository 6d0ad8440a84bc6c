"""The one place that builds Z3 solvers: pinned seed, budget in resource units, never wall time."""

from __future__ import annotations

import z3

# Z3 counts rlimit in deterministic resource units: the same query gets the same answer on every
# machine and every xdist worker, which a timeout in seconds cannot promise.
RLIMIT = 5_000_000
SEED = 0


def make_solver(rlimit: int = RLIMIT) -> z3.Solver:
    """A fresh solver with the project's seed and resource limit."""
    solver = z3.Solver()
    solver.set("random_seed", SEED)
    solver.set("rlimit", rlimit)
    return solver


def self_test() -> str:
    """Solve a tiny problem under the resource limit; describe the Z3 that did it."""
    solver = make_solver()
    x = z3.Real("x")
    solver.add(x > 1, x < 2)
    verdict = solver.check()
    if verdict != z3.sat:
        raise RuntimeError(f"Z3 answered {verdict} to 1 < x < 2, which is satisfiable")
    return f"z3 {z3.get_version_string()}: solved a test problem under rlimit {RLIMIT}"
