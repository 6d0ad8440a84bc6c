"""MPPI's noise (nav2_mppi_controller src/noise_generator.cpp at jazzy f4108e5b): with
regenerate_noises, each cycle's noise is drawn in a thread of its own while the cycle before
runs. Our own code."""

from __future__ import annotations

import threading

import numpy as np
import numpy.typing as npt


class NoiseDrawer:
    """The optimizer's noise, (2, T, B) standard normal float32 a cycle, each cycle's drawn in a
    thread of its own while the cycle before runs, as Nav2's NoiseGenerator draws it
    (noise_generator.cpp, noiseThread, with regenerate_noises). One generator draws every
    cycle's in turn, so the values are the same as drawn one after another in line; numpy lets
    go of the GIL while it draws, so the draw overlaps the critics where a core is free."""

    def __init__(self, rng: np.random.Generator, shape: tuple[int, int, int]) -> None:
        self.rng = rng
        # Two buffers: the cycle's, and the next one's being drawn.
        self._buffers = [np.empty(shape, dtype=np.float32) for _ in range(2)]
        self._drawing: threading.Thread | None = None
        self._ready = 0  # the buffer the next draw goes to, or has gone to

    def next(self) -> npt.NDArray[np.float32]:
        """This cycle's noise; the next cycle's starts drawing."""
        if self._drawing is None:
            self._draw(self._ready)
        else:
            self._drawing.join()
        noise, self._ready = self._buffers[self._ready], 1 - self._ready
        self._drawing = threading.Thread(target=self._draw, args=(self._ready,), daemon=True)
        self._drawing.start()
        return noise

    def _draw(self, buffer: int) -> None:
        self.rng.standard_normal(dtype=np.float32, out=self._buffers[buffer])
