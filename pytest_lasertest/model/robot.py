"""The robot under test, as far as the gate needs to know it: its laser mount, shape and motion."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pytest_lasertest.model.body import HUSKY_BODY, Body
from pytest_lasertest.model.geometry import FloatArray, Pose3D

# A ROS 2 parameter's value, as a params file gives it.
ParameterValue = bool | int | float | str | tuple["ParameterValue", ...]

# The largest mobile robots are a few metres across; costmaps rasterise the footprint in cells.
# As far as a footprint's corner or a collision shape may lie from the base.
MAX_FOOTPRINT_REACH = 20.0  # m
# Costmaps test every edge of the footprint at every cell they check; costmap_2d footprints
# have 4 to a few dozen corners.
MAX_CORNERS = 100


@dataclass(frozen=True)
class Robot:
    """A differential-drive base with one laser, in its ground-level frame (base_footprint)."""

    name: str
    laser_mount: Pose3D  # where a profile without its own pose is mounted
    footprint: tuple[tuple[float, float], ...]  # m, convex polygon, counter-clockwise, padded
    max_linear_velocity: float  # m/s
    max_linear_acceleration: float  # m/s^2, also its braking deceleration
    max_angular_velocity: float  # rad/s
    max_angular_acceleration: float  # rad/s^2
    nominal_speed: float  # m/s, cruising speed along the nominal path
    nominal_turn_rate: float  # rad/s, turning in place at waypoints
    reaction_time: float  # s, from a scan to the first braking command
    # Its navigation stack's parameters as its configuration sets them: (section, name, value)
    # with the names of pytest_lasertest.nav.move_base.settings; the rest keep ROS's defaults.
    navigation: tuple[tuple[str, str, float | bool], ...] = ()
    # Its Nav2 parameters as a ROS 2 params file sets them: (node, dotted name, value), read by
    # pytest_lasertest.nav.nav2.params; and the Nav2 release imitated.
    nav2: tuple[tuple[str, str, ParameterValue], ...] = ()
    nav2_release: str = "jazzy"
    nav2_file: str | None = None  # the params file `nav2` was read from, as reports name it
    body: Body = HUSKY_BODY

    @property
    def braking_distance(self) -> float:
        """How far the robot travels from a detection at nominal speed until it stands (m)."""
        speed = self.nominal_speed
        return speed * self.reaction_time + speed**2 / (2.0 * self.max_linear_acceleration)

    def footprint_array(self) -> FloatArray:
        """The footprint's vertices, shape (V, 2), m."""
        return np.array(self.footprint, dtype=float)


def pad_footprint(
    points: tuple[tuple[float, float], ...], padding: float
) -> tuple[tuple[float, float], ...]:
    """Each vertex moved `padding` away from the origin along x and y, as costmap_2d pads it."""
    return tuple(
        (x + float(np.sign(x)) * padding, y + float(np.sign(y)) * padding) for x, y in points
    )
