"""The one place that builds Z3 solvers: pinned seed, budget in resource units, never wall time.

Queries come in as labelled SMT-LIB blocks over real variables and leave as a `Solution`: Z3's
own objects never leave this module.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Literal

import z3

# Z3 counts rlimit in deterministic resource units: the same query gets the same answer on every
# machine and every xdist worker, which a timeout in seconds cannot promise.
RLIMIT = 5_000_000
SEED = 0

Verdict = Literal["sat", "unsat", "unknown"]


@dataclass(frozen=True)
class Solution:
    """Z3's answer: a model's values when sat, the labels of an unsat core when unsat."""

    verdict: Verdict
    values: Mapping[str, float]
    core: tuple[str, ...] = ()
    reason: str = ""  # why Z3 gave up, when unknown


def make_solver(rlimit: int = RLIMIT, context: z3.Context | None = None) -> z3.Solver:
    """A fresh solver with the project's seed and resource limit."""
    solver = z3.Solver(ctx=context)
    solver.set("random_seed", SEED)
    solver.set("rlimit", rlimit)
    return solver


def make_optimizer(rlimit: int = RLIMIT, context: z3.Context | None = None) -> z3.Optimize:
    """A fresh optimiser with the project's seed and resource limit."""
    optimizer = z3.Optimize(ctx=context)
    optimizer.set("random_seed", SEED)
    optimizer.set("rlimit", rlimit)
    return optimizer


class Workspace:
    """A Z3 context that a run of related queries shares.

    Making a context can cost more than solving a small linear program (from 0.5 to 5 ms, as
    measured here), so a search, or a proof, asks all its queries in one. Z3's answers in a
    context may depend on what it was asked before; a search or a proof asks the same queries in
    the same order every time, so its answers stay the same.
    """

    def __init__(self) -> None:
        self._context = z3.Context()

    def solve(
        self,
        variables: Sequence[str],
        blocks: Mapping[str, str],
        maximize: Sequence[str] = (),
        rlimit: int = RLIMIT,
        explained: bool = True,
    ) -> Solution:
        """Check the conjunction of labelled SMT-LIB formulas over real `variables`.

        The model maximises the `maximize` terms in order (`-S` minimises S). When `explained`,
        an unsat answer names the labels of the blocks that together admit no model; tracking
        them makes a check about half again as dear, so searches that need only the verdict do
        without.
        """
        context = self._context
        # Optimising is much dearer than deciding: a plain solver when nothing is to be maximised.
        optimizer = make_optimizer(rlimit, context) if maximize else make_solver(rlimit, context)
        declarations = "".join(f"(declare-const {name} Real)" for name in variables)
        asserted = "".join(f"(assert {text})" for text in blocks.values())
        formulas = z3.parse_smt2_string(declarations + asserted, ctx=context)
        for label, formula in zip(blocks, formulas, strict=True):
            if explained:
                optimizer.assert_and_track(formula, z3.Bool(label, context))
            else:
                optimizer.add(formula)
        for term in maximize:
            variable = z3.Real(term.lstrip("-"), context)
            optimizer.maximize(-variable if term.startswith("-") else variable)
        return _answer(optimizer, [z3.Real(name, context) for name in variables])


def _answer(optimizer: z3.Solver | z3.Optimize, variables: list[z3.ArithRef]) -> Solution:
    """Check, and put Z3's answer in a Solution."""
    verdict = optimizer.check()
    if verdict == z3.sat:
        model = optimizer.model()
        return Solution("sat", {str(variable): _value(model, variable) for variable in variables})
    if verdict == z3.unsat:
        return Solution("unsat", {}, tuple(sorted(str(label) for label in optimizer.unsat_core())))
    return Solution("unknown", {}, reason=optimizer.reason_unknown())


def _value(model: z3.ModelRef, variable: z3.ArithRef) -> float:
    value = model.eval(variable, model_completion=True)
    if z3.is_rational_value(value):
        return float(Fraction(value.numerator_as_long(), value.denominator_as_long()))
    # An algebraic number (never from linear constraints, but Z3 may say so): approximate it.
    return float(value.approx(20).as_fraction())


def self_test() -> str:
    """Solve a tiny problem under the resource limit; describe the Z3 that did it."""
    solution = Workspace().solve(("x",), {"bounds": "(and (> x 1.0) (< x 2.0))"})
    if solution.verdict != "sat":
        raise RuntimeError(f"Z3 answered {solution.verdict} to 1 < x < 2, which is satisfiable")
    return f"z3 {z3.get_version_string()}: solved a test problem under rlimit {RLIMIT}"
