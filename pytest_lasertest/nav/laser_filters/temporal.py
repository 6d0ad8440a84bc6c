"""laser_filters' filters over time: LaserArrayFilter (and ROS 1's LaserMedianFilter) passing
each reading, beam by beam, through a chain of the `filters` package's multi-channel filters,
which remember the last scans.

A filter with memory starts empty on each run (`ArrayFilter.start`), as a node starts with its
launch. Cited: ros-perception/laser_filters at ros2 905f5e9a and noetic-devel 75913d51, and
ros/filters at ros2 e33463ae and noetic-devel 310202ed.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.nav.laser_filters.scan_filters import replaced
from pytest_lasertest.nav.protocol import LaserScan

Statistic = Literal["mean", "median"]


@dataclass(frozen=True)
class ChannelFilter:
    """filters/MultiChannelMeanFilter or MultiChannelMedianFilter (Float or Double): each
    channel's mean, or lower median, over the last `number_of_observations` inputs, fewer
    while fewer have come (mean.hpp:190-221, median.hpp:237-257 at ros2; mean.hpp:195-226,
    median.hpp:242-266 at noetic-devel)."""

    statistic: Statistic
    number_of_observations: int


@dataclass(frozen=True)
class ArrayFilter:
    """LaserArrayFilter: the ranges through `range_chain`, one channel a beam, and the
    intensities through the intensity chain, which has nothing to filter here: the simulated
    scanner publishes no intensities (array_filter.h:89-114 at ros2; array_filter.cpp:85-111
    at noetic-devel). ROS 1's LaserMedianFilter runs its internal_filter chain the same way
    (median_filter.cpp:66-100 at noetic-devel)."""

    range_chain: tuple[ChannelFilter, ...]

    def start(self) -> Callable[[LaserScan], LaserScan]:
        """A fresh filter, remembering no scan."""
        return _Running(self.range_chain).apply


class _Running:
    """An ArrayFilter during one run: each channel filter's last inputs."""

    def __init__(self, chain: tuple[ChannelFilter, ...]) -> None:
        self.chain = chain
        self.inputs = [deque[FloatArray](maxlen=step.number_of_observations) for step in chain]
        self.beams: int | None = None

    def apply(self, scan: LaserScan) -> LaserScan:
        if len(scan.ranges) != self.beams:
            # A scan of another size makes the filter configure its chains afresh
            # (array_filter.h:100-107 at ros2; array_filter.cpp:96-103 at noetic-devel).
            self.beams = len(scan.ranges)
            for kept in self.inputs:
                kept.clear()
        ranges = scan.ranges
        for step, kept in zip(self.chain, self.inputs, strict=True):
            kept.append(ranges)  # RealtimeCircularBuffer: oldest first, the oldest dropped
            rows = np.stack(kept)
            ranges = _mean(rows) if step.statistic == "mean" else _median(rows)
        return replaced(scan, ranges)


def _mean(rows: FloatArray) -> FloatArray:
    """Each channel's mean, summed row by row from the oldest (mean.hpp:212-218 at ros2)."""
    total = np.zeros(rows.shape[1])
    with np.errstate(invalid="ignore"):
        for row in rows:
            total += row
    mean: FloatArray = total / len(rows)
    return mean


def _median(rows: FloatArray) -> FloatArray:
    """Each channel's lower median by Wirth's kth_smallest (median.hpp:64-92 at ros2): the
    k-th smallest, k = (n - 1) // 2, which any selection finds where no value is NaN; a channel
    with a NaN gets what Wirth's exchanges make of it, in the buffer's order."""
    count, k = len(rows), (len(rows) - 1) // 2
    if count <= _PACKED:
        return _wirth_by_pattern(rows, k)
    median: FloatArray = np.partition(rows, k, axis=0)[k]
    for channel in np.flatnonzero(np.isnan(rows).any(axis=0)):
        median[channel] = kth_smallest([float(value) for value in rows[:, channel]], k)
    return median


# Wirth's exchanges depend on nothing but which value is below which: channels alike in that
# are selected alike, once. Up to 8 rows the pattern, a bit for each ordered pair, fits 64 bits.
_PACKED = 8


def _wirth_by_pattern(rows: FloatArray, k: int) -> FloatArray:
    """Each channel's kth_smallest, Wirth run once for each pattern of the channels' order."""
    count, channels = rows.shape
    with np.errstate(invalid="ignore"):
        below = rows[:, np.newaxis, :] < rows[np.newaxis, :, :]
    bits = np.left_shift(np.uint64(1), np.arange(count * count, dtype=np.uint64))
    patterns = (below.reshape(count * count, channels) * bits[:, np.newaxis]).sum(axis=0)
    _, first, inverse = np.unique(patterns, return_index=True, return_inverse=True)
    chosen = np.array([_kth_row(rows[:, channel], k) for channel in first], dtype=np.intp)
    median: FloatArray = rows[chosen[inverse.reshape(-1)], np.arange(channels)]
    return median


def _kth_row(values: FloatArray, k: int) -> int:
    """The row Wirth's kth_smallest of `values` selects."""
    order = [(float(value), row) for row, value in enumerate(values)]
    return _kth(order, k)[1]


def kth_smallest(values: list[float], k: int) -> float:
    """Wirth's kth_smallest as filters' median.hpp:64-86 writes it, exchanges and all."""
    return _kth([(value, row) for row, value in enumerate(values)], k)[0]


def _kth(a: list[tuple[float, int]], k: int) -> tuple[float, int]:
    """kth_smallest on (value, row) pairs, compared by value alone, so that the row of the
    value selected is known."""
    a, low, high = list(a), 0, len(a) - 1
    while low < high:
        x, i, j = a[k][0], low, high
        while i <= j:
            while a[i][0] < x:
                i += 1
            while x < a[j][0]:
                j -= 1
            if i <= j:
                a[i], a[j] = a[j], a[i]
                i, j = i + 1, j - 1
        if j < k:
            low = i
        if k < i:
            high = j
    return a[k]
