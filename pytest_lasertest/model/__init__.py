"""The domain: geometry, scanners, the robot, its route, the exact verifier, coverage and policy. numpy only."""
