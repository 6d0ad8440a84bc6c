"""Nav2's MPPI controller (nav2_mppi_controller), every sample at once.

Read in ros-navigation/navigation2 at jazzy f4108e5b: src/optimizer.cpp (evalControl,
optimize, generateNoisedTrajectories, integrateStateVelocities, updateControlSequence,
applyControlSequenceConstraints, shiftControlSequence), src/noise_generator.cpp,
include/nav2_mppi_controller/motion_models.hpp (DiffDrive's predict), tools/utils.hpp
(savitskyGolayFilter, findPathFurthestReachedPoint, findPathCosts, withinPositionGoalTolerance)
and the critics under src/critics; the defaults are nav2_bringup/params/nav2_params.yaml's.
Our own numpy code, in float32 as MPPI's xtensor arrays are.

One cycle: the control sequence (T,) plus Gaussian noise makes batch_size noised sequences
(B, T); the motion model bounds each step's change by the acceleration limits, from the robot's
speed on; the sequences are integrated into trajectories (yaw first, each step moving along the
heading of the step before); the critics add up a cost per trajectory; a softmax of the costs
(at `temperature`, plus the control cost gamma / std^2 sum(u (noised - u))) weights the noised
sequences into the new control sequence, which is clipped to the limits and smoothed with a
9-point Savitzky-Golay filter over the last four commands. The command is the sequence's second
element (shift_control_sequence), and the sequence shifts one step.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from pytest_lasertest.nav.move_base.cost_values import INSCRIBED, LETHAL, UNKNOWN
from pytest_lasertest.nav.nav2 import kernels
from pytest_lasertest.nav.nav2.motion_model import F32 as F32  # re-exported
from pytest_lasertest.nav.nav2.motion_model import changes, integrate, predict
from pytest_lasertest.nav.nav2.noise import NoiseDrawer

# Savitzky-Golay, quadratic, 9 points (utils.hpp savitskyGolayFilter).
SAVITZKY_GOLAY = np.array([-21, 14, 39, 54, 59, 54, 39, 14, -21], dtype=np.float32) / 231.0


@dataclass(frozen=True)
class MppiSettings:
    """The optimizer's parameters, with Nav2's names; defaults from Jazzy's nav2_params.yaml."""

    time_steps: int = 56
    model_dt: float = 0.05  # s
    batch_size: int = 2000
    iteration_count: int = 1
    vx_std: float = 0.2  # m/s
    wz_std: float = 0.4  # rad/s
    vx_max: float = 0.5  # m/s
    vx_min: float = -0.35  # m/s
    vy_max: float = 0.5  # m/s: unused by a differential drive, but ConstraintCritic reads it
    wz_max: float = 1.9  # rad/s
    ax_max: float = 3.0  # m/s^2
    ax_min: float = -3.0  # m/s^2
    az_max: float = 3.5  # rad/s^2
    temperature: float = 0.3
    gamma: float = 0.015
    retry_attempt_limit: int = 1
    # nav2_params.yaml's; the code's default is false (noise_generator.cpp:35 at jazzy f4108e5b
    # and humble 3c3db59d): one draw of noise serves every cycle until a reset (`noise.py`).
    regenerate_noises: bool = True


@dataclass(frozen=True)
class CostGrid:
    """The local costmap as the critics read it: costs indexed [y, x], where cell (0, 0)'s lower
    left corner lies, the cell size, and whether unknown cells are tracked."""

    costs: npt.NDArray[np.uint8]  # (H, W)
    origin: tuple[float, float]  # m
    resolution: float  # m per cell
    tracking_unknown: bool

    def at(self, x: F32, y: F32) -> npt.NDArray[np.float32]:
        """The costs under points (any shape) m, 255 (no information) off the grid, as the
        CostCritic's worldToMapFloat reads them, in float32."""
        cells_x, cells_y, on = self._cells(x, y)
        found: npt.NDArray[np.float32] = np.where(on, self.costs[cells_y, cells_x], UNKNOWN).astype(
            np.float32
        )
        return found

    def valid(self, points: F32) -> npt.NDArray[np.bool_]:
        """findPathCosts over points (P, 2): on the grid, neither lethal nor inscribed, and
        unknown only where unknown space is tracked."""
        cells_x, cells_y, on = self._cells(points[:, 0], points[:, 1])
        costs = np.where(on, self.costs[cells_y, cells_x], UNKNOWN)
        blocked = (costs == INSCRIBED) | (costs == LETHAL)
        blocked |= (costs == UNKNOWN) & (not self.tracking_unknown)
        valid: npt.NDArray[np.bool_] = on & ~blocked
        return valid

    def _cells(
        self, x: F32, y: F32
    ) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64], npt.NDArray[np.bool_]]:
        """worldToMapFloat: the cells (x, y) of points, (0, 0) where they lie off the grid, and
        which lie on it."""
        column = (x - np.float32(self.origin[0])) / np.float32(self.resolution)
        row = (y - np.float32(self.origin[1])) / np.float32(self.resolution)
        height, width = self.costs.shape
        on = (x >= np.float32(self.origin[0])) & (y >= np.float32(self.origin[1]))
        on &= (column < width) & (row < height)
        return np.where(on, column, 0).astype(np.int64), np.where(on, row, 0).astype(np.int64), on


@dataclass
class CriticData:
    """What the critics read and what they add to: one cycle's samples, shapes (B, T)."""

    pose: tuple[float, float, float]  # m, m, rad
    goal: tuple[float, float]  # m
    path: F32  # (P, 2) m, the plan from the robot on
    cvx: F32  # (B, T) m/s, each sample's noised controls, bounded as predict bounds them
    cwz: F32  # (B, T) rad/s
    vx: F32  # (B, T) m/s, each sample's speed at each step
    wz: F32  # (B, T) rad/s
    x: F32  # (B, T) m, each sample's trajectory
    y: F32  # (B, T) m
    yaw: F32  # (B, T) rad
    model_dt: float  # s
    costs: F32  # (B,)
    costmap: CostGrid | None = None  # the local costmap; None: no obstacle anywhere
    path_valid: npt.NDArray[np.bool_] | None = None  # (P - 1,) findPathCosts; None: all
    fail: bool = False  # a critic found no sample to take
    furthest: int | None = field(default=None)  # the path point the samples reach furthest

    def within(self, threshold: float) -> bool:
        """withinPositionGoalTolerance: whether the robot is nearer the goal than `threshold`."""
        distance = (self.goal[0] - self.pose[0]) ** 2 + (self.goal[1] - self.pose[1]) ** 2
        return bool(distance < threshold**2)

    def time_major(self) -> tuple[F32, F32]:
        """The positions x and y time-major (T, B) m, in order in memory: the samples' own
        arrays (copies only of data made another way)."""
        return np.ascontiguousarray(self.x.T), np.ascontiguousarray(self.y.T)

    def time_major_speeds(self) -> F32:
        """The speeds vx time-major (T, B) m/s, in order in memory (see `time_major`)."""
        return np.ascontiguousarray(self.vx.T)

    def path_points_valid(self) -> npt.NDArray[np.bool_]:
        """findPathCosts, once a cycle: which path points but the last the costmap leaves
        free to drive to, shape (P - 1,); all of them without a costmap."""
        if self.path_valid is None:
            points = self.path[:-1]
            self.path_valid = (
                np.ones(len(points), dtype=bool)
                if self.costmap is None
                else self.costmap.valid(points)
            )
        return self.path_valid

    def ahead_of_furthest(self, offset: int) -> int:
        """The path point `offset` past the furthest the samples reach, the last at most."""
        return min(self.furthest_reached() + offset, len(self.path) - 1)

    def furthest_reached(self) -> int:
        """findPathFurthestReachedPoint: trajectory by trajectory, the path point nearest its
        end among those at or past the furthest found so far; remembered for the cycle."""
        if self.furthest is None:
            self.furthest = _furthest_reached(self.x[:, -1], self.y[:, -1], self.path)
        return self.furthest


Critic = Callable[[CriticData], None]


@dataclass(frozen=True)
class Cycle:
    """What one controller cycle starts from."""

    pose: tuple[float, float, float]  # m, m, rad
    speed: tuple[float, float]  # m/s, rad/s
    path: F32  # (P, 2) m
    goal: tuple[float, float]  # m
    costmap: CostGrid | None


def _furthest_reached(end_x: F32, end_y: F32, path: F32) -> int:
    """findPathFurthestReachedPoint over ends (B,) and a path (P, 2), compiled
    (`kernels.furthest_reached`)."""
    return kernels.furthest_reached(
        np.ascontiguousarray(end_x), np.ascontiguousarray(end_y), np.ascontiguousarray(path)
    )


# s: how near the controller's period must be to model_dt to count as equal (setOffset's eps).
SAME_PERIOD = 1e-6


class Optimizer:
    """MPPI's optimizer for a differential drive: one command per call of `command`."""

    def __init__(
        self,
        settings: MppiSettings,
        critics: Sequence[Critic],
        rng: np.random.Generator,
        shift: bool = True,
    ) -> None:
        """`shift`: whether the controller's period equals model_dt, so that each command is
        the sequence's second step and the sequence moves on a step after it (else the first,
        and it stays: Optimizer::setOffset, optimizer.cpp:115-136 at jazzy f4108e5b)."""
        self.settings, self.critics = settings, tuple(critics)
        self._offset = 1 if shift else 0
        self.vx = np.zeros(settings.time_steps, dtype=np.float32)  # (T,) the control sequence
        self.wz = np.zeros(settings.time_steps, dtype=np.float32)
        self.history = np.zeros((4, 2), dtype=np.float32)  # the last four commands [vx, wz]
        shape = (2, settings.time_steps, settings.batch_size)
        self._noise = NoiseDrawer(rng, shape, settings.regenerate_noises)
        s = settings
        self._changes = changes(s.model_dt, s.ax_max, s.ax_min, s.az_max)

    def command(
        self,
        pose: tuple[float, float, float],
        speed: tuple[float, float],
        path: F32,
        goal: tuple[float, float],
        costmap: CostGrid | None = None,
    ) -> tuple[float, float] | None:
        """The twist [vx, wz] (m/s, rad/s) to drive now, or None when every sample failed
        more than retry_attempt_limit times in a row (the controller's NoValidControl); each
        failure starts the sequence afresh, as Optimizer::fallback resets it."""
        cycle, failures = Cycle(pose, speed, path, goal, costmap), 0
        while not self._optimize(cycle):
            self.reset()
            failures += 1
            if failures > self.settings.retry_attempt_limit:
                return None
        self._smooth()
        command = float(self.vx[self._offset]), float(self.wz[self._offset])
        if self._offset:
            self._shift()
        return command

    def _optimize(self, cycle: Cycle) -> bool:
        """iteration_count rounds of sampling, scoring and updating; False if a critic failed."""
        for _ in range(self.settings.iteration_count):
            data = self._samples(cycle)
            for critic in self.critics:
                critic(data)
            if data.fail:
                return False
            self._update(data)
        return True

    def reset(self) -> None:
        """Optimizer::reset: the sequence and the command history zeroed, the noise drawn
        afresh. The controller server resets its controllers whenever a FollowPath action ends
        (publishZeroVelocity, controller_server.cpp:779-798 at jazzy f4108e5b); a cycle in
        which every sample failed resets it too (fallback)."""
        self.vx[:], self.wz[:] = 0.0, 0.0
        self.history[:] = 0.0
        self._noise.reset()

    def _samples(self, cycle: Cycle) -> CriticData:
        """Noised sequences, bounded from the robot's speed on, and their trajectories."""
        s = self.settings
        # Time-major (T, B) inside, so that each step's samples lie together; the critics
        # read (B, T) views of them.
        noise = self._noise.next()  # read-only: without regenerate_noises, the next cycle's too
        noised_vx = noise[0] * np.float32(s.vx_std)
        noised_vx += self.vx[:, np.newaxis]
        noised_wz = noise[1] * np.float32(s.wz_std)
        noised_wz += self.wz[:, np.newaxis]
        vx, wz = predict(noised_vx, noised_wz, cycle.speed, self._changes)
        x, y, yaw = integrate(vx, wz, cycle.pose, s.model_dt)
        costs = np.zeros(s.batch_size, dtype=np.float32)
        return CriticData(
            cycle.pose,
            cycle.goal,
            cycle.path,
            noised_vx.T,
            noised_wz.T,
            vx.T,
            wz.T,
            x.T,
            y.T,
            yaw.T,
            s.model_dt,
            costs,
            cycle.costmap,
        )

    def _update(self, data: CriticData) -> None:
        """The softmax-weighted mean of the noised sequences becomes the sequence."""
        s, costs = self.settings, data.costs
        # Time-major (T, B), as the samples lie in memory; compiled, numpy's sums to the bit.
        noised_vx, noised_wz = (np.ascontiguousarray(cv.T) for cv in (data.cvx, data.cwz))
        costs += s.gamma / s.vx_std**2 * kernels.control_costs(self.vx, noised_vx)
        costs += s.gamma / s.wz_std**2 * kernels.control_costs(self.wz, noised_wz)
        weights = np.exp(-1.0 / s.temperature * (costs - costs.min()))
        weights /= weights.sum()
        self.vx = kernels.weighted_means(noised_vx, weights)
        self.wz = kernels.weighted_means(noised_wz, weights)
        self._constrain()

    def _constrain(self) -> None:
        """applyControlSequenceConstraints: the limits, then each step's change bounded."""
        s = self.settings
        np.clip(self.vx, s.vx_min, s.vx_max, out=self.vx)
        np.clip(self.wz, -s.wz_max, s.wz_max, out=self.wz)
        kernels.bound_steps(self.vx, self.wz, *self._changes)

    def _smooth(self) -> None:
        """savitskyGolayFilter over the sequence, the last four commands before it."""
        if self.settings.time_steps - 1 < 20:
            return
        for axis, sequence in enumerate((self.vx, self.wz)):
            padded = np.concatenate([self.history[:, axis], sequence, np.repeat(sequence[-1:], 4)])
            # Each of the first T - 1 points from its 9-point window; the last is kept.
            windows = np.lib.stride_tricks.sliding_window_view(padded, 9)[: len(sequence) - 1]
            sequence[:-1] = windows @ SAVITZKY_GOLAY
        latest = [self.vx[self._offset], self.wz[self._offset]]
        self.history = np.vstack([self.history[1:], [latest]])

    def _shift(self) -> None:
        """shiftControlSequence: one step on, the last step repeated."""
        for sequence in (self.vx, self.wz):
            sequence[:-1] = sequence[1:].copy()
