"""What a change did where both robots drove, and which outcomes fail the gate.

A failure is the change's doing, a *regression*, only where the candidate fails and the baseline
passes under the run's scan noise and again under every further draw (`REDRAWS`) of what must
not decide it: the scan noise, and where within `JITTER` each obstacle stands (`draws.Draw`).
A failure decided by a millimetre of progress, or by which costmap cell an obstacle's edge falls
in, flips with such a draw, and a gate that fails on such a flip is a gate teams switch off. One
that does not hold under every draw is *marginal*; so is one where the baseline passed the
collision or the stuck oracle by less than `NEAR_MISS` (a collision missed by 4 mm, say): both
robots came within a centimetre of failing, and which side of it each ended on says nothing
about the change. Every item decides with `fails`: under the `regression` policy (the
default) only a regression fails it; under `candidate` any failure of the candidate does,
marginal and pre-existing ones included.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Literal, get_args

Policy = Literal["regression", "candidate"]
POLICIES: tuple[Policy, ...] = get_args(Policy)
DEFAULT_POLICY: Policy = "regression"
Classification = Literal["regression", "marginal", "pre-existing", "improvement", "unchanged"]
# The classes in which the candidate failed.
CANDIDATE_FAILED: tuple[Classification, ...] = ("regression", "marginal", "pre-existing")
# The further draws (scan noise and obstacle positions) a regression must survive before it is
# reported as one.
REDRAWS = 2
# m: how far, in x and in y, a draw may move each obstacle. Scan noise alone decides little under
# a stack that marks 5 cm costmap cells: 1 mm of noise seldom moves an obstacle's edge into
# another cell, and a harmless 1 cm re-mount on the Husky under Nav2 failed one placement under
# every noise draw yet passed 7 of 10 placements within a centimetre of it, while the baseline
# failed 2 of them. A centimetre is also about how well a placed obstacle's position is known.
JITTER = 0.01
# m: the least margin by which the baseline must pass the collision and the stuck oracle, in
# every draw, for a failure of the candidate to be the change's, whichever oracle it failed (on
# a harmless swap under move_base the baseline grazed a pole with 2 mm to spare while the
# candidate got stuck beside it). A centimetre: the order of the catalogue scanners' noise
# (sigma 10-20 mm), far above PyBullet's contact slop (~1 mm).
NEAR_MISS = 0.01
# The oracles whose margin says how near the baseline came to failing them. Not the goal's: a
# robot stops as soon as it is within the goal tolerance, so every passing run's goal margin is
# near zero.
NEAR_MISS_ORACLES = ("collision", "stuck")

# (baseline passed, candidate passed) in one draw of the scan noise.
Outcomes = tuple[bool, bool]


def classify(
    baseline_passed: bool,
    candidate_passed: bool,
    redrawn: Iterable[Outcomes] = (),
    near_miss: bool = False,
) -> Classification:
    """What the change did here: broke it (under every draw in `redrawn` too, and not by a
    `near_miss` of the baseline's, else it is marginal), found it broken, fixed it, or left it
    as it was."""
    if baseline_passed != candidate_passed:
        if not baseline_passed:
            return "improvement"
        held = all(outcomes == (True, False) for outcomes in redrawn) and not near_miss
        return "regression" if held else "marginal"
    return "unchanged" if baseline_passed else "pre-existing"


def fails(policy: Policy, classification: Classification) -> bool:
    """Whether the policy fails an outcome of this class: under `regression` only a
    regression, under `candidate` any failure of the candidate."""
    if policy == "regression":
        return classification == "regression"
    return classification in CANDIDATE_FAILED
