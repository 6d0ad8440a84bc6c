"""The domain: geometry, obstacles, scanners, the robot and its route, the exact verifier, the
plan's result types, coverage and policy. numpy only."""
