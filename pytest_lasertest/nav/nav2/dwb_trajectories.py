"""DWB's trajectory generation (dwb_plugins), every candidate at once: the XYThetaIterator's
velocities and StandardTrajectoryGenerator's rollouts of them.

Read in ros-navigation/navigation2 at humble@3c3db59d6969d8ecee8e68468693d006397f4a0c, under
nav2_dwb_controller/dwb_plugins/: src/standard_traj_generator.cpp, src/xy_theta_iterator.cpp,
src/kinematic_parameters.cpp and include/dwb_plugins/one_d_velocity_iterator.hpp. Our own code,
in float64 as DWB's doubles.

- Velocities: vx from min_vel_x to max_vel_x (outer), theta from -max_vel_theta to max_vel_theta
  (inner), vx_samples and vtheta_samples evenly spaced, 0 put in where a range crosses it, (0, 0)
  and speeds above max_speed_xy left out. The window is the robot's speed plus or minus
  acc_lim x sim_time, not x 1 / controller_frequency: Humble's StandardTrajectoryGenerator passes
  sim_time to the iterator, so at these limits every velocity is reachable. A differential drive
  only: the y iterator yields 0 alone (min_vel_y = max_vel_y = 0), so vy_samples plays no part.
- Trajectories: ceil(max(|vx| sim_time / linear_granularity, |theta| sim_time /
  angular_granularity)) steps of equal time; each step's speed moves from the last toward the
  command by at most acc_lim (decel_lim) x dt; the pose moves along the heading of the step
  before; with include_last_point (its default) the last pose once more, as generateTrajectory
  appends it (standard_traj_generator.cpp:181-182). The rollouts are compiled
  (`kernels.roll_out`); `roll_out_in_numpy` is the reference a test holds them equal to.
"""

from __future__ import annotations

import math

import numpy as np

from pytest_lasertest.nav.nav2 import kernels
from pytest_lasertest.nav.nav2.dwb_critics import F64, Bools, Pose, Rollouts
from pytest_lasertest.nav.nav2.dwb_settings import DwbSettings

# one_d_velocity_iterator.hpp's and xy_theta_iterator.cpp's tolerance.
EPSILON = 1e-5


def project_velocity(start: float, acc: float, decel: float, dt: float, target: float) -> float:
    """projectVelocity: from `start` toward `target` by at most acc dt up or decel dt down."""
    if start < target:
        return min(target, start + acc * dt)
    return max(target, start + decel * dt)


def velocity_samples(
    current: float, low: float, high: float, acc: float, decel: float, dt: float, count: int
) -> list[float]:
    """OneDVelocityIterator's values in order: from the least to the greatest velocity reachable
    within dt, in count - 1 equal increments (added one at a time, as Nav2 adds them), and 0
    once, where the values pass from negative to positive."""
    current = min(max(current, low), high)
    top = project_velocity(current, acc, decel, dt, high)
    value = project_velocity(current, acc, decel, dt, low)
    if abs(value - top) < EPSILON:
        return [value]
    increment = (top - value) / max(1, max(2, count) - 1)
    values, zero_due = [], True
    while value <= top + EPSILON:
        values.append(value)
        if zero_due and value < 0.0 < value + increment <= top + EPSILON:
            values.append(0.0)
            zero_due = False
        value += increment
    return values


def sample_twists(s: DwbSettings, speed: tuple[float, float]) -> tuple[F64, F64]:
    """XYThetaIterator's valid velocities (vx, theta), (K,) each, vx outer and theta inner."""
    vx = velocity_samples(
        speed[0], s.min_vel_x, s.max_vel_x, s.acc_lim_x, s.decel_lim_x, s.sim_time, s.vx_samples
    )
    wz = velocity_samples(
        speed[1],
        -s.max_vel_theta,
        s.max_vel_theta,
        s.acc_lim_theta,
        s.decel_lim_theta,
        s.sim_time,
        s.vtheta_samples,
    )
    x, theta = (grid.ravel() for grid in np.meshgrid(vx, wz, indexing="ij"))
    valid = _valid_speeds(s, x * x, theta)  # vy is 0: vx^2 is the speed squared
    return x[valid], theta[valid]


def _valid_speeds(s: DwbSettings, speed_sq: F64, theta: F64) -> Bools:
    """isValidSpeed: not above max_speed_xy, not below both minimum speeds, not standing."""
    valid = ~((s.max_speed_xy >= 0.0) & (speed_sq > s.max_speed_xy**2 + EPSILON))
    too_slow = (speed_sq + EPSILON < s.min_speed_xy**2) & (
        np.abs(theta) + EPSILON < s.min_speed_theta
    )
    valid &= ~(too_slow & (s.min_speed_xy >= 0.0) & (s.min_speed_theta >= 0.0))
    valid &= ~((speed_sq == 0.0) & (theta == 0.0))
    return valid


def rollout_poses(s: DwbSettings) -> int:
    """The most poses a cycle rolls out: every sampled twist, the longest steps of any."""
    longest = max(
        s.max_vel_x * s.sim_time / s.linear_granularity,
        s.max_vel_theta * s.sim_time / s.angular_granularity,
        abs(s.min_vel_x) * s.sim_time / s.linear_granularity,
    )
    return (s.vx_samples + 1) * (s.vtheta_samples + 1) * (math.ceil(longest) + 2)


def roll_out(s: DwbSettings, pose: Pose, speed: tuple[float, float], vx: F64, wz: F64) -> Rollouts:
    """generateTrajectory for every command (K,), N = 1 + the most steps poses each, one more
    with include_last_point (the last repeated), compiled (kernels.roll_out)."""
    limits = (s.sim_time, s.acc_lim_x, s.decel_lim_x, s.acc_lim_theta, s.decel_lim_theta)
    steps = _time_steps(s, vx, wz)
    start = (float(pose[0]), float(pose[1]), float(pose[2]))
    moving = (float(speed[0]), float(speed[1]))
    x, y, yaw = kernels.roll_out(start, moving, vx, wz, steps, limits, s.include_last_point)
    return Rollouts(vx, wz, x, y, yaw)


def _time_steps(s: DwbSettings, vx: F64, wz: F64) -> F64:
    """getTimeSteps: how many steps each command's trajectory takes, (K,)."""
    steps = np.ceil(
        np.maximum(
            np.abs(vx) * s.sim_time / s.linear_granularity,
            np.abs(wz) * s.sim_time / s.angular_granularity,
        )
    )
    found: F64 = np.maximum(steps, 1.0)  # getTimeSteps makes one step of none
    return found


def roll_out_in_numpy(
    s: DwbSettings, pose: Pose, speed: tuple[float, float], vx: F64, wz: F64
) -> Rollouts:
    """roll_out in numpy, the reference its kernel is tested against: time-major inside,
    (S, K), where a running sum adds whole rows; the critics read (K, N) views."""
    steps = _time_steps(s, vx, wz)
    dt = s.sim_time / steps  # (K,) s
    moving = np.arange(1.0, steps.max(initial=1.0) + 1.0)[:, np.newaxis] <= steps  # (S, K)
    linear = _ramp(speed[0], vx, s.acc_lim_x, s.decel_lim_x, dt, moving.shape)
    angular = _ramp(speed[1], wz, s.acc_lim_theta, s.decel_lim_theta, dt, moving.shape)
    yaw = _walk(pose[2], np.where(moving, angular * dt, 0.0))  # (N, K)
    # Each step moves along the heading of the pose before it; the cosine and sine only where
    # the trajectory still moves (about half the steps): past its end the step adds nothing.
    cos = np.cos(yaw[:-1], out=np.zeros(moving.shape), where=moving)
    sin = np.sin(yaw[:-1], out=np.zeros(moving.shape), where=moving)
    x = _walk(pose[0], linear * cos * dt)
    y = _walk(pose[1], linear * sin * dt)
    if s.include_last_point:
        x, y, yaw = (np.vstack((walked, walked[-1:])) for walked in (x, y, yaw))
    return Rollouts(vx, wz, x.T, y.T, yaw.T)


def _ramp(
    start: float, target: F64, acc: float, decel: float, dt: F64, shape: tuple[int, int]
) -> F64:
    """computeNewVelocity step after step, (S, K): the speed after each step, from `start`
    toward each target by acc dt (or decel dt) a step, added one step at a time as Nav2 adds
    them, the target capping it."""
    rising = start < target  # (K,)
    change = np.broadcast_to(np.where(rising, acc * dt, decel * dt), shape)
    speeds = _walk(start, change)[1:]
    capped: F64 = np.where(rising, np.minimum(speeds, target), np.maximum(speeds, target))
    return capped


def _walk(start: float, changes: F64) -> F64:
    """`start` and then its running sum with `changes` (S, K), row after row: (S + 1, K). Whole
    rows at a time are faster than numpy's cumsum along either axis."""
    walked = np.empty((len(changes) + 1, changes.shape[1]))
    walked[0] = start
    for row, change in enumerate(changes):
        np.add(walked[row], change, out=walked[row + 1])
    return walked
