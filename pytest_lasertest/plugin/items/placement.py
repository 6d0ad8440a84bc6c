"""The placement items of a pair: one per direction and witness index, solved when first run,
each searching around its witness.

Collection does no solving: item names come from the pair's name, the two directions and
`settings.witnesses`, so every run and every pytest-xdist worker collects the same items. The
first item of a pair to run plans the pair (Z3, imported only then) and the plan is kept for the
session; planning is deterministic, so workers that plan the same pair find the same witnesses.
Each item then perturbs its witness with Hypothesis (`perturb.py`, imported only then) within
the box where it stays discriminating (`offsets.py`), and a failure shrinks toward the witness.
"""

from __future__ import annotations

import dataclasses
import hashlib
from pathlib import Path
from typing import Any, cast

import numpy as np
import pytest
from _pytest._code.code import TerminalRepr, TracebackStyle

from pytest_lasertest.artifacts.files import artifact_path, write_json
from pytest_lasertest.plugin.items.control import CONTROL, control_drive, physics_client, run_cache
from pytest_lasertest.search.drives import PairDrive, solver_path
from pytest_lasertest.reports.failure import (
    MEANINGS,
    beam_lines,
    failure_properties,
    margin_line,
    margins_text,
    oracle_lines,
    search_line,
    search_properties,
    trial_lines,
)
from pytest_lasertest.search.offsets import OffsetBox, offset_box
from pytest_lasertest.plugin.items.base import PairItem
from pytest_lasertest.model.verify import (
    DIRECTIONS,
    REQUIRED_MARGIN,
    Direction,
    DirectionPlan,
    PairPlan,
    Scene,
    Verification,
    Witness,
    verify,
)
from pytest_lasertest.reports.plan import DETECTED_BY, describe_obstacle, witness_json
from pytest_lasertest.pairsfile import Pair, PairsFile
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.inputs.errors import display_path
from pytest_lasertest.search.trials import Setting, TrialFailed, TrialResult, Trials

REPRO_SUFFIX = ".lasertest.yaml"

# The session's plans, by (pairs file path, pair name): the items of a pair plan it once.
PLANS_KEY = pytest.StashKey[dict[tuple[Path, str], PairPlan]]()


class VerificationFailed(Exception):
    """The exact ray cast rejects a witness the solver returned: a bug in the solver."""

    def __init__(self, witness: Witness, verification: Verification, artifact: Path | None) -> None:
        super().__init__(witness.id)
        self.witness = witness
        self.verification = verification
        self.artifact = artifact


class PlacementFailed(Exception):
    """The search found a perturbation of the witness that the policy fails, and shrank it."""

    def __init__(
        self,
        witness: Witness,
        result: TrialResult,
        trials: Trials,
        box: OffsetBox,
        artifacts: tuple[Path, ...],
        notes: tuple[str, ...],
    ) -> None:
        super().__init__(witness.id)
        self.witness = witness
        self.result = result
        self.trials = trials
        self.box = box
        self.artifacts = artifacts
        self.notes = notes


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
        plan = self._pair_plan()
        directed = plan.direction(self.direction)
        witness = _witness(directed, self.index)
        if witness is None:
            # Reported at the pair's line, not at this one.
            raise pytest.skip.Exception(skip_reason(directed), _use_item_location=True)
        verification = verify(plan.scene, witness.placement)
        self._record(witness, verification)
        if not verification.holds():
            artifact = self._write_artifact(witness, verification)
            raise VerificationFailed(witness, verification, artifact)
        if self._control().fails(self.options.policy):
            raise pytest.skip.Exception(
                f"the candidate already fails without any obstacle: see {self.pair.name}"
                f"[{CONTROL}]",
                _use_item_location=True,
            )
        self._search(plan.scene, witness)

    def _search(self, scene: Scene, witness: Witness) -> None:
        """Perturb the witness with Hypothesis; a failure shrinks and fails the item."""
        from pytest_lasertest.search.perturb import search

        budget, settings = self.options.budget, self.spec.settings
        sizes = (settings.min_obstacle_size, settings.max_obstacle_size)
        seed = self._seed()
        box = offset_box(scene, witness.placement, sizes, np.random.default_rng(seed))
        trials = Trials(
            self._setting(),
            scene,
            witness.placement,
            sizes,
            self.options.policy,
            budget.shrink_simulations,
        )
        outcome = search(
            box,
            trials,
            TrialFailed,
            budget,
            key=self.nodeid,
            seed=seed,
            database=self._database(),
        )
        # Hypothesis's pytest plugin shows this under --hypothesis-show-statistics.
        self.hypothesis_statistics = outcome.statistics
        self.user_properties += [
            ("lasertest.controller", self.controller.name),
            *search_properties(box, trials),
        ]
        if outcome.failure is not None:
            self._fail(witness, cast(TrialFailed, outcome.failure), trials, box)

    def _fail(self, witness: Witness, failure: TrialFailed, trials: Trials, box: OffsetBox) -> None:
        """Record the minimal failure, write its artifacts, and fail the item with it."""
        result = failure.result
        self.user_properties += failure_properties(result)
        paths = self._write_failure(witness, result, trials, box)
        notes = tuple(str(note) for note in getattr(failure, "__notes__", ()))
        raise PlacementFailed(witness, result, trials, box, paths, notes)

    def _setting(self) -> Setting:
        return Setting(
            self.spec,
            self.pair,
            self.controller,
            self.options.seed,
            physics_client(self.config),
            run_cache(self.config),
        )

    def _seed(self) -> int:
        """The search's seed: the run's, made the item's own by its node id."""
        digest = hashlib.sha256(f"{self.options.seed}:{self.nodeid}".encode()).digest()
        return int.from_bytes(digest[:4], "big")

    def _database(self) -> Path:
        return self.config.rootpath / ".hypothesis" / "examples"

    def _pair_plan(self) -> PairPlan:
        plans = self.config.stash.setdefault(PLANS_KEY, {})
        key = (self.spec.path, self.pair.name)
        if key not in plans:
            from pytest_lasertest.solver.plan import plan_pair

            control = self._control()
            plans[key] = plan_pair(self.spec, self.pair, solver_path(self.spec, control.baseline))
        return plans[key]

    def _control(self) -> PairDrive:
        return control_drive(self.config, self.spec, self.pair, self.controller)

    def _record(self, witness: Witness, verification: Verification) -> None:
        self.user_properties += [
            ("lasertest.seed", self.options.seed),
            ("lasertest.obstacle", describe_obstacle(witness.placement.obstacle)),
            ("lasertest.margin", verification.margin),
            ("lasertest.lead", verification.lead),
            ("lasertest.late", verification.late),
            ("lasertest.detected_by", DETECTED_BY[self.direction]),
        ]

    def _write_artifact(self, witness: Witness, verification: Verification) -> Path | None:
        if self.options.artifacts is None:
            return None
        evidence = {
            "item": self.nodeid,
            "pairs_file": str(self.spec.path),
            "pair": self.pair.name,
            "seed": self.options.seed,
            "policy": self.options.policy,
            "witness": witness_json(witness),
            "verification": dataclasses.asdict(verification),
        }
        return write_json(artifact_path(self.options.artifacts, self.nodeid, ".json"), evidence)

    def _write_failure(
        self, witness: Witness, result: TrialResult, trials: Trials, box: OffsetBox
    ) -> tuple[Path, ...]:
        """The failure's artifacts, if the run asked for them."""
        options = self.options
        if options.artifacts is None:
            return ()
        from pytest_lasertest.artifacts.evidence import Failure, write_evidence

        failure = Failure(
            self.nodeid,
            self.spec,
            self.pair,
            witness,
            result,
            trials,
            box,
            options.seed,
            options.recorded(),
        )
        return write_evidence(options.artifacts, failure)

    def repr_failure(
        self, excinfo: pytest.ExceptionInfo[BaseException], style: TracebackStyle | None = None
    ) -> str | TerminalRepr:
        if isinstance(excinfo.value, VerificationFailed):
            return self._rejection_report(excinfo.value)
        if isinstance(excinfo.value, PlacementFailed):
            return self._failure_report(excinfo.value)
        return super().repr_failure(excinfo, style)

    def _failure_report(self, failed: PlacementFailed) -> str:
        pair, result, options = self.pair, failed.result, self.options
        scene = self._pair_plan().scene
        oracles = " and ".join(result.oracles())
        lines = [
            f"the candidate fails ({oracles}) near witness {failed.witness.id}: "
            f"{MEANINGS[result.classification]}",
            f"  pair       {pair.name} ({pair.location})",
            f"  controller {self.controller.name} ({self.controller.source})",
            *oracle_lines(result),
            f"  witness    {describe_obstacle(failed.witness.placement.obstacle)}",
            f"  minimal    {describe_obstacle(result.placement.obstacle)}",
            f"  change     {result.offset.describe()} (the smallest the search found that fails)",
            margin_line(result.verification),
            *beam_lines(scene, result),
            *trial_lines(result, pair),
            search_line(failed.trials, failed.box),
            # Hypothesis's own notes: the falsifying example and, in profiles that explain, what
            # its explain phase found.
            *(f"  hypothesis {note}" for note in failed.notes),
            f"  policy     {options.policy}",
            f"  seed       {options.seed}",
            *self._replay_lines(failed.artifacts),
        ]
        return "\n".join(lines)

    def _replay_lines(self, artifacts: tuple[Path, ...]) -> list[str]:
        rerun = f"pytest '{self.nodeid}' {self.options.replay_options()}"
        repro = [path for path in artifacts if path.name.endswith(REPRO_SUFFIX)]
        if not repro:
            return [f"  replay     {rerun}  (replays this case first, from .hypothesis/)"]
        return [
            f"  replay     pytest '{display_path(repro[0])}'  (this case alone, pinned)",
            f"  rerun      {rerun}  (replays this case first, from .hypothesis/)",
            *(f"  artifact   {display_path(path)}" for path in artifacts),
        ]

    def _rejection_report(self, rejected: VerificationFailed) -> str:
        pair, witness, verification = self.pair, rejected.witness, rejected.verification
        x, y, yaw = witness.pose
        lines = [
            f"the exact ray cast rejects witness {witness.id}, which the solver returned as "
            "verified: this is a bug in pytest-lasertest's solver, please report it with this "
            "pairs file",
            f"  pair       {pair.name} ({pair.location})",
            f"  baseline   {pair.baseline.label}: {pair.baseline.profile.describe()}",
            f"  candidate  {pair.candidate.label}: {pair.candidate.profile.describe()}",
            f"  obstacle   {describe_obstacle(witness.placement.obstacle)}",
            f"  read by    the {DETECTED_BY[self.direction]} at t = "
            f"{witness.placement.anchor:.2f} s, robot at ({x:.2f}, {y:.2f}, {yaw:.2f})",
            f"  margins    {margins_text(verification)}; each must reach "
            f"{REQUIRED_MARGIN * 1000:.1f} mm",
        ]
        if verification.seen_by_misser_at:
            times = ", ".join(f"{time:.2f}" for time in verification.seen_by_misser_at)
            lines.append(f"  misser     reads it at t = {times} s")
        lines.append(f"  replay     pytest '{self.nodeid}' {self.options.replay_options()}")
        if rejected.artifact is not None:
            lines.append(f"  evidence   {display_path(rejected.artifact)}")
        return "\n".join(lines)


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
