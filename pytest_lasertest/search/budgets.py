"""How hard each placement item searches: the budget profiles `--laser-profile` names."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal, get_args

BudgetName = Literal["dev", "ci", "nightly", "triage"]
BUDGET_NAMES: tuple[BudgetName, ...] = get_args(BudgetName)
MAX_EXAMPLES = 10_000


@dataclass(frozen=True)
class Budget:
    """How hard each placement item searches around its witness."""

    examples: int  # perturbations tried, the witness itself among them
    shrink_simulations: int  # simulations spent making a failure smaller
    explain: bool  # run Hypothesis's explain phase on a failure

    def with_examples(self, examples: int | None) -> Budget:
        """The budget with `examples` perturbations instead, if given."""
        if examples is None:
            return self
        return Budget(examples, self.shrink_simulations, self.explain)


# dev keeps a local run short; ci tries more perturbations for a gate on a CI service; nightly
# explores; triage replays a stored failure and spends its budget on shrinking and explaining
# it. What a run costs is measured, not promised here: docs/explanation/performance.md.
BUDGETS: dict[BudgetName, Budget] = {
    "dev": Budget(examples=10, shrink_simulations=24, explain=False),
    "ci": Budget(examples=16, shrink_simulations=24, explain=False),
    "nightly": Budget(examples=100, shrink_simulations=200, explain=True),
    "triage": Budget(examples=4, shrink_simulations=400, explain=True),
}
