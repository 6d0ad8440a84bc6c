"""nav2_mppi_controller's motion model tests (motion_model_tests.cpp), DiffDriveTest rebuilt on
our differential drive's predict (`motion_model.predict`): the speeds of each step are the controls
of the step before, bounded by the acceleration limits.

Not applicable: DiffDriveTest's vy and isHolonomic checks (our model has no lateral axis at
all), and OmniTest, AckermannTest and AckermannReversingTest (models we do not imitate).
"""

from __future__ import annotations

import numpy as np

from pytest_lasertest.nav.nav2.motion_model import changes, predict
from pytest_lasertest.nav.nav2.mppi import MppiSettings
from tests.helpers.upstream import NAVIGATION2_JAZZY, NotPorted, Source

MOTION_MODEL = Source(
    "Nav2 MPPI: motion model",
    NAVIGATION2_JAZZY,
    "nav2_mppi_controller/test/motion_model_tests.cpp",
)
NOT_PORTED: tuple[NotPorted, ...] = (
    NotPorted(
        MOTION_MODEL,
        "MotionModelTests.DiffDriveTest",
        2,
        "DiffDrive's applyConstraints leaves vx and wz as they are: our optimizer has no motion "
        "model hook after its own clipping (applyControlSequenceConstraints), so there is "
        "nothing of ours to call on its own",
    ),
)


@MOTION_MODEL.test("MotionModelTests.DiffDriveTest", assertions=2)
def test_predict_makes_each_steps_speed_the_control_of_the_step_before() -> None:
    # The test's model is never initialised: no time step, no acceleration limits, so that the
    # controls (10 m/s, 1 rad/s) pass only because the robot already drives at them.
    settings = MppiSettings(ax_max=0.0, ax_min=0.0, az_max=0.0)
    steps, batch = 50, 1000
    controls_vx = np.full((steps, batch), 10.0, dtype=np.float32)  # (T, B), time first
    controls_wz = np.full((steps, batch), 1.0, dtype=np.float32)
    change = changes(settings.model_dt, settings.ax_max, settings.ax_min, settings.az_max)
    vx, wz = predict(controls_vx, controls_wz, (10.0, 1.0), change)
    assert np.array_equal(vx, controls_vx)
    assert np.array_equal(wz, controls_wz)
