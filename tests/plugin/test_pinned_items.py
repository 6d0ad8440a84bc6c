"""Pinned items: a pair that pins placements yields only its pinned items, each judged by the
policy like any placement."""

from __future__ import annotations

import pytest

from tests.helpers.runs import outcomes

PINNED = """\
robot: husky
world:
  start: {{x: 0.0, y: 0.0, yaw: 0.0}}
  goal: {{x: 6.0, y: 0.0}}
  time_limit: 40.0
pairs:
  size:
    baseline: {{model: clearpath_lms1xx_gazebo, samples: 32, range: {{max: 10.0}}}}
    candidate: {{model: clearpath_lms1xx_gazebo, samples: 16, range: {{max: 10.0}}}}
    placements:
      - obstacle: {obstacle}
        seed: 3
"""

# Far off the route: neither robot comes near it.
ASIDE = "{shape: cylinder, x: 3.0, y: 4.0, radius: 0.2, height: 0.5}"

# A wall across the route that both scanners read: both robots stop before it, stuck.
WALL = "{shape: box, x: 3.0, y: 0.0, yaw: 0.0, length: 0.2, width: 6.0, height: 0.5}"


def test_a_pair_that_pins_placements_yields_only_its_pinned_items(
    pytester: pytest.Pytester,
) -> None:
    pytester.makefile(".lasertest.yaml", gate=PINNED.format(obstacle=ASIDE))
    result = pytester.runpytest("--co", "-q")
    assert [line for line in result.stdout.lines if "::" in line] == [
        "gate.lasertest.yaml::size[pinned-0]"
    ]


def test_a_pinned_placement_both_robots_pass_passes(pytester: pytest.Pytester) -> None:
    pytester.makefile(".lasertest.yaml", gate=PINNED.format(obstacle=ASIDE))
    pytester.runpytest().assert_outcomes(passed=1)


def test_a_pinned_failure_both_robots_share_fails_only_under_the_candidate_policy(
    pytester: pytest.Pytester,
) -> None:
    pytester.makefile(".lasertest.yaml", gate=PINNED.format(obstacle=WALL))
    failed = pytester.runpytest("--laser-policy=candidate")
    failed.assert_outcomes(failed=1)
    failed.stdout.fnmatch_lines(
        [
            "the candidate fails at the pinned placement size[[]pinned-0[]]: pre-existing: the "
            "baseline fails here too",
            "  obstacle   box 0.200 x 6.000 m, yaw 0.000 rad, at (3.000, 0.000) m, 0.500 m high "
            "(gate.lasertest.yaml:11)",
            "  noise seed 3 (pinned; --laser-seed does not change it)",
        ]
    )
    noted = pytester.runpytest()  # the default, regression
    assert noted.ret == pytest.ExitCode.OK
    assert outcomes(noted) == {"pre-existing": 1}
