"""The simulated laser: PyBullet's ray casts and the flat ray cast read alike beam for beam, the
robot is transparent to its own scanner, readings follow REP 117, and noise stays in range."""

from __future__ import annotations

import math

import numpy as np

from pytest_lasertest.model.geometry import Pose2D, Pose3D
from pytest_lasertest.model.obstacles import (
    Box,
    Cylinder,
    Obstacle,
    ray_distances,
    segment_clearances,
)
from pytest_lasertest.model.sensor import GaussianNoise, LaserProfile
from pytest_lasertest.sim.client import PhysicsWorld
from pytest_lasertest.sim.lidar import (
    FlatLidar,
    noisy,
    ranges_from_fractions,
    scan_rays,
)
from tests.helpers.model import profile
from tests.helpers.sim import TIME_STEP

HUSKY_LASER = Pose3D((0.337, 0.0, 0.308), (math.pi, 0.0, 0.0))
SCANNER = profile(min_angle=-2.3, max_angle=2.3, range_max=8.0, pose=HUSKY_LASER)
# PyBullet reports hits up to about 1 mm outside exact shapes, further along oblique rays.
EDGE = 0.005  # m: beams nearer than this to an obstacle's edge, or its top, are not compared


def pybullet_ranges(world: PhysicsWorld, scanner: LaserProfile, pose: np.ndarray) -> np.ndarray:
    starts, ends = scan_rays(scanner, pose)
    return ranges_from_fractions(scanner, world.cast(starts, ends))


def random_scene(rng: np.random.Generator) -> tuple[Obstacle, ...]:
    """Six boxes and cylinders 1.2-8 m from the origin, none with its top within EDGE of the
    scan plane."""
    obstacles: list[Obstacle] = []
    while len(obstacles) < 6:
        x, y = (float(value) for value in rng.uniform(-6.0, 6.0, 2))
        height = float(rng.uniform(0.1, 1.0))
        if math.hypot(x, y) < 1.2 or abs(height - SCANNER.scan_height) < EDGE:
            continue
        if rng.integers(2):
            obstacles.append(Cylinder(x, y, float(rng.uniform(0.02, 0.4)), height))
        else:
            length, width = (float(side) for side in rng.uniform(0.05, 1.0, 2))
            obstacles.append(Box(x, y, float(rng.uniform(0.0, 3.0)), length, width, height))
    return tuple(obstacles)


def test_pybullet_and_the_flat_ray_cast_read_the_same_ranges_beam_for_beam() -> None:
    rng = np.random.default_rng(1)
    compared = 0
    for _ in range(20):
        obstacles = random_scene(rng)
        with PhysicsWorld(
            Pose2D(0.0, 0.0, float(rng.uniform(-3, 3))), obstacles, TIME_STEP
        ) as world:
            pose = world.base_pose()
            simulated = pybullet_ranges(world, SCANNER, pose)
        flat = FlatLidar(SCANNER, obstacles).ranges(pose)

        origins, directions = SCANNER.rays(pose[np.newaxis, :])
        count = SCANNER.beam_count
        standing = [o for o in obstacles if o.height > SCANNER.scan_height]
        clearance = np.min(
            [
                segment_clearances(
                    origins[0], directions[0], np.zeros(count), np.full(count, 8.0), o
                )
                for o in standing
            ],
            axis=0,
        )
        sure = np.abs(clearance) >= EDGE
        np.testing.assert_array_equal(np.isfinite(simulated[sure]), np.isfinite(flat[sure]))
        read = sure & np.isfinite(flat)
        np.testing.assert_allclose(simulated[read], flat[read], rtol=0, atol=EDGE)
        compared += int(read.sum())
    assert compared > 1000


def test_the_robot_is_transparent_to_its_own_scanner_and_the_ground_is_not_read() -> None:
    with PhysicsWorld(Pose2D(0.0, 0.0, 0.0), (), TIME_STEP) as world:
        for _ in range(50):
            world.step(0.0, 0.0)
        ranges = pybullet_ranges(world, SCANNER, world.base_pose())
    assert np.all(ranges == np.inf)


def test_nearer_than_range_min_reads_minus_inf_and_beyond_range_max_plus_inf() -> None:
    near = Box(0.6, 0.0, 0.0, 0.1, 0.6, 1.0)  # 0.26 m from the scanner, range_min 0.5 m
    far = Cylinder(-9.5, 0.0, 0.3, 1.0)  # behind, beyond 8 m
    scanner = profile(
        min_angle=-math.pi, max_angle=math.pi, range_min=0.5, range_max=8.0, pose=HUSKY_LASER
    )
    with PhysicsWorld(Pose2D(0.0, 0.0, 0.0), (near, far), TIME_STEP) as world:
        ranges = pybullet_ranges(world, scanner, np.zeros(3))
    ahead = np.abs(scanner.beam_angles_in_base()) < 0.2
    behind = np.abs(scanner.beam_angles_in_base()) > math.pi - 0.02
    assert np.all(ranges[ahead] == -np.inf)
    assert np.all(ranges[behind] == np.inf)


def test_noise_touches_only_in_range_readings_clamped_to_the_range_and_repeats_by_seed() -> None:
    scanner = profile(range_min=0.1, range_max=10.0, noise=GaussianNoise(0.0, 0.5))
    ranges = np.array([np.inf, -np.inf, 0.2, 5.0, 9.9])

    first = noisy(scanner, ranges, np.random.default_rng(7))
    again = noisy(scanner, ranges, np.random.default_rng(7))

    np.testing.assert_array_equal(first, again)
    assert first[0] == np.inf
    assert first[1] == -np.inf
    assert np.all((first[2:] >= 0.1) & (first[2:] <= 10.0))
    assert np.any(first[2:] != ranges[2:])


def exact_ranges(
    scanner: LaserProfile, pose: np.ndarray, obstacles: tuple[Obstacle, ...]
) -> np.ndarray:
    """Every beam cast against every standing obstacle with `geometry.ray_distances` (REP 117)."""
    origins, directions = scanner.rays(pose[np.newaxis, :])
    distances = np.full(scanner.beam_count, np.inf)
    for obstacle in obstacles:
        if obstacle.height > scanner.scan_height:
            distances = np.minimum(distances, ray_distances(origins[0], directions[0], obstacle))
    distances[distances > scanner.range_max] = np.inf
    distances[distances < scanner.range_min] = -np.inf
    return distances


def test_the_flat_lidar_equals_the_exact_ray_cast_of_geometry_beam_for_beam() -> None:
    rng = np.random.default_rng(3)
    rear = Pose3D((-0.2, 0.1, 0.3), (0.0, 0.0, 2.5))
    scanners = (
        SCANNER,  # mounted upside down: its beams run clockwise
        profile(min_angle=-math.pi, max_angle=math.pi, range_min=0.0, range_max=5.0),
        profile(min_angle=-1.0, max_angle=2.0, samples=50, pose=rear),
    )
    for scanner in scanners:
        for _ in range(30):
            obstacles = random_scene(rng)
            pose = np.array([*rng.uniform(-7.0, 7.0, 2), rng.uniform(-math.pi, math.pi)])
            flat = FlatLidar(scanner, obstacles).ranges(pose)
            exact = exact_ranges(scanner, pose, obstacles)
            np.testing.assert_allclose(flat, exact, rtol=1e-9, atol=1e-9)


def test_the_flat_lidar_reads_zero_from_inside_an_obstacle() -> None:
    scanner = profile(min_angle=-math.pi, max_angle=math.pi, range_min=0.0)
    for obstacle in (Box(1.0, 2.0, 0.3, 1.0, 0.5, 1.0), Cylinder(1.0, 2.0, 0.4, 1.0)):
        ranges = FlatLidar(scanner, (obstacle,)).ranges(np.array([1.1, 2.05, 0.7]))
        assert np.all(ranges == 0.0)
