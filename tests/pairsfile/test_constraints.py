"""The placement-constraint grammar: what it accepts, and how it refuses everything else."""

from __future__ import annotations

import math
import os
import re
from pathlib import Path

import pytest

from pytest_lasertest.inputs.errors import Location, SpecError
from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.pairsfile.constraints import (
    Arithmetic,
    Call,
    Comparison,
    Formula,
    Junction,
    Negative,
    Not,
    Number,
    Variable,
    admits,
    obstacle_variables,
    parse_formula,
    read_constraint,
)

SPEC = Path("f.lasertest.yaml")


def node(value: object) -> SpecNode:
    return SpecNode(value, Location(SPEC, 7), "constraints[0]")


def refusal(value: object) -> SpecError:
    with pytest.raises(SpecError) as refused:
        read_constraint(node(value))
    return refused.value


X, Y = Variable("x"), Variable("y")


@pytest.mark.parametrize(
    ("text", "formula"),
    [
        ("x > 2", Comparison(">", X, Number(2.0))),
        (
            "0 < x < 5",
            Junction("and", (Comparison("<", Number(0.0), X), Comparison("<", X, Number(5.0)))),
        ),
        (
            "size <= 0.3 and abs(y) < 1",
            Junction(
                "and",
                (
                    Comparison("<=", Variable("size"), Number(0.3)),
                    Comparison("<", Call("abs", (Y,)), Number(1.0)),
                ),
            ),
        ),
        (
            "not (x > 1) or yaw == pi",
            Junction(
                "or",
                (
                    Not(Comparison(">", X, Number(1.0))),
                    Comparison("==", Variable("yaw"), Number(math.pi)),
                ),
            ),
        ),
        (
            "2 * x - y / 4 >= -1",
            Comparison(
                ">=",
                Arithmetic("-", Arithmetic("*", Number(2.0), X), Arithmetic("/", Y, Number(4.0))),
                Negative(Number(1.0)),
            ),
        ),
        ("min(x, y) > 0", Comparison(">", Call("min", (X, Y)), Number(0.0))),
        ("-x < 3", Comparison("<", Negative(X), Number(3.0))),
        ("height != 0.5", Comparison("!=", Variable("height"), Number(0.5))),
    ],
)
def test_a_linear_condition_on_the_obstacle_is_read_as_written(text: str, formula: Formula) -> None:
    assert parse_formula(text) == formula


def test_a_constraint_keeps_its_text_and_where_it_was_written() -> None:
    constraint = read_constraint(node("x > 2"))

    assert constraint.text == "x > 2"
    assert constraint.location == Location(SPEC, 7)
    assert constraint.formula == Comparison(">", X, Number(2.0))


LONG = " or ".join(["x > 1"] * 67) + " "


@pytest.mark.parametrize(
    ("value", "problem", "fix"),
    [
        ("__import__('os').system('true')", "is not a condition", "compare it"),
        ("__import__('os').system('true') > 0", "is not allowed", "the functions are abs"),
        ("x.real > 0", r"`x\.real` is not allowed", "the variables x, y, yaw, size, height"),
        ("x * y > 1", "nonlinear", "multiply variables by numbers only"),
        ("1 / x > 0", "nonlinear", "divide by numbers only"),
        ("x / 0 > 1", "division by zero", "non-zero number"),
        ("z > 1", "unknown name `z`", "the variables are x (m), y (m), yaw (rad)"),
        ("xx > 1", "unknown name `xx`", "did you mean `x`?"),
        ("x + 2", r"`x \+ 2` is not a condition", "compare it"),
        ("x >", "not an expression", "write comparisons such as `x > 2`"),
        ("'a' < x", "'a' is not a number", "write a number"),
        ("x in [1, 2]", "not allowed", "use numbers"),
        ("x in y", "the comparison `in` is not allowed", "use <, <=, >, >=, == or !="),
        ("x is not y", "the comparison `is not` is not allowed", "use <, <=, >, >=, == or !="),
        ("lambda: 1", "is not a condition", "compare it"),
        ("abs(x, y) > 0", r"abs\(\) takes exactly one", "abs(y)"),
        ("max(x) > 0", r"max\(\) takes at least two", "max("),
        ("x > 1e999", "not a finite number", "finite number"),
        ("True < x", "True is not a number", "write a number"),
        ("x ** 2 > 1", r"`x \*\* 2` is not allowed", "+ - * /"),
        (LONG, "600 characters long", "keep it under 500"),
        (3, "expected a condition as text, got 3", 'write it quoted, e.g. "x > 2"'),
        ("  ", "expected a condition as text", 'write it quoted, e.g. "x > 2"'),
    ],
)
def test_anything_outside_the_grammar_is_refused_at_its_line_and_field_with_a_fix(
    value: object, problem: str, fix: str
) -> None:
    error = refusal(value)

    assert error.location == Location(SPEC, 7)
    assert error.field == "constraints[0]"
    assert str(error).startswith("f.lasertest.yaml:7: constraints[0]: ")
    assert re.search(problem, error.problem), error.problem
    assert fix in error.fix


def test_an_overlong_constraint_is_refused_for_its_length_alone() -> None:
    assert len(LONG) == 600
    assert parse_formula(LONG) == Junction("or", (Comparison(">", X, Number(1.0)),) * 67)


def test_a_constraint_is_never_evaluated(monkeypatch: pytest.MonkeyPatch) -> None:
    calls: list[str] = []
    monkeypatch.setattr(os, "system", calls.append)

    for text in ("__import__('os').system('true')", "__import__('os').system('true') > 0"):
        refusal(text)

    assert calls == []


def test_the_fix_offered_for_a_one_argument_max_is_itself_accepted() -> None:
    fix = refusal("max(x) > 0").fix
    example = fix.removeprefix("write e.g. ")

    parse_formula(f"{example} > 0")


def test_a_huge_integer_literal_is_refused_as_not_finite() -> None:
    error = refusal("x > 1" + "0" * 400)

    assert "finite" in error.problem


@pytest.mark.parametrize("text", ["x / -0 > 1", "x / (1 - 1) > 0"])
def test_dividing_by_an_expression_equal_to_zero_is_refused(text: str) -> None:
    assert "division by zero" in refusal(text).problem


@pytest.mark.parametrize(
    ("text", "x", "y", "admitted"),
    [
        ("x > 2 and abs(y) < 1", 2.5, -0.5, True),
        ("x > 2 and abs(y) < 1", 2.5, -1.5, False),
        ("not (x < 1 or y > 3)", 1.0, 3.0, True),
        ("max(x, 2 * y) <= 4 - 1", 3.0, 1.5, True),
        ("max(x, 2 * y) <= 4 - 1", 3.0, 1.6, False),
        ("x / 2 != -y", 2.0, -1.0, False),
    ],
)
def test_a_placement_is_admitted_only_if_it_meets_every_constraint(
    text: str, x: float, y: float, admitted: bool
) -> None:
    constraints = (read_constraint(node(text)), read_constraint(node("height >= 0.1")))
    variables = {"x": x, "y": y, "yaw": 0.0, "size": 0.1, "height": 0.5}
    assert admits(constraints, variables) is admitted


def test_a_cylinders_size_is_its_diameter_and_a_boxs_its_longer_side() -> None:
    from pytest_lasertest.model.obstacles import Box, Cylinder

    assert obstacle_variables(Cylinder(1.0, 2.0, 0.1, 0.5))["size"] == pytest.approx(0.2)
    box = obstacle_variables(Box(1.0, 2.0, 0.3, 0.4, 0.2, 0.5))
    assert (box["size"], box["yaw"]) == (0.4, 0.3)
