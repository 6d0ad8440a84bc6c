"""Obstacle footprints, exact ray casts and segment clearances, by hand and against brute force."""

from __future__ import annotations

import math
import warnings

import numpy as np
import numpy.typing as npt
import pytest

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.obstacles import (
    Box,
    Cylinder,
    Obstacle,
    ray_distances,
    segment_clearances,
)

# A 2 m by 1 m box centred 5 m ahead of the world origin, and a 1 m radius cylinder there too.
AHEAD_BOX = Box(x=5.0, y=0.0, yaw=0.0, length=2.0, width=1.0, height=1.0)
AHEAD_CYLINDER = Cylinder(x=5.0, y=0.0, radius=1.0, height=1.0)
# A 4 m by 2 m box at the world origin, its length axis turned 30 degrees to the left.
TURNED_BOX = Box(x=0.0, y=0.0, yaw=math.radians(30.0), length=4.0, width=2.0, height=1.0)

ALONG_X = (1.0, 0.0)


def rays(*pairs: tuple[tuple[float, float], tuple[float, float]]) -> tuple[FloatArray, FloatArray]:
    """Origins and directions, each shape (R, 2), from (origin, direction) pairs."""
    origins = np.array([origin for origin, _ in pairs], dtype=np.float64).reshape(-1, 2)
    directions = np.array([direction for _, direction in pairs], dtype=np.float64).reshape(-1, 2)
    return origins, directions


def cast(origin: tuple[float, float], direction: tuple[float, float], obstacle: Obstacle) -> float:
    """The entry distance of one ray."""
    return float(ray_distances(*rays((origin, direction)), obstacle)[0])


def clearance(
    origin: tuple[float, float],
    direction: tuple[float, float],
    start: float,
    end: float,
    obstacle: Obstacle,
) -> float:
    """The clearance of one segment."""
    origins, directions = rays((origin, direction))
    return float(
        segment_clearances(origins, directions, np.array([start]), np.array([end]), obstacle)[0]
    )


def unit(angle: float) -> tuple[float, float]:
    return (math.cos(angle), math.sin(angle))


# Hand-computed ray casts.


def test_a_ray_through_the_centre_of_a_box_enters_at_its_near_face() -> None:
    assert cast((0.0, 0.0), ALONG_X, AHEAD_BOX) == 4.0


def test_a_ray_from_behind_a_box_enters_at_its_far_face() -> None:
    assert cast((10.0, 0.2), (-1.0, 0.0), AHEAD_BOX) == 4.0


def test_a_ray_across_a_box_enters_at_its_side_face() -> None:
    assert cast((5.5, -3.0), (0.0, 1.0), AHEAD_BOX) == 2.5


def test_a_ray_along_the_world_x_axis_enters_a_turned_box_where_its_long_side_crosses() -> None:
    # On y = 0 the box frame has y' = -x sin 30, so |y'| <= 1 bounds x to [-2, 2] before
    # |x'| = |x| cos 30 <= 2 does (|x| <= 2.31).
    assert cast((-10.0, 0.0), ALONG_X, TURNED_BOX) == pytest.approx(8.0, abs=1e-12)


def test_a_ray_along_the_length_axis_of_a_turned_box_enters_at_its_end_face() -> None:
    origin = (-10.0 * math.cos(math.radians(30.0)), -10.0 * math.sin(math.radians(30.0)))
    assert cast(origin, unit(math.radians(30.0)), TURNED_BOX) == pytest.approx(8.0, abs=1e-12)


def test_a_ray_across_the_width_axis_of_a_turned_box_enters_at_its_long_side() -> None:
    across = math.radians(120.0)
    origin = (-10.0 * math.cos(across), -10.0 * math.sin(across))
    assert cast(origin, unit(across), TURNED_BOX) == pytest.approx(9.0, abs=1e-12)


def test_a_ray_towards_the_centre_of_a_cylinder_enters_one_radius_short_of_it() -> None:
    cylinder = Cylinder(x=3.0, y=4.0, radius=1.0, height=2.0)
    assert cast((0.0, 0.0), (0.6, 0.8), cylinder) == pytest.approx(4.0, abs=1e-15)


def test_an_off_centre_ray_enters_a_cylinder_where_the_chord_begins() -> None:
    # The chord at 0.6 m from the centre runs 0.8 m either side of its midpoint.
    assert cast((0.0, 0.6), ALONG_X, AHEAD_CYLINDER) == pytest.approx(4.2, abs=1e-15)


@pytest.mark.parametrize(
    ("origin", "obstacle"),
    [
        ((5.0, 0.0), AHEAD_BOX),
        ((5.9, -0.45), AHEAD_BOX),
        ((5.3, 0.2), AHEAD_CYLINDER),
        ((0.0, 0.0), TURNED_BOX),
        ((1.6, 0.9), TURNED_BOX),
    ],
)
def test_a_ray_from_inside_an_obstacle_is_in_it_at_distance_zero(
    origin: tuple[float, float], obstacle: Obstacle
) -> None:
    for angle in np.linspace(-math.pi, math.pi, 13):
        assert cast(origin, unit(angle), obstacle) == 0.0


@pytest.mark.parametrize(
    ("origin", "obstacle"),
    [((4.0, 0.0), AHEAD_BOX), ((5.0, 0.5), AHEAD_BOX), ((6.0, 0.0), AHEAD_CYLINDER)],
)
def test_a_ray_from_the_boundary_is_in_the_obstacle_at_distance_zero(
    origin: tuple[float, float], obstacle: Obstacle
) -> None:
    assert cast(origin, (0.0, 1.0), obstacle) == 0.0
    assert cast(origin, (-1.0, 0.0), obstacle) == 0.0


@pytest.mark.parametrize("obstacle", [AHEAD_BOX, AHEAD_CYLINDER, TURNED_BOX])
def test_a_ray_pointing_away_from_an_obstacle_misses_it(obstacle: Obstacle) -> None:
    assert cast((obstacle.x - 3.0, obstacle.y), (-1.0, 0.0), obstacle) == math.inf
    assert cast((obstacle.x, obstacle.y + 3.0), (0.0, 1.0), obstacle) == math.inf


def test_a_ray_sliding_along_the_side_of_a_box_grazes_it_at_its_corner() -> None:
    assert cast((0.0, 0.5), ALONG_X, AHEAD_BOX) == 4.0
    assert cast((0.0, -0.5), ALONG_X, AHEAD_BOX) == 4.0


def test_a_ray_just_outside_the_side_of_a_box_misses_it() -> None:
    assert cast((0.0, 0.5 + 1e-12), ALONG_X, AHEAD_BOX) == math.inf


def test_a_diagonal_ray_touching_only_a_corner_of_a_box_grazes_it_there() -> None:
    box = Box(x=0.0, y=0.0, yaw=0.0, length=2.0, width=2.0, height=1.0)
    diagonal = (math.sqrt(0.5), math.sqrt(0.5))
    assert cast((-2.0, 0.0), diagonal, box) == pytest.approx(math.sqrt(2.0), abs=1e-15)
    assert cast((-2.0, 1e-9), diagonal, box) == math.inf


def test_a_ray_tangent_to_a_cylinder_grazes_it_at_the_point_of_contact() -> None:
    assert cast((0.0, 1.0), ALONG_X, AHEAD_CYLINDER) == 5.0
    assert cast((0.0, -1.0), ALONG_X, AHEAD_CYLINDER) == 5.0
    assert cast((0.0, 1.0 + 1e-9), ALONG_X, AHEAD_CYLINDER) == math.inf


# Hand-computed segment clearances.


def test_a_zero_length_segment_is_as_clear_of_a_box_as_its_point_in_the_box_metric() -> None:
    box = Box(x=0.0, y=0.0, yaw=0.0, length=2.0, width=1.0, height=1.0)
    assert clearance((3.0, 0.0), ALONG_X, 0.0, 0.0, box) == 2.0
    # The box metric takes the larger axis gap, not the Euclidean distance to the corner.
    assert clearance((3.0, 3.0), ALONG_X, 0.0, 0.0, box) == 2.5
    assert clearance((0.2, 0.1), ALONG_X, 0.0, 0.0, box) == pytest.approx(-0.4)


def test_a_zero_length_segment_is_as_clear_of_a_cylinder_as_its_point() -> None:
    cylinder = Cylinder(x=0.0, y=0.0, radius=1.0, height=1.0)
    assert clearance((3.0, 4.0), ALONG_X, 0.0, 0.0, cylinder) == 4.0
    assert clearance((0.0, 0.25), (0.0, 1.0), 2.0, 2.0, cylinder) == 1.25


def test_a_zero_length_segment_on_the_boundary_has_zero_clearance() -> None:
    assert clearance((4.0, 0.3), ALONG_X, 0.0, 0.0, AHEAD_BOX) == 0.0
    assert clearance((4.0, 0.0), ALONG_X, 0.0, 0.0, AHEAD_CYLINDER) == 0.0


@pytest.mark.parametrize("obstacle", [AHEAD_BOX, AHEAD_CYLINDER])
def test_a_segment_stopping_short_of_an_obstacle_clears_it_by_the_remaining_distance(
    obstacle: Obstacle,
) -> None:
    assert clearance((0.0, 0.0), ALONG_X, 0.0, 3.0, obstacle) == 1.0
    assert clearance((0.0, 0.0), ALONG_X, 1.0, 3.5, obstacle) == 0.5


def test_a_segment_ending_at_the_face_of_a_box_has_zero_clearance() -> None:
    assert clearance((0.0, 0.0), ALONG_X, 0.0, 4.0, AHEAD_BOX) == 0.0


def test_a_segment_starting_past_a_box_clears_it_by_its_distance_behind() -> None:
    assert clearance((0.0, 0.0), ALONG_X, 7.5, 9.0, AHEAD_BOX) == 1.5


def test_a_segment_passing_a_box_corner_obliquely_is_clearest_where_both_gaps_are_equal() -> None:
    # On x + y = 4 the gaps |x| - 1 and |y| - 0.5 are equal at x = 2.25, and g is 1.25 there.
    box = Box(x=0.0, y=0.0, yaw=0.0, length=2.0, width=1.0, height=1.0)
    direction = (math.sqrt(0.5), -math.sqrt(0.5))
    assert clearance((0.0, 4.0), direction, 0.0, 10.0, box) == pytest.approx(1.25, abs=1e-12)


def test_a_segment_alongside_a_turned_box_clears_it_by_its_offset_from_the_long_side() -> None:
    side = unit(math.radians(120.0))
    origin = (-5.0 * math.cos(math.radians(30.0)) + 3.0 * side[0], 3.0 * side[1] - 2.5)
    assert clearance(origin, unit(math.radians(30.0)), 0.0, 10.0, TURNED_BOX) == pytest.approx(
        2.0, abs=1e-12
    )


@pytest.mark.parametrize("angle", [0.0, 0.4, 1.2, math.pi / 2, 2.5])
def test_a_segment_through_the_centre_of_a_box_is_in_it_by_its_smaller_half_size(
    angle: float,
) -> None:
    direction = unit(angle)
    origin = (-5.0 * direction[0], -5.0 * direction[1])
    assert clearance(origin, direction, 0.0, 10.0, TURNED_BOX) == pytest.approx(-1.0, abs=1e-12)
    origin = (5.0 - 5.0 * direction[0], -5.0 * direction[1])
    assert clearance(origin, direction, 0.0, 10.0, AHEAD_BOX) == pytest.approx(-0.5, abs=1e-12)


@pytest.mark.parametrize("angle", [0.0, 0.4, 1.2, math.pi / 2, 2.5])
def test_a_segment_through_the_centre_of_a_cylinder_is_in_it_by_its_radius(angle: float) -> None:
    direction = unit(angle)
    origin = (5.0 - 5.0 * direction[0], -5.0 * direction[1])
    assert clearance(origin, direction, 0.0, 10.0, AHEAD_CYLINDER) == pytest.approx(-1.0, abs=1e-12)


def test_a_segment_tangent_to_a_cylinder_has_zero_clearance() -> None:
    assert clearance((0.0, 1.0), ALONG_X, 0.0, 10.0, AHEAD_CYLINDER) == 0.0


# Dilation.


def test_a_dilated_box_keeps_its_centre_yaw_and_height_and_grows_on_every_side() -> None:
    grown = TURNED_BOX.grown(0.25)
    assert grown == Box(x=0.0, y=0.0, yaw=TURNED_BOX.yaw, length=4.5, width=2.5, height=1.0)


def test_a_dilated_cylinder_grows_its_radius_by_the_margin() -> None:
    assert AHEAD_CYLINDER.grown(-0.25) == Cylinder(x=5.0, y=0.0, radius=0.75, height=1.0)


@pytest.mark.parametrize(
    ("obstacle", "margin"),
    [(AHEAD_BOX, -0.5), (AHEAD_BOX, -2.0), (AHEAD_CYLINDER, -1.0), (AHEAD_CYLINDER, math.nan)],
)
def test_a_margin_that_empties_the_footprint_is_refused(obstacle: Obstacle, margin: float) -> None:
    with pytest.raises(ValueError, match="no area"):
        obstacle.grown(margin)


# Input checks and vectorisation.


@pytest.mark.parametrize("count", [0, 1, 1000])
@pytest.mark.parametrize("obstacle", [AHEAD_BOX, AHEAD_CYLINDER, TURNED_BOX])
def test_every_ray_and_segment_gets_one_answer_whatever_the_count(
    count: int, obstacle: Obstacle
) -> None:
    rng = np.random.default_rng(count)
    origins = rng.uniform(-10.0, 10.0, size=(count, 2))
    angles = rng.uniform(-math.pi, math.pi, size=count)
    directions = np.column_stack([np.cos(angles), np.sin(angles)])
    starts = rng.uniform(0.0, 2.0, size=count)

    distances = ray_distances(origins, directions, obstacle)
    clearances = segment_clearances(origins, directions, starts, starts + 3.0, obstacle)

    assert distances.shape == (count,)
    assert clearances.shape == (count,)
    assert distances.dtype == clearances.dtype == np.float64
    for i in range(min(count, 20)):
        assert distances[i] == ray_distances(origins[i : i + 1], directions[i : i + 1], obstacle)


def test_rays_of_the_wrong_shape_are_refused() -> None:
    with pytest.raises(ValueError, match=r"shape \(R, 2\)"):
        ray_distances(np.zeros((3, 3)), np.zeros((3, 3)), AHEAD_BOX)
    with pytest.raises(ValueError, match=r"shape \(R, 2\)"):
        ray_distances(np.zeros((3, 2)), np.zeros((2, 2)), AHEAD_BOX)


def test_segment_bounds_of_the_wrong_shape_or_order_are_refused() -> None:
    origins, directions = np.zeros((2, 2)), np.tile(ALONG_X, (2, 1))
    with pytest.raises(ValueError, match=r"shape \(2,\)"):
        segment_clearances(origins, directions, np.zeros(3), np.ones(3), AHEAD_BOX)
    with pytest.raises(ValueError, match="no later than"):
        segment_clearances(origins, directions, np.ones(2), np.zeros(2), AHEAD_CYLINDER)


# Randomised cross-checks against brute force.

STEP = 1e-3  # m, between the samples of the brute-force checks
REACH = 20.0  # m, of the sampled part of every ray: past every random obstacle


def random_obstacle(rng: np.random.Generator) -> Obstacle:
    x, y = rng.uniform(-2.0, 2.0, size=2)
    if rng.random() < 0.5:
        return Cylinder(x=x, y=y, radius=rng.uniform(0.05, 2.0), height=1.0)
    length, width = rng.uniform(0.05, 3.0, size=2)
    return Box(x=x, y=y, yaw=rng.uniform(-math.pi, math.pi), length=length, width=width, height=1.0)


def random_rays(
    rng: np.random.Generator, count: int, obstacle: Obstacle, spread: float = 0.6
) -> tuple[FloatArray, ...]:
    """Origins and unit directions, shape (count, 2), aimed at the obstacle give or take spread."""
    origins = rng.uniform(-6.0, 6.0, size=(count, 2))
    towards = np.arctan2(obstacle.y - origins[:, 1], obstacle.x - origins[:, 0])
    angles = towards + rng.normal(0.0, spread, size=count)  # rad
    return origins, np.column_stack([np.cos(angles), np.sin(angles)])


def footprint_gaps(points: FloatArray, obstacle: Obstacle) -> FloatArray:
    """The clearance metric at points of shape (..., 2), worked out independently of geometry."""
    dx, dy = points[..., 0] - obstacle.x, points[..., 1] - obstacle.y
    if isinstance(obstacle, Cylinder):
        gaps: FloatArray = np.hypot(dx, dy) - obstacle.radius
        return gaps
    along = dx * math.cos(obstacle.yaw) + dy * math.sin(obstacle.yaw)
    across = -dx * math.sin(obstacle.yaw) + dy * math.cos(obstacle.yaw)
    box_gaps: FloatArray = np.maximum(
        np.abs(along) - obstacle.length / 2, np.abs(across) - obstacle.width / 2
    )
    return box_gaps


def sampled(origins: FloatArray, directions: FloatArray, ts: FloatArray) -> FloatArray:
    """Points o + t d, shape (R, T, 2), for t in ts of shape (R, T)."""
    points: FloatArray = origins[:, None, :] + ts[..., None] * directions[:, None, :]
    return points


@pytest.mark.parametrize("seed", [1, 2, 3, 4, 5, 6])
def test_ray_distances_agree_with_dense_sampling_along_each_ray(seed: int) -> None:
    rng = np.random.default_rng(seed)
    ts = np.arange(0.0, REACH, STEP)
    for _ in range(10):
        obstacle = random_obstacle(rng)
        origins, directions = random_rays(rng, 10, obstacle)

        exact = ray_distances(origins, directions, obstacle)
        inside = footprint_gaps(sampled(origins, directions, np.tile(ts, (10, 1))), obstacle) <= 0
        brute = np.where(inside.any(axis=1), ts[inside.argmax(axis=1)], np.inf)

        hit = np.isfinite(brute)
        assert np.all(exact[hit] <= brute[hit] + 1e-9)
        assert np.all(exact[hit] >= brute[hit] - STEP - 1e-9)
        # The only hits sampling may skip are chords shorter than a step; they must be real.
        skipped = ~hit & np.isfinite(exact)
        entry_points = origins[skipped] + exact[skipped, None] * directions[skipped]
        np.testing.assert_allclose(footprint_gaps(entry_points, obstacle), 0.0, atol=1e-9)


@pytest.mark.parametrize("seed", [11, 12, 13, 14, 15, 16])
def test_ray_distances_end_on_the_boundary_of_the_footprint(seed: int) -> None:
    rng = np.random.default_rng(seed)
    obstacle = random_obstacle(rng)
    origins, directions = random_rays(rng, 200, obstacle, spread=0.2)

    exact = ray_distances(origins, directions, obstacle)

    outside = footprint_gaps(origins, obstacle) > 0
    entered = outside & np.isfinite(exact)
    assert entered.sum() > 20
    np.testing.assert_array_equal(exact[~outside], 0.0)
    entry_points = origins[entered] + exact[entered, None] * directions[entered]
    np.testing.assert_allclose(footprint_gaps(entry_points, obstacle), 0.0, atol=1e-9)


@pytest.mark.parametrize("seed", [21, 22, 23, 24, 25, 26])
def test_segment_clearances_agree_with_the_least_gap_over_a_dense_grid(seed: int) -> None:
    rng = np.random.default_rng(seed)
    fractions = np.linspace(0.0, 1.0, 8001)
    for _ in range(10):
        obstacle = random_obstacle(rng)
        origins, directions = random_rays(rng, 30, obstacle)
        starts = rng.uniform(-1.0, 4.0, size=30)
        lengths = np.where(rng.random(30) < 0.1, 0.0, rng.uniform(0.0, 8.0, size=30))
        ends = starts + lengths

        exact = segment_clearances(origins, directions, starts, ends, obstacle)
        ts = starts[:, None] + fractions * lengths[:, None]
        brute = footprint_gaps(sampled(origins, directions, ts), obstacle).min(axis=1)

        # Both metrics change by at most 1 m per metre along a unit direction.
        step = lengths * (fractions[1] - fractions[0])
        assert np.all(exact <= brute + 1e-9)
        assert np.all(brute <= exact + 1e-6 + step)


Segments = tuple[FloatArray, FloatArray, FloatArray, FloatArray]


def random_segments(rng: np.random.Generator, count: int, box: Box) -> Segments:
    """Origins and directions, shape (count, 2), and bounds, shape (count,), with starts >= 0."""
    origins, directions = random_rays(rng, count, box)
    starts = rng.uniform(0.0, 3.0, size=count)
    ends = starts + np.where(rng.random(count) < 0.1, 0.0, rng.uniform(0.0, 8.0, size=count))
    return origins, directions, starts, ends


def crosses(segments: Segments, obstacle: Obstacle) -> npt.NDArray[np.bool_]:
    """Whether each segment touches the obstacle's footprint, shape (R,) of bool."""
    origins, directions, starts, ends = segments
    firsts = origins + starts[:, None] * directions
    crossed: npt.NDArray[np.bool_] = ray_distances(firsts, directions, obstacle) <= ends - starts
    return crossed


def one_of(segments: Segments, i: int) -> Segments:
    """Segment i alone, as a batch of one."""
    origins, directions, starts, ends = segments
    return origins[i : i + 1], directions[i : i + 1], starts[i : i + 1], ends[i : i + 1]


def random_box(rng: np.random.Generator) -> Box:
    obstacle = random_obstacle(rng)
    while not isinstance(obstacle, Box):
        obstacle = random_obstacle(rng)
    return obstacle


@pytest.mark.parametrize("seed", [31, 32, 33, 34, 35, 36])
def test_a_segment_misses_a_dilated_box_exactly_when_its_clearance_exceeds_the_margin(
    seed: int,
) -> None:
    rng = np.random.default_rng(seed)
    outcomes = set()
    for _ in range(20):
        box = random_box(rng)
        segments = random_segments(rng, 20, box)
        clearances = segment_clearances(*segments, box)
        deepest = -min(box.length, box.width) / 2  # m, the margin that leaves no area
        margins = rng.uniform(0.98 * deepest, 3.0, size=20)
        # Half the margins lie a micrometre either side of the clearance, to test it is tight.
        near = rng.random(20) < 0.5
        margins[near] = clearances[near] + rng.choice([-1e-6, 1e-6], size=near.sum())
        for i in np.flatnonzero(margins > 0.98 * deepest):
            crossed = bool(crosses(one_of(segments, int(i)), box.grown(margins[i]))[0])
            assert crossed == (clearances[i] < margins[i])
            outcomes.add(crossed)
    assert outcomes == {True, False}


@pytest.mark.parametrize("seed", [41, 42, 43, 44, 45, 46])
def test_a_segment_inside_a_box_crosses_the_box_shrunk_by_half_its_depth(seed: int) -> None:
    rng = np.random.default_rng(seed)
    crossings = 0
    for _ in range(20):
        box = random_box(rng)
        segments = random_segments(rng, 20, box)
        clearances = segment_clearances(*segments, box)
        for i in np.flatnonzero(clearances < -1e-9):
            assert crosses(one_of(segments, int(i)), box.grown(clearances[i] / 2))[0]
            crossings += 1
    assert crossings > 20


def test_a_segment_all_but_parallel_to_a_box_side_gives_its_clearance_without_a_warning() -> None:
    box = Box(x=0.0, y=0.0, yaw=0.0, length=1.0, width=1.0, height=1.0)
    # Along y = 1, off by 1e-310 rad: a kink with a denominator that overflows the division.
    origins = np.array([[-3.0, 1.0]])
    directions = np.array([[1.0, 1e-310]])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        clearance = segment_clearances(origins, directions, np.zeros(1), np.full(1, 6.0), box)
    assert clearance == pytest.approx([0.5])
