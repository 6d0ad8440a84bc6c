"""The faults put into Nav2 (benchmarks/nav2_faults.py): that each reaches Nav2 as the plugin builds
it for the Husky, what it does on hand-made scans and parameters, that the old scanner passes it
as a team tuned it, and that the equivalent ones change nothing Nav2 does."""

from __future__ import annotations

import dataclasses
import importlib
import math
import types
from types import ModuleType
from typing import Any

import numpy as np
import pytest

from pytest_lasertest.model.geometry import FloatArray, Point2D, Pose2D
from pytest_lasertest.model.obstacles import Cylinder
from pytest_lasertest.model.sensor import LaserProfile, LaserScanMeta
from pytest_lasertest.nav.move_base.cost_values import LETHAL
from pytest_lasertest.nav.nav2.collision_monitor import scan_points
from pytest_lasertest.nav.nav2.costmap import Nav2Costmap
from pytest_lasertest.nav.nav2.nav2 import Nav2
from pytest_lasertest.nav.nav2.params import configured
from pytest_lasertest.nav.nav2.settings import CostmapConfig, Nav2Settings
from pytest_lasertest.nav.protocol import OPTIONAL, InFront, LaserScan, Odometry
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.sim.scenario import Scenario, run_scenario
from tests.helpers import REPO
from tests.helpers.model import profile

# The benchmark's robot and its six scanner changes.
SPEC = load_pairs_file(REPO / "benchmarks" / "fault_finding_pairs.yaml")
PAIRS = {pair.name: pair for pair in SPEC.pairs}
HUSKY_LASER = PAIRS["fewer_beams"].baseline.profile  # the Gazebo LMS1xx, upside down at 0.44 m
SPARSE = PAIRS["fewer_beams"].candidate.profile  # 180 beams over the same 270 deg
UPRIGHT = PAIRS["upright"].candidate.profile  # the right way up, at 0.54 m
LMS111 = PAIRS["lms111_to_rplidar_a1"].baseline.profile  # publishes 0.0 for no return
SCANNERS = tuple(
    dict.fromkeys(side.profile for pair in SPEC.pairs for side in (pair.baseline, pair.candidate))
)
ROUTE = SPEC.world.route
STILL = Odometry(0.0, 0.0, 0.0, 0.0, 0.0)
# The robot's pose (m, m, rad), a cell's centre across, so that the laser's and the rays' cells
# are not on a cell's edge.
AT_START = (0.0, 0.03, 0.0)
AHEAD, Y = 0.337, AT_START[1]  # m: the laser's x ahead of the base, and its y in the world
EQUIVALENT = ("zero_replacement", "no_return_at_range_max", "ccw_only", "time_increment_crash")
# Five beams at -90, -45, 0, 45 and 90 degrees, 0.1-10 m, 50 Hz, from the base origin.
FIVE = profile(samples=5, min_angle=-math.pi / 2, max_angle=math.pi / 2)


def scan_of(scanner: LaserProfile, ranges: object, stamp: float = 0.0) -> LaserScan:
    """A scan of `scanner` reading `ranges` (m), as it publishes it."""
    readings = np.asarray(ranges, dtype=np.float64)
    return LaserScan(stamp, readings, scanner.to_laserscan_meta(), scanner.pose)


def angles_of(scanner: LaserProfile) -> FloatArray:
    """Each beam's angle in the laser frame (rad); upright or upside down, |angle| is its
    bearing's from straight ahead."""
    meta = scanner.to_laserscan_meta()
    angles = meta.angle_min + np.arange(scanner.beam_count) * meta.angle_increment
    return angles.astype(np.float64)


def wall_ahead(scanner: LaserProfile, distance: float, spread: float = 0.1) -> FloatArray:
    """Readings of `distance` m for the beams within `spread` rad of straight ahead, and no
    return for the rest."""
    return np.where(np.abs(angles_of(scanner)) <= spread, distance, np.inf)


def pole_ahead(scanner: LaserProfile, distance: float) -> FloatArray:
    """A thin pole straight ahead read by the one beam nearest it; the rest return nothing."""
    ranges = np.full(scanner.beam_count, np.inf)
    ranges[int(np.argmin(np.abs(angles_of(scanner))))] = distance
    return ranges


def mutant_named(mutants: ModuleType, name: str) -> Any:
    return next(mutant for mutant in mutants.MUTANTS if mutant.name == name)


def built(mutants: ModuleType, name: str, baseline: LaserProfile = HUSKY_LASER) -> InFront:
    """The controller the mutant's factory makes for the Husky on the benchmark's route."""
    controller = mutant_named(mutants, name).factory(baseline)(SPEC.robot, ROUTE)
    assert isinstance(controller, InFront)
    return controller


def settings_of(
    mutants: ModuleType, name: str, baseline: LaserProfile = HUSKY_LASER
) -> Nav2Settings:
    """The parameters Nav2 is built with under the mutant tuned for `baseline`."""
    inner = built(mutants, name, baseline).inner
    assert isinstance(inner, Nav2)
    return inner.settings


def costmap_of(settings: Nav2Settings, config: CostmapConfig) -> Nav2Costmap:
    """A fresh costmap of Nav2's as `config` (one of `settings`' two) sets it."""
    assert config.footprint is not None  # the Husky's file gives one
    return Nav2Costmap(config.costmap, np.array(config.footprint), config.source, settings.marking)


def lethal_at(costmap: Nav2Costmap, x: float, y: float) -> bool:
    """Whether the cell holding (x, y) m is lethal."""
    cell_x, cell_y, inside = costmap.cell_of(np.array([[x, y]]))
    assert inside[0]
    return bool(costmap.grid[cell_y[0], cell_x[0]] == LETHAL)


def lethal_cells(costmap: Nav2Costmap) -> int:
    return int((costmap.grid == LETHAL).sum())


def own_settings() -> Nav2Settings:
    """The Husky's Nav2 parameters, from its bundled params file."""
    return configured(SPEC.robot.nav2, SPEC.robot.nav2_release).settings


# The set.


def test_the_nav2_faults_are_named_once_put_into_nav2_and_four_are_equivalent(
    mutants: ModuleType, faults: ModuleType
) -> None:
    assert len(faults.NAV2_MUTANTS) == 8
    assert set(faults.NAV2_MUTANTS) <= set(mutants.MUTANTS)
    assert all(
        mutant.stack == "nav2" and mutant.bug and mutant.source for mutant in faults.NAV2_MUTANTS
    )
    assert all(mutant.stack == "move_base" for mutant in mutants.MOVE_BASE_MUTANTS)
    equivalent = [mutant.name for mutant in faults.NAV2_MUTANTS if mutant.equivalent]
    assert equivalent == list(EQUIVALENT)


def test_a_mutant_may_set_only_the_parameters_of_the_stack_it_is_put_into(
    mutation: ModuleType, faults: ModuleType
) -> None:
    def unchanged(baseline: LaserProfile) -> object:
        return mutation.Fault()

    with pytest.raises(ValueError, match="a stack it is not put into"):
        mutation.Mutant("x", "bug", "source", unchanged, nav2=faults._inf_is_valid)
    with pytest.raises(ValueError, match="a stack it is not put into"):
        mutation.Mutant("x", "bug", "source", unchanged, stack="nav2", navigation=lambda s, b: s)


def test_a_nav2_fault_stands_in_front_of_nav2_built_as_the_plugin_builds_it_for_the_husky(
    mutation: ModuleType, mutants: ModuleType
) -> None:
    controller = built(mutants, "zero_replacement")
    assert isinstance(controller.inner, Nav2)
    assert controller.inner.settings == own_settings()  # a scan fault leaves the params file's
    assert controller.inner.settings.dwb is not None  # Clearpath's a200 file runs DWB
    bare = mutation.bare("nav2")(SPEC.robot, ROUTE)
    assert isinstance(bare, Nav2)
    assert bare.settings == own_settings()


def test_the_wrapped_nav2_keeps_every_optional_attribute_the_bare_nav2_has(
    mutants: ModuleType,
) -> None:
    wrapped, bare = built(mutants, "source_timeout"), Nav2(SPEC.robot, ROUTE)
    assert {name for name in OPTIONAL if hasattr(wrapped, name)} == {
        name for name in OPTIONAL if hasattr(bare, name)
    }
    for name in ("goal_tolerance", "control_frequency", "stuck_window"):
        assert getattr(wrapped, name) == getattr(bare, name)


def test_fault_finding_drives_a_nav2_mutant_against_nav2_without_it(
    mutants: ModuleType,
) -> None:
    fault_finding = importlib.import_module("fault_finding")
    bench = types.SimpleNamespace(spec=SPEC)
    search = fault_finding.Search(bench, fault_finding.Cell("voxel_top", "upright", 1), "gate")
    assert (search.fault.name, search.clean.name) == ("nav2+voxel_top", "nav2")
    assert isinstance(search.clean.factory(SPEC.robot, ROUTE), Nav2)
    old = fault_finding.Search(bench, fault_finding.Cell("speckle", "upright", 1), "gate")
    assert (old.fault.name, old.clean.name) == ("move_base+speckle", "move_base")


def test_the_equivalent_faults_leave_nav2_driving_exactly_as_without_them(
    mutants: ModuleType,
) -> None:
    # A pole beside the route: the costmaps mark it and the collision monitor reads it.
    scenario = Scenario(
        SPEC.robot,
        HUSKY_LASER,
        (Cylinder(2.0, 0.9, 0.1, 1.0),),
        Pose2D(0.0, 0.0, 0.0),
        (Point2D(3.0, 0.0),),
        12.0,
        seed=1,
    )
    bare = run_scenario(scenario, Nav2)
    assert bare.verdicts.goal.time is not None  # it drives, past the pole, to the goal
    for name in EQUIVALENT:
        behind = run_scenario(scenario, mutant_named(mutants, name).factory(HUSKY_LASER))
        assert np.array_equal(bare.poses, behind.poses), name
        assert np.array_equal(bare.commands, behind.commands), name
        assert bare.verdicts == behind.verdicts, name


# The real faults.


def test_the_layer_height_marks_the_old_scan_plane_and_only_clears_a_raised_one(
    mutants: ModuleType, faults: ModuleType
) -> None:
    assert faults.plane_top(HUSKY_LASER) == pytest.approx(0.5)  # over 0.44 m
    settings = settings_of(mutants, "marking_height")
    for config in (settings.local, settings.global_):
        assert config.source.marks_at(HUSKY_LASER.scan_height)
        assert not config.source.marks_at(UPRIGHT.scan_height)  # 0.54 m
        assert config.source.sees(UPRIGHT.scan_height)  # so its rays still clear
        costmap = costmap_of(settings, config)
        costmap.update(scan_of(HUSKY_LASER, wall_ahead(HUSKY_LASER, 1.5)), AT_START)
        assert lethal_at(costmap, AHEAD + 1.5, Y)
        marked = lethal_cells(costmap)
        # The raised scanner reads past it: its rays clear, and what it reads is not marked.
        costmap.update(scan_of(UPRIGHT, wall_ahead(UPRIGHT, 1.9)), AT_START)
        assert lethal_cells(costmap) < marked
        assert not lethal_at(costmap, AHEAD + 1.9, Y)
    assert own_settings().local.source.marks_at(UPRIGHT.scan_height)  # the a200 file's 0.8 m


def test_the_short_voxel_grid_leaves_the_local_costmap_blind_to_a_raised_scan(
    mutants: ModuleType,
) -> None:
    settings = settings_of(mutants, "voxel_top")
    local, global_ = costmap_of(settings, settings.local), costmap_of(settings, settings.global_)
    local.update(scan_of(HUSKY_LASER, wall_ahead(HUSKY_LASER, 1.5)), AT_START)
    assert lethal_at(local, AHEAD + 1.5, Y)  # the old plane lies inside the grid
    # From above the grid: no mark, and no ray clears the old mark.
    local.update(scan_of(UPRIGHT, wall_ahead(UPRIGHT, 1.9)), AT_START)
    assert lethal_at(local, AHEAD + 1.5, Y)
    assert not lethal_at(local, AHEAD + 1.9, Y)
    global_.update(scan_of(UPRIGHT, wall_ahead(UPRIGHT, 1.9)), AT_START)
    assert lethal_at(global_, AHEAD + 1.9, Y)  # the global costmap is no voxel layer
    assert settings.global_ == own_settings().global_


def monitor_stops(fault: Any, rate: float, seconds: float = 1.0) -> list[bool]:
    """At each of the collision monitor's commands (20 Hz) over `seconds`, whether `fault` stops
    the robot, a scanner publishing at `rate` Hz: the calls fall as the simulator makes them, at
    each scan and at each tick of Nav2's 20 Hz clock between."""
    scans = [k / rate for k in range(math.ceil(seconds * rate))]
    ticks = [k / 20.0 for k in range(round(seconds * 20.0))]
    stops: list[bool] = []
    latest: LaserScan | None = None
    for time in sorted(set(scans) | set(ticks)):
        if time in scans:
            latest = scan_of(FIVE, [np.inf] * 5, stamp=time)
        assert latest is not None
        fault.tick(time)
        stopped = fault.command((0.5, 0.2), latest) == (0.0, 0.0)
        if time in ticks:
            stops.append(stopped)
    return stops


def test_the_monitors_watchdog_sized_for_50_hz_stops_the_robot_between_slower_scans(
    faults: ModuleType,
) -> None:
    assert faults.SourceTimeout(HUSKY_LASER).timeout == pytest.approx(0.04)
    assert not any(monitor_stops(faults.SourceTimeout(HUSKY_LASER), 50.0))
    # Stopped while the latest scan is more than 0.04 s old, at the commands of 2 s: about one
    # in two with a 10 Hz scanner, most with the 5.5 Hz RPLIDAR A1.
    slower = monitor_stops(faults.SourceTimeout(HUSKY_LASER), 10.0, 2.0)
    assert len(slower) / 3 < sum(slower) < 2 * len(slower) / 3
    rplidar = monitor_stops(faults.SourceTimeout(HUSKY_LASER), 5.5, 2.0)
    assert sum(rplidar) > 2 * len(rplidar) / 3
    # Sized for the 10 Hz scanner it would let it drive.
    assert not any(monitor_stops(faults.SourceTimeout(PAIRS["slower"].candidate.profile), 10.0))


def test_inf_is_valid_keeps_a_pole_every_scan_reads_and_erases_one_a_sparse_scan_misses(
    mutants: ModuleType,
) -> None:
    settings = settings_of(mutants, "inf_is_valid")
    assert settings.local.costmap.inf_is_valid
    assert settings.global_.costmap.inf_is_valid
    # The 720-beam scanner reads the pole with a beam in every scan: it stays.
    dense = costmap_of(settings, settings.local)
    for _ in range(2):
        dense.update(scan_of(HUSKY_LASER, pole_ahead(HUSKY_LASER, 1.5)), AT_START)
    assert lethal_cells(dense) == 1
    # The 180-beam one reads it, then misses it: the beam that returns nothing clears it.
    sparse, bare = (
        costmap_of(settings, settings.local),
        costmap_of(own_settings(), own_settings().local),
    )
    for costmap in (sparse, bare):
        costmap.update(scan_of(SPARSE, pole_ahead(SPARSE, 1.5)), AT_START)
        costmap.update(scan_of(SPARSE, np.full(SPARSE.beam_count, np.inf)), AT_START)
    assert lethal_cells(sparse) == 0
    assert lethal_cells(bare) == 1  # without inf_is_valid no ray clears it


def test_inf_is_valid_rings_the_robot_with_phantoms_for_a_scanner_shorter_than_its_range(
    mutants: ModuleType,
) -> None:
    settings = settings_of(mutants, "inf_is_valid")
    short = profile(samples=181, min_angle=-math.pi / 2, max_angle=math.pi / 2, range_max=2.0)
    costmap = costmap_of(settings, settings.local)
    costmap.update(scan_of(short, np.full(181, np.inf)), AT_START)
    assert lethal_cells(costmap) > 50  # +inf read as 1.9999 m, within obstacle_max_range 2.5
    # The LMS111 publishes 0.0 for no return, which inf_is_valid does not touch.
    lms111 = costmap_of(settings, settings.local)
    lms111.update(scan_of(LMS111, np.zeros(LMS111.beam_count)), AT_START)
    assert lethal_cells(lms111) == 0


# The equivalent faults.


def nav2_reads(scan: LaserScan) -> tuple[FloatArray, FloatArray]:
    """What the Husky's Nav2 reads of a scan: the costmaps' points (range_min to below range_max,
    inf_is_valid unset) and the collision monitor's within 5 m, beyond its reach (m)."""
    costmaps = scan.points_in_base(within=scan.meta.range_max)
    monitor = scan_points(scan)
    return costmaps, monitor[np.hypot(monitor[:, 0], monitor[:, 1]) < 5.0]


def readings_of_every_kind(scanner: LaserProfile) -> FloatArray:
    """Each kind of reading the simulated drivers publish, over the scanner's beams: no return,
    too near, a driver's 0.0, range_min, range_max, and in between."""
    kinds = [np.inf, -np.inf, 0.0, scanner.range_min, scanner.range_max, 1.0, 0.7, 3.0]
    return np.resize(np.array(kinds), scanner.beam_count)


def test_the_range_filter_replaces_what_it_cuts_by_zero(faults: ModuleType) -> None:
    zero = faults.ZeroReplacement(HUSKY_LASER)  # upper_threshold 30 m, the old range_max
    scan = scan_of(
        HUSKY_LASER, np.resize([-np.inf, 0.0, 0.05, 2.0, 29.9, 30.0, np.inf, np.nan], 720)
    )
    out = zero.scan(scan, STILL).ranges[:8]
    np.testing.assert_array_equal(out, [0.0, 0.0, 0.05, 2.0, 29.9, 0.0, 0.0, np.nan])


def test_no_return_at_range_max_puts_points_the_monitor_counts_before_a_short_source(
    faults: ModuleType,
) -> None:
    short = profile(samples=5, min_angle=-math.pi / 2, max_angle=math.pi / 2, range_max=1.0)
    scan = scan_of(short, [np.inf, 0.5, np.inf, np.inf, -np.inf])
    out = faults.NoReturnAtRangeMax().scan(scan, STILL)
    np.testing.assert_array_equal(out.ranges, [1.0, 0.5, 1.0, 1.0, -np.inf])
    assert len(scan_points(scan)) == 1
    assert len(scan_points(out)) == 4  # a metre away: inside the monitor's reach
    assert len(out.points_in_base(within=1.0)) == 1  # the costmaps stop below range_max


@pytest.mark.parametrize("name", ["zero_replacement", "no_return_at_range_max"])
def test_a_no_return_encoding_changes_nothing_the_husky_nav2_reads_of_the_benchmarks_scans(
    mutants: ModuleType, name: str
) -> None:
    mutant = mutant_named(mutants, name)
    for pair in SPEC.pairs:  # tuned for the pair's old scanner, reading either
        fault = mutant.make(pair.baseline.profile)
        for scanner in (pair.baseline.profile, pair.candidate.profile):
            scan = scan_of(scanner, readings_of_every_kind(scanner))
            out = fault.scan(scan, STILL)
            assert not np.array_equal(out.ranges, scan.ranges, equal_nan=True)  # it changes it
            for read, read_out in zip(nav2_reads(scan), nav2_reads(out), strict=True):
                np.testing.assert_array_equal(read, read_out)
    assert not own_settings().local.costmap.inf_is_valid  # why: the a200 file leaves it unset


def test_the_counter_clockwise_relay_passes_every_simulated_scan_as_it_is(
    faults: ModuleType,
) -> None:
    relay = faults.CounterClockwiseOnly()
    for scanner in SCANNERS:
        scan = scan_of(scanner, readings_of_every_kind(scanner))
        assert relay.scan(scan, STILL) is scan
    # A clockwise scan comes out mirrored about its first beam: a reading at -1 rad is taken
    # to lie at 3 rad.
    clockwise = LaserScanMeta(1.0, -1.0, -1.0, 0.0, 0.02, 0.1, 10.0)  # beams at 1, 0, -1 rad
    scan = LaserScan(0.0, np.array([np.inf, np.inf, 2.0]), clockwise, FIVE.pose)
    ((x, y),), ((x_out, y_out),) = scan.points_in_base(), relay.scan(scan, STILL).points_in_base()
    assert math.atan2(y, x) == pytest.approx(-1.0)
    assert math.atan2(y_out, x_out) == pytest.approx(3.0)


def test_a_malformed_time_increment_ends_the_controller_a_simulated_scan_never_does(
    faults: ModuleType,
) -> None:
    crash = faults.TimeIncrementCrash()
    for scanner in SCANNERS:
        scan = scan_of(scanner, readings_of_every_kind(scanner), stamp=12.0)
        assert scanner.to_laserscan_meta().time_increment == 0.0  # one instant, as Gazebo's
        assert crash.scan(scan, STILL) is scan
        assert crash.command((0.5, 0.2), scan) == (0.5, 0.2)
    meta = HUSKY_LASER.to_laserscan_meta()
    backwards = dataclasses.replace(meta, time_increment=-1e-3)  # s: the sweep ends before 0
    malformed = LaserScan(0.01, np.full(720, 3.0), backwards, HUSKY_LASER.pose)
    crash.scan(malformed, STILL)
    assert crash.command((0.5, 0.2), scan_of(HUSKY_LASER, np.full(720, 3.0), 0.03)) == (0.0, 0.0)
