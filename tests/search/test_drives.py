"""The run cache a session keeps (`search/drives.py`): no scenario is simulated twice, and
memory stays bounded."""

from __future__ import annotations

from typing import Any

import pytest

from pytest_lasertest.nav.reactive import ReactiveController
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.search import drives
from pytest_lasertest.search.drives import RunCache, scenario
from tests.helpers import EXAMPLES

SPEC = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
PROFILE = SPEC.pairs[0].baseline.profile
REACTIVE = ControllerChoice("reactive", "the default", ReactiveController)


@pytest.fixture
def simulated(monkeypatch: pytest.MonkeyPatch) -> list[object]:
    """The scenarios the cache simulates, each answered with a stand-in run."""
    runs: list[object] = []

    def run_scenario(world: object, factory: object, client: object) -> Any:
        runs.append(world)
        return object()

    monkeypatch.setattr(drives, "run_scenario", run_scenario)
    return runs


def test_a_scenario_is_simulated_once_and_then_found(simulated: list[object]) -> None:
    cache = RunCache()
    world = scenario(SPEC, PROFILE, (), seed=1)
    first = cache.run(world, REACTIVE, client=None)
    assert cache.knows(world, REACTIVE)
    assert cache.run(scenario(SPEC, PROFILE, (), seed=1), REACTIVE, None) is first
    assert len(simulated) == 1


def test_another_seed_or_controller_is_another_scenario(simulated: list[object]) -> None:
    cache = RunCache()
    cache.run(scenario(SPEC, PROFILE, (), seed=1), REACTIVE, None)
    cache.run(scenario(SPEC, PROFILE, (), seed=2), REACTIVE, None)
    other = ControllerChoice("reactive", "from other.lasertest.yaml:3", ReactiveController)
    cache.run(scenario(SPEC, PROFILE, (), seed=1), other, None)
    assert len(simulated) == 3


def test_the_least_recently_used_run_is_dropped_beyond_the_size(simulated: list[object]) -> None:
    cache = RunCache(size=2)
    worlds = [scenario(SPEC, PROFILE, (), seed=seed) for seed in range(3)]
    for world in worlds:
        cache.run(world, REACTIVE, None)
    assert not cache.knows(worlds[0], REACTIVE)
    assert cache.knows(worlds[1], REACTIVE)
    assert cache.knows(worlds[2], REACTIVE)
