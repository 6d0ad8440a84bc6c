"""The navigation stacks' compiled code: the `compiled` factory every kernels module of the
stacks compiles with (nav/move_base/kernels.py, nav/nav2/kernels.py), and the kernel they share,
costmap_2d's Bresenham line (raytrace.py).

The line's cells are whole-number arithmetic, exact in any order: raytrace.bresenham_in_numpy's
to the unit, which tests/nav/test_raytrace.py holds.

numba compiles these when this module is imported (each for the one signature it is called
with), outside any controller call's time, and keeps the machine code in __pycache__: the first
import on a machine takes about 10 s, later ones a fraction of a second.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar, cast

import numba
import numpy as np

Function = TypeVar("Function", bound=Callable[..., Any])


def compiled(signature: str | None = None) -> Callable[[Function], Function]:
    """Compile a function in nopython mode, its machine code cached on disk: now, for
    `signature`, or else for the types of whatever compiled function calls it."""

    def compile_for(function: Function) -> Function:
        if signature is None:
            return cast(Function, numba.njit(function, cache=True, nogil=True))
        return cast(Function, numba.njit(signature, cache=True, nogil=True)(function))

    return compile_for


# numba's types: f8 is a float64, i8 an int64, u1 a byte, [::1] a C-contiguous axis.
CELLS = "f8[:, ::1]"  # (N, 2) m


@compiled("i8[::1](i8[::1], i8[::1], i8[::1], i8[::1], i8[::1], i8)")
def bresenham(start_x: Any, start_y: Any, end_x: Any, end_y: Any, steps: Any, stride: int) -> Any:
    """The cells bresenham2D visits from each start cell toward each end cell (K,) in `steps`
    (K,) steps along the longer axis, and the cell it then stands on, as flat indices
    x + y * stride, ray after ray (M,): each `step` cells along the longer axis and, Bresenham's
    error count, (major // 2 + step x minor) // major along the other."""
    cells = np.empty(int(np.sum(steps)) + len(steps), np.int64)
    at = 0
    for k in range(len(end_x)):
        dx, dy = end_x[k] - start_x[k], end_y[k] - start_y[k]
        major, minor = max(abs(dx), abs(dy)), min(abs(dx), abs(dy))
        unit_x, unit_y = 1 if dx > 0 else -1, stride if dy > 0 else -stride
        along, across = (unit_x, unit_y) if abs(dx) >= abs(dy) else (unit_y, unit_x)
        origin, divisor = start_x[k] + start_y[k] * stride, max(major, 1)
        for step in range(steps[k] + 1):
            cells[at] = origin + step * along + (major // 2 + step * minor) // divisor * across
            at += 1
    return cells
