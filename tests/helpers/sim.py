"""What the simulator tests share."""

from __future__ import annotations

TIME_STEP = 0.01  # s, of the PyBullet worlds the simulator tests step
