"""The faults of the mutation analysis (benchmarks/mutants.py), each on hand-made scans: what it
does to a scan or a command, and that the old scanner's scans pass it as a team tuned it to."""

from __future__ import annotations

import math
from types import ModuleType
from typing import Any

import numpy as np
import pytest

from pytest_lasertest.model.geometry import FloatArray, Pose3D
from pytest_lasertest.model.route import place
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.nav.move_base import MoveBase
from pytest_lasertest.nav.move_base.settings import NavigationSettings
from pytest_lasertest.nav.protocol import LaserScan, Odometry
from pytest_lasertest.pairsfile import load_pairs_file
from tests.helpers import REPO
from tests.helpers.model import HUSKY_MOUNT, profile

# The benchmark's robot and its six scanner changes.
SPEC = load_pairs_file(REPO / "benchmarks" / "fault_finding_pairs.yaml")
PAIRS = {pair.name: pair for pair in SPEC.pairs}
HUSKY_LASER = PAIRS["fewer_beams"].baseline.profile  # the Gazebo LMS1xx, upside down at 0.44 m
LMS111 = PAIRS["lms111_to_rplidar_a1"].baseline.profile  # publishes 0.0 for no return
ROUTE = SPEC.world.route
STILL = Odometry(0.0, 0.0, 0.0, 0.0, 0.0)
# Five beams at -90, -45, 0, 45 and 90 degrees, 0.1-10 m, 50 Hz, from the base origin.
FIVE = profile(samples=5, min_angle=-math.pi / 2, max_angle=math.pi / 2)


def scan_of(scanner: LaserProfile, ranges: object, stamp: float = 0.0) -> LaserScan:
    """A scan of `scanner` reading `ranges` (m), as it publishes it."""
    readings = np.asarray(ranges, dtype=np.float64)
    return LaserScan(stamp, readings, scanner.to_laserscan_meta(), scanner.pose)


def in_world(scan: LaserScan, odometry: Odometry) -> FloatArray:
    """Where the scan's readings lie in the world, the robot where `odometry` says."""
    return place(scan.points_in_base(), np.array([odometry.x, odometry.y, odometry.yaw]))


def mutant_named(mutants: ModuleType, name: str) -> Any:
    return next(mutant for mutant in mutants.MUTANTS if mutant.name == name)


def built_settings(mutants: ModuleType, name: str, baseline: LaserProfile) -> NavigationSettings:
    """The parameters move_base is built with under the mutant tuned for `baseline`."""
    controller = mutant_named(mutants, name).factory(baseline)(SPEC.robot, ROUTE)
    assert isinstance(controller.inner, MoveBase)
    settings: NavigationSettings = controller.inner.settings
    return settings


# The set.


def test_every_mutant_is_named_once_and_names_its_source(mutants: ModuleType) -> None:
    names = [mutant.name for mutant in mutants.MUTANTS]
    assert len(names) == len(set(names)) == 26  # 18 in move_base, 8 in Nav2 (nav2_faults.py)
    assert all(mutant.bug and mutant.source for mutant in mutants.MUTANTS)
    assert len(mutants.MOVE_BASE_MUTANTS) == 18
    move_base = [mutant.name for mutant in mutants.MOVE_BASE_MUTANTS if mutant.equivalent]
    assert move_base == ["nan_guard"]


def test_every_mutant_makes_a_fault_for_each_benchmark_baseline(
    mutation: ModuleType, mutants: ModuleType
) -> None:
    for mutant in mutants.MUTANTS:
        for pair in SPEC.pairs:
            assert isinstance(mutant.make(pair.baseline.profile), mutation.Fault)


def test_a_scan_fault_leaves_move_base_the_robots_own_parameters(mutants: ModuleType) -> None:
    settings = built_settings(mutants, "speckle", HUSKY_LASER)
    assert settings == NavigationSettings.from_parameters(SPEC.robot.navigation)
    assert settings.costmap.obstacle_range == 5.5  # the Husky's, not costmap_2d's default


# The faults as they were.


def test_the_speckle_filter_drops_a_reading_no_neighbour_confirms(mutants: ModuleType) -> None:
    scan = scan_of(FIVE, [np.inf, 3.0, np.inf, 2.0, 2.05])
    out = mutants.Speckle().scan(scan, STILL).ranges
    assert np.isnan(out[1])  # a pole one beam reads
    assert (out[3], out[4]) == (2.0, 2.05)  # two beams agree within 0.1 m
    assert out[0] == out[2] == np.inf  # beyond max_range: left alone


def test_the_stride_keeps_every_fourth_beam_however_many_the_scanner_has(
    mutants: ModuleType,
) -> None:
    stride = mutants.Stride(HUSKY_LASER)  # 720 beams, 180 kept
    sparse = PAIRS["fewer_beams"].candidate.profile  # 180 beams, 45 kept
    scan = scan_of(sparse, np.arange(sparse.beam_count, dtype=np.float64) + 1.0)
    out = stride.scan(scan, STILL)
    np.testing.assert_array_equal(out.ranges, scan.ranges[::4])
    assert out.meta.angle_increment == pytest.approx(4 * scan.meta.angle_increment)
    assert out.meta.angle_max == pytest.approx(
        scan.meta.angle_min + 44 * 4 * sparse.angle_increment
    )


def test_the_temporal_median_shows_a_new_obstacle_from_its_second_reading(
    mutants: ModuleType,
) -> None:
    median = mutants.TemporalMedian()
    readings = [
        median.scan(scan_of(FIVE, [ahead] * 5), STILL).ranges[2] for ahead in (np.inf, 2.0, 2.0)
    ]
    # The upper median of (inf, 2) is inf; of (inf, 2, 2), 2.
    assert readings == [np.inf, np.inf, 2.0]


def test_readings_up_to_the_old_range_min_too_near_among_them_become_no_return(
    mutants: ModuleType,
) -> None:
    near_as_far = mutants.NearAsFar(HUSKY_LASER)  # range_min 0.1 m
    scan = scan_of(FIVE, [-np.inf, 0.1, 0.3, np.inf, 5.0])
    np.testing.assert_array_equal(
        near_as_far.scan(scan, STILL).ranges, [np.inf, np.inf, 0.3, np.inf, 5.0]
    )


def test_beam_angles_come_from_the_old_configuration_not_the_message(mutants: ModuleType) -> None:
    narrow = PAIRS["narrower"].candidate.profile  # 720 beams over 2 rad
    scan = scan_of(narrow, np.full(narrow.beam_count, 3.0))
    out = mutants.AngleTable(HUSKY_LASER).scan(scan, STILL)
    old = HUSKY_LASER.to_laserscan_meta()
    assert (out.meta.angle_min, out.meta.angle_increment) == (old.angle_min, old.angle_increment)
    assert out.meta.angle_max == pytest.approx(old.angle_max)  # the same count of beams
    np.testing.assert_array_equal(out.ranges, scan.ranges)


def test_the_index_mask_blanks_the_old_edges_and_a_wider_arc_of_a_sparser_scanner(
    mutants: ModuleType,
) -> None:
    mask = mutants.IndexMask(HUSKY_LASER)  # 0.25 rad of 720 beams: 38 at each end
    dense = mask.scan(scan_of(HUSKY_LASER, np.full(720, 3.0)), STILL).ranges
    np.testing.assert_array_equal(np.isnan(dense).nonzero()[0], np.r_[0:38, 682:720])
    sparse_scanner = PAIRS["fewer_beams"].candidate.profile
    sparse = mask.scan(scan_of(sparse_scanner, np.full(180, 3.0)), STILL).ranges
    # The same 38 indices are 57 degrees of 180 beams; the old last indices are not there.
    np.testing.assert_array_equal(np.isnan(sparse).nonzero()[0], np.arange(38))


def test_the_skewed_scan_is_placed_where_the_robot_is_a_scan_period_later(
    mutants: ModuleType,
) -> None:
    slow = profile(samples=5, min_angle=-math.pi / 2, max_angle=math.pi / 2, update_rate=10.0)
    moving = Odometry(0.0, 0.0, 0.0, 1.0, 0.5)  # 1 m/s, 0.5 rad/s: 0.1 m, 0.05 rad a period
    out = mutants.SweepSkew().scan(scan_of(slow, [np.inf, np.inf, 2.0, np.inf, np.inf]), moving)
    assert out.mount.xyz == pytest.approx((0.1, 0.0, 0.0))
    assert out.mount.rpy == pytest.approx((0.0, 0.0, 0.05))
    (point,) = out.points_in_base()
    assert point == pytest.approx([0.1 + 2.0 * math.cos(0.05), 2.0 * math.sin(0.05)])


def test_the_stale_driver_publishes_the_previous_sweep(mutants: ModuleType) -> None:
    stale = mutants.StaleSweep()
    first, second = scan_of(FIVE, [1.0] * 5), scan_of(FIVE, [2.0] * 5, stamp=0.02)
    assert stale.scan(first, STILL) is first  # nothing before it
    out = stale.scan(second, STILL)
    np.testing.assert_array_equal(out.ranges, first.ranges)
    assert out.stamp == 0.02


def test_move_base_refuses_to_drive_between_scans_further_apart_than_expected(
    mutants: ModuleType,
) -> None:
    expected = mutants.ExpectedRate()  # 0.05 s, for 50 Hz
    commands = [
        expected.command((0.5, 0.2), scan_of(FIVE, [np.inf] * 5, stamp))
        for stamp in (0.0, 0.02, 0.12)
    ]
    assert commands == [(0.5, 0.2), (0.5, 0.2), (0.0, 0.0)]


def test_the_stale_mount_mirrors_a_scanner_turned_upright(mutants: ModuleType) -> None:
    upright = PAIRS["upright"].candidate.profile
    ranges = np.full(upright.beam_count, np.inf)
    ranges[500] = 2.0  # a beam to the left of the laser's x axis
    scan = scan_of(upright, ranges)
    out = mutants.StaleMount(HUSKY_LASER).scan(scan, STILL)
    assert out.mount == HUSKY_LASER.pose
    ((_, truly),), ((_, taken),) = scan.points_in_base(), out.points_in_base()
    assert truly > 0.0
    assert taken == pytest.approx(-truly)


def test_the_nan_guard_reads_nan_as_no_return_and_leaves_the_rest(mutants: ModuleType) -> None:
    scan = scan_of(FIVE, [np.nan, -np.inf, 2.0, np.inf, np.nan])
    np.testing.assert_array_equal(
        mutants.NanGuard().scan(scan, STILL).ranges, [np.inf, -np.inf, 2.0, np.inf, np.inf]
    )


# The faults added.


def test_the_costmaps_height_limit_keeps_the_old_scan_plane_and_drops_a_raised_one(
    mutants: ModuleType,
) -> None:
    height = mutants.ObstacleHeight(HUSKY_LASER)  # 0.44 m: the limit is 0.5 m
    assert height.max_height == pytest.approx(0.5)
    old = scan_of(HUSKY_LASER, np.full(720, 3.0))
    assert height.scan(old, STILL) is old
    raised = PAIRS["upright"].candidate.profile  # 0.54 m
    out = height.scan(scan_of(raised, np.full(720, 3.0)), STILL)
    assert np.isnan(out.ranges).all()
    assert len(out.points_in_base()) == 0  # nothing to mark, no ray to clear along


def test_dropping_scans_forwards_every_fifth_and_the_last_one_again_where_it_was_taken(
    mutants: ModuleType,
) -> None:
    drop = mutants.DropScans(HUSKY_LASER)  # 50 Hz to 10 Hz: drop 4 of 5
    poses = [Odometry(0.1 * k, 0.02 * k, 0.15 * k, 0.5, 0.75) for k in range(7)]
    scans = [scan_of(FIVE, [1.0 + k, 2.0, 3.0, 4.0, 5.0], stamp=0.02 * k) for k in range(7)]
    out = [drop.scan(scan, pose) for scan, pose in zip(scans, poses, strict=True)]
    assert all(np.isnan(scan.ranges).all() for scan in out[:4])  # nothing forwarded yet
    assert out[4] is scans[4]
    for later, pose in zip(out[5:], poses[5:], strict=True):
        np.testing.assert_array_equal(later.ranges, scans[4].ranges)
        assert later.stamp == scans[4].stamp
        np.testing.assert_allclose(in_world(later, pose), in_world(scans[4], poses[4]), atol=1e-12)


def test_dropping_scans_sized_for_a_10_hz_scanner_forwards_all(mutants: ModuleType) -> None:
    drop = mutants.DropScans(PAIRS["slower"].candidate.profile)
    scans = [scan_of(FIVE, [1.0 + k] * 5, stamp=0.1 * k) for k in range(3)]
    assert [drop.scan(scan, STILL) for scan in scans] == scans


def test_the_safety_relay_stops_forward_motion_for_a_too_near_reading_ahead(
    mutants: ModuleType,
) -> None:
    relay = mutants.TooNearStops()  # 0.25 m
    upside_down = profile(samples=5, min_angle=-2.0, max_angle=2.0, pose=HUSKY_MOUNT)

    def commanded(*ranges: float) -> tuple[float, float]:
        result: tuple[float, float] = relay.command((0.5, 0.3), scan_of(upside_down, ranges))
        return result

    assert commanded(np.inf, np.inf, -np.inf, np.inf, np.inf) == (0.0, 0.3)  # the turn passes
    assert commanded(np.inf, 0.2, np.inf, np.inf, np.inf) == (0.0, 0.3)
    assert commanded(np.inf, 0.3, np.inf, np.inf, np.inf) == (0.5, 0.3)  # beyond 0.25 m
    assert commanded(-np.inf, np.inf, np.inf, np.inf, -np.inf) == (0.5, 0.3)  # behind, at 2 rad
    assert commanded(np.inf, 0.0, np.nan, np.inf, np.inf) == (0.5, 0.3)  # no echo, no reading


def test_the_base_frame_scan_bins_points_by_their_bearing_from_the_base(
    mutants: ModuleType,
) -> None:
    # The old scanner: one degree between beams, 0.1-10 m.
    old = profile(samples=181, min_angle=-math.pi / 2, max_angle=math.pi / 2)
    to_base = mutants.ScanToBaseFrame(old)
    laser = profile(samples=3, min_angle=-0.5, max_angle=0.5, pose=HUSKY_MOUNT)
    out = to_base.scan(scan_of(laser, [2.0, 1.5, -np.inf]), STILL)
    assert (out.meta.angle_min, out.meta.angle_max) == (-math.pi, math.pi)
    assert out.meta.angle_increment == pytest.approx(math.pi / 180)
    assert (out.meta.range_min, out.meta.range_max) == (0.1, 10.0)
    assert len(out.ranges) == 360
    assert out.mount == Pose3D()
    # The upside-down laser's -0.5 rad beam points 0.5 rad left in the base frame.
    left = np.array([0.337 + 2.0 * math.cos(0.5), 2.0 * math.sin(0.5)])
    ahead = np.array([0.337 + 1.5, 0.0])
    assert np.isfinite(out.ranges).sum() == 2  # the too-near reading is no point
    for point in (left, ahead):
        index = int((math.atan2(point[1], point[0]) + math.pi) / (math.pi / 180))
        assert out.ranges[index] == pytest.approx(math.hypot(*point))


def test_the_base_frame_scan_leaves_the_bins_between_a_sparser_scanners_readings_empty(
    mutants: ModuleType,
) -> None:
    to_base = mutants.ScanToBaseFrame(HUSKY_LASER)  # bins of 0.375 deg
    sparse = PAIRS["fewer_beams"].candidate.profile  # beams 1.5 deg apart
    wall = np.full(sparse.beam_count, 3.0)
    dense = to_base.scan(scan_of(HUSKY_LASER, np.full(720, 3.0)), STILL).ranges
    thin = to_base.scan(scan_of(sparse, wall), STILL).ranges
    ahead = slice(len(dense) // 2 - 40, len(dense) // 2 + 40)  # 30 degrees about ahead
    assert np.isfinite(dense[ahead]).all()
    # Most bins read +inf, which inf_is_valid clears along, between the readings.
    assert np.isinf(thin[ahead]).mean() > 0.6


def test_the_slow_costmap_mutant_updates_the_costmaps_once_a_second(mutants: ModuleType) -> None:
    settings = built_settings(mutants, "slow_costmap", HUSKY_LASER)
    own = NavigationSettings.from_parameters(SPEC.robot.navigation)
    assert own.costmap.update_frequency == 4.0
    assert settings.costmap.update_frequency == 1.0
    assert settings.costmap.obstacle_range == own.costmap.obstacle_range
    scan = scan_of(FIVE, [2.0] * 5)
    assert mutant_named(mutants, "slow_costmap").make(HUSKY_LASER).scan(scan, STILL) is scan


def test_inf_is_valid_is_left_false_only_where_the_old_scanner_published_zero(
    mutants: ModuleType,
) -> None:
    assert not built_settings(mutants, "inf_not_valid", LMS111).costmap.inf_is_valid
    # With an old scanner that published +inf the team would have set it, as the Husky has it.
    assert built_settings(mutants, "inf_not_valid", HUSKY_LASER).costmap.inf_is_valid


def test_navfn_may_not_plan_through_unseen_cells_where_the_old_scanner_cleared_open_space(
    mutants: ModuleType,
) -> None:
    assert not built_settings(mutants, "known_space_only", HUSKY_LASER).navfn.allow_unknown
    # With a 0.0 no-return nothing clears open space: a team would never have set it.
    assert built_settings(mutants, "known_space_only", LMS111).navfn.allow_unknown
