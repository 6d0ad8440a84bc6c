"""Both robots of a pair driven through one world, and what the policy makes of it.

The baseline and the candidate are the same robot with different scanners: each drives the
pairs file's route with a fresh controller from the same factory (the one the pairs file, a
conftest hook or the default chose), in a world holding the given obstacles (none for the pair's
control run), with scan noise from the run's seed. Runs go through the session's `RunCache`.
Where the candidate fails and the baseline passes, both drive again under `REDRAWS` further
draws (`model/draws.py`: fresh scan noise, each obstacle moved within a centimetre), and only a
failure that holds under every draw is a regression (`model/policy.py`).
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass

from pytest_lasertest.model.draws import Draw, redraw
from pytest_lasertest.model.obstacles import Obstacle, placed
from pytest_lasertest.model.policy import (
    NEAR_MISS,
    NEAR_MISS_ORACLES,
    REDRAWS,
    Classification,
    Policy,
    classify,
    fails,
)
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.nav.laser_filters import ScanFilterChain
from pytest_lasertest.nav.protocol import ControllerFactory
from pytest_lasertest.pairsfile import Pair, PairsFile
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.sim.client import PhysicsClient
from pytest_lasertest.sim.scenario import Run, Scenario, run_scenario

# What a run is known by: the controller's name and where it was chosen, the scan filter chain
# in front of it, and the scenario.
_Key = tuple[str, str, ScanFilterChain | None, Scenario]


@dataclass(frozen=True, eq=False)
class PairDrive:
    """The runs of the baseline and the candidate through one world, and, where the candidate
    alone failed, both again under further draws (`draws.Draw`)."""

    baseline: Run
    candidate: Run
    redrives: tuple[PairDrive, ...] = ()  # under draws 1, 2, ... in order
    draw: Draw | None = None  # what this drive drew; None: the run's own seed and obstacles

    @property
    def classification(self) -> Classification:
        """What the change did here, over every draw (see `policy.classify`)."""
        redrawn = [(drive.baseline.passed, drive.candidate.passed) for drive in self.redrives]
        near = any(near_misses(drive.baseline, drive.candidate) for drive in self.draws)
        return classify(self.baseline.passed, self.candidate.passed, redrawn, near)

    @property
    def draws(self) -> tuple[PairDrive, ...]:
        """This drive, then its re-drives."""
        return (self, *self.redrives)

    def fails(self, policy: Policy) -> bool:
        """Whether the policy fails these runs (see `policy.fails`)."""
        return fails(policy, self.classification)

    @property
    def simulations(self) -> int:
        """The runs this holds, the re-drives included."""
        return 2 + sum(drive.simulations for drive in self.redrives)


def near_misses(baseline: Run, candidate: Run) -> list[tuple[str, float]]:
    """Where the candidate failed, the oracles (collision, stuck) the baseline passed by less
    than `NEAR_MISS`, each with the baseline's margin (m): whichever oracle the candidate
    failed, a baseline that came within a centimetre of failing passed by luck."""
    if candidate.passed:
        return []
    return [
        (name, verdict.margin)
        for name, verdict in baseline.verdicts.named()
        if name in NEAR_MISS_ORACLES and verdict.passed and verdict.margin < NEAR_MISS
    ]


def redrawn(
    first: tuple[Run, Run | None], drive: Callable[[str, Draw], Run]
) -> tuple[PairDrive, ...]:
    """Both robots again under each further draw, while the candidate alone keeps failing; none
    where `first` (the candidate's run, then the baseline's, driven only if the candidate
    failed) is no regression or a near miss of the baseline's. `drive(side, draw)` drives one
    side ("baseline" or "candidate") under a draw."""
    candidate, baseline = first
    if candidate.passed or baseline is None or not baseline.passed:
        return ()
    if near_misses(baseline, candidate):
        return ()  # marginal already
    scenario = candidate.scenario
    drives: list[PairDrive] = []
    for number in range(1, REDRAWS + 1):
        draw = redraw(scenario.seed, number, len(scenario.obstacles))
        again = PairDrive(drive("baseline", draw), drive("candidate", draw), draw=draw)
        drives.append(again)
        if not again.baseline.passed or again.candidate.passed:
            break  # marginal already: the draws left cannot make it a regression
    return tuple(drives)


class RunCache:
    """The runs of one session by scenario and controller: shrinking a failure and classifying
    it revisit scenarios, and a scenario's run never changes, so none is simulated twice.

    The least recently used runs are dropped beyond `size`, which bounds the memory (a run of
    60 s keeps about 0.2 MB of trajectory).
    """

    def __init__(self, size: int = 256) -> None:
        self.size = size
        self._runs: OrderedDict[_Key, Run] = OrderedDict()

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


def _key(scenario: Scenario, controller: ControllerChoice) -> _Key:
    # The name alone could be two modules' of one name; where it was chosen tells them apart.
    # One controller behind two pairs files' scan filter chains drives two robots.
    return controller.name, controller.source, controller.scan_filters, scenario


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
    (see `run_scenario`), each with a controller from `controller`; where the candidate alone
    fails, again under further draws (`redrawn`)."""

    def side(name: str, draw: Draw | None = None) -> Run:
        profile = pair.candidate.profile if name == "candidate" else pair.baseline.profile
        world = scenario(spec, profile, obstacles, seed, draw)
        return cache.run(world, controller, client)

    baseline, candidate = side("baseline"), side("candidate")
    return PairDrive(baseline, candidate, redrawn((candidate, baseline), side))


def scenario(
    spec: PairsFile,
    profile: LaserProfile,
    obstacles: tuple[Obstacle, ...],
    seed: int,
    draw: Draw | None = None,
) -> Scenario:
    """One robot of the pairs file, carrying `profile`, on the file's route through a world
    holding `obstacles`, each placed to a micrometre (`obstacles.placed`: a pinned replay writes
    them so, and drives the same), with scan noise from `seed`; under a further `draw`, with its
    noise and the obstacles moved as it says."""
    world = spec.world
    if draw is not None:
        obstacles, seed = draw.moved(obstacles), draw.noise
    return Scenario(
        spec.robot,
        profile,
        tuple(placed(obstacle) for obstacle in obstacles),
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
