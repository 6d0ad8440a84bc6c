"""ROS 1 base_local_planner's VelocityIterator tests (base_local_planner/test/
velocity_iterator_test.cpp), on our DWA's sampling of one velocity range
(pytest_lasertest/nav/move_base/dwa.py: velocity_samples): evenly spaced samples from the least
to the most, one sample when they are equal, at least two otherwise, and 0 added between a
negative and a positive sample.

Every test of the file is ported.
"""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.nav.move_base.dwa import velocity_samples
from tests.helpers.upstream import NAVIGATION_NOETIC, Source

ITERATOR = Source(
    "ROS 1 base_local_planner: DWA velocity iterator",
    NAVIGATION_NOETIC,
    "base_local_planner/test/velocity_iterator_test.cpp",
)


def float_eq(value: float, expected: float) -> bool:
    """gtest's EXPECT_FLOAT_EQ: equal as single-precision floats within 4 units in the last
    place."""
    a, b = np.float32(value), np.float32(expected)
    return bool(abs(a - b) <= 4 * np.spacing(abs(b)))


@pytest.mark.parametrize(
    ("low", "high", "count", "expected"),
    [
        pytest.param(
            0.0,
            0.0,
            1,
            [0.0],
            marks=ITERATOR.test("VelocityIteratorTest.testsingle", 2),
            id="one-value-zero",
        ),
        pytest.param(
            2.2,
            2.2,
            1,
            [2.2],
            marks=ITERATOR.test("VelocityIteratorTest.testsingle_pos", 2),
            id="one-value-positive",
        ),
        pytest.param(
            -3.3,
            -3.3,
            1,
            [-3.3],
            marks=ITERATOR.test("VelocityIteratorTest.testsingle_neg", 2),
            id="one-value-negative",
        ),
        pytest.param(
            -30.0,
            30.0,
            1,
            [-30.0, 0.0, 30.0],
            marks=ITERATOR.test("VelocityIteratorTest.test1", 2),
            id="one-sample-across-zero",
        ),
        pytest.param(
            10.0,
            30.0,
            1,
            [10.0, 30.0],
            marks=ITERATOR.test("VelocityIteratorTest.test1_pos", 2),
            id="one-sample-positive",
        ),
        pytest.param(
            -30.0,
            -10.0,
            1,
            [-30.0, -10.0],
            marks=ITERATOR.test("VelocityIteratorTest.test1_neg", 2),
            id="one-sample-negative",
        ),
        pytest.param(
            -30.0,
            30.0,
            3,
            [-30.0, 0.0, 30.0],
            marks=ITERATOR.test("VelocityIteratorTest.test3", 2),
            id="three-across-zero",
        ),
        pytest.param(
            -30.0,
            30.0,
            4,
            [-30.0, -10.0, 0.0, 10.0, 30.0],
            marks=ITERATOR.test("VelocityIteratorTest.test4", 2),
            id="four-across-zero",
        ),
        pytest.param(
            -10.0,
            50.0,
            4,
            [-10.0, 0.0, 10.0, 30.0, 50.0],
            marks=ITERATOR.test("VelocityIteratorTest.test_shifted", 2),
            id="four-zero-off-centre",
        ),
    ],
)
def test_the_samples_span_the_range_evenly_with_zero_added_where_it_crosses(
    low: float, high: float, count: int, expected: list[float]
) -> None:
    samples = velocity_samples(low, high, count)
    assert len(samples) == len(expected)
    assert samples.tolist() == expected  # EXPECT_EQ on doubles: exactly


@ITERATOR.test("VelocityIteratorTest.test_cranky", assertions=2)
def test_a_sample_just_below_zero_still_gets_zero_added_after_it() -> None:
    samples = velocity_samples(-10.00001, 10.0, 3)
    assert len(samples) == 4
    expected = [-10.00001, -0.000005, 0.0, 10.0]
    # Upstream's loop also compares a fifth, never written element; only four exist.
    assert all(float_eq(value, want) for value, want in zip(samples, expected, strict=True))
