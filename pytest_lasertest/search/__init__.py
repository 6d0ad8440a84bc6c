"""What the gate does with a pair, without pytest: plans, drives, trials, offsets, the
Hypothesis search and its budgets."""
