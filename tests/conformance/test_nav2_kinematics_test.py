"""nav2_collision_monitor's kinematics tests (test/kinematics_test.cpp): its one applicable test
cannot be set up with our collision monitor (see `NOT_PORTED`). Not applicable:
testProjectState (a sideways velocity)."""

from __future__ import annotations

from tests.helpers.upstream import NAVIGATION2_JAZZY, NotPorted, Source

KINEMATICS = Source(
    "Nav2 collision monitor", NAVIGATION2_JAZZY, "nav2_collision_monitor/test/kinematics_test.cpp"
)
NOT_PORTED = (
    NotPorted(
        KINEMATICS,
        "KinematicsTest.testTransformPoints",
        4,
        "transformPoints has no counterpart of its own: `_collision_time` moves the points into "
        "the robot's frame inline, only by the poses one constant differential-drive command "
        "reaches from (0, 0, 0) step by step, and upstream's pose (2 m, 1 m, pi/6 rad: turned "
        "pi/6 at a bearing of atan(1/2) from the start) is not one such a command reaches",
    ),
)
