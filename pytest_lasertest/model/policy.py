"""What a change did where both robots drove, and which outcomes fail the gate.

Every item decides with `fails`: under the `candidate` policy any failure of the candidate
fails it; under `regression` only one the baseline robot does not share.
"""

from __future__ import annotations

from typing import Literal, get_args

Policy = Literal["candidate", "regression"]
POLICIES: tuple[Policy, ...] = get_args(Policy)
Classification = Literal["regression", "pre-existing", "improvement", "unchanged"]


def classify(baseline_passed: bool, candidate_passed: bool) -> Classification:
    """What the change did here: broke it, found it broken, fixed it, or left it as it was."""
    if baseline_passed != candidate_passed:
        return "regression" if baseline_passed else "improvement"
    return "unchanged" if baseline_passed else "pre-existing"


def fails(policy: Policy, baseline_passed: bool, candidate_passed: bool) -> bool:
    """Whether the policy fails the outcome: any failure of the candidate, or under
    `regression` only one where the baseline passed."""
    if policy == "regression":
        return classify(baseline_passed, candidate_passed) == "regression"
    return not candidate_passed
