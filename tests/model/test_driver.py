"""A scanner's driver: what it publishes for each kind of reading, its range_max, its beam order
and its stamp, and the words a report gives each difference."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pytest_lasertest.model.driver import DEFAULT_DRIVER, Driver, describe, differences, publish
from pytest_lasertest.model.sensor import ProfileError

MEASURED = np.array([1.5, np.inf, -np.inf, 2.5, np.inf])  # m, REP 117


def published(**traits: object) -> tuple[list[float], float]:
    ranges, range_max = publish(Driver(**traits), MEASURED, 0.1, 10.0)  # type: ignore[arg-type]
    return ranges.tolist(), range_max


def test_gazebos_driver_publishes_what_the_scanner_measured() -> None:
    ranges, range_max = publish(DEFAULT_DRIVER, MEASURED, 0.1, 10.0)
    assert ranges is MEASURED
    assert range_max == 10.0


@pytest.mark.parametrize(
    ("encoding", "value"), [("nan", math.nan), ("zero", 0.0), ("range_max", 10.0)]
)
def test_each_no_return_encoding_replaces_every_plus_infinity(encoding: str, value: float) -> None:
    ranges, _ = published(no_return=encoding)
    np.testing.assert_array_equal(ranges, [1.5, value, -np.inf, 2.5, value])


def test_a_reading_nearer_than_range_min_may_be_published_as_range_min() -> None:
    ranges, _ = published(too_near="range_min")
    assert ranges[2] == 0.1


def test_a_per_scan_range_max_is_the_largest_reading_and_no_return_may_read_it() -> None:
    ranges, range_max = published(range_max="per_scan", no_return="range_max")
    assert range_max == 2.5
    assert ranges == [1.5, 2.5, -np.inf, 2.5, 2.5]


def test_a_per_scan_range_max_of_a_scan_that_read_nothing_is_the_fixed_one() -> None:
    _, range_max = publish(Driver(range_max="per_scan"), np.full(3, np.inf), 0.1, 10.0)
    assert range_max == 10.0


def test_a_clockwise_driver_publishes_the_ranges_in_reverse_order() -> None:
    ranges, _ = published(beam_order="clockwise")
    assert ranges == [np.inf, 2.5, -np.inf, np.inf, 1.5]


def test_a_driver_that_stamps_the_sweeps_end_delays_the_stamp_by_the_sweep() -> None:
    assert Driver(latency=0.05, stamp="end").delay(0.1) == pytest.approx(0.15)
    assert Driver(latency=0.05).delay(0.1) == pytest.approx(0.05)


@pytest.mark.parametrize(
    ("traits", "field"),
    [
        ({"no_return": "-inf"}, "driver.no_return"),
        ({"too_near": "range_max"}, "driver.too_near"),
        ({"beam_order": "backwards"}, "driver.beam_order"),
        ({"latency": -0.1}, "driver.latency"),
        ({"latency": math.nan}, "driver.latency"),
        ({"latency": 60.0}, "driver.latency"),
    ],
)
def test_a_driver_no_scanner_has_is_refused_naming_its_field(
    traits: dict[str, object], field: str
) -> None:
    with pytest.raises(ProfileError) as refused:
        Driver(**traits)  # type: ignore[arg-type]
    assert refused.value.field == field


def test_differences_name_each_trait_and_what_it_does_downstream() -> None:
    said = dict(differences(DEFAULT_DRIVER, Driver(no_return="nan", latency=0.2)))
    assert set(said) == {"no_return", "latency"}
    assert "clears nothing even with inf_is_valid" in said["no_return"]
    assert said["latency"].startswith("stamp later than the measurement by 0.2 s")


def test_a_default_driver_is_described_as_gazebos() -> None:
    assert "Gazebo" in describe(DEFAULT_DRIVER)
    assert describe(Driver(range_max="per_scan")) == ("range_max the largest reading of each scan")
