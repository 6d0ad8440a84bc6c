"""nav2_mppi_controller's tests of its tools/utils.hpp (utils_test.cpp), rebuilt on what does their
work here: `CriticData.within`, `furthest_reached` and `path_points_valid` (mppi.py), the
PathAngleCritic's angle to the path point (posePointAngle) and wrapped heading differences
(shortest_angular_distance) in critics.py, and the Savitzky-Golay filter of `Optimizer`.

Not applicable: MarkerPopulationUtils and ConversionTests (ROS messages), the goal-checker form
of withinPositionGoalTolerance (our critics take their thresholds, not a goal checker),
posePointAngle with a path point's yaw (PathAngleCritic's mode 2, not imitated), the vy parts of
SmootherTest (a differential drive has no lateral speed), and FindPathInversionTest and
RemovePosesAfterPathInversionTest (enforce_path_inversion is not imitated).
"""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np
import pytest

from pytest_lasertest.nav.move_base.cost_values import INSCRIBED, LETHAL
from pytest_lasertest.nav.nav2.mppi import F32, CriticData, MppiSettings, Optimizer
from tests.helpers.mppi import critic, critic_data, dummy_costmap, path_along_x
from tests.helpers.upstream import NAVIGATION2_JAZZY, NotPorted, Source

UTILS = Source("Nav2 MPPI: utils", NAVIGATION2_JAZZY, "nav2_mppi_controller/test/utils_test.cpp")
NOT_PORTED: tuple[NotPorted, ...] = (
    NotPorted(
        UTILS,
        "UtilsTests.AnglesTests",
        1,
        "normalize_angles of 100 large angles lies in [-pi, pi]: our critics have no angle "
        "normalisation of their own (they wrap differences through arctan2(sin, cos))",
    ),
)


# WithTolTests: the robot at (10, 1), a tolerance of 0.25 m.


def within(goal: tuple[float, float]) -> bool:
    return critic_data(1, 1, pose=(10.0, 1.0, 0.0), goal=goal).within(0.25)


@UTILS.test("UtilsTests.WithTolTests", assertions=4)
def test_a_goal_is_within_tolerance_nearer_than_it() -> None:
    assert not within((0.0, 0.0))
    assert within((9.8, 0.95))
    assert within((10.0, 0.76))
    assert within((9.76, 1.0))


# AnglesTests, through the PathAngleCritic, whose gate is posePointAngle and whose cost per
# trajectory is |shortest_angular_distance| x weight: the robot at (0, 0), its goal 10 m away,
# the samples reaching path point 0, so that the critic aims at point 4.


def aiming(point: tuple[float, float], heading: float, batch: int = 10) -> CriticData:
    path = np.tile(np.array(point, dtype=np.float32), (10, 1))
    data = critic_data(batch, 5, pose=(0.0, 0.0, heading), goal=(10.0, 0.0), path=path)
    data.furthest = 0
    return data


def scored(point: tuple[float, float], forward_preference: bool, max_angle: float) -> bool:
    """Whether posePointAngle from the robot heading along x to `point` reaches `max_angle`:
    whether the PathAngleCritic with that max_angle_to_furthest scores at all."""
    data = aiming(point, 0.0)
    data.yaw[:, -1] = 1.0  # rad off every bearing from the trajectory ends: a score is above 0
    parameters = {
        "FollowPath.PathAngleCritic.mode": 0 if forward_preference else 1,
        "FollowPath.PathAngleCritic.max_angle_to_furthest": max_angle,
    }
    critic("PathAngleCritic", parameters)(data)
    return bool(data.costs.any())


@UTILS.test("UtilsTests.AnglesTests", assertions=1)
def test_heading_differences_are_wrapped_into_0_to_pi() -> None:
    angles = np.array([(-1) ** (i + 1) * i * i for i in range(100)], dtype=np.float32)
    # The robot faces away from the point ahead (the critic scores); the trajectory ends at
    # (0, 0) look toward it at bearing 0, with final headings `angles`.
    data = aiming((1.0, 0.0), math.pi, batch=len(angles))
    data.yaw[:, -1] = angles
    critic("PathAngleCritic", {"FollowPath.PathAngleCritic.cost_weight": 1.0})(data)
    assert np.all((data.costs >= 0.0) & (data.costs <= np.float32(math.pi)))


@UTILS.test("UtilsTests.AnglesTests", assertions=2)
def test_the_angle_to_a_point_with_forward_preference_is_its_bearing_off_the_heading() -> None:
    assert not scored((1.0, 0.0), forward_preference=True, max_angle=1e-6)  # 0 rad
    assert scored((-1.0, 0.0), forward_preference=True, max_angle=math.pi - 1e-6)  # pi rad


@UTILS.test("UtilsTests.AnglesTests", assertions=2)
def test_the_angle_to_a_point_either_way_is_off_the_heading_or_its_reverse() -> None:
    assert not scored((1.0, 0.0), forward_preference=False, max_angle=1e-6)
    assert not scored((-1.0, 0.0), forward_preference=False, max_angle=1e-6)


# FurthestAndClosestReachedPoint


@UTILS.test("UtilsTests.FurthestAndClosestReachedPoint", assertions=3)
def test_the_furthest_reached_path_point_is_found_once_a_cycle() -> None:
    preset = critic_data(1, 1)
    preset.furthest = 99999
    assert preset.furthest_reached() == 99999  # already known: kept
    assert critic_data(0, 30).furthest_reached() == 0  # no trajectories, no path
    # Trajectories ending at (1, 0) m, the path along x every 0.2 m.
    data = critic_data(100, 2, path=path_along_x([0.2 * i for i in range(10)]))
    data.x[:] = 1.0
    assert data.furthest_reached() == 5


# findPathCosts


@UTILS.test("UtilsTests.findPathCosts", assertions=2)
def test_path_point_validity_found_already_is_kept() -> None:
    data = critic_data(1, 1)
    data.path_valid = np.zeros(10, dtype=bool)
    valid = data.path_points_valid()
    assert len(valid) == 10
    assert not valid.any()


@UTILS.test("UtilsTests.findPathCosts", assertions=3)
def test_path_points_off_the_costmap_or_on_lethal_cells_are_invalid() -> None:
    costmap = dummy_costmap()
    costmap.costs[10:31, 10:31] = LETHAL  # an island from 1.0 to 3.1 m
    costmap.costs[45, 40:46] = INSCRIBED  # a strip at y = 4.5 m
    path = np.zeros((50, 2), dtype=np.float32)
    path[1] = (999999999.0, 999999999.0)  # off the costmap
    path[10] = (1.5, 1.5)  # on the island
    path[20] = (4.2, 4.2)  # on a free cell
    data = critic_data(1, 1, path=path, costmap=costmap)
    valid = data.path_points_valid()
    assert data.path_valid is not None
    assert not valid[[1, 10]].any()
    assert np.delete(valid, [1, 10]).all()


# SmootherTest: constant sequences (vx 0.2 m/s, wz 0.3 rad/s) with Gaussian noise of 0.2
# added, the history before them [0, 0.1, 0.1, 0.1] m/s and [0, 0.3, 0.3, 0.3] rad/s.


def xtensor_randn(count: int, stddev: float) -> F32:
    """The first `count` values of xt::random::randn<float> in a fresh test process, whose
    figures the test's tolerances fit: libstdc++'s std::normal_distribution<float> (Marsaglia's
    polar method, each uniform from generate_canonical<float>) on xtensor's default engine, a
    std::mt19937 of the default seed 5489, which numpy's legacy RandomState seeds alike."""
    words: Iterator[np.uint64] = iter(
        np.random.RandomState(5489).randint(0, 2**32, size=8 * count, dtype=np.uint64)
    )

    def uniform() -> float:
        canonical = np.float32(next(words)) / np.float32(2.0**32)
        canonical = min(canonical, np.nextafter(np.float32(1.0), np.float32(0.0)))
        # 2.0f * u - 1.0 is worked in double, then kept in float.
        return float(np.float32(float(np.float32(2.0) * canonical) - 1.0))

    drawn: list[np.float32] = []
    while len(drawn) < count:
        x, y = np.float32(uniform()), np.float32(uniform())
        squared = np.float32(x * x + y * y)
        if squared > 1.0 or squared == 0.0:
            continue
        scale = np.sqrt(np.float32(-2.0) * np.log(squared) / squared)
        drawn += [np.float32(y * scale), np.float32(x * scale)]  # y's first, x's saved
    values: F32 = (np.array(drawn[:count], dtype=np.float32) * np.float32(stddev)).astype(
        np.float32
    )
    return values


class Smoothed:
    """The test's sequences before and after our filter, and the history after it."""

    def __init__(self) -> None:
        noise = xtensor_randn(90, 0.2)  # vx's 30 draws, vy's, then wz's
        self.vx = (np.float32(0.2) + noise[:30]).astype(np.float32)
        self.wz = (np.float32(0.3) + noise[60:]).astype(np.float32)
        self.history = np.array([[0.0, 0.0], [0.1, 0.3], [0.1, 0.3], [0.1, 0.3]], np.float32)
        # shift_control_sequence false, "so result stores 0th value in history": a controller
        # period shorter than model_dt sets it so (Optimizer::setOffset).
        settings = MppiSettings(time_steps=30)
        optimizer = Optimizer(settings, [], np.random.default_rng(0), shift=False)
        optimizer.vx[:], optimizer.wz[:] = self.vx, self.wz
        optimizer.history[:] = self.history
        optimizer._smooth()  # the filter has no entry of its own but this
        self.smoothed = optimizer.vx, optimizer.wz
        self.history_after = optimizer.history


@UTILS.test("UtilsTests.SmootherTest", assertions=2)
def test_the_filter_moves_the_command_history_back_one() -> None:
    smoothed = Smoothed()
    assert smoothed.history_after[2] == pytest.approx(smoothed.history[3], abs=0.02)


@UTILS.test("UtilsTests.SmootherTest", assertions=1)
def test_the_newest_history_entry_is_a_smoothed_speed() -> None:
    assert Smoothed().history_after[3, 0] == pytest.approx(0.2, abs=0.05)


@UTILS.test("UtilsTests.SmootherTest", assertions=1)
def test_the_newest_history_entry_is_the_smoothed_first_turn_rate() -> None:
    assert Smoothed().history_after[3, 1] == pytest.approx(0.23, abs=0.02)


@UTILS.test("UtilsTests.SmootherTest", assertions=1)
def test_the_filter_brings_the_sequence_nearer_its_noiseless_values() -> None:
    smoothed = Smoothed()
    inner = slice(1, 29)  # the points the test sums, neither end

    def off(vx: F32, wz: F32) -> float:
        return float(np.abs(vx[inner] - 0.2).sum() + np.abs(wz[inner] - 0.3).sum())

    assert off(*smoothed.smoothed) < off(smoothed.vx, smoothed.wz)
