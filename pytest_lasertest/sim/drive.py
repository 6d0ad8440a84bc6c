"""The drive: a commanded twist, limited as the robot's velocity controller limits it, turned
into wheel speeds that reach it on PyBullet's contact (or, for a body without wheels, driven as
it is).

The Husky steers by driving its left and right wheels at different speeds and letting the tyres
slide sideways. Wheel speeds from the URDF's geometry miss the commanded twist (8 % too fast
straight ahead; turns slip), so the drive uses an effective radius and track, measured in
PyBullet, and closes a slow integral loop on the measured twist to remove what remains, as the
robot's own odometry-fed controller would. A description's wheels start from their own radius and
track, as gazebo_ros's diff_drive plugin takes them, and the same loop closes on what slips.
"""

from __future__ import annotations

from dataclasses import dataclass

from pytest_lasertest.model.body import Body
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.sim.client import PhysicsWorld


@dataclass(frozen=True)
class Twist:
    """A base velocity in the robot's frame."""

    linear: float  # m/s, forward
    angular: float  # rad/s, counter-clockwise


@dataclass(frozen=True)
class WheelGeometry:
    """How wheel speeds turn into a twist on the simulated ground."""

    radius: float  # m, effective
    track: float  # m, effective distance between the left and right wheels
    gain: float  # 1/s, how fast the twist loop removes a steady error


# Measured with pybullet_data's Husky at time steps of 0.005-0.02 s: 0.5 m/s straight ahead needs
# the URDF's 0.1651 m wheel to count as 1.0808 times larger, and turning in place with the tyres'
# sideways friction of `client.TYRE_SIDEWAYS_FRICTION` behaves as a track of 0.62 m.
HUSKY_WHEELS = WheelGeometry(radius=0.1651 * 1.0808, track=0.62, gain=3.0)


def wheel_geometry(body: Body) -> WheelGeometry | None:
    """How the body's wheels turn into a twist; None for a body without wheels."""
    if body.kind == "husky":
        return HUSKY_WHEELS
    if not body.wheels:
        return None
    radius, track = body.track()
    return WheelGeometry(radius, track, HUSKY_WHEELS.gain)


class Drive:
    """The twist the wheels are driven toward, ramped within the robot's limits, and the
    integral of what the measured twist lacked."""

    def __init__(self, robot: Robot) -> None:
        self.robot = robot
        self.wheels = wheel_geometry(robot.body)
        # Plain floats, not Twists: the drive runs at every physics step.
        self._target = (0.0, 0.0)  # m/s, rad/s
        self._correction = (0.0, 0.0)  # m/s, rad/s

    def twist(self, command: Twist, step: float) -> tuple[float, float]:
        """The twist (m/s, rad/s) to drive for the next `step` seconds: the command within the
        robot's speeds, reached within its accelerations."""
        self._ramp(command, step)
        return self._target

    def wheel_speeds(self, command: Twist, measured: Twist, step: float) -> tuple[float, float]:
        """Left and right wheel speeds (rad/s) for the next `step` seconds."""
        if self.wheels is None:
            raise ValueError(f"{self.robot.body.describe()} has no wheels to drive")
        limited = self._ramp(command, step)
        linear, angular = self._target
        # Only a steady error is the loop's to remove: while the target ramps, the robot lags it
        # by design, and integrating that lag would overshoot.
        gain = self.wheels.gain * step if self._target == limited else 0.0
        self._correction = (
            self._correction[0] + gain * (linear - measured.linear),
            self._correction[1] + gain * (angular - measured.angular),
        )
        linear += self._correction[0]
        angular += self._correction[1]
        half_track = self.wheels.track / 2.0
        return (
            (linear - angular * half_track) / self.wheels.radius,
            (linear + angular * half_track) / self.wheels.radius,
        )

    def _ramp(self, command: Twist, step: float) -> tuple[float, float]:
        """Move the target toward the command within the limits; the command, limited."""
        robot = self.robot
        limited = (
            _clamp(command.linear, robot.max_linear_velocity),
            _clamp(command.angular, robot.max_angular_velocity),
        )
        linear, angular = self._target
        self._target = (
            linear + _clamp(limited[0] - linear, robot.max_linear_acceleration * step),
            angular + _clamp(limited[1] - angular, robot.max_angular_acceleration * step),
        )
        return limited


def drive_step(
    world: PhysicsWorld, drive: Drive, command: Twist, measured: Twist, yaw: float, step: float
) -> tuple[float, float]:
    """Step `world` once with its body driven toward `command`, heading `yaw` (rad); what drove
    it: the wheel speeds (rad/s), or the twist a body without wheels moved at (m/s, rad/s)."""
    if drive.wheels is not None:
        left, right = drive.wheel_speeds(command, measured, step)
        world.step(left, right)
        return left, right
    linear, angular = drive.twist(command, step)
    world.glide(linear, angular, yaw)
    return linear, angular


def _clamp(value: float, limit: float) -> float:
    return max(-limit, min(limit, value))
