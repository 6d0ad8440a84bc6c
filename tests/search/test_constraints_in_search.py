"""The pairs file's constraints hold wherever the search places an obstacle, not only where the
solver does: the seeds both scanners read are kept only if they meet them, and a perturbation
that leaves them is rejected before it is driven."""

from __future__ import annotations

import dataclasses

import pytest

from pytest_lasertest.inputs.errors import Location
from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.pairsfile.constraints import read_constraint
from pytest_lasertest.search.offsets import Offset, Untested
from pytest_lasertest.search.plans import avoid_for
from pytest_lasertest.search.trials import OUTSIDE_CONSTRAINTS, Setting, Trials
from tests.helpers.paper import PAPER, scene


def constrained(*texts: str) -> object:
    nodes = [SpecNode(text, Location(PAPER.path, 9), "constraints[0]") for text in texts]
    return dataclasses.replace(PAPER, constraints=tuple(map(read_constraint, nodes)))


def test_seeds_both_scanners_read_are_kept_only_where_the_constraints_allow() -> None:
    free = avoid_for(PAPER, scene("size"))
    assert any(witness.placement.obstacle.y < 0.0 for witness in free)
    kept = avoid_for(constrained("y >= 0"), scene("size"))  # type: ignore[arg-type]
    assert kept
    assert all(witness.placement.obstacle.y >= 0.0 for witness in kept)
    assert len(kept) < len(free)


def test_a_perturbation_that_leaves_the_constraints_is_rejected_and_never_driven() -> None:
    spec = constrained("x < 100")
    pair = PAPER.pairs[1]
    witness = avoid_for(PAPER, scene(pair.name))[0]
    setting = Setting(spec, pair, PAPER.controller, 0, None, None)  # type: ignore[arg-type]
    trials = Trials(setting, scene(pair.name), witness.placement, (0.05, 1.0), "candidate", 24)
    with pytest.raises(Untested, match=OUTSIDE_CONSTRAINTS):
        trials(Offset(x=200.0))
    assert (trials.simulations, trials.rejected) == (0, 1)
