"""Witnesses for both directions of a pair: diverse, verified, or a reason why there are none."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from pytest_lasertest.model.plan import DirectionPlan, PairPlan, Witness
from pytest_lasertest.model.sensor import same_geometry
from pytest_lasertest.model.verify import DIRECTIONS, Direction, Scene
from pytest_lasertest.solver.backend import Workspace
from pytest_lasertest.solver.encoding import ObstacleShape
from pytest_lasertest.solver.proof import prove
from pytest_lasertest.solver.search import (
    Found,
    Query,
    SearchSettings,
    anchor_times,
    needed_room,
    shapes_for,
)
from pytest_lasertest.solver.seeds import Candidates, Seed, candidates, seeds

SEEDS_PER_ANCHOR = 3  # seeds tried per anchor and shape before the search moves on


class DirectionSearch:
    """The witnesses of one direction, found anchor by anchor; seeds are computed once each."""

    def __init__(self, scene: Scene, direction: Direction, settings: SearchSettings) -> None:
        self.scene = scene
        self.direction = direction
        self.settings = settings
        self.witnesses: list[Witness] = []
        self._candidates: dict[float, Candidates] = {}
        self._seeds: dict[tuple[float, float], list[Seed]] = {}
        self._workspace = Workspace()
        # Candidates serve every shape: they keep what leaves the least demanding one room.
        self._least_room = min(needed_room(shape, settings) for shape in shapes_for(0, 0.0))

    def run(self) -> DirectionPlan:
        """Up to `settings.witnesses` witnesses, each from the next anchor that yields one."""
        scene, direction = self.scene, self.direction
        if same_geometry(scene.detector(direction), scene.misser(direction)):
            return DirectionPlan(direction, "unsat", (), SAME)
        anchors = anchor_times(scene, direction, self.settings.anchor_spacing)
        if not anchors:
            return DirectionPlan(direction, "unsat", (), "the path leaves no room to brake")
        for _ in self.found(anchors):
            pass
        if self.witnesses:
            return DirectionPlan(direction, "sat", tuple(self.witnesses), self._shortfall())
        return self._without_witness(anchors)

    def _shortfall(self) -> str:
        """Why fewer witnesses than asked for, if so."""
        found = len(self.witnesses)
        if found >= self.settings.witnesses:
            return ""
        return f"only {found} diverse witness{'es' if found > 1 else ''} found"

    def found(self, anchors: list[float]) -> Iterator[Witness]:
        """Each witness as soon as it is verified, each from the next anchor that yields one."""
        cursor = 0
        for index in range(self.settings.witnesses):
            for step in range(len(anchors)):
                anchor = anchors[(cursor + step) % len(anchors)]
                witness = self._at_anchor(anchor, index)
                if witness is not None:
                    self.witnesses.append(witness)
                    cursor = (cursor + step + 1) % len(anchors)
                    yield witness
                    break
            else:
                return

    def _at_anchor(self, anchor: float, index: int) -> Witness | None:
        pose = self.scene.path.poses_at(np.array([anchor]))[0]
        apart = tuple(witness.placement.obstacle for witness in self.witnesses)
        for shape in shapes_for(index, float(pose[2])):
            for seed in self._fresh_seeds(anchor, shape)[:SEEDS_PER_ANCHOR]:
                query = Query(self.scene, self.direction, anchor, seed, shape, self.settings, apart)
                result = query.run(self._workspace)
                if isinstance(result, Found):
                    x, y, yaw = (float(value) for value in pose)
                    return Witness(index, result.placement, result.verification, (x, y, yaw))
        return None

    def _fresh_seeds(self, anchor: float, shape: ObstacleShape) -> list[Seed]:
        """The anchor's seeds for this shape, without those near a witness already found."""
        gap = self.settings.diversity
        taken = [witness.placement.obstacle for witness in self.witnesses]
        return [
            seed
            for seed in self._seeds_at(anchor, shape)
            if all(
                max(abs(seed.point[0] - other.x), abs(seed.point[1] - other.y)) >= gap
                for other in taken
            )
        ]

    def _seeds_at(self, anchor: float, shape: ObstacleShape) -> list[Seed]:
        """The anchor's seeds for this shape, found once; the candidates, once for all shapes."""
        if anchor not in self._candidates:
            near = candidates(self.scene, self.direction, anchor, self._least_room)
            self._candidates[anchor] = near
        needed = needed_room(shape, self.settings)
        if (anchor, needed) not in self._seeds:
            near = self._candidates[anchor]
            self._seeds[anchor, needed] = seeds(self.scene, self.direction, near, needed)
        return self._seeds[anchor, needed]

    def _without_witness(self, anchors: list[float]) -> DirectionPlan:
        heading = float(self.scene.path.poses_at(np.array([anchors[0]]))[0, 2])
        shapes = tuple(shapes_for(0, heading))
        proof = prove(self.scene, self.direction, anchors[0], self.settings, shapes)
        if proof.witness is not None:
            self.witnesses.append(proof.witness)
            return DirectionPlan(self.direction, "sat", (proof.witness,), self._shortfall())
        others = len(anchors) - 1
        searched = (
            f"; no witness found at the other {others} anchors along the path" if others else ""
        )
        return DirectionPlan(self.direction, proof.verdict, (), proof.explanation + searched)


SAME = (
    "the two scanners cast the same beams from the same place at the same instants, so every "
    "obstacle one reads the other reads too"
)


def plan_direction(scene: Scene, direction: Direction, settings: SearchSettings) -> DirectionPlan:
    """The witnesses of one direction, or why there are none."""
    return DirectionSearch(scene, direction, settings).run()


def plan_pair(name: str, scene: Scene, settings: SearchSettings) -> PairPlan:
    """Both directions of the pair `name`, whose two scanners and path `scene` holds."""
    plans = tuple(plan_direction(scene, direction, settings) for direction in DIRECTIONS)
    return PairPlan(name, scene, plans)
