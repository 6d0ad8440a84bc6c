"""Both robots of a pair driven through one world, and what the policy makes of it.

The baseline and the candidate are the same robot with different scanners: each drives the
pairs file's route with a fresh controller from the same factory (the one the pairs file, a
conftest hook or the default chose), in a world holding the given obstacles (none for the pair's
control run), with scan noise from the run's seed. Runs go through the session's `RunCache`.
"""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass

from pytest_lasertest.model.obstacles import Obstacle
from pytest_lasertest.model.policy import Policy, fails
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.nav.protocol import ControllerFactory
from pytest_lasertest.pairsfile import Pair, PairsFile
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.sim.client import PhysicsClient
from pytest_lasertest.sim.scenario import Run, Scenario, run_scenario


@dataclass(frozen=True, eq=False)
class PairDrive:
    """The runs of the baseline and the candidate through one world."""

    baseline: Run
    candidate: Run

    def fails(self, policy: Policy) -> bool:
        """Whether the policy fails these runs (see `policy.fails`)."""
        return fails(policy, self.baseline.passed, self.candidate.passed)


class RunCache:
    """The runs of one session by scenario and controller: shrinking a failure and classifying
    it revisit scenarios, and a scenario's run never changes, so none is simulated twice.

    The least recently used runs are dropped beyond `size`, which bounds the memory (a run of
    60 s keeps about 0.2 MB of trajectory).
    """

    def __init__(self, size: int = 256) -> None:
        self.size = size
        self._runs: OrderedDict[tuple[str, str, Scenario], Run] = OrderedDict()

    def knows(self, scenario: Scenario, controller: ControllerChoice) -> bool:
        """Whether the scenario's run with this controller is kept."""
        return _key(scenario, controller) in self._runs

    def run(self, scenario: Scenario, controller: ControllerChoice, client: PhysicsClient) -> Run:
        """The scenario's run with a controller from `controller`, simulated if not known."""
        key = _key(scenario, controller)
        if key in self._runs:
            self._runs.move_to_end(key)
            return self._runs[key]
        run = run_scenario(scenario, controller.factory, client)
        self._runs[key] = run
        if len(self._runs) > self.size:
            self._runs.popitem(last=False)
        return run


def _key(scenario: Scenario, controller: ControllerChoice) -> tuple[str, str, Scenario]:
    # The name alone could be two modules' of one name; where it was chosen tells them apart.
    return controller.name, controller.source, scenario


def drive_pair(
    spec: PairsFile,
    pair: Pair,
    obstacles: tuple[Obstacle, ...],
    seed: int,
    controller: ControllerChoice,
    client: PhysicsClient,
    cache: RunCache,
) -> PairDrive:
    """Drive both robots of the pair through a world holding `obstacles`, built in `client`
    (see `run_scenario`), each with a controller from `controller`."""
    return PairDrive(
        baseline=cache.run(
            scenario(spec, pair.baseline.profile, obstacles, seed), controller, client
        ),
        candidate=cache.run(
            scenario(spec, pair.candidate.profile, obstacles, seed), controller, client
        ),
    )


def scenario(
    spec: PairsFile, profile: LaserProfile, obstacles: tuple[Obstacle, ...], seed: int
) -> Scenario:
    """One robot of the pairs file, carrying `profile`, on the file's route through a world
    holding `obstacles`, with scan noise from `seed`."""
    world = spec.world
    return Scenario(
        spec.robot,
        profile,
        obstacles,
        world.start,
        world.route,
        world.time_limit,
        seed,
        walls=world.walls,
    )


def drive(
    spec: PairsFile,
    profile: LaserProfile,
    obstacles: tuple[Obstacle, ...],
    seed: int,
    make_controller: ControllerFactory,
    client: PhysicsClient | None = None,
) -> Run:
    """One robot of the pairs file, carrying `profile`, through a world holding `obstacles`,
    driven by a controller from `make_controller`, outside any cache."""
    return run_scenario(scenario(spec, profile, obstacles, seed), make_controller, client)
