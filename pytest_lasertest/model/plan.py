"""What the solver returns for a pair: verified witnesses for each direction, or why there are
none. Z3 finds them (`solver/`); they are plain values here, so that items, reports and the
command line read them without loading the solver."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from pytest_lasertest.model.verify import Direction, Placement, Scene, Verification

Status = Literal["sat", "unsat", "unknown"]
# The name of a placement both scanners read, which the robot must act on (`avoid.py`).
AVOID = "avoid"


@dataclass(frozen=True)
class Witness:
    """A verified placement, numbered within its direction."""

    index: int
    placement: Placement
    verification: Verification
    pose: tuple[float, float, float]  # m, m, rad: the robot at the anchor

    @property
    def id(self) -> str:
        """`candidate-misses-0`, or `avoid-0` for one both scanners read: the direction and the
        index, as in the item's name."""
        return f"{self.placement.direction or AVOID}-{self.index}"


@dataclass(frozen=True)
class DirectionPlan:
    """What the search found for one direction of a pair."""

    direction: Direction
    status: Status
    witnesses: tuple[Witness, ...]
    explanation: str  # why there are no (more) witnesses; empty when all were found


@dataclass(frozen=True)
class PairPlan:
    """Both directions of one pair."""

    name: str
    scene: Scene
    directions: tuple[DirectionPlan, ...]

    @property
    def status(self) -> Status:
        """sat when either direction has a witness; unknown when Z3 could not decide; else
        unsat."""
        statuses = {direction.status for direction in self.directions}
        if "sat" in statuses:
            return "sat"
        return "unknown" if "unknown" in statuses else "unsat"

    def direction(self, direction: Direction) -> DirectionPlan:
        """The plan of one direction."""
        return next(plan for plan in self.directions if plan.direction == direction)

    def witnesses(self) -> tuple[Witness, ...]:
        """Every witness, direction by direction, in the order `lasertest plan` prints them."""
        return tuple(witness for plan in self.directions for witness in plan.witnesses)

    def find(self, witness_id: str) -> Witness | None:
        """The witness with this id, or None."""
        return next((witness for witness in self.witnesses() if witness.id == witness_id), None)
