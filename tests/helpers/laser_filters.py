"""laser_filters' test scans and chains as the tests set them up: a LaserScan message as an
upstream test fills one, a chain read from a params file's text by the pairs file's reader,
and the readings' check of the upstream tests' expect_ranges_equal."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import numpy.typing as npt

from pytest_lasertest.inputs.errors import Location
from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.model.geometry import FloatArray, Pose3D
from pytest_lasertest.model.sensor import LaserScanMeta
from pytest_lasertest.nav.laser_filters import ScanFilterChain
from pytest_lasertest.nav.protocol import LaserScan, Odometry
from pytest_lasertest.pairsfile.scan_filters import read_scan_filters

STANDING = Odometry(0.0, 0.0, 0.0, 0.0, 0.0)
# Every reading, finite or not, replaced by NaN, no reading: a chain that blinds the stack.
BLINDING = """\
scan_to_scan_filter_chain:
  ros__parameters:
    filter1:
      name: everything
      type: laser_filters/LaserScanRangeFilter
      params:
        lower_threshold: 1000.0
        upper_threshold: 2000.0
        lower_replacement_value: .nan
        upper_replacement_value: .nan
"""


def message(
    ranges: Sequence[float],
    angle_min: float,
    angle_max: float,
    range_min: float,
    range_max: float,
    angle_increment: float | None = None,
    mount: Pose3D | None = None,
) -> LaserScan:
    """A scan of `ranges` (m); the angle increment, unless given, spreads the beams from
    angle_min to angle_max, both ends sampled, as the upstream tests' create_message does.
    The laser sits at the base's origin unless `mount` says where."""
    count = len(ranges)
    increment = (
        (angle_max - angle_min) / (count - 1) if angle_increment is None else angle_increment
    )
    meta = LaserScanMeta(angle_min, angle_max, increment, 0.1 / count, 0.1, range_min, range_max)
    return LaserScan(0.0, np.array(ranges, dtype=float), meta, mount or Pose3D())


def chain_of(directory: Path, text: str) -> ScanFilterChain:
    """The chain of a laser_filters params file holding `text`, read as a pairs file's
    `navigation: {scan_filters: filters.yaml}` in `directory` reads it."""
    (directory / "filters.yaml").write_text(text)
    node = SpecNode(
        "filters.yaml", Location(directory / "gate.lasertest.yaml", 4), "navigation.scan_filters"
    )
    return read_scan_filters(node)


def filtered(chain: ScanFilterChain, *scans: LaserScan) -> list[LaserScan]:
    """Each scan as one run of the chain passes it on, in order."""
    running = chain.start()
    return [running(scan, STANDING, float(time)) for time, scan in enumerate(scans)]


def assert_ranges(actual: FloatArray, expected: Sequence[float], tolerance: float = 1e-6) -> None:
    """expect_ranges_equal: as many readings, NaN where NaN is expected, the rest within
    `tolerance` m."""
    wanted = np.array(expected, dtype=float)
    assert len(actual) == len(wanted)
    nan = np.isnan(wanted)
    assert np.isnan(actual[nan]).all(), actual
    assert np.allclose(actual[~nan], wanted[~nan], rtol=0.0, atol=tolerance), actual


# The shadow detector tests' grid (test/test_shadow_detector.cpp).
def stepped(start: float, stop: float, step: float) -> list[float]:
    """A C `for (float x = start; x < stop; x += step)` loop's values."""
    values, x = [], np.float32(start)
    while x < stop:
        values.append(float(x))
        x = np.float32(x + np.float32(step))
    return values


def pure_shadow(
    first: FloatArray, second: FloatArray, angle: float, min_angle: float, max_angle: float
) -> npt.NDArray[np.bool_]:
    """isShadowPureImpl: the line's angle (degrees) outside [min_angle, max_angle]."""
    seen = np.abs(
        np.degrees(np.arctan2(second * math.sin(angle), first - second * math.cos(angle)))
    )
    result: npt.NDArray[np.bool_] = (seen < min_angle) | (seen > max_angle)
    return result


def thresholds() -> list[tuple[float, float]]:
    """The test's (min_angle, max_angle) pairs, degrees: 90 down to 0, 90 up to 180, by 5."""
    return [(90.0 - 5.0 * i, 90.0 + 5.0 * j) for i in range(19) for j in range(19)]


RANGES = np.array(stepped(0.1, 1.0, 0.1))  # m, the detector tests' r1 and r2
