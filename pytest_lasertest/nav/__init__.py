"""Controllers under test: what a robot does with its scans. Numpy only, no simulator, no Z3."""
