"""Users' placement constraints (already parsed by `spec.constraints`) as SMT-LIB terms."""

from __future__ import annotations

from decimal import Decimal

from pytest_lasertest.pairsfile.constraints import (
    Arithmetic,
    Call,
    Comparison,
    Formula,
    Junction,
    Negative,
    Term,
    Variable,
)
from pytest_lasertest.solver.encoding import number

# The constraint language's variables and the query's: yaw is fixed in each query, not solved for.
SOLVER_NAMES = {"x": "X", "y": "Y", "size": "S", "height": "H"}


def formula_text(formula: Formula, yaw: float) -> str:
    """The SMT-LIB form of a constraint, with the obstacle's yaw fixed at `yaw` (rad)."""
    if isinstance(formula, Comparison):
        left, right = term_text(formula.left, yaw), term_text(formula.right, yaw)
        if formula.operator == "!=":
            return f"(not (= {left} {right}))"
        return f"({formula.operator.replace('==', '=')} {left} {right})"
    if isinstance(formula, Junction):
        return f"({formula.operator} {' '.join(formula_text(f, yaw) for f in formula.operands)})"
    return f"(not {formula_text(formula.operand, yaw)})"


def term_text(term: Term, yaw: float) -> str:
    """The SMT-LIB form of an arithmetic term."""
    if isinstance(term, Variable):
        return number(yaw) if term.name == "yaw" else SOLVER_NAMES[term.name]
    if isinstance(term, Arithmetic):
        return f"({term.operator} {term_text(term.left, yaw)} {term_text(term.right, yaw)})"
    if isinstance(term, Negative):
        return f"(- {term_text(term.operand, yaw)})"
    if isinstance(term, Call):
        return _call_text(term, yaw)
    return exact(term.value)


def exact(value: float) -> str:
    """A user's number as the SMT-LIB decimal it was written as: `encoding.number` rounds to
    10 um, which would turn `size >= 0.000001` into `size >= 0`."""
    text = format(Decimal(repr(abs(value))), "f")
    text = text if "." in text else f"{text}.0"
    return f"(- {text})" if value < 0 else text


def _call_text(call: Call, yaw: float) -> str:
    values = [term_text(argument, yaw) for argument in call.arguments]
    if call.function == "abs":
        return f"(ite (>= {values[0]} 0.0) {values[0]} (- {values[0]}))"
    comparison = "<=" if call.function == "min" else ">="
    result = values[0]
    for value in values[1:]:
        result = f"(ite ({comparison} {result} {value}) {result} {value})"
    return result
