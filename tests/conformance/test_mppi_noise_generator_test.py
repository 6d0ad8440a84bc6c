"""nav2_mppi_controller's noise generator tests (noise_generator_test.cpp), rebuilt on our
optimizer's noised controls: the `NoiseDrawer` (noise.py) draws standard normal noise, which
`Optimizer` scales by vx_std and wz_std and adds to the control sequence (mppi.py `_samples`,
setNoisedControls).

Not applicable: NoiseGeneratorLifecycle (thread start and shutdown, no assertion), the vy
checks of NoiseGeneratorMain and its holonomic half (a differential drive has no lateral
speed).
"""

from __future__ import annotations

import numpy as np
import pytest

from pytest_lasertest.nav.nav2.mppi import CriticData, Cycle, MppiSettings, Optimizer
from tests.helpers.upstream import NAVIGATION2_JAZZY, NotPorted, Source

NOISE = Source(
    "Nav2 MPPI: noise", NAVIGATION2_JAZZY, "nav2_mppi_controller/test/noise_generator_test.cpp"
)
NOT_PORTED: tuple[NotPorted, ...] = (
    NotPorted(
        NOISE,
        "NoiseGeneratorTest.NoiseGeneratorMain",
        4,
        "before any noise is drawn (after reset zeroes it) the noised controls equal the "
        "sequence: our NoiseDrawer has no zeroed state; every cycle's noise is drawn before the "
        "cycle uses it",
    ),
)


def noised_controls() -> CriticData:
    """One cycle's noised controls of the sequence vx = wz = 0, 1, ..., 24, with the test's
    100 x 25 samples and standard deviations of 0.1."""
    settings = MppiSettings(
        batch_size=100,
        time_steps=25,
        vx_std=0.1,
        wz_std=0.1,
        # Acceleration limits that bound nothing: the noise generator knows none, and ours
        # are applied to the noised controls in the same step (DiffDrive's predict).
        ax_max=1000.0,
        ax_min=-1000.0,
        az_max=1000.0,
    )
    optimizer = Optimizer(settings, [], np.random.default_rng(0))
    optimizer.vx[:] = optimizer.wz[:] = np.arange(25, dtype=np.float32)
    path = np.zeros((2, 2), dtype=np.float32)
    # _samples is the optimizer's step that noises its sequence; it has no public entry.
    return optimizer._samples(Cycle((0.0, 0.0, 0.0), (0.0, 0.0), path, (0.0, 0.0), None))


@NOISE.test("NoiseGeneratorTest.NoiseGeneratorMain", assertions=4)
def test_noise_is_added_to_every_control() -> None:
    data = noised_controls()
    # Sample 0's controls at steps 0 and 9, as the test reads cvx(0) and cvx(9).
    assert data.cvx[0, 0] != 0.0
    assert data.cwz[0, 0] != 0.0
    assert data.cvx[0, 9] != 9.0
    assert data.cwz[0, 9] != 9.0


@NOISE.test("NoiseGeneratorTest.NoiseGeneratorMain", assertions=4)
def test_the_noise_is_of_the_sampling_standard_deviation() -> None:
    data = noised_controls()
    assert data.cvx[0, 0] == pytest.approx(0.0, abs=0.3)
    assert data.cwz[0, 0] == pytest.approx(0.0, abs=0.3)
    assert data.cvx[0, 9] == pytest.approx(9.0, abs=0.3)
    assert data.cwz[0, 9] == pytest.approx(9.0, abs=0.3)
