"""What a candidate scanner loses or gains against its baseline, attribute by attribute."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import pytest

from pytest_lasertest.model.coverage import (
    CoverageComparison,
    Sector,
    compare_coverage,
    sector_difference,
    sure_detection_distance,
)
from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.sensor import GaussianNoise, LaserProfile
from tests.helpers.model import HUSKY_MOUNT, profile

PAPER_SIZE = 0.0507  # m, the paper's "size" pole
MAX_SPEED = 1.0  # m/s


def husky(**overrides: Any) -> LaserProfile:
    return profile(**{"pose": HUSKY_MOUNT, **overrides})


def compare(baseline: LaserProfile, candidate: LaserProfile) -> CoverageComparison:
    return compare_coverage(baseline, candidate, min_obstacle_size=PAPER_SIZE, max_speed=MAX_SPEED)


def assert_sectors(
    actual: Sequence[Sector], expected: Sequence[tuple[float, float]], *, tol: float = 1e-9
) -> None:
    """Sectors equal (start, extent) pairs, in any order."""
    got = sorted((sector.start, sector.extent) for sector in actual)
    assert len(got) == len(expected), got
    for (start, extent), (want_start, want_extent) in zip(got, sorted(expected), strict=True):
        assert start == pytest.approx(want_start, abs=tol)
        assert extent == pytest.approx(want_extent, abs=tol)


PAPER_PAIRS = {
    "blind_spot": (husky(), husky(min_angle=-1.0, max_angle=1.0)),
    "distance": (husky(), husky(range_max=5.0)),
    "size": (husky(samples=32), husky(samples=16)),
}


@pytest.mark.parametrize(
    ("kept", "removed", "remaining"),
    [
        pytest.param(
            Sector(-1.0, 2.0), Sector(-0.25, 0.5), [(-1.0, 0.75), (0.25, 0.75)], id="inside"
        ),
        pytest.param(Sector(0.0, 1.0), Sector(2.0, 0.5), [(0.0, 1.0)], id="disjoint"),
        pytest.param(Sector(0.0, 1.0), Sector(-math.pi, 2 * math.pi), [], id="full-turn"),
        pytest.param(Sector(0.0, 1.0), Sector(-0.5, 2.0), [], id="covering"),
        pytest.param(Sector(0.0, 1.0), Sector(0.5, 2.0), [(0.0, 0.5)], id="overlapping-end"),
        pytest.param(
            Sector(3.0, 1.0),
            Sector(-3.0, 0.5),
            [(3.0, 2 * math.pi - 6.0), (-2.5, 6.5 - 2 * math.pi)],
            id="kept-crosses-pi",
        ),
        pytest.param(
            Sector(-1.0, 2.0),
            Sector(3.0, 2.5),
            [(5.5 - 2 * math.pi, 2 * math.pi - 4.5)],
            id="removed-crosses-pi",
        ),
    ],
)
def test_removing_a_sector_leaves_the_arcs_it_does_not_cover(
    kept: Sector, removed: Sector, remaining: list[tuple[float, float]]
) -> None:
    assert_sectors(sector_difference(kept, removed), remaining)


def test_narrowing_the_field_of_view_loses_exactly_the_two_side_sectors() -> None:
    comparison = compare(*PAPER_PAIRS["blind_spot"])

    assert [change.attribute for change in comparison.losses] == ["field of view"]
    assert_sectors(comparison.lost_sectors, [(-1.57, 0.57), (1.0, 0.57)], tol=1e-4)
    assert comparison.gained_sectors == ()


def test_halving_the_range_loses_only_the_far_range() -> None:
    comparison = compare(*PAPER_PAIRS["distance"])

    [loss] = comparison.losses
    assert loss.attribute == "range.max"
    assert (loss.baseline, loss.candidate) == (10.0, 5.0)
    assert comparison.lost_sectors == ()


def test_halving_the_samples_loses_only_beam_spacing_and_says_how_far_a_pole_is_sure_seen() -> None:
    baseline, candidate = PAPER_PAIRS["size"]
    comparison = compare(baseline, candidate)

    [loss] = comparison.losses
    assert loss.attribute == "beam spacing"
    assert loss.candidate == pytest.approx(3.14 / 15)
    assert sure_detection_distance(candidate, PAPER_SIZE) == pytest.approx(0.2427, abs=1e-4)
    assert sure_detection_distance(baseline, PAPER_SIZE) == pytest.approx(0.5007, abs=1e-4)
    assert "out to 0.24 m, was 0.50 m" in loss.detail
    assert "16 beams, was 32" in loss.detail


def test_identical_scanners_show_no_change_at_all() -> None:
    comparison = compare(husky(), husky())

    assert comparison.changes == ()
    assert comparison.lost_sectors == ()
    assert comparison.gained_sectors == ()


@pytest.mark.parametrize("name", ["distance", "size"])
def test_the_reverse_of_a_downgrade_is_an_upgrade_with_no_losses(name: str) -> None:
    better, worse = PAPER_PAIRS[name]
    comparison = compare(worse, better)

    assert comparison.changes
    assert comparison.losses == ()
    assert comparison.lost_sectors == ()


def test_widening_the_field_of_view_with_the_same_samples_gains_sectors_but_spreads_the_beams() -> (
    None
):
    wide, narrow = PAPER_PAIRS["blind_spot"]
    comparison = compare(narrow, wide)

    assert comparison.lost_sectors == ()
    assert_sectors(comparison.gained_sectors, [(-1.57, 0.57), (1.0, 0.57)], tol=1e-4)
    [field_of_view] = [c for c in comparison.changes if c.attribute == "field of view"]
    assert not field_of_view.worse
    # 720 beams over 3.14 rad instead of 2 rad: a thin pole is sure to be hit less far out.
    assert [change.attribute for change in comparison.losses] == ["beam spacing"]


@pytest.mark.parametrize(
    ("candidate", "attribute", "worse"),
    [
        pytest.param(
            husky(pose=Pose3D((0.337, 0.0, 0.5), HUSKY_MOUNT.rpy)), "scan height", True, id="raised"
        ),
        pytest.param(
            husky(pose=Pose3D((0.337, 0.0, 0.1), HUSKY_MOUNT.rpy)),
            "scan height",
            False,
            id="lowered",
        ),
        pytest.param(husky(update_rate=25.0), "update_rate", True, id="slower"),
        pytest.param(husky(update_rate=100.0), "update_rate", False, id="faster"),
        pytest.param(husky(range_min=0.5), "range.min", True, id="higher-range-min"),
        pytest.param(husky(range_min=0.05), "range.min", False, id="lower-range-min"),
        pytest.param(husky(range_max=20.0), "range.max", False, id="longer-range"),
        pytest.param(
            husky(pose=Pose3D((0.337, 0.1, 0.44023), HUSKY_MOUNT.rpy)),
            "mount position",
            False,
            id="moved-sideways",
        ),
        pytest.param(husky(noise=GaussianNoise(stddev=0.01)), "noise.stddev", False, id="noisier"),
    ],
)
def test_each_changed_attribute_is_reported_once_and_is_worse_only_if_it_blinds_the_robot(
    candidate: LaserProfile, attribute: str, worse: bool
) -> None:
    comparison = compare(husky(), candidate)

    [change] = comparison.changes
    assert change.attribute == attribute
    assert change.worse is worse
    assert comparison.losses == ((change,) if worse else ())


def test_a_scanner_moved_sideways_reports_how_far_it_moved() -> None:
    moved = husky(pose=Pose3D((0.337, 0.1, 0.44023), HUSKY_MOUNT.rpy))

    [change] = compare(husky(), moved).changes

    assert change.candidate == pytest.approx(0.1)


@pytest.mark.parametrize(
    ("samples", "min_angle", "max_angle", "size"),
    [(16, -1.57, 1.57, PAPER_SIZE), (720, -1.57, 1.57, 0.05), (5, -0.3, 2.0, 0.2)],
)
def test_an_obstacle_at_the_sure_detection_distance_midway_between_beams_is_just_grazed(
    samples: int, min_angle: float, max_angle: float, size: float
) -> None:
    scanner = profile(samples=samples, min_angle=min_angle, max_angle=max_angle)
    distance = sure_detection_distance(scanner, size)
    step = (max_angle - min_angle) / (samples - 1)
    left_beam, right_beam = min_angle + step, min_angle + 2 * step
    middle = (left_beam + right_beam) / 2
    centre = distance * np.array([math.cos(middle), math.sin(middle)])

    for beam in (left_beam, right_beam):
        direction = np.array([math.cos(beam), math.sin(beam)])
        along = float(direction @ centre)
        across = float(np.linalg.norm(centre - along * direction))
        assert along > 0
        assert across == pytest.approx(size / 2, rel=1e-9)


def test_a_yawed_mount_loses_one_sector_and_gains_another() -> None:
    comparison = compare(profile(), profile(pose=Pose3D(rpy=(0.0, 0.0, 0.5))))

    [change] = comparison.changes
    assert change.attribute == "field of view"
    assert change.worse
    assert_sectors(comparison.lost_sectors, [(-1.57, 0.5)], tol=1e-9)
    assert_sectors(comparison.gained_sectors, [(1.57, 0.5)], tol=1e-9)


def test_a_single_beam_candidate_loses_the_whole_field_of_view_but_its_one_direction() -> None:
    comparison = compare_coverage(
        profile(), profile(samples=1), min_obstacle_size=0.05, max_speed=1.0
    )
    field_of_view = next(c for c in comparison.changes if c.attribute == "field of view")
    assert field_of_view.worse
    assert field_of_view.candidate == 0.0
    assert [(s.start, s.extent) for s in comparison.lost_sectors] == [
        (pytest.approx(-1.57), pytest.approx(1.57)),
        (pytest.approx(0.0), pytest.approx(1.57)),
    ]


def test_a_driver_change_is_listed_in_words_and_loses_no_coverage() -> None:
    from pytest_lasertest.model.driver import Driver

    baseline = profile()
    candidate = profile(driver=Driver(beam_order="clockwise", latency=0.1))
    comparison = compare_coverage(baseline, candidate, min_obstacle_size=0.05, max_speed=1.0)
    assert comparison.losses == ()
    changes = {change.attribute: change for change in comparison.changes}
    assert set(changes) == {"driver.beam_order", "driver.latency"}
    assert changes["driver.beam_order"].candidate == "clockwise"
    assert "mirrored" in changes["driver.beam_order"].detail
    assert changes["driver.latency"].unit == "s"
