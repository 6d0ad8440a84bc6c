"""User constraints on obstacle placements, parsed with `ast` into a small expression tree.

A constraint is a condition such as `x > 2` or `size <= 0.3 and abs(y) < 1` over the
obstacle's centre `x`, `y` (m, world frame), `yaw` (rad), `size` (m) and `height` (m).
It is linear: numbers may multiply or divide a variable, variables may not multiply each other.
Nothing of the text is evaluated; anything outside this grammar is refused with the reason.
The solver's witnesses meet the constraints by construction; `admits` checks a placement made
or moved elsewhere against the parsed tree.
"""

from __future__ import annotations

import ast
import difflib
import math
import operator
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Literal

from pytest_lasertest.inputs.errors import Location
from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.model.obstacles import Cylinder, Obstacle

VARIABLES = {
    "x": "m",
    "y": "m",
    "yaw": "rad",
    "size": "m",
    "height": "m",
}
CONSTANTS = {"pi": math.pi}
FUNCTIONS = ("abs", "min", "max")
MAX_LENGTH = 500  # characters; a placement constraint is a line, not a program
# Every constraint goes into every solver query of the pairs file.
MAX_CONSTRAINTS = 100
# The solver reasons about metres and radians near the route: a number beyond this is a typo,
# and one smaller than this (but not zero) is below anything it can tell apart.
MAX_NUMBER = 1e6
MIN_NUMBER = 1e-6

ArithmeticOperator = Literal["+", "-", "*", "/"]
ComparisonOperator = Literal["<", "<=", ">", ">=", "==", "!="]
_ARITHMETIC: dict[type[ast.operator], ArithmeticOperator] = {
    ast.Add: "+",
    ast.Sub: "-",
    ast.Mult: "*",
    ast.Div: "/",
}
_REFUSED_COMPARISON = {ast.In: "in", ast.NotIn: "not in", ast.Is: "is", ast.IsNot: "is not"}
_COMPARISON: dict[type[ast.cmpop], ComparisonOperator] = {
    ast.Lt: "<",
    ast.LtE: "<=",
    ast.Gt: ">",
    ast.GtE: ">=",
    ast.Eq: "==",
    ast.NotEq: "!=",
}


@dataclass(frozen=True)
class Number:
    value: float


@dataclass(frozen=True)
class Variable:
    name: str


@dataclass(frozen=True)
class Arithmetic:
    operator: ArithmeticOperator
    left: Term
    right: Term


@dataclass(frozen=True)
class Negative:
    operand: Term


@dataclass(frozen=True)
class Call:
    function: Literal["abs", "min", "max"]
    arguments: tuple[Term, ...]


@dataclass(frozen=True)
class Comparison:
    operator: ComparisonOperator
    left: Term
    right: Term


@dataclass(frozen=True)
class Junction:
    operator: Literal["and", "or"]
    operands: tuple[Formula, ...]


@dataclass(frozen=True)
class Not:
    operand: Formula


Term = Number | Variable | Arithmetic | Negative | Call
Formula = Comparison | Junction | Not


@dataclass(frozen=True)
class Constraint:
    """One user constraint: its text as written, where, and its parsed formula."""

    text: str
    location: Location
    formula: Formula


class _Refused(Exception):
    """A part of the expression outside the grammar; the message says which and why."""

    def __init__(self, problem: str, fix: str) -> None:
        super().__init__(problem)
        self.problem = problem
        self.fix = fix


def read_constraints(node: SpecNode) -> tuple[Constraint, ...]:
    """Every constraint of a `constraints:` list."""
    items = node.items(what="constraints")
    if len(items) > MAX_CONSTRAINTS:
        raise node.error(
            f"{len(items)} constraints are more than the {MAX_CONSTRAINTS} the gate accepts: "
            "every one goes into every solver query",
            "join conditions with `and` in fewer constraints",
        )
    return tuple(read_constraint(item) for item in items)


def read_constraint(node: SpecNode) -> Constraint:
    """One constraint, or a SpecError naming what is not allowed in it."""
    text = node.text(what="a condition as text", fix='write it quoted, e.g. "x > 2"')
    if len(text) > MAX_LENGTH:
        raise node.error(
            f"the constraint is {len(text)} characters long", f"keep it under {MAX_LENGTH}"
        )
    try:
        return Constraint(text, node.location, parse_formula(text))
    except _Refused as refused:
        raise node.error(f"in {text!r}: {refused.problem}", refused.fix) from None


def parse_formula(text: str) -> Formula:
    """The formula `text` states; raises _Refused for anything else."""
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as error:
        raise _Refused(
            f"this is not an expression ({error.msg})",
            "write comparisons such as `x > 2`, joined with `and`, `or`, `not`",
        ) from None
    return _formula(tree.body)


def _formula(node: ast.expr) -> Formula:
    if isinstance(node, ast.Compare):
        return _comparison(node)
    if isinstance(node, ast.BoolOp):
        operator: Literal["and", "or"] = "and" if isinstance(node.op, ast.And) else "or"
        return Junction(operator, tuple(_formula(value) for value in node.values))
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not):
        return Not(_formula(node.operand))
    raise _Refused(
        f"`{ast.unparse(node)}` is not a condition",
        "compare it with something, e.g. `x > 2` or `abs(y) <= 1`",
    )


def _comparison(node: ast.Compare) -> Formula:
    terms = [_term(node.left), *(_term(right) for right in node.comparators)]
    parts = []
    for op, left, right in zip(node.ops, terms, terms[1:], strict=False):
        if type(op) not in _COMPARISON:
            raise _Refused(
                f"the comparison `{_REFUSED_COMPARISON.get(type(op), type(op).__name__)}` is not "
                "allowed",
                "use <, <=, >, >=, == or !=",
            )
        parts.append(Comparison(_COMPARISON[type(op)], left, right))
    return parts[0] if len(parts) == 1 else Junction("and", tuple(parts))


def _term(node: ast.expr) -> Term:
    if isinstance(node, ast.Constant):
        return _number(node.value)
    if isinstance(node, ast.Name):
        return _name(node.id)
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd):
        operand = _term(node.operand)
        return Negative(operand) if isinstance(node.op, ast.USub) else operand
    if isinstance(node, ast.BinOp) and type(node.op) in _ARITHMETIC:
        return _arithmetic(_ARITHMETIC[type(node.op)], _term(node.left), _term(node.right))
    if isinstance(node, ast.Call):
        return _call(node)
    raise _Refused(
        f"`{ast.unparse(node)}` is not allowed",
        f"use numbers, the variables {', '.join(VARIABLES)}, pi, + - * /, and "
        f"{', '.join(FUNCTIONS)}()",
    )


def _number(value: object) -> Number:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise _Refused(f"{value!r} is not a number", "write a number, e.g. 0.3")
    try:
        number = float(value)
    except OverflowError:
        number = math.inf
    if not math.isfinite(number):
        raise _Refused(f"{str(value)[:20]} is not a finite number", "write a finite number")
    if abs(number) > MAX_NUMBER or 0.0 < abs(number) < MIN_NUMBER:
        raise _Refused(
            f"{number:g} is outside what the solver tells apart: the variables are metres and "
            f"radians near the route, and numbers run from {MIN_NUMBER:g} to {MAX_NUMBER:g}",
            f"write a number of at most {MAX_NUMBER:g} and at least {MIN_NUMBER:g} (or 0)",
        )
    return Number(number)


def _name(name: str) -> Term:
    if name in VARIABLES:
        return Variable(name)
    if name in CONSTANTS:
        return Number(CONSTANTS[name])
    close = difflib.get_close_matches(name, [*VARIABLES, *CONSTANTS], n=1, cutoff=0.6)
    hint = f"did you mean `{close[0]}`? " if close else ""
    raise _Refused(
        f"unknown name `{name}`",
        f"{hint}the variables are "
        + ", ".join(f"{variable} ({unit})" for variable, unit in VARIABLES.items()),
    )


def _arithmetic(operator: ArithmeticOperator, left: Term, right: Term) -> Term:
    if operator == "*" and _has_variable(left) and _has_variable(right):
        raise _Refused(
            "variables multiply each other, which makes the constraint nonlinear",
            "multiply variables by numbers only",
        )
    if operator == "/" and _has_variable(right):
        raise _Refused(
            "dividing by a variable makes the constraint nonlinear", "divide by numbers only"
        )
    if operator == "/" and _value(right) == 0:
        raise _Refused("division by zero", "divide by a non-zero number")
    return Arithmetic(operator, left, right)


def _call(node: ast.Call) -> Term:
    if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS or node.keywords:
        raise _Refused(
            f"`{ast.unparse(node.func)}(...)` is not allowed",
            f"the functions are {', '.join(FUNCTIONS)}",
        )
    arguments = tuple(_term(argument) for argument in node.args)
    function: Literal["abs", "min", "max"] = node.func.id  # type: ignore[assignment]
    if function == "abs" and len(arguments) != 1:
        raise _Refused("abs() takes exactly one argument", "write e.g. abs(y)")
    if function != "abs" and len(arguments) < 2:
        raise _Refused(f"{function}() takes at least two arguments", f"write e.g. {function}(x, 0)")
    return Call(function, arguments)


def _has_variable(term: Term) -> bool:
    match term:
        case Variable():
            return True
        case Number():
            return False
        case Negative(operand=operand):
            return _has_variable(operand)
        case Arithmetic(left=left, right=right):
            return _has_variable(left) or _has_variable(right)
        case Call(arguments=arguments):
            return any(_has_variable(argument) for argument in arguments)
    return False


def _value(term: Term, variables: Mapping[str, float] | None = None) -> float:
    """The value of a term, its variables at `variables` (none if not given); division by zero
    was refused when it was parsed, and a divisor holds no variable."""
    match term:
        case Number(value=value):
            return value
        case Variable(name=name) if variables is not None:
            return variables[name]
        case Negative(operand=operand):
            return -_value(operand, variables)
        case Arithmetic(operator="+", left=left, right=right):
            return _value(left, variables) + _value(right, variables)
        case Arithmetic(operator="-", left=left, right=right):
            return _value(left, variables) - _value(right, variables)
        case Arithmetic(operator="*", left=left, right=right):
            return _value(left, variables) * _value(right, variables)
        case Arithmetic(operator="/", left=left, right=right):
            return _value(left, variables) / _value(right, variables)
        case Call(function="abs", arguments=arguments):
            return abs(_value(arguments[0], variables))
        case Call(function=function, arguments=arguments):
            values = [_value(argument, variables) for argument in arguments]
            return min(values) if function == "min" else max(values)
    raise ValueError(f"{term} holds a variable")


def admits(constraints: Sequence[Constraint], variables: Mapping[str, float]) -> bool:
    """Whether an obstacle whose x, y (m), yaw (rad), size and height (m) are `variables`
    meets every constraint: the solver's witnesses do by construction; a placement made or
    moved elsewhere (a seed both scanners read, a perturbation) is asked here."""
    return all(_holds(constraint.formula, variables) for constraint in constraints)


def obstacle_variables(obstacle: Obstacle) -> dict[str, float]:
    """The constraint language's variables for an obstacle, as the solver reads them: a
    cylinder's size is its diameter (its yaw 0), a box's its longer side."""
    if isinstance(obstacle, Cylinder):
        size, yaw = 2.0 * obstacle.radius, 0.0
    else:
        size, yaw = max(obstacle.length, obstacle.width), obstacle.yaw
    return {"x": obstacle.x, "y": obstacle.y, "yaw": yaw, "size": size, "height": obstacle.height}


def _holds(formula: Formula, variables: Mapping[str, float]) -> bool:
    match formula:
        case Comparison(operator=relation, left=left, right=right):
            return _COMPARE[relation](_value(left, variables), _value(right, variables))
        case Junction(operator="and", operands=operands):
            return all(_holds(operand, variables) for operand in operands)
        case Junction(operands=operands):
            return any(_holds(operand, variables) for operand in operands)
        case Not(operand=operand):
            return not _holds(operand, variables)
    raise TypeError(formula)


_COMPARE: dict[str, Callable[[float, float], bool]] = {
    "<": operator.lt,
    "<=": operator.le,
    ">": operator.gt,
    ">=": operator.ge,
    "==": operator.eq,
    "!=": operator.ne,
}
