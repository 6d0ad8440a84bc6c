"""nav2_behaviors' unit tests (test/test_behaviors.cpp), rebuilt on our `Wait`. They test
TimedBehavior, the base of every behaviour, through a DummyBehavior whose "Testing success"
goal runs for 1 s and then succeeds: that is what Nav2's Wait does with a 1 s goal
(plugins/wait.cpp: RUNNING while time is left, then SUCCEEDED), so our Wait of 1 s, stepped at
the behaviour server's cycle_frequency, stands for it.

Not applicable: testingFailureOnRun, testingFailureOnInit, testingSequentialFailures and the two
zero-elapsed-time tests: they test a DummyBehavior whose onRun refuses its goal, a start check
that none of our behaviours (nor Nav2's Wait) has.
"""

from __future__ import annotations

from pytest_lasertest.nav.nav2.behaviors import BehaviorSettings, Wait
from tests.helpers.upstream import NAVIGATION2_JAZZY, Source

BEHAVIORS = Source("Nav2 behaviors", NAVIGATION2_JAZZY, "nav2_behaviors/test/test_behaviors.cpp")
MOTION = 1.0  # s, the DummyBehavior's motion_duration
CYCLES = 100  # a limit, ten times the cycles the behaviour should take


def run_to_the_end(behavior: Wait) -> float | None:
    """Step the behaviour once a cycle of the behaviour server's default 10 Hz from 0 s; the time
    (s) of the cycle at which it ended, or None if it ran past `CYCLES` cycles."""
    period = BehaviorSettings().cycle_period  # s
    for cycle in range(CYCLES):
        time = cycle * period  # s
        if behavior.step((0.0, 0.0, 0.0), time) is None:
            return time
    return None


@BEHAVIORS.test("BehaviorTest.testingSuccess", assertions=1)
def test_a_timed_behaviour_succeeds_once_its_time_has_run() -> None:
    wait = Wait(MOTION)
    assert run_to_the_end(wait) is not None
    assert not wait.failed


@BEHAVIORS.test("BehaviorTest.testingTotalElapsedTimeIsGratherThanZeroIfStarted", assertions=1)
def test_a_timed_behaviour_that_ran_took_at_least_a_whole_second() -> None:
    # Upstream compares total_elapsed_time's whole seconds with 0: at least 1 s went by.
    ended = run_to_the_end(Wait(MOTION))
    assert ended is not None
    assert int(ended) > 0
