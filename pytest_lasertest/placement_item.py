"""The placement items of a pair: one per direction and witness index, solved when first run.

Collection does no solving: item names come from the pair's name, the two directions and
`settings.witnesses`, so every run and every pytest-xdist worker collects the same items. The
first item of a pair to run plans the pair (Z3, imported only then) and the plan is kept for the
session; planning is deterministic, so workers that plan the same pair find the same witnesses.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import pytest
from _pytest._code.code import TerminalRepr, TracebackStyle

from pytest_lasertest.artifacts.files import artifact_path, write_json
from pytest_lasertest.drive_item import (
    CONTROL,
    DriveFailed,
    control_drive,
    drive_report,
    physics_client,
)
from pytest_lasertest.drives import PairDrive, drive_pair, solver_path
from pytest_lasertest.options import OPTIONS_KEY, LaserOptions
from pytest_lasertest.placement import (
    DIRECTIONS,
    REQUIRED_MARGIN,
    Direction,
    DirectionPlan,
    PairPlan,
    Verification,
    Witness,
    verify,
)
from pytest_lasertest.plan_report import DETECTED_BY, describe_obstacle, witness_json
from pytest_lasertest.spec import Pair, PairsFile
from pytest_lasertest.spec.controller import ControllerChoice
from pytest_lasertest.spec.errors import display_path

# The session's plans, by (pairs file path, pair name): the items of a pair plan it once.
PLANS_KEY = pytest.StashKey[dict[tuple[Path, str], PairPlan]]()


class VerificationFailed(Exception):
    """The exact ray cast rejects a witness the solver returned: a bug in the solver."""

    def __init__(self, witness: Witness, verification: Verification, artifact: Path | None) -> None:
        super().__init__(witness.id)
        self.witness = witness
        self.verification = verification
        self.artifact = artifact


class PlacementItem(pytest.Item):
    """One witness of one direction of a pair: the obstacle only one of the scanners reads."""

    def __init__(
        self,
        *,
        spec: PairsFile,
        pair: Pair,
        controller: ControllerChoice,
        direction: Direction,
        index: int,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self.spec = spec
        self.pair = pair
        self.controller = controller
        self.direction: Direction = direction
        self.index = index
        self.add_marker("lasertest")
        self.add_marker("placement")

    @property
    def options(self) -> LaserOptions:
        return self.config.stash[OPTIONS_KEY]

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
        self._drive(witness)

    def _drive(self, witness: Witness) -> None:
        """Both robots through the world holding the witness; the policy judges the runs."""
        obstacles = (witness.placement.obstacle,)
        client = physics_client(self.config)
        factory = self.controller.factory
        drives = drive_pair(self.spec, self.pair, obstacles, self.options.seed, factory, client)
        self.user_properties += [
            ("lasertest.controller", self.controller.name),
            *drives.properties(),
        ]
        if drives.fails(self.options.policy):
            raise DriveFailed(
                f"the candidate fails where witness {witness.id} stands: the obstacle the "
                f"{DETECTED_BY[self.direction]} reads and the other scanner misses",
                drives,
                [f"  obstacle   {describe_obstacle(witness.placement.obstacle)}"],
            )

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

    def repr_failure(
        self, excinfo: pytest.ExceptionInfo[BaseException], style: TracebackStyle | None = None
    ) -> str | TerminalRepr:
        if isinstance(excinfo.value, VerificationFailed):
            return self._rejection_report(excinfo.value)
        if isinstance(excinfo.value, DriveFailed):
            return drive_report(self, self.pair, self.controller, excinfo.value)
        return super().repr_failure(excinfo, style)

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
            f"  margins    {_margins(verification)}; each must reach "
            f"{REQUIRED_MARGIN * 1000:.1f} mm",
        ]
        if verification.seen_by_misser_at:
            times = ", ".join(f"{time:.2f}" for time in verification.seen_by_misser_at)
            lines.append(f"  misser     reads it at t = {times} s")
        lines.append(f"  replay     pytest '{self.nodeid}' {self.options.replay_options()}")
        if rejected.artifact is not None:
            lines.append(f"  evidence   {display_path(rejected.artifact)}")
        return "\n".join(lines)

    def reportinfo(self) -> tuple[Path, int, str]:
        return self.path, self.pair.location.line - 1, self.name


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


def _margins(verification: Verification) -> str:
    margins = {
        "detection": verification.detection,
        "concealment": verification.concealment,
        "clearance": verification.clearance,
        "obstruction": verification.obstruction,
    }
    return ", ".join(f"{name} {value * 1000:.1f} mm" for name, value in margins.items())
