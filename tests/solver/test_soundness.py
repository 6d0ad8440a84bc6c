"""Whatever two scanners are compared, the solver's answer agrees with the exact ray cast: a
witness it returns verifies, and no model it builds on the way fails the verifier (the answer
is then `unknown` with "failed the ray cast" in its explanation, a bug in an encoding)."""

from __future__ import annotations

import dataclasses
import math

from hypothesis import given, settings
from hypothesis import strategies as st

from pytest_lasertest.model.geometry import Point2D, Pose2D, Pose3D
from pytest_lasertest.model.route import NominalPath, nominal_path
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.model.verify import DIRECTIONS, Scene, verify
from pytest_lasertest.solver.plan import plan_direction
from tests.helpers.paper import PAPER, SETTINGS

LMS1XX = PAPER.pairs[0].baseline.profile
ROUTES = (
    nominal_path(Pose2D(0.0, 0.0, 0.0), (Point2D(6.0, 0.0),), 0.5, 1.0),
    nominal_path(Pose2D(0.0, 0.0, 0.0), (Point2D(2.0, 0.0), Point2D(2.0, 4.0)), 0.5, 1.0),
)
# A tenth of the default: an undecided answer is allowed here, a model the ray cast rejects is not.
QUICK = dataclasses.replace(SETTINGS, rlimit=500_000)


@st.composite
def scanners(draw: st.DrawFn) -> LaserProfile:
    """A scanner on the Husky: beams, field of view, ranges, rate and mount drawn."""
    low = draw(st.floats(0.5, 2.356))
    high = draw(st.floats(0.5, 2.356))
    range_min = draw(st.floats(0.02, 1.0))
    x, z = draw(st.floats(0.1, 0.45)), draw(st.floats(0.2, 0.6))
    upside_down = draw(st.booleans())
    return dataclasses.replace(
        LMS1XX,
        samples=draw(st.integers(16, 1081)),
        min_angle=-low,
        max_angle=high,
        range_min=range_min,
        range_max=draw(st.floats(range_min + 2.0, 30.0)),
        update_rate=draw(st.sampled_from((5.5, 10.0, 15.0, 40.0, 50.0))),
        pose=Pose3D((x, 0.0, z), (math.pi if upside_down else 0.0, 0.0, 0.0)),
        noise=None,
    )


@settings(max_examples=40, deadline=None, derandomize=True)
@given(baseline=scanners(), candidate=scanners(), route=st.sampled_from(ROUTES))
def test_no_answer_of_the_solver_disagrees_with_the_ray_cast(
    baseline: LaserProfile, candidate: LaserProfile, route: NominalPath
) -> None:
    scene = Scene(baseline, candidate, PAPER.robot, route)
    for direction in DIRECTIONS:
        plan = plan_direction(scene, direction, QUICK)
        assert "failed the ray cast" not in plan.explanation
        for witness in plan.witnesses:
            assert verify(scene, witness.placement).holds()
