"""Every text and JSON a person reads: failures, drives, coverage, plans, explanations,
profiles, the catalogue and the run's summary."""
