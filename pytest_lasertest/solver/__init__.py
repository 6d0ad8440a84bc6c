"""The only package that imports z3; its objects never leave it."""

from __future__ import annotations

from pytest_lasertest.solver.backend import self_test

__all__ = ["self_test"]
