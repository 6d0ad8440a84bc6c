"""Whatever two scanners are compared, the solver decides, and its answer agrees with the exact
ray cast: a witness it returns verifies, and no model it builds on the way fails the verifier
(which would leave the direction `unknown`, "failed the ray cast": a bug in an encoding). And
the gaps a proof leaves out can hold nothing of the smallest size."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pytest_lasertest.model.geometry import Point2D, Pose2D, Pose3D
from pytest_lasertest.model.route import NominalPath, nominal_path
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.model.verify import DIRECTIONS, Scene, verify
from pytest_lasertest.solver.plan import plan_direction
from pytest_lasertest.solver.scans import _nearest_in_gap
from tests.helpers.paper import PAPER, SETTINGS

LMS1XX = PAPER.pairs[0].baseline.profile
ROUTES = (
    nominal_path(Pose2D(0.0, 0.0, 0.0), (Point2D(6.0, 0.0),), 0.5, 1.0),
    nominal_path(Pose2D(0.0, 0.0, 0.0), (Point2D(2.0, 0.0), Point2D(2.0, 4.0)), 0.5, 1.0),
)


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
def test_every_direction_of_any_two_scanners_is_decided_and_agrees_with_the_ray_cast(
    baseline: LaserProfile, candidate: LaserProfile, route: NominalPath
) -> None:
    scene = Scene(baseline, candidate, PAPER.robot, route)
    for direction in DIRECTIONS:
        plan = plan_direction(scene, direction, SETTINGS)
        assert plan.status in ("sat", "unsat"), plan.explanation
        for witness in plan.witnesses:
            assert verify(scene, witness.placement).holds()


@settings(max_examples=200, deadline=None, derandomize=True)
@given(
    spacing=st.floats(0.001, 0.2),  # rad between two beams
    size=st.floats(0.05, 1.0),  # m, a side of the square
    yaw=st.floats(0.0, math.pi / 2.0),
    lateral=st.floats(-0.5, 0.5),  # of the wedge's width where the square sits
)
def test_no_square_fits_between_two_beams_nearer_than_the_bound_proofs_leave_gaps_out_by(
    spacing: float, size: float, yaw: float, lateral: float
) -> None:
    # The bisector is +x; the square's centre moves out along it (and across, by `lateral`)
    # until all four corners lie between the rays at -spacing/2 and +spacing/2.
    half = size / 2.0
    corners = np.array([[-half, -half], [half, -half], [half, half], [-half, half]])
    turned = corners @ np.array([[math.cos(yaw), math.sin(yaw)], [-math.sin(yaw), math.cos(yaw)]])
    slope = math.tan(spacing / 2.0)

    def fits(out: float) -> bool:
        points = turned + np.array([out, lateral * out * slope])
        return bool((np.abs(points[:, 1]) <= points[:, 0] * slope).all())

    low, high = 0.0, 10.0 * size / slope
    assert fits(high)
    for _ in range(60):
        middle = (low + high) / 2.0
        low, high = (low, middle) if fits(middle) else (middle, high)
    nearest = float((turned[:, 0] + high).min())
    assert nearest >= _nearest_in_gap(spacing, size) - 1e-9
