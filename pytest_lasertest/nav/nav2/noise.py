"""MPPI's noise (nav2_mppi_controller src/noise_generator.cpp at jazzy f4108e5b): with
regenerate_noises, each cycle's noise is drawn in a thread of its own while the cycle before
runs; without it (the code's default), one draw serves every cycle until the optimizer resets.
Our own code."""

from __future__ import annotations

import threading

import numpy as np
import numpy.typing as npt


class NoiseDrawer:
    """The optimizer's noise, (2, T, B) standard normal float32, read-only.

    With `regenerate` (regenerate_noises, as nav2_params.yaml sets it), each cycle's is drawn
    in a thread of its own while the cycle before runs, as NoiseGenerator's noiseThread draws
    it. One generator draws every cycle's in turn, so the values are the same as drawn one
    after another in line; numpy lets go of the GIL while it draws, so the draw overlaps the
    critics where a core is free.

    Without it, the noise is drawn once (NoiseGenerator::initialize) and again at each `reset`
    (NoiseGenerator::reset, which the optimizer's reset and fallback call); every cycle between
    reads the same, and draws nothing: the draw (2 T B normals) is a large part of a cycle.
    """

    def __init__(
        self, rng: np.random.Generator, shape: tuple[int, int, int], regenerate: bool = True
    ) -> None:
        self.rng, self.regenerate = rng, regenerate
        # With regenerate, two buffers: the cycle's, and the next one's being drawn.
        self._buffers = [np.empty(shape, dtype=np.float32) for _ in range(1 + regenerate)]
        self._drawing: threading.Thread | None = None
        self._ready = 0  # the buffer the next draw goes to, or has gone to
        if not regenerate:
            self._draw(0)

    def next(self) -> npt.NDArray[np.float32]:
        """This cycle's noise; with `regenerate`, the next cycle's starts drawing."""
        if not self.regenerate:
            return self._read_only(0)
        if self._drawing is None:
            self._draw(self._ready)
        else:
            self._drawing.join()
        noise, self._ready = self._read_only(self._ready), 1 - self._ready
        self._drawing = threading.Thread(target=self._draw, args=(self._ready,), daemon=True)
        self._drawing.start()
        return noise

    def reset(self) -> None:
        """NoiseGenerator::reset: noise drawn once is drawn afresh; regenerated noise is drawn
        afresh each cycle already."""
        if not self.regenerate:
            self._draw(0)

    def _read_only(self, buffer: int) -> npt.NDArray[np.float32]:
        view = self._buffers[buffer].view()
        view.flags.writeable = False  # a cycle that noised it in place would spoil the next
        return view

    def _draw(self, buffer: int) -> None:
        self.rng.standard_normal(dtype=np.float32, out=self._buffers[buffer])
