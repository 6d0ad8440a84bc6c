"""Every text and JSON a person reads: failures, drives, plans, explanations, profiles, the summary."""
