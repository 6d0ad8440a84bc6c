"""A pair of a pairs file as the gate plans it: both scanners on the pairs file's robot, along
its route, with its settings and constraints; the solver's witnesses, and the placements both
scanners read that the robot must act on.

The path is the route's legs and turns, timed as the baseline robot drove them without an
obstacle when that run is given (as the gate's items and `lasertest plan` do), else at the robot's
nominal speed and turn rate. The solver, and with it Z3, is imported on the first plan.
"""

from __future__ import annotations

import dataclasses

from pytest_lasertest.model.avoid import avoid_witnesses
from pytest_lasertest.model.plan import PairPlan, Witness
from pytest_lasertest.model.route import NominalPath, nominal_path, timed_to
from pytest_lasertest.model.verify import Scene
from pytest_lasertest.pairsfile import Pair, PairsFile
from pytest_lasertest.pairsfile.constraints import admits, obstacle_variables
from pytest_lasertest.sim.scenario import Run


def plan_for(spec: PairsFile, pair: Pair, control: Run | None = None) -> PairPlan:
    """Both directions of the pair, along the path `control` (the baseline's obstacle-free run)
    drove, or the nominal path without it."""
    return plan_scene(spec, pair, pair_scene(spec, pair, control))


def plan_scene(spec: PairsFile, pair: Pair, scene: Scene) -> PairPlan:
    """Both directions of the pair in `scene`, with the pairs file's settings and constraints."""
    from pytest_lasertest.solver.plan import plan_pair
    from pytest_lasertest.solver.search import SearchSettings

    settings = SearchSettings(
        witnesses=spec.settings.witnesses,
        min_size=spec.settings.min_obstacle_size,
        max_size=spec.settings.max_obstacle_size,
        constraints=spec.constraints,
    )
    if spec.settings.solver_rlimit is not None:
        settings = dataclasses.replace(settings, rlimit=spec.settings.solver_rlimit)
    return plan_pair(pair.name, scene, settings)


def avoid_for(spec: PairsFile, scene: Scene) -> tuple[Witness, ...]:
    """The placements both scanners read that the robot must act on (`model/avoid.py`)."""
    witnesses = avoid_witnesses(scene, spec.settings.obstacle_sizes)
    # Seeds are placed by rule, not by the solver: the pairs file's constraints are asked here.
    return tuple(
        witness
        for witness in witnesses
        if admits(spec.constraints, obstacle_variables(witness.placement.obstacle))
    )


def pair_scene(spec: PairsFile, pair: Pair, control: Run | None = None) -> Scene:
    """Both scanners of the pair on the pairs file's robot, along the path the solver plans on."""
    path = route_path(spec) if control is None else driven_path(spec, control)
    baseline, candidate = pair.baseline.profile, pair.candidate.profile
    return Scene(baseline, candidate, spec.robot, path, spec.world.walls)


def route_path(spec: PairsFile) -> NominalPath:
    """The route's legs and turns at the robot's nominal speed and turn rate."""
    world, robot = spec.world, spec.robot
    return nominal_path(world.start, world.route, robot.nominal_speed, robot.nominal_turn_rate)


def driven_path(spec: PairsFile, control: Run) -> NominalPath:
    """The route's legs and turns, timed as `control`, the baseline's obstacle-free run, drove
    them."""
    return timed_to(route_path(spec), control.times, control.poses)
