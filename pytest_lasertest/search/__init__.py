"""What the gate does with a pair, without pytest: drives, trials, offsets, the Hypothesis search, budgets."""
