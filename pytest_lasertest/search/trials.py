"""Trials: what one perturbation of a witness does to the two robots, and how it is classified.

A trial moves the witness's obstacle by an offset, checks with the exact ray cast that it still
discriminates, and drives the candidate through it. Only when the candidate fails is the
baseline driven on the same placement, to tell a regression (the baseline is fine there) from a
pre-existing failure (both fail); a regression is then driven again under further draws (fresh
scan noise, the obstacle moved within a centimetre), and is marginal unless it holds under
every one (`drives.redrawn`). The policy
decides which of them fail the item; the re-drives count among the item's simulations. Runs
come from the session's cache, so the shrinker revisiting a scenario costs nothing; after the
first failure, the search's new scenarios are counted against the shrink budget, whether or not
another item of the process drove them before.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from pytest_lasertest.model.draws import Draw
from pytest_lasertest.model.obstacles import Obstacle
from pytest_lasertest.model.policy import Classification, Policy, fails
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.model.verify import Placement, Scene, Verification, verify
from pytest_lasertest.pairsfile import Pair, PairsFile
from pytest_lasertest.pairsfile.constraints import admits, obstacle_variables
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.search.drives import PairDrive, RunCache, redrawn, scenario
from pytest_lasertest.search.offsets import Offset, Untested, discriminates, perturbed
from pytest_lasertest.sim.client import PhysicsClient
from pytest_lasertest.sim.scenario import Run, Scenario

NOT_DISCRIMINATING = "rejected: no longer discriminating"
OUTSIDE_CONSTRAINTS = "rejected: outside the pairs file's constraints"
BUDGET_SPENT = "not simulated: the shrink budget is spent"


@dataclass(frozen=True, eq=False)
class TrialResult:
    """One perturbed placement and the runs through it."""

    offset: Offset
    placement: Placement
    verification: Verification
    candidate: Run
    baseline: Run | None  # driven only when the candidate failed
    redrives: tuple[PairDrive, ...] = ()  # both again, where the candidate alone failed

    @property
    def baseline_passed(self) -> bool:
        """Whether the baseline passed here; not driven, it is taken to pass."""
        return self.baseline.passed if self.baseline is not None else True

    @property
    def drive(self) -> PairDrive | None:
        """Both robots' runs and re-drives; None where the candidate passed and the baseline was
        not driven."""
        if self.baseline is None:
            return None
        return PairDrive(self.baseline, self.candidate, self.redrives)

    @property
    def classification(self) -> Classification:
        """What the change did here, over every draw."""
        drive = self.drive
        return "unchanged" if drive is None else drive.classification

    def fails(self, policy: Policy) -> bool:
        """Whether the policy fails the item on this trial (see `policy.fails`)."""
        return fails(policy, self.classification)

    def oracles(self) -> list[str]:
        """The candidate's failing oracles, by name."""
        return [name for name, verdict in self.candidate.verdicts.named() if not verdict.passed]


class TrialFailed(Exception):
    """A trial the policy fails; the search shrinks toward the smallest such offset."""

    def __init__(self, result: TrialResult) -> None:
        super().__init__(result.offset.describe())
        self.result = result


@dataclass(frozen=True)
class Setting:
    """Where trials drive: the pairs file, the pair, its controller and the run's seed."""

    spec: PairsFile
    pair: Pair
    controller: ControllerChoice
    seed: int
    client: PhysicsClient
    cache: RunCache

    def scenario(
        self, profile: LaserProfile, placement: Placement, draw: Draw | None = None
    ) -> Scenario:
        """One robot of the pair, carrying `profile`, past the placement's obstacle, with scan
        noise from the run's seed, or as a further `draw` says."""
        return scenario(self.spec, profile, (placement.obstacle,), self.seed, draw)

    def drive(self, profile: LaserProfile, placement: Placement, draw: Draw | None = None) -> Run:
        """The run of `scenario`, through the session's cache."""
        return self.drive_past(profile, placement.obstacle, draw)

    def drive_past(
        self, profile: LaserProfile, obstacle: Obstacle, draw: Draw | None = None
    ) -> Run:
        """One robot past `obstacle` alone (a placement's, or a pinned one), as `scenario` says,
        through the session's cache."""
        world = scenario(self.spec, profile, (obstacle,), self.seed, draw)
        return self.cache.run(world, self.controller, self.client)


@dataclass
class Trials:
    """The trials of one placement item's search, and what they cost."""

    setting: Setting
    scene: Scene
    witness: Placement
    sizes: tuple[float, float]  # m, the smallest and largest obstacle the pairs file allows
    policy: Policy
    shrink_budget: int  # simulations after the first failure
    simulations: int = field(default=0, init=False)
    # Simulations up to the candidate's run that first failed, not counting its classification.
    simulations_to_failure: int | None = field(default=None, init=False)
    results: dict[Offset, TrialResult] = field(default_factory=dict, init=False)
    rejections: set[Offset] = field(default_factory=set, init=False)
    _at_candidate: int = field(default=0, init=False)  # simulations up to the last candidate run
    # Scenarios this search drove, from the cache or not: what other items of the process cached
    # must not change how far this one's budget goes (xdist's distribution, a -k selection).
    _driven: set[Scenario] = field(default_factory=set, init=False)

    def __call__(self, offset: Offset) -> str:
        placement = perturbed(self.witness, offset)
        # The witness itself meets them (the solver's, or a seed `plans.avoid_for` kept).
        constraints = self.setting.spec.constraints
        if offset != Offset() and not admits(constraints, obstacle_variables(placement.obstacle)):
            self.rejections.add(offset)
            raise Untested(OUTSIDE_CONSTRAINTS)
        if not discriminates(self.scene, placement, self.sizes):
            self.rejections.add(offset)
            raise Untested(NOT_DISCRIMINATING)
        result = self.results.get(offset)
        if result is None:
            result = self.results[offset] = self.trial(offset, placement)
        if result.fails(self.policy):
            if self.simulations_to_failure is None:
                self.simulations_to_failure = self._at_candidate
            raise TrialFailed(result)
        return _outcome(result)

    def trial(self, offset: Offset, placement: Placement) -> TrialResult:
        """Drive the candidate through the placement, the baseline if the candidate fails, and
        both again under further draws if only the candidate failed."""
        pair = self.setting.pair
        candidate = self._drive(pair.candidate.profile, placement)
        self._at_candidate = self.simulations
        baseline = None if candidate.passed else self._drive(pair.baseline.profile, placement)

        def side(name: str, draw: Draw) -> Run:
            return self._drive(getattr(pair, name).profile, placement, draw)

        redrives = redrawn((candidate, baseline), side)
        verification = verify(self.scene, placement)
        return TrialResult(offset, placement, verification, candidate, baseline, redrives)

    @property
    def examples(self) -> int:
        """Distinct offsets that discriminated and were driven."""
        return len(self.results)

    @property
    def rejected(self) -> int:
        """Distinct offsets that no longer discriminated."""
        return len(self.rejections)

    @property
    def failures(self) -> int:
        """Distinct offsets the policy fails."""
        return sum(result.fails(self.policy) for result in self.results.values())

    def count(self, classification: Classification) -> int:
        """Distinct offsets of one class."""
        return sum(result.classification == classification for result in self.results.values())

    @property
    def witness_result(self) -> TrialResult | None:
        """The trial of the witness itself, if the search drove it."""
        return self.results.get(Offset())

    @property
    def rejection_rate(self) -> float:
        """The share of drawn offsets that no longer discriminated."""
        drawn = self.examples + self.rejected
        return self.rejected / drawn if drawn else 0.0

    @property
    def shrink_simulations(self) -> int:
        """Simulations spent after the first failure."""
        if self.simulations_to_failure is None:
            return 0
        return self.simulations - self.simulations_to_failure

    def _drive(self, profile: LaserProfile, placement: Placement, draw: Draw | None = None) -> Run:
        world = self.setting.scenario(profile, placement, draw)
        if world not in self._driven:
            # The shrink budget bounds only what follows the first failure: without one, a budget
            # of 0 would refuse the first trial too.
            shrinking = self.simulations_to_failure is not None
            if shrinking and self.shrink_simulations >= self.shrink_budget:
                raise Untested(BUDGET_SPENT)
            self.simulations += 1
            self._driven.add(world)
        return self.setting.drive(profile, placement, draw)


def noted_result(trials: Trials) -> TrialResult | None:
    """Where the search found no failure its policy fails, the first trial in which the
    candidate failed all the same, a marginal one before a pre-existing one: the item reports
    it without failing the run."""
    for kind in ("marginal", "pre-existing"):
        for result in trials.results.values():  # in the order they were tried
            if result.classification == kind and not result.fails(trials.policy):
                return result
    return None


def _outcome(result: TrialResult) -> str:
    """The event a trial counts as: `passed`, or the candidate's failing oracles and the class."""
    if result.candidate.passed:
        return "candidate passed"
    return f"candidate failed ({', '.join(result.oracles())}): {result.classification}"
