"""The placement items of a pair: one per direction and witness index, solved when first run,
each searching around its witness.

Collection does no solving: item names come from the pair's name, the two directions and
`settings.witnesses`, so every run and every pytest-xdist worker collects the same items. The
first item of a pair to run plans the pair (`LaserSession.plan`; Z3 is imported only then) and
the plan is kept for the session. Each item then perturbs its witness with Hypothesis
(`search/perturb.py`, imported only then) within the box where it stays discriminating
(`search/offsets.py`), and a failure shrinks toward the witness.
"""

from __future__ import annotations

import hashlib
from pathlib import Path
from typing import Any, cast

import numpy as np
import pytest

from pytest_lasertest.model.plan import DirectionPlan, Witness
from pytest_lasertest.model.verify import DIRECTIONS, Direction, Scene, Verification, verify
from pytest_lasertest.pairsfile import Pair, PairsFile
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.plugin.items.base import ItemFailure, PairItem
from pytest_lasertest.plugin.items.control import ControlItem
from pytest_lasertest.reports.failure import (
    PlacementFailure,
    failure_properties,
    failure_report,
    rejection_report,
    search_properties,
    witness_properties,
)
from pytest_lasertest.search.offsets import OffsetBox, offset_box
from pytest_lasertest.search.trials import TrialFailed, Trials


class PlacementItem(PairItem):
    """One witness of one direction of a pair: the obstacle only one of the scanners reads."""

    kind = "placement"

    def __init__(
        self, *, controller: ControllerChoice, direction: Direction, index: int, **kwargs: Any
    ) -> None:
        super().__init__(**kwargs)
        self.controller = controller
        self.direction: Direction = direction
        self.index = index

    def runtest(self) -> None:
        session = self.lasertest
        plan = session.plan(self.spec, self.pair, self.controller)
        directed = plan.direction(self.direction)
        witness = _witness(directed, self.index)
        if witness is None:
            # Reported at the pair's line, not at this one.
            raise pytest.skip.Exception(skip_reason(directed), _use_item_location=True)
        verification = verify(plan.scene, witness.placement)
        self.user_properties += [
            ("lasertest.seed", self.options.seed),
            *witness_properties(witness, verification),
        ]
        if not verification.holds():
            self._reject(witness, verification)
        if session.control_drive(self.spec, self.pair, self.controller).fails(self.options.policy):
            raise pytest.skip.Exception(
                f"the candidate already fails without any obstacle: see "
                f"{ControlItem.name_of(self.pair)}",
                _use_item_location=True,
            )
        self._search(plan.scene, witness)

    def _search(self, scene: Scene, witness: Witness) -> None:
        """Perturb the witness with Hypothesis; a failure shrinks and fails the item."""
        from pytest_lasertest.search.perturb import search

        options, sizes, seed = self.options, self.spec.settings.obstacle_sizes, self._seed()
        box = offset_box(scene, witness.placement, sizes, np.random.default_rng(seed))
        setting = self.lasertest.setting(self.spec, self.pair, self.controller)
        shrink = options.budget.shrink_simulations
        trials = Trials(setting, scene, witness.placement, sizes, options.policy, shrink)
        database = self.config.rootpath / ".hypothesis" / "examples"
        outcome = search(
            box, trials, TrialFailed, options.budget, key=self.nodeid, seed=seed, database=database
        )
        # Hypothesis's pytest plugin shows this under --hypothesis-show-statistics.
        self.hypothesis_statistics = outcome.statistics
        self.user_properties += [
            ("lasertest.controller", self.controller.name),
            *search_properties(box, trials),
        ]
        if outcome.failure is not None:
            self._fail(witness, cast(TrialFailed, outcome.failure), trials, box)

    def _fail(self, witness: Witness, failed: TrialFailed, trials: Trials, box: OffsetBox) -> None:
        """Record the minimal failure, write its artifacts, and fail the item with it."""
        self.user_properties += failure_properties(failed.result)
        failure = PlacementFailure(
            self.nodeid,
            self.spec,
            self.pair,
            self.controller,
            witness,
            failed.result,
            trials,
            box,
            tuple(str(note) for note in getattr(failed, "__notes__", ())),
            self.options.seed,
            self.options.recorded(),
        )
        raise ItemFailure(failure_report(failure, self.replay, self._write_failure(failure)))

    def _reject(self, witness: Witness, verification: Verification) -> None:
        """Fail the item with the witness the solver should not have returned."""
        artifact = None
        options = self.options
        if options.artifacts is not None:
            from pytest_lasertest.artifacts.evidence import (
                evidence_header,
                write_rejection_evidence,
            )

            header = evidence_header(self.nodeid, self.spec, self.pair, options.recorded())
            artifact = write_rejection_evidence(
                options.artifacts, self.nodeid, witness, verification, header
            )
        report = rejection_report(self.pair, witness, verification, self.replay, artifact)
        raise ItemFailure(report)

    def _seed(self) -> int:
        """The search's seed: the run's, made the item's own by its node id."""
        digest = hashlib.sha256(f"{self.options.seed}:{self.nodeid}".encode()).digest()
        return int.from_bytes(digest[:4], "big")

    def _write_failure(self, failure: PlacementFailure) -> tuple[Path, ...]:
        """The failure's artifacts, if the run asked for them."""
        if self.options.artifacts is None:
            return ()
        from pytest_lasertest.artifacts.evidence import write_evidence

        return write_evidence(self.options.artifacts, failure)


def placement_items(
    parent: pytest.File, spec: PairsFile, pair: Pair, controller: ControllerChoice
) -> list[pytest.Item]:
    """The pair's items, `PAIR[DIRECTION-INDEX]`: they depend on the YAML alone, never on Z3."""
    return [
        PlacementItem.from_parent(
            parent,
            name=f"{pair.name}[{direction}-{index}]",
            spec=spec,
            pair=pair,
            controller=controller,
            direction=direction,
            index=index,
        )
        for direction in DIRECTIONS
        for index in range(spec.settings.witnesses)
    ]


def skip_reason(plan: DirectionPlan) -> str:
    """Why a direction has no witness with some index: its status and the search's explanation."""
    if plan.status == "sat":
        return plan.explanation or f"only {len(plan.witnesses)} diverse witnesses found"
    return f"{plan.status}: {plan.explanation}"


def _witness(plan: DirectionPlan, index: int) -> Witness | None:
    return next((witness for witness in plan.witnesses if witness.index == index), None)
