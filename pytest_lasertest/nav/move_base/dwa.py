"""The local planner: dwa_local_planner's dynamic window, rolled out for all samples at once.

Each control cycle samples forward speeds and turn rates the robot can reach within one cycle
(`vx_samples` x `vth_samples`, with 0 added where a range crosses it, as its VelocityIterator
does), rolls each out for `sim_time` at constant velocity in steps of `sim_granularity` m or
`angular_sim_granularity` rad, and scores it with DWAPlanner's critics:

- obstacle (`occdist_scale`): the highest cost under the footprint along the way, the footprint
  grown with speed (`scaling_speed`, `max_scaling_factor`); a lethal cell under it rejects it;
- path and alignment (`path_distance_bias` per cell): how far its end, and the point
  `forward_point_distance` ahead of its end, lie from the global plan (alignment only while the
  local goal is further than that);
- goal and goal-front (`goal_distance_bias` per cell): how far its end lies from the local goal,
  the last point of the plan within the local window, and its forward point from a point
  `forward_point_distance` beyond the local goal;
- an end within the inscribed radius of a lethal cell rejects it; a forward point there costs
  what base_local_planner's MapGrid charges an obstacle cell, the local window's cell count.

The least score wins; the first sampled wins a tie. No valid trajectory is a failure, for
move_base to handle.

Where this differs from ROS, on purpose: the distances to the plan and the goal are straight
lines, not the cell-by-cell wavefront of base_local_planner's MapGrid (which goes around
obstacles); the footprint is checked against lethal cell centres, inside and on its outline,
at every step of the rollout, not only along its outline's cells.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.nav.move_base import kernels
from pytest_lasertest.nav.move_base.clearance import Edges, Poses, cell_within, least_gaps
from pytest_lasertest.nav.move_base.costmap import InflationCost

# What SimpleTrajectoryGenerator allows a velocity below its limits.
EPSILON = 1e-4
SQUARE_CELLS = 3


@dataclass(frozen=True)
class DwaSettings:
    """DWAPlannerROS's parameters, with its names; the defaults are its own."""

    max_vel_x: float = 0.55  # m/s
    min_vel_x: float = 0.0  # m/s; 0 never reverses
    max_trans_vel: float = 0.55  # m/s
    min_trans_vel: float = 0.1  # m/s
    max_rot_vel: float = 1.0  # rad/s
    min_rot_vel: float = 0.4  # rad/s
    acc_lim_x: float = 2.5  # m/s^2
    acc_lim_theta: float = 3.2  # rad/s^2
    sim_time: float = 1.7  # s
    sim_granularity: float = 0.025  # m
    angular_sim_granularity: float = 0.1  # rad
    vx_samples: int = 3
    vth_samples: int = 20
    path_distance_bias: float = 32.0  # per cell
    goal_distance_bias: float = 24.0  # per cell
    occdist_scale: float = 0.01  # per unit of cost
    forward_point_distance: float = 0.325  # m
    scaling_speed: float = 0.25  # m/s
    max_scaling_factor: float = 0.2
    xy_goal_tolerance: float = 0.1  # m
    oscillation_reset_dist: float = 0.05  # m
    oscillation_reset_angle: float = 0.2  # rad


@dataclass(frozen=True)
class Surroundings:
    """What the local planner scores against, in the odom frame."""

    plan: FloatArray  # (K, 2) m, the global plan from near the robot to the local goal
    goal: tuple[float, float]  # m, the global goal
    lethal: FloatArray  # (N, 2) m, the centres of the lethal cells near the robot


@dataclass(frozen=True)
class Rollouts:
    """The sampled velocities and where each takes the robot: S samples of at most T steps."""

    linear: FloatArray  # (S,) m/s
    angular: FloatArray  # (S,) rad/s
    # The pose after each step, the last valid step repeated: (S, T) each, m, m, rad. Apart,
    # not stacked: the obstacle check reads each whole, and stacking copies 8,000 poses.
    x: FloatArray
    y: FloatArray
    yaw: FloatArray

    @property
    def poses(self) -> FloatArray:
        """The pose [x, y, yaw] after each step, shape (S, T, 3)."""
        return np.stack([self.x, self.y, self.yaw], axis=2)

    @property
    def ends(self) -> FloatArray:
        """The pose [x, y, yaw] of each one's last step, shape (S, 3)."""
        return np.column_stack([self.x[:, -1], self.y[:, -1], self.yaw[:, -1]])


class LocalPlanner:
    """DWA for one robot: a velocity command from its pose, speed and surroundings."""

    def __init__(
        self,
        settings: DwaSettings,
        footprint: FloatArray,
        cost: InflationCost,
        period: float,
        resolution: float,
        window: int,
    ) -> None:
        self.settings = settings
        self.period = period  # s, one control cycle: the dynamic window's reach
        self.cost = cost
        # m: a lethal cell is a square, and costmap_2d checks the cells the footprint's outline
        # passes through, so the footprint meets one within half a cell of its centre.
        self.half_cell = resolution / 2.0
        # m: MapGrid's distance for a cell in an obstacle, the local window's cell count in
        # cells (`window` along each side).
        self.obstacle_distance = resolution * window**2
        self.edges = Edges.of(footprint)
        # m: lethal cells are grouped in squares of three cells a side to skip those that cannot
        # be nearest the footprint (clearance.py).
        self.square = SQUARE_CELLS * resolution
        self.oscillation = Oscillation(
            settings.oscillation_reset_dist, settings.oscillation_reset_angle
        )
        # m, the circumscribed radius: the farthest the footprint reaches from the base
        self.reach = float(np.hypot(footprint[:, 0], footprint[:, 1]).max())

    def command(
        self,
        pose: tuple[float, float, float],
        velocity: tuple[float, float],
        around: Surroundings,
    ) -> tuple[float, float] | None:
        """The best velocity [m/s, rad/s] to drive for the next cycle, or None if every
        sampled trajectory is rejected."""
        rollouts = self.rollouts(pose, velocity)
        if not len(rollouts.linear):
            return None
        scores = self.scores(rollouts, pose, around)
        allowed = self.oscillation.allowed(rollouts.linear, rollouts.angular)
        scores = np.where(allowed, scores, np.inf)
        if not np.isfinite(scores).any():
            return None
        best = int(np.argmin(scores))  # the first of equals, as DWA keeps the first
        chosen = float(rollouts.linear[best]), float(rollouts.angular[best])
        self.oscillation.record(pose, chosen, self.settings.min_trans_vel)
        return chosen

    def rollouts(self, pose: tuple[float, float, float], velocity: tuple[float, float]) -> Rollouts:
        """Every sampled velocity rolled out from `pose` for `sim_time`."""
        linear, angular = self._samples(velocity)
        steps, dt = time_steps(self.settings, linear, angular)
        start = (float(pose[0]), float(pose[1]), float(pose[2]))
        x, y, yaw = kernels.dwa_rollouts(start, linear, angular, steps, dt)  # compiled
        return Rollouts(linear, angular, x, y, yaw)

    def scores(
        self, rollouts: Rollouts, pose: tuple[float, float, float], around: Surroundings
    ) -> FloatArray:
        """Each rollout's total cost, shape (S,); inf where rejected."""
        settings, lethal = self.settings, around.lethal
        last, reach = rollouts.ends, settings.forward_point_distance
        ends, yaw = last[:, :2], last[:, 2]
        ahead = ends + reach * np.column_stack([np.cos(yaw), np.sin(yaw)])
        # The local goal is the plan's last point in the window; the nose is drawn to a point
        # forward_point_distance beyond it, on the bearing from the robot.
        local_goal = around.plan[-1] if len(around.plan) else np.array(around.goal)
        bearing = math.atan2(local_goal[1] - pose[1], local_goal[0] - pose[0])
        front_goal = local_goal + reach * np.array([math.cos(bearing), math.sin(bearing)])
        # DWA scales a distance in cells by resolution x bias: the bias is per metre.
        path_bias, goal_bias = settings.path_distance_bias, settings.goal_distance_bias
        score = self._obstacle_scores(rollouts, around)
        score = score + path_bias * _nearest(ends, around.plan)
        score += goal_bias * _distance(ends, local_goal)
        # A nose in an obstacle does not reject a sample: MapGrid charges its obstacle cost.
        nose_blocked = self._too_near(ahead, lethal)
        nose_to_goal = _distance(ahead, front_goal)
        score += goal_bias * np.where(nose_blocked, self.obstacle_distance, nose_to_goal)
        if math.dist(pose[:2], local_goal) > reach:  # nearer, DWA stops aligning the nose
            nose_to_plan = _nearest(ahead, around.plan)
            score += path_bias * np.where(nose_blocked, self.obstacle_distance, nose_to_plan)
        return np.where(self._too_near(ends, lethal), np.inf, score)

    def _samples(self, velocity: tuple[float, float]) -> tuple[FloatArray, FloatArray]:
        """The sampled velocities within one cycle's reach, v outer and w inner, as DWA
        generates them, less those SimpleTrajectoryGenerator refuses."""
        settings, period = self.settings, self.period
        linear = velocity_samples(
            max(settings.min_vel_x, velocity[0] - settings.acc_lim_x * period),
            min(settings.max_vel_x, velocity[0] + settings.acc_lim_x * period),
            settings.vx_samples,
        )
        angular = velocity_samples(
            max(-settings.max_rot_vel, velocity[1] - settings.acc_lim_theta * period),
            min(settings.max_rot_vel, velocity[1] + settings.acc_lim_theta * period),
            settings.vth_samples,
        )
        v, w = (grid.ravel() for grid in np.meshgrid(linear, angular, indexing="ij"))
        speed = np.abs(v)
        too_slow = (speed + EPSILON < settings.min_trans_vel) & (
            np.abs(w) + EPSILON < settings.min_rot_vel
        )
        # Standing still rolls out no step: the trajectory generator makes none of it.
        standing = (v == 0.0) & (w == 0.0)
        kept = ~too_slow & ~standing & (speed - EPSILON <= settings.max_trans_vel)
        return v[kept], w[kept]

    def _obstacle_scores(self, rollouts: Rollouts, around: Surroundings) -> FloatArray:
        """occdist_scale times the highest cost under each rollout's footprint, shape (S,);
        inf where a lethal cell lies under it."""
        settings, count = self.settings, len(rollouts.linear)
        speed, slowest = np.abs(rollouts.linear), settings.scaling_speed
        # getScalingFactor grows the footprint only above scaling_speed: when that is
        # max_trans_vel or more, no sample is fast enough.
        span = max(settings.max_trans_vel - slowest, EPSILON)
        grow = np.where(speed > slowest, (speed - slowest) / span, 0.0)
        scale = 1.0 + settings.max_scaling_factor * grow  # (S,)
        x, y = rollouts.x.ravel(), rollouts.y.ravel()
        # A lethal cell raises the cost under the footprint out to the inflation radius beyond
        # its outline (footprintCost reads the inflated costmap).
        reach = self.reach * float(scale.max()) + self.cost.inflation_radius
        near = _within(around.lethal, x, y, reach)
        if not len(near):
            return np.zeros(count)
        poses = Poses(x, y, rollouts.yaw.ravel(), np.repeat(scale, rollouts.x.shape[1]), count)
        least = least_gaps(self.edges, poses, near, self.square) - self.half_cell  # m
        return np.where(least <= 0.0, np.inf, settings.occdist_scale * self.cost(least))

    def clear(self, poses: FloatArray, lethal: FloatArray) -> bool:
        """Whether the footprint at every pose (P, 3) is clear of the lethal cell centres
        (N, 2)."""
        if not len(lethal):
            return True
        x, y, yaw = poses.T
        one = Poses(x, y, yaw, np.ones(len(poses)), groups=1)
        return bool(least_gaps(self.edges, one, lethal, self.square)[0] > self.half_cell)

    def _too_near(self, points: FloatArray, lethal: FloatArray) -> np.ndarray:
        """Which points (P, 2) lie in an inscribed cell: within the inscribed radius of a
        lethal cell, shape (P,)."""
        return cell_within(points, lethal, self.cost.inscribed)


@dataclass
class Way:
    """One way of moving, driving or turning: the sign last chosen, and the only sign allowed
    (0 for either)."""

    last: int = 0
    only: int = 0

    def choose(self, sign: int) -> bool:
        """Record `sign` as chosen; True, and only it allowed, if it reverses the last."""
        if sign == 0:
            return False
        reverses = self.last == -sign
        if reverses:
            self.only = sign
        self.last = sign
        return reverses


@dataclass
class Oscillation:
    """base_local_planner's OscillationCostFunction: once the chosen velocity reverses the
    robot's way of driving, or its way of turning while it stands, only the new way is allowed
    until the robot has moved `reset_distance` m or turned `reset_angle` rad."""

    reset_distance: float  # m
    reset_angle: float  # rad
    driving: Way = field(default_factory=Way)
    turning: Way = field(default_factory=Way)  # on the spot
    since: tuple[float, float, float] = (0.0, 0.0, 0.0)  # where the last restriction began

    def allowed(self, linear: FloatArray, angular: FloatArray) -> npt.NDArray[np.bool_]:
        """Which samples (S,) the restrictions allow."""
        return (self.driving.only * linear >= 0.0) & (self.turning.only * angular >= 0.0)

    def record(
        self, pose: tuple[float, float, float], chosen: tuple[float, float], min_trans_vel: float
    ) -> None:
        """Note the velocity chosen at `pose`; lift the restrictions once far enough."""
        linear, angular = chosen
        restricted = self.driving.choose(int(np.sign(linear)))
        if abs(linear) <= min_trans_vel:
            restricted |= self.turning.choose(int(np.sign(angular)))
        if restricted:
            self.since = pose
        moved = math.dist(pose[:2], self.since[:2]) > self.reset_distance
        if moved or abs(pose[2] - self.since[2]) > self.reset_angle:
            self.reset()

    def reset(self) -> None:
        """Forget the ways chosen and lift every restriction, as DWA does for a new plan."""
        self.driving, self.turning = Way(), Way()


def velocity_samples(low: float, high: float, count: int) -> FloatArray:
    """base_local_planner's VelocityIterator: `count` evenly spaced values from `low` to
    `high`, and 0 between a negative and a positive one."""
    if low == high:
        return np.array([low])
    values = np.linspace(low, high, max(count, 2))
    crossing = (values[:-1] < 0.0) & (values[1:] > 0.0)
    if crossing.any():
        values = np.insert(values, int(np.argmax(crossing)) + 1, 0.0)
    samples: FloatArray = values
    return samples


def _distance(points: FloatArray, target: FloatArray) -> FloatArray:
    """The distance from each point (P, 2) to one target (2,), m."""
    gaps: FloatArray = np.hypot(points[:, 0] - target[0], points[:, 1] - target[1])
    return gaps


def _nearest(points: FloatArray, others: FloatArray) -> FloatArray:
    """The distance from each point (P, 2) to the nearest of `others` (Q, 2), m; inf if none."""
    if not len(others):
        return np.full(len(points), np.inf)
    others = _candidates(points, others)
    gaps = np.hypot(points[:, 0:1] - others[:, 0], points[:, 1:2] - others[:, 1])
    nearest: FloatArray = gaps.min(axis=1)
    return nearest


def _candidates(points: FloatArray, others: FloatArray) -> FloatArray:
    """The `others` (Q, 2) that may be nearest to one of the points (P, 2): no point lies
    further from its nearest than the least, over the others, of the distance to the far
    corner of the points' bounding box, and an other further than that from the box is
    nobody's nearest. The plan runs metres past the rollouts' ends; this leaves the metre
    around them."""
    low, high = points.min(axis=0), points.max(axis=0)
    far = np.maximum(np.abs(others - low), np.abs(others - high))  # (Q, 2) m
    bound = float(np.hypot(far[:, 0], far[:, 1]).min())
    out = np.maximum(np.maximum(low - others, others - high), 0.0)
    # The margin covers hypot's rounding: an other kept in doubt changes no minimum.
    kept: FloatArray = others[np.hypot(out[:, 0], out[:, 1]) <= bound * (1.0 + 1e-9) + 1e-12]
    return kept


def _within(points: FloatArray, x: FloatArray, y: FloatArray, reach: float) -> FloatArray:
    """The points (N, 2) within `reach` m of the bounding box of the positions (P,) x, (P,) y."""
    if not len(points):
        return points
    inside = (points[:, 0] >= x.min() - reach) & (points[:, 0] <= x.max() + reach)
    inside &= (points[:, 1] >= y.min() - reach) & (points[:, 1] <= y.max() + reach)
    kept: FloatArray = points[inside]
    return kept


def time_steps(
    settings: DwaSettings, linear: FloatArray, angular: FloatArray
) -> tuple[npt.NDArray[np.int64], FloatArray]:
    """How many steps each sample (S,) rolls out in, of sim_granularity m or
    angular_sim_granularity rad at most, and each one's step dt (S,) s."""
    steps = np.ceil(
        np.maximum(
            settings.sim_time * np.abs(linear) / settings.sim_granularity,
            settings.sim_time * np.abs(angular) / settings.angular_sim_granularity,
        )
    ).astype(np.int64)
    dt: FloatArray = settings.sim_time / np.maximum(steps, 1)
    return steps, dt


def roll_out_in_numpy(
    pose: tuple[float, float, float],
    linear: FloatArray,
    angular: FloatArray,
    steps: npt.NDArray[np.int64],
    dt: FloatArray,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """`kernels.dwa_rollouts` in numpy, the reference it is tested against: x, y and yaw (S, T)
    of S samples rolled out from `pose` in `steps` (S,) steps of dt (S,) s."""
    # Step j of each is the pose after j steps; past its own last step it stays there.
    j = np.arange(int(steps.max(initial=1)))
    turned = np.minimum(j, steps[:, np.newaxis] - 1)
    yaw = pose[2] + (angular * dt)[:, np.newaxis] * turned  # (S, T) rad
    heading = np.concatenate([np.full((len(linear), 1), pose[2]), yaw[:, :-1]], axis=1)
    moving = (j > 0) & (j < steps[:, np.newaxis])
    advance = (linear * dt)[:, np.newaxis] * moving  # (S, T) m
    # The heading's cosine and sine only where the rollout moves (about half its steps):
    # elsewhere the advance is zero, and so is what it adds.
    cos = np.cos(heading, out=np.zeros_like(heading), where=moving)
    sin = np.sin(heading, out=np.zeros_like(heading), where=moving)
    x = pose[0] + np.cumsum(advance * cos, axis=1)
    y = pose[1] + np.cumsum(advance * sin, axis=1)
    return x, y, yaw
