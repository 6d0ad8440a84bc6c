"""The Nav2 stack's compiled loops give the numpy code's answers to the bit: the collision
monitor's count of points inside a footprint at a pose and the time of the first step that
holds min_points, DWB's rollouts, and MPPI's motion model, integration, CostCritic's sums,
PathAlignCritic's distances, the GoalCritic's means, the ConstraintCritic's and
PreferForwardCritic's sums and the softmax update's sums."""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.nav.nav2.collision_monitor import (
    CollisionMonitorSettings,
    collision_time_of,
    inside,
    transform_points,
)
from pytest_lasertest.nav.nav2.critics import (
    CostCritic,
    cost_critic_sums_in_numpy,
    path_align_gaps_in_numpy,
)
from pytest_lasertest.nav.nav2.dwb_settings import DwbSettings
from pytest_lasertest.nav.nav2.dwb_trajectories import roll_out, roll_out_in_numpy, sample_twists
from pytest_lasertest.nav.nav2.kernels import (
    NO_COLLISION,
    bound_steps,
    collision_time,
    control_costs,
    cost_critic_sums,
    count_inside,
    mean_distances,
    path_align_gaps,
    speed_beyond,
    weighted_means,
)
from pytest_lasertest.nav.nav2.motion_model import (
    changes,
    integrate,
    integrate_in_numpy,
    limit,
    predict,
    predict_in_numpy,
)
from pytest_lasertest.nav.nav2.mppi import CostGrid, Cycle
from tests.helpers.mppi import optimizer

# A Husky-sized box and a concave outline with edges level with each other, where ray
# crossings could err.
FOOTPRINTS = [
    np.array([[0.5, 0.35], [-0.5, 0.35], [-0.5, -0.35], [0.5, -0.35]]),
    np.array([[1.0, 1.0], [1.0, 0.0], [2.0, 0.0], [2.0, -1.0], [-1.0, -1.0], [-1.0, 1.0]]),
]  # m


def scattered(rng: np.random.Generator, count: int, spread: float = 2.5) -> np.ndarray:
    """Points (count, 2) m within `spread` m of the robot along each axis, a third of them on a
    5 cm grid (level with the footprints' corners and edges)."""
    points = rng.uniform(-spread, spread, (count, 2))
    points[: count // 3] = np.round(points[: count // 3] * 20.0) / 20.0
    return points


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("footprint", FOOTPRINTS, ids=["box", "concave"])
def test_the_count_inside_at_a_pose_is_the_numpy_count_of_the_points_moved_there(
    footprint: np.ndarray, seed: int
) -> None:
    rng = np.random.default_rng(seed)
    for _ in range(50):
        points, pose = scattered(rng, 200), tuple(rng.uniform(-1.0, 1.0, 3))
        expected = inside(transform_points(pose, points), footprint)
        assert count_inside(points, footprint, *pose) == expected


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("footprint", FOOTPRINTS, ids=["box", "concave"])
def test_the_collision_time_is_the_numpy_loops_to_the_bit(footprint: np.ndarray, seed: int) -> None:
    rng = np.random.default_rng(seed)
    settings = CollisionMonitorSettings(time_before_collision=1.2, simulation_time_step=0.1)
    found = 0
    for _ in range(100):
        points = scattered(rng, int(rng.integers(0, 60)), spread=1.5)
        linear, angular = rng.uniform(-1.0, 1.0), rng.choice([0.0, rng.uniform(-2.0, 2.0)])
        expected = collision_time_of((linear, angular), points, footprint, settings)
        time = collision_time(linear, angular, points, footprint, 0.1, 1.2, settings.min_points)
        assert time == (NO_COLLISION if expected is None else expected)
        found += expected is not None
    assert 10 < found < 90  # both answers were compared, often


@pytest.mark.parametrize("seed", range(6))
def test_dwbs_compiled_rollouts_are_the_numpy_rollouts_to_the_bit(seed: int) -> None:
    rng = np.random.default_rng(seed)
    settings = DwbSettings(
        include_last_point=bool(seed % 2),
        sim_time=float(rng.uniform(0.5, 2.0)),
        decel_lim_x=float(rng.uniform(-3.0, -0.5)),
        acc_lim_theta=float(rng.uniform(0.5, 4.0)),
    )
    for _ in range(20):
        pose = (float(rng.uniform(-5, 5)), float(rng.uniform(-5, 5)), float(rng.uniform(-4, 4)))
        speed = (float(rng.uniform(-0.2, 0.6)), float(rng.uniform(-1.0, 1.0)))
        vx, wz = sample_twists(settings, speed)
        compiled, expected = (
            way(settings, pose, speed, vx, wz) for way in (roll_out, roll_out_in_numpy)
        )
        for name in ("x", "y", "yaw"):
            assert np.array_equal(getattr(compiled, name), getattr(expected, name)), name


def bits(array: np.ndarray) -> np.ndarray:
    """float32 values as their bit patterns, so that 0.0 and -0.0 differ."""
    return np.ascontiguousarray(array, dtype=np.float32).view(np.uint32)


def noised_controls(rng: np.random.Generator, steps: int, batch: int) -> np.ndarray:
    """Noised (vx, wz) controls (2, T, B) m/s, rad/s, a quarter of them 0.0 or -0.0, where a
    clip that kept the other zero would show."""
    controls = rng.normal(0.0, 0.4, (2, steps, batch)).astype(np.float32)
    zeros = rng.random(controls.shape) < 0.25
    controls[zeros] = np.where(rng.random(int(zeros.sum())) < 0.5, 0.0, -0.0)
    return controls


@pytest.mark.parametrize("seed", range(6))
def test_mppis_compiled_motion_model_bounds_the_samples_as_numpy_does_to_the_bit(
    seed: int,
) -> None:
    rng = np.random.default_rng(seed)
    # Nav2's symmetric limits, then braking harder than speeding up (ax_min -3 against 0.5).
    ax_min = -3.0 if seed % 2 else -0.5
    change = changes(0.05, 0.5, ax_min, float(rng.uniform(1.0, 4.0)))
    speed = (float(rng.choice([0.0, -0.0, rng.uniform(-0.3, 0.5)])), float(rng.normal(0, 0.5)))
    controls = noised_controls(rng, 56, 300)
    given, reference = controls.copy(), controls.copy()
    compiled = predict(given[0], given[1], speed, change)
    expected = predict_in_numpy(reference[0], reference[1], speed, change)
    for ours, theirs in zip((*compiled, *given), (*expected, *reference), strict=True):
        assert np.array_equal(bits(ours), bits(theirs))


@pytest.mark.parametrize("seed", range(6))
def test_mppis_compiled_integration_is_the_numpy_integration_to_the_bit(seed: int) -> None:
    rng = np.random.default_rng(seed)
    vx, wz = noised_controls(rng, 56, 300)
    pose = (float(rng.uniform(-20, 20)), float(rng.uniform(-20, 20)), float(rng.uniform(-4, 4)))
    compiled = integrate(vx, wz, pose, 0.05)
    expected = integrate_in_numpy(vx, wz, pose, 0.05)
    for ours, theirs in zip(compiled, expected, strict=True):
        assert np.array_equal(bits(ours), bits(theirs))


@pytest.mark.parametrize("step", [1, 2, 4, 5])
@pytest.mark.parametrize("seed", range(3))
def test_path_aligns_compiled_distances_are_the_numpy_distances_to_the_bit(
    seed: int, step: int
) -> None:
    rng = np.random.default_rng(seed)
    # A winding plan of 5 cm steps ahead of the robot, a tenth of its points blocked, and one
    # cycle's samples as MPPI draws them (a thousand of 56 steps, read as (B, T) views).
    turns = np.cumsum(rng.normal(0.0, 0.15, 60))
    path = np.column_stack(
        [np.cumsum(0.05 * np.cos(turns)), np.cumsum(0.05 * np.sin(turns))]
    ).astype(np.float32)
    valid = rng.random(len(path)) > 0.1
    speed = (float(rng.uniform(0.0, 0.5)), float(rng.normal(0.0, 0.3)))
    mppi = optimizer({"FollowPath.batch_size": 1000})
    mppi.vx[:] = np.float32(rng.uniform(0.1, 0.5))
    data = mppi._samples(Cycle((0.0, 0.0, 0.0), speed, path, (3.0, 0.0), None))
    along = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(path, axis=0).T))])
    compiled = path_align_gaps(data.x.T, data.y.T, step, along, path, valid)
    expected = path_align_gaps_in_numpy(data, step, along, path, valid)
    assert np.array_equal(compiled[1], expected[1])
    assert np.array_equal(bits(compiled[0]), bits(expected[0]))


@pytest.mark.parametrize("critical_cost", [300.0, 300.3])
@pytest.mark.parametrize("seed", range(4))
def test_cost_critics_compiled_sums_are_the_numpy_sums_to_the_bit(
    seed: int, critical_cost: float
) -> None:
    rng = np.random.default_rng(seed)
    # A 2 m costmap, smaller than the samples' reach, of every cost (near-lethal ones often);
    # a critical cost that is not a whole number makes the order of the sum show.
    costs = rng.choice([0, 17, 100, 252, 253, 254, 255], size=(40, 40)).astype(np.uint8)
    grid = CostGrid(costs, (-0.7, -1.0), 0.05, tracking_unknown=bool(seed % 2))
    critic = CostCritic(critical_cost=critical_cost, near_goal_distance=0.5 + seed % 3)
    mppi = optimizer({"FollowPath.batch_size": 500})
    mppi.vx[:] = np.float32(0.4)
    path = np.array([[0.0, 0.0], [2.0, 0.0]], dtype=np.float32)
    data = mppi._samples(Cycle((0.0, 0.0, 0.2), (0.3, 0.0), path, (1.2, 0.0), grid))
    points = data.x.shape[1] // critic.trajectory_point_step
    compiled = cost_critic_sums(
        data.x.T,
        data.y.T,
        critic.trajectory_point_step,
        points,
        costs,
        np.float32(-0.7),
        np.float32(-1.0),
        np.float32(0.05),
        grid.tracking_unknown,
        np.float32(critic.near_collision_cost),
        critical_cost,
        data.within(critic.near_goal_distance),
    )
    expected = cost_critic_sums_in_numpy(critic, data, grid)
    assert np.array_equal(compiled[1], expected[1])
    assert np.array_equal(bits(compiled[0]), bits(expected[0]))


@pytest.mark.parametrize("seed", range(4))
def test_mppis_compiled_update_sums_are_numpys_to_the_bit(seed: int) -> None:
    rng = np.random.default_rng(seed)
    mppi = optimizer({"FollowPath.batch_size": 2000})
    mppi.vx[:] = rng.uniform(-0.2, 0.5, len(mppi.vx)).astype(np.float32)
    mppi.vx[::7] = 0.0  # where a product is a signed zero
    path = np.array([[0.0, 0.0], [2.0, 0.0]], dtype=np.float32)
    data = mppi._samples(Cycle((0.0, 0.0, 0.0), (0.2, 0.1), path, (2.0, 0.0), None))
    noised = np.ascontiguousarray(data.cvx.T)  # time-major, as the samples lie
    expected = (mppi.vx * (data.cvx - mppi.vx)).sum(axis=1)
    assert np.array_equal(bits(control_costs(mppi.vx, noised)), bits(expected))
    weights = rng.exponential(1.0, 2000).astype(np.float32)
    weights[::5] = 0.0
    weights /= weights.sum()
    expected = (data.cvx * weights[:, np.newaxis]).sum(axis=0).astype(np.float32)
    assert np.array_equal(bits(weighted_means(noised, weights)), bits(expected))


@pytest.mark.parametrize("seed", range(4))
def test_mppis_compiled_goal_constraint_and_forward_sums_are_numpys_to_the_bit(seed: int) -> None:
    rng = np.random.default_rng(seed)
    mppi = optimizer({"FollowPath.batch_size": 2000})
    mppi.vx[:] = rng.uniform(-0.3, 0.4, len(mppi.vx)).astype(np.float32)
    path = np.array([[0.0, 0.0], [2.0, 0.0]], dtype=np.float32)
    data = mppi._samples(Cycle((0.0, 0.0, 0.3), (0.1, 0.0), path, (0.9, 0.4), None))
    speeds = data.time_major_speeds().copy()  # (T, B), and vx its (B, T) view, as the critics'
    speeds[:, ::9] = 0.0  # at rest, and the signed zeros of -vx
    vx = speeds.T
    goal = np.hypot(data.x - 0.9, data.y - 0.4).mean(axis=1)
    ours = mean_distances(*data.time_major(), np.float32(0.9), np.float32(0.4))
    assert np.array_equal(bits(ours), bits(goal))
    fastest, slowest = 0.26, -0.1  # m/s, the ConstraintCritic's
    beyond = (np.maximum(vx - fastest, 0.0) + np.maximum(slowest - vx, 0.0)).sum(axis=1)
    ours = speed_beyond(speeds, np.float32(fastest), np.float32(slowest))
    assert np.array_equal(bits(ours), bits(beyond))
    backwards = np.maximum(-vx, 0.0).sum(axis=1)
    ours = speed_beyond(speeds, np.float32(np.inf), np.float32(0.0))
    assert np.array_equal(bits(ours), bits(backwards))


@pytest.mark.parametrize("seed", range(6))
def test_mppis_compiled_step_bounds_clip_as_pythons_min_and_max_do(seed: int) -> None:
    rng = np.random.default_rng(seed)
    change = changes(0.05, 0.5, -3.0 if seed % 2 else -0.5, 3.2)
    vx, wz = noised_controls(rng, 2, 56)[:, 0]  # a sequence (T,) each, zeros of both signs
    expected_vx, expected_wz = vx.copy(), wz.copy()
    for step in range(1, len(vx)):  # the optimizer's loop before the kernel
        low_vx, high_vx, low_wz, high_wz = limit(
            expected_vx[step - 1], expected_wz[step - 1], change
        )
        expected_vx[step] = min(max(expected_vx[step], low_vx), high_vx)
        expected_wz[step] = min(max(expected_wz[step], low_wz), high_wz)
    bound_steps(vx, wz, *change)
    assert np.array_equal(bits(vx), bits(expected_vx))
    assert np.array_equal(bits(wz), bits(expected_wz))
