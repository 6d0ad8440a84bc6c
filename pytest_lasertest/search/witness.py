"""The search around one witness: the box of offsets in which it stays discriminating, then
Hypothesis drawing from it, each offset a trial, a failure shrunk toward the witness.

A placement item runs one of these; so does `benchmarks/fault_finding.py`, outside pytest. The
placements both scanners read, which the robot must act on, are searched only where the baseline
robot passes.
Hypothesis is imported on the first search (`perturb.py`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from pytest_lasertest.model.plan import Witness
from pytest_lasertest.model.policy import Policy
from pytest_lasertest.model.verify import Scene
from pytest_lasertest.search.budgets import Budget
from pytest_lasertest.search.offsets import OffsetBox, offset_box
from pytest_lasertest.search.trials import Setting, TrialFailed, Trials


@dataclass(frozen=True)
class WitnessSearch:
    """What one search tried and found."""

    box: OffsetBox
    trials: Trials
    failure: TrialFailed | None  # the minimal failure the policy fails, if any
    statistics: str  # Hypothesis's own description, for --hypothesis-show-statistics


def search_witness(
    setting: Setting,
    scene: Scene,
    witness: Witness,
    sizes: tuple[float, float],  # m, the thinnest and the widest obstacle the search may place
    policy: Policy,
    budget: Budget,
    *,
    key: str,
    seed: int,
    database: Path | None,
) -> WitnessSearch:
    """Search around `witness` with `budget`; `key` files its failures in `database`."""
    from pytest_lasertest.search.perturb import search

    box = offset_box(scene, witness.placement, sizes, np.random.default_rng(seed))
    shrink = budget.shrink_simulations
    trials = Trials(setting, scene, witness.placement, sizes, policy, shrink)
    outcome = search(box, trials, TrialFailed, budget, key=key, seed=seed, database=database)
    failure = outcome.failure if isinstance(outcome.failure, TrialFailed) else None
    return WitnessSearch(box, trials, failure, outcome.statistics)


def passed_by_baseline(
    setting: Setting, witnesses: tuple[Witness, ...], count: int
) -> tuple[Witness, ...]:
    """The first `count` witnesses past which the baseline robot drives, and passes, numbered
    anew: a placement both robots fail tells nothing of the change. Each drive goes through the
    session's cache."""
    passed: list[Witness] = []
    for witness in witnesses:
        if len(passed) == count:
            break
        if setting.drive(setting.pair.baseline.profile, witness.placement).passed:
            passed.append(dataclasses.replace(witness, index=len(passed)))
    return tuple(passed)
