"""The budget profiles: how many examples a placement item tries, and how hard it shrinks."""

from __future__ import annotations

from pytest_lasertest.search.budgets import BUDGETS


def test_ci_keeps_the_database_budget_small_and_explains_nothing() -> None:
    assert BUDGETS["ci"].examples < BUDGETS["nightly"].examples
    assert not BUDGETS["ci"].explain
    assert BUDGETS["triage"].shrink_simulations > BUDGETS["dev"].shrink_simulations
