"""The costs a costmap cell holds, as costmap_2d's cost_values.h names them (ROS 1 and Nav2 alike),
and the grid type that holds them."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

FREE, INSCRIBED, LETHAL, UNKNOWN = 0, 253, 254, 255
Grid = npt.NDArray[np.uint8]  # (N, N) costs, indexed [y, x]
