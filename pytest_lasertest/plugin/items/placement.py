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

import abc
import hashlib
from pathlib import Path
from typing import Any

import pytest

from pytest_lasertest.model.plan import AVOID, DirectionPlan, Witness
from pytest_lasertest.model.verify import DIRECTIONS, Direction, Scene, Verification, verify
from pytest_lasertest.pairsfile import Pair, PairsFile
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.plugin.items.base import ItemFailure, PairItem
from pytest_lasertest.plugin.items.control import ControlItem
from pytest_lasertest.plugin.options import unwritable
from pytest_lasertest.reports.failure import (
    PlacementFailure,
    failure_properties,
    failure_report,
    rejection_report,
    search_properties,
    witness_properties,
)
from pytest_lasertest.reports.formats import Artifacts
from pytest_lasertest.search.blame import ChainTried, TraitTried, blame
from pytest_lasertest.search.offsets import OffsetBox
from pytest_lasertest.search.trials import TrialResult, Trials, noted_result
from pytest_lasertest.search.witness import search_witness


class SearchItem(PairItem):
    """An item searching around one witness: a placement one scanner misses (`PlacementItem`)
    or one both read, which the robot must act on (`AvoidItem`)."""

    def __init__(self, *, controller: ControllerChoice, index: int, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.controller = controller
        self.index = index

    @abc.abstractmethod
    def _witness(self) -> tuple[Scene, Witness]:
        """The scene and this item's witness; a skip, reported at the pair's line, without it."""

    def runtest(self) -> None:
        scene, witness = self._witness()
        verification = verify(scene, witness.placement)
        self.user_properties += [
            ("lasertest.seed", self.seed),
            *witness_properties(witness, verification),
        ]
        if not verification.holds():
            self._reject(witness, verification)
        self._skip_if_the_control_fails()
        self._search(scene, witness)

    def _skip_if_the_control_fails(self) -> None:
        """A candidate that fails without any obstacle fails everywhere, whatever the baseline
        does: the control item reports it, and this item says so in one line."""
        control = self.lasertest.control_drive(self.spec, self.pair, self.controller)
        if not control.candidate.passed:
            raise pytest.skip.Exception(
                f"the candidate already fails without any obstacle: see "
                f"{ControlItem.name_of(self.pair)}",
                _use_item_location=True,
            )

    def _search(self, scene: Scene, witness: Witness) -> None:
        """Perturb the witness with Hypothesis; a failure shrinks and fails the item."""
        options = self.options
        found = search_witness(
            self.lasertest.setting(self.spec, self.pair, self.controller),
            scene,
            witness,
            self.spec.settings.obstacle_sizes,
            options.policy,
            options.budget,
            key=self.nodeid,
            seed=self._seed(),
            database=self._database(),
        )
        # Hypothesis's pytest plugin shows this under --hypothesis-show-statistics.
        self.hypothesis_statistics = found.statistics
        self.user_properties += [
            ("lasertest.controller", self.controller.name),
            *search_properties(found.box, found.trials),
        ]
        if found.failure is not None:
            failed = found.failure
            notes = tuple(str(note) for note in getattr(failed, "__notes__", ()))
            self._fail(witness, failed.result, found.trials, found.box, notes)
        noted = noted_result(found.trials)
        if noted is not None:
            self._fail(witness, noted, found.trials, found.box, ())

    def _fail(
        self,
        witness: Witness,
        result: TrialResult,
        trials: Trials,
        box: OffsetBox,
        notes: tuple[str, ...],
    ) -> None:
        """Record the failure (the minimal one the policy fails, or one it notes), write its
        artifacts, and fail the item with it."""
        self.user_properties += failure_properties(result)
        failure = PlacementFailure(
            self.nodeid,
            self.spec,
            self.pair,
            self.controller,
            witness,
            result,
            trials,
            box,
            notes,
            self.seed,
            self.options.recorded(self.path),
            # Hypothesis drops what it cannot save without a word: say so, or the rerun misleads.
            unwritable(self._database()),
            *self._blame(result),
        )
        artifacts = self._write_failure(failure)
        report = failure_report(failure, self.replay, artifacts)
        raise self.failure(result.classification, report, artifacts)

    def _blame(self, result: TrialResult) -> tuple[tuple[TraitTried, ...], ChainTried | None]:
        """The driver traits and the scan filter chain tried at a regression's placement: only
        a regression is the change's doing, and only then may a trait or the chain be to blame."""
        if result.classification != "regression":
            return (), None
        setting = self.lasertest.setting(self.spec, self.pair, self.controller)
        return blame(setting, result.placement.obstacle)

    def _reject(self, witness: Witness, verification: Verification) -> None:
        """Fail the item with the witness the solver should not have returned."""
        artifacts = Artifacts()
        options = self.options
        if options.artifacts is not None:
            from pytest_lasertest.artifacts.evidence import (
                evidence_header,
                write_rejection_evidence,
            )

            header = evidence_header(self.nodeid, self.spec, self.pair, options.recorded(self.path))
            artifacts = write_rejection_evidence(
                options.artifacts, self.nodeid, witness, verification, header
            )
        report = rejection_report(self.pair, witness, verification, self.replay, artifacts)
        raise ItemFailure(report, artifacts.written)

    def _database(self) -> Path:
        """Where Hypothesis keeps the failures it found, to replay them first next run."""
        return self.config.rootpath / ".hypothesis" / "examples"

    def _seed(self) -> int:
        """The search's seed: the run's, made the item's own by its node id."""
        digest = hashlib.sha256(f"{self.seed}:{self.nodeid}".encode()).digest()
        return int.from_bytes(digest[:4], "big")

    def _write_failure(self, failure: PlacementFailure) -> Artifacts:
        """The failure's artifacts, if the run asked for them."""
        if self.options.artifacts is None:
            return Artifacts()
        from pytest_lasertest.artifacts.evidence import write_evidence

        return write_evidence(self.options.artifacts, failure)


class PlacementItem(SearchItem):
    """One witness of one direction of a pair: the obstacle only one of the scanners reads."""

    kind = "placement"

    def __init__(self, *, direction: Direction, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.direction: Direction = direction

    def _witness(self) -> tuple[Scene, Witness]:
        plan = self.lasertest.plan(self.spec, self.pair, self.controller)
        directed = plan.direction(self.direction)
        if directed.status == "unknown":
            self._undecided(directed)
        witness = _witness(directed, self.index)
        if witness is None:
            raise pytest.skip.Exception(skip_reason(directed), _use_item_location=True)
        return plan.scene, witness

    def _undecided(self, plan: DirectionPlan) -> None:
        """Fail the direction's first item, and skip the others pointing at it: a direction
        Z3 could not decide is neither a pass nor a skip, which CI would read as one."""
        first = f"{self.pair.name}[{self.direction}-0]"
        if self.index > 0:
            raise pytest.skip.Exception(f"undecided: see {first}", _use_item_location=True)
        raise ItemFailure(undecided_report(self.path, first, plan.explanation))


class AvoidItem(SearchItem):
    """One placement both scanners read that the robot must act on: partly in its way, so that it
    steers round it, or beside it, read too near by a candidate with a larger range_min. A fault
    in the software reading the new scanner shows here (`model/avoid.py`)."""

    kind = "placement"

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.add_marker("avoid")

    def _witness(self) -> tuple[Scene, Witness]:
        # Before the baseline drives past the placements: without an obstacle it must pass.
        self._skip_if_the_control_fails()
        session = self.lasertest
        witnesses = session.avoid(self.spec, self.pair, self.controller)
        if self.index >= len(witnesses):
            raise pytest.skip.Exception(
                f"only {len(witnesses)} of the placements to steer round on this route are "
                "passed by the baseline robot",
                _use_item_location=True,
            )
        return session.scene(self.spec, self.pair, self.controller), witnesses[self.index]


def placement_items(
    parent: pytest.File, spec: PairsFile, pair: Pair, controller: ControllerChoice
) -> list[pytest.Item]:
    """The pair's items, `PAIR[avoid-INDEX]` then `PAIR[DIRECTION-INDEX]`: they depend on the
    YAML alone, never on Z3."""
    indices = range(spec.settings.witnesses)
    common = {"spec": spec, "pair": pair, "controller": controller}
    avoid: list[pytest.Item] = [
        AvoidItem.from_parent(parent, name=f"{pair.name}[{AVOID}-{index}]", index=index, **common)
        for index in indices
    ]
    return avoid + [
        PlacementItem.from_parent(
            parent,
            name=f"{pair.name}[{direction}-{index}]",
            direction=direction,
            index=index,
            **common,
        )
        for direction in DIRECTIONS
        for index in indices
    ]


def undecided_report(path: Path, name: str, explanation: str) -> str:
    """Why an undecided direction fails, and what to do about it."""
    return (
        f"{name}: undecided. The solver neither found a placement for this direction nor "
        "proved that none exists, so the gate cannot say whether the change is safe here.\n"
        f"  {explanation}\n"
        f"  Fix: raise `settings: solver_rlimit:` in {path.name} above the rlimit named above "
        "(each tenfold can cost up to ten times the planning time), or shorten the route to the "
        "stretch that matters; `lasertest plan` shows the verdict without driving."
    )


def skip_reason(plan: DirectionPlan) -> str:
    """Why a direction has no witness with some index: its status and the search's explanation."""
    if plan.status == "sat":
        return plan.explanation or f"only {len(plan.witnesses)} diverse witnesses found"
    return f"{plan.status}: {plan.explanation}"


def _witness(plan: DirectionPlan, index: int) -> Witness | None:
    return next((witness for witness in plan.witnesses if witness.index == index), None)
