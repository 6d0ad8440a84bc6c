"""Scanner profiles and obstacles tests build."""

from __future__ import annotations

from typing import Any

import numpy as np

from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.obstacles import Cylinder
from pytest_lasertest.model.sensor import LaserProfile

# The bundled Husky's laser mount (robots/husky/robot.yaml): upside down, 0.44 m up.
HUSKY_MOUNT = Pose3D((0.337, 0.0, 0.44023), (3.14159, 0.0, 0.0))  # m, rad
# A failure the solver recorded: numpy floats with no short decimal form.
RECORDED = Cylinder(np.float64(5.943000000000001), 0.1 + 0.2, 1.0 / 30.0, 0.323)  # m


def profile(**overrides: Any) -> LaserProfile:
    """The paper's scanner (720 beams over +-1.57 rad, 0.1-10 m, 50 Hz) with `overrides`."""
    fields: dict[str, Any] = {
        "samples": 720,
        "min_angle": -1.57,
        "max_angle": 1.57,
        "range_min": 0.1,
        "range_max": 10.0,
        "update_rate": 50.0,
    }
    fields.update(overrides)
    return LaserProfile(**fields)
