"""MPPI's motion model for a differential drive (motion_models.hpp's DiffDrive::predict) and
its integration of the speeds into trajectories (Optimizer::integrateStateVelocities), over
every sample at once, time-major (T, B) in float32 as MPPI's xtensor arrays are.

Read in ros-navigation/navigation2 at jazzy f4108e5b: nav2_mppi_controller/include/
nav2_mppi_controller/motion_models.hpp and src/optimizer.cpp. The loops are compiled
(`kernels.predict`, `kernels.running_sum`, `kernels.advance`, and the optimizer's
`kernels.bound_steps`); the cosines and sines stay numpy's, whose float32 ones are not the C
library's. `predict_in_numpy`, `integrate_in_numpy` and `limit` are the references
tests/nav/nav2/test_kernels.py holds them equal to.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from pytest_lasertest.nav.nav2 import kernels

F32 = npt.NDArray[np.float32]
Changes = tuple[np.float32, np.float32, np.float32]  # m/s, m/s, rad/s a step
Bounds = tuple[np.float32, np.float32, np.float32, np.float32]


def changes(model_dt: float, ax_max: float, ax_min: float, az_max: float) -> Changes:
    """The most a step of model_dt (s) may change the speed up (ax_max m/s^2) and down (ax_min,
    negative) and the turn rate either way (az_max rad/s^2), in float32 as Nav2 keeps them."""
    return (
        np.float32(model_dt * ax_max),
        np.float32(model_dt * ax_min),
        np.float32(model_dt * az_max),
    )


def limit(last_vx: np.float32, last_wz: np.float32, change: Changes) -> Bounds:
    """The bounds [low_vx, high_vx, low_wz, high_wz] on the speeds of the step after speeds
    `last_vx` (m/s), `last_wz` (rad/s): ax_min brakes a robot moving forward, and mirrored one
    that is not (DiffDrive's predict and applyControlSequenceConstraints alike). The reference
    `kernels.bound_steps` is tested against, step by step."""
    up, down, turn = change
    forward = last_vx > 0
    low_vx = last_vx + (down if forward else -up)
    high_vx = last_vx + (up if forward else -down)
    return low_vx, high_vx, last_wz - turn, last_wz + turn


def predict(
    noised_vx: F32, noised_wz: F32, speed: tuple[float, float], change: Changes
) -> tuple[F32, F32]:
    """DiffDrive's predict over time-major (T, B) controls: the speed at step 0 is the
    robot's (m/s, rad/s), and at each later step the noised control of the step before,
    bounded by the acceleration limits (which bound the noised control itself too, as Nav2's
    does in place)."""
    return kernels.predict(
        noised_vx, noised_wz, np.float32(speed[0]), np.float32(speed[1]), *change
    )


def integrate(
    vx: F32, wz: F32, pose: tuple[float, float, float], dt: float
) -> tuple[F32, F32, F32]:
    """integrateStateVelocities over time-major (T, B) speeds from `pose` (m, m, rad), a step
    of dt (s) each: x, y and yaw (T, B). Yaw is the running sum of wz dt; each step moves along
    the yaw of the step before (the start's for the first)."""
    x0, y0, yaw0 = (np.float32(value) for value in pose)
    step = np.float32(dt)
    yaw = kernels.running_sum(wz, step, yaw0)
    heading = np.empty_like(yaw)
    heading[0], heading[1:] = yaw0, yaw[:-1]
    x, y = kernels.advance(vx, np.cos(heading), np.sin(heading), step, x0, y0)
    return x, y, yaw


def predict_in_numpy(
    noised_vx: F32, noised_wz: F32, speed: tuple[float, float], change: Changes
) -> tuple[F32, F32]:
    """`predict` in numpy, the reference its kernel is tested against."""
    vx = np.empty_like(noised_vx)
    wz = np.empty_like(noised_wz)
    vx[0], wz[0] = speed
    for step in range(1, len(noised_vx)):
        low_vx, high_vx, low_wz, high_wz = _limits(vx[step - 1], wz[step - 1], change)
        np.clip(noised_vx[step - 1], low_vx, high_vx, out=noised_vx[step - 1])
        np.clip(noised_wz[step - 1], low_wz, high_wz, out=noised_wz[step - 1])
        vx[step], wz[step] = noised_vx[step - 1], noised_wz[step - 1]
    return vx, wz


def _limits(last_vx: F32, last_wz: F32, change: Changes) -> tuple[F32, F32, F32, F32]:
    """`limit` of a step's speeds (B,)."""
    up, down, turn = change
    if down == -up:  # symmetric limits, as Nav2's: the same bounds either way
        low_vx, high_vx = last_vx - up, last_vx + up
    else:
        forward = last_vx > 0
        low_vx = last_vx + np.where(forward, down, -up)
        high_vx = last_vx + np.where(forward, up, -down)
    return low_vx, high_vx, last_wz - turn, last_wz + turn


def integrate_in_numpy(
    vx: F32, wz: F32, pose: tuple[float, float, float], dt: float
) -> tuple[F32, F32, F32]:
    """`integrate` in numpy, the reference its kernels are tested against."""
    x0, y0, yaw0 = pose
    step = np.float32(dt)
    yaw = _running_sum(wz * step, np.float32(yaw0))
    heading = np.empty_like(yaw)
    heading[0], heading[1:] = np.float32(yaw0), yaw[:-1]
    moved = vx * step
    x = _running_sum(moved * np.cos(heading), np.float32(x0))
    y = _running_sum(moved * np.sin(heading), np.float32(y0))
    return x, y, yaw


def _running_sum(steps: F32, start: np.float32) -> F32:
    """`start` plus the running sum of time-major `steps` (T, B) along time, whole rows at a
    time."""
    total = np.empty_like(steps)
    np.add(steps[0], start, out=total[0])
    for row in range(1, len(steps)):
        np.add(total[row - 1], steps[row], out=total[row])
    return total
