"""The run cache a session keeps (`search/drives.py`): no scenario is simulated twice, and
memory stays bounded."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from pytest_lasertest.nav.reactive import ReactiveController
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.pairsfile.scan_filters import with_scan_filters
from pytest_lasertest.search import drives
from pytest_lasertest.search.drives import RunCache, scenario
from tests.helpers import EXAMPLES
from tests.helpers.laser_filters import chain_of

SPEC = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
RANGE = """\
scan_filter_chain:
- {{name: r, type: laser_filters/LaserScanRangeFilter, params: {{lower_threshold: {lower}}}}}
"""
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


def test_one_controller_behind_two_scan_filter_chains_drives_two_scenarios(
    simulated: list[object], tmp_path: Path
) -> None:
    # Two pairs files of one robot and world, each with its own chain, share the session's
    # cache: the chain is part of what a run is.
    chains = []
    for name, lower in (("near", 0.1), ("far", 0.3)):
        (tmp_path / name).mkdir()
        chains.append(chain_of(tmp_path / name, RANGE.format(lower=lower)))
    cache, world = RunCache(), scenario(SPEC, PROFILE, (), seed=1)
    for chain in chains:
        cache.run(world, with_scan_filters(REACTIVE, chain), None)
    cache.run(world, with_scan_filters(REACTIVE, chains[0]), None)
    assert len(simulated) == 2


def test_the_least_recently_used_run_is_dropped_beyond_the_size(simulated: list[object]) -> None:
    cache = RunCache(size=2)
    worlds = [scenario(SPEC, PROFILE, (), seed=seed) for seed in range(3)]
    for world in worlds:
        cache.run(world, REACTIVE, None)
    assert not cache.knows(worlds[0], REACTIVE)
    assert cache.knows(worlds[1], REACTIVE)
    assert cache.knows(worlds[2], REACTIVE)
