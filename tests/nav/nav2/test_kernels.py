"""The Nav2 stack's compiled loops give the numpy code's answers to the bit: the collision
monitor's count of points inside a footprint at a pose and the time of the first step that
holds min_points, and DWB's rollouts."""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.nav.nav2.collision_monitor import (
    CollisionMonitorSettings,
    collision_time_of,
    inside,
    transform_points,
)
from pytest_lasertest.nav.nav2.dwb_settings import DwbSettings
from pytest_lasertest.nav.nav2.dwb_trajectories import roll_out, roll_out_in_numpy, sample_twists
from pytest_lasertest.nav.nav2.kernels import NO_COLLISION, collision_time, count_inside

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
