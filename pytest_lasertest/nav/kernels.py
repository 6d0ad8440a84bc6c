"""The navigation stacks' compiled code: the `compiled` factory every kernels module of the
stacks compiles with (nav/move_base/kernels.py, nav/nav2/kernels.py), and the kernels they share:
costmap_2d's Bresenham line (raytrace.py) and numpy's pairwise summation, with which the stacks'
kernels add up a row where the numpy code they replace summed one.

The line's cells are whole-number arithmetic, exact in any order: raytrace.bresenham_in_numpy's
to the unit, which tests/nav/test_raytrace.py holds, as it holds the pairwise sum equal to
numpy's sum of a float32 row to the bit.

numba compiles these when this module is imported (each for the one signature it is called
with), outside any controller call's time, and keeps the machine code in __pycache__: the first
import on a machine takes about 10 s, later ones a fraction of a second. The first compiles in a
child process (`_compile_apart`): LLVM keeps about 110 MB of what it compiled the stacks' kernels
with for as long as the process lives, and a process that only loads the cached machine code does
without it (docs/explanation/performance.md).
"""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar, cast

import numba
import numpy as np

Function = TypeVar("Function", bound=Callable[..., Any])
# Set in the child that compiles a kernels module, so that it compiles rather than spawn one.
COMPILING = "PYTEST_LASERTEST_COMPILING"
_compiled_apart: set[str] = set()  # the kernels modules this process had a child compile
# The stacks' kernels modules: the first of them found not cached has one child compile them
# all, which costs one process start where a child each cost three.
STACK_KERNELS = (
    "pytest_lasertest.nav.kernels",
    "pytest_lasertest.nav.move_base.kernels",
    "pytest_lasertest.nav.nav2.kernels",
)


def compiled(signature: str | None = None) -> Callable[[Function], Function]:
    """Compile a function in nopython mode, its machine code cached on disk: now, for
    `signature`, or else for the types of whatever compiled function calls it."""

    def compile_for(function: Function) -> Function:
        if signature is None:
            return cast(Function, numba.njit(function, cache=True, nogil=True))
        if not _cached(function):
            _compile_apart(function.__module__)
        return cast(Function, numba.njit(signature, cache=True, nogil=True)(function))

    return compile_for


def _cached(function: Callable[..., Any]) -> bool:
    """Whether numba's index of `function`'s machine code lies in its module's __pycache__,
    written since the module was (numba's own check, of the source's stamp, follows). Where
    __pycache__ cannot be written numba caches elsewhere, and this says no."""
    source = Path(function.__code__.co_filename)
    version = f"py{sys.version_info.major}{sys.version_info.minor}"
    name = f"{source.stem}.{function.__qualname__}-{function.__code__.co_firstlineno}"
    index = source.parent / "__pycache__" / f"{name}.{version}.nbi"
    try:
        return index.stat().st_mtime >= source.stat().st_mtime
    except OSError:
        return False


def _compile_apart(module: str) -> None:
    """Have a child process import `module` (and the stacks' kernels modules with it), compiling
    their kernels into numba's cache, once per module and process: this process then loads
    their machine code without keeping LLVM's memory of compiling it. Should the child fail,
    this process compiles them itself, and a kernel that does not compile raises here."""
    if os.environ.get(COMPILING) or module in _compiled_apart:
        return
    modules = [module, *(name for name in STACK_KERNELS if name not in _compiled_apart)]
    _compiled_apart.update(modules)
    # The child finds the modules where this process found them, not other copies.
    path = os.pathsep.join(sys.path)
    environment = {**os.environ, COMPILING: "1", "PYTHONPATH": path}
    command = [sys.executable, "-c", f"import {', '.join(dict.fromkeys(modules))}"]
    subprocess.run(command, env=environment, check=False, capture_output=True)


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


@compiled("f4(f4[::1], i8, i8)")
def pairwise_sum(values: Any, start: int, count: int) -> Any:
    """numpy's pairwise summation of values[start:start + count] (float32): a plain sum under
    8 values, eight running sums joined pairwise up to 128, halves of a multiple of 8 above."""
    if count < 8:
        total = np.float32(-0.0)
        for index in range(start, start + count):
            total += values[index]
        return total
    if count > 128:
        half = count // 2
        half -= half % 8
        return pairwise_sum(values, start, half) + pairwise_sum(values, start + half, count - half)
    s0, s1, s2, s3 = values[start], values[start + 1], values[start + 2], values[start + 3]
    s4, s5, s6, s7 = values[start + 4], values[start + 5], values[start + 6], values[start + 7]
    index = start + 8
    while index < start + count - count % 8:
        s0, s1, s2, s3 = (
            s0 + values[index],
            s1 + values[index + 1],
            s2 + values[index + 2],
            s3 + values[index + 3],
        )
        s4, s5, s6, s7 = (
            s4 + values[index + 4],
            s5 + values[index + 5],
            s6 + values[index + 6],
            s7 + values[index + 7],
        )
        index += 8
    total = ((s0 + s1) + (s2 + s3)) + ((s4 + s5) + (s6 + s7))
    while index < start + count:
        total += values[index]
        index += 1
    return total
