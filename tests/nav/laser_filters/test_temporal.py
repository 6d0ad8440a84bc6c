"""The median over the last scans: selected once per pattern of the channels' order, it is
what Wirth's kth_smallest selects channel by channel, NaN, infinities and ties included."""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.nav.laser_filters.temporal import ArrayFilter, ChannelFilter, kth_smallest
from tests.helpers.laser_filters import message


@pytest.mark.parametrize("observations", [1, 2, 3, 5, 8, 9])
def test_the_median_of_each_reading_is_wirths_selection_of_its_last_scans(
    observations: int,
) -> None:
    rng = np.random.default_rng(observations)
    # Readings from few values, so that ties and repeated patterns are common.
    choices = np.array([np.nan, -np.inf, 0.5, 1.0, 1.0, 2.0, np.inf])
    scans = rng.choice(choices, size=(observations + 3, 400))
    run = ArrayFilter((ChannelFilter("median", observations),)).start()
    for count, ranges in enumerate(scans, start=1):
        out = run(message(list(ranges), -1.0, 1.0, 0.1, 10.0)).ranges
        rows = scans[max(count - observations, 0) : count]
        k = (len(rows) - 1) // 2
        wanted = [kth_smallest(list(rows[:, channel]), k) for channel in range(400)]
        np.testing.assert_array_equal(out, wanted)
