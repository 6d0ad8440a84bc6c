"""One solver query: a witness at a given anchor and shape, the same every time, and verified."""

from __future__ import annotations

import pytest

from pytest_lasertest.model.verify import Direction
from pytest_lasertest.solver.encoding import ObstacleShape
from pytest_lasertest.solver.search import Found, Query, needed_room
from pytest_lasertest.solver.seeds import candidates, seeds
from tests.helpers.paper import SETTINGS, scene


def test_the_same_query_gives_the_same_witness_every_time() -> None:
    query = _query("baseline-misses", 1.0, ObstacleShape("box"))
    first, second = query.run(), query.run()
    assert isinstance(first, Found)
    assert first == second


def _query(direction: Direction, anchor: float, shape: ObstacleShape) -> Query:
    size = scene("size")
    needed = needed_room(shape, SETTINGS)
    (seed, *_) = seeds(size, direction, candidates(size, direction, anchor, needed), needed)
    return Query(size, direction, anchor, seed, shape, SETTINGS)


@pytest.mark.parametrize("shape", ["box", "cylinder"])
def test_a_witness_survives_the_required_margin_in_both_ray_casts(shape: str) -> None:
    obstacle_shape = ObstacleShape("box" if shape == "box" else "cylinder")
    found = _query("candidate-misses", 0.0, obstacle_shape).run()
    assert isinstance(found, Found)
    assert found.verification.holds()
