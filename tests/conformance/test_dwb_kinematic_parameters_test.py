"""DWB's test of KinematicsHandler's parameters (dwb_plugins/test/kinematic_parameters_test.cpp),
rebuilt on our params file reader (`params.configure`, FollowPath as DWB): upstream sets each
kinematic parameter at run time through the node's parameter callback; here a params file sets
it under the same name, and each lands in the `DwbSettings` field of that name.

Not applicable: SetAllParameters' four assertions on the y limits (min_vel_y, max_vel_y,
acc_lim_y, decel_lim_y), a holonomic robot's, as the imitation is a differential drive."""

from __future__ import annotations

from tests.helpers.dwb import dwb_settings
from tests.helpers.upstream import NAVIGATION2_HUMBLE, Source

KINEMATICS = Source(
    "Nav2 DWB: kinematics",
    NAVIGATION2_HUMBLE,
    "nav2_dwb_controller/dwb_plugins/test/kinematic_parameters_test.cpp",
)
# The upstream values, each distinct, so that a parameter read into the wrong field shows.
VALUES = {
    "min_vel_x": 12.34,  # m/s
    "max_vel_x": 23.45,  # m/s
    "acc_lim_x": 56.78,  # m/s^2
    "decel_lim_x": 78.90,  # m/s^2
    "min_speed_xy": 90.12,  # m/s
    "max_speed_xy": 123.456,  # m/s
    "acc_lim_theta": 234.567,  # rad/s^2
    "max_vel_theta": 345.678,  # rad/s
    "decel_lim_theta": 456.789,  # rad/s^2
    "min_speed_theta": 567.890,  # rad/s
}


@KINEMATICS.test("KinematicParameters.SetAllParameters", assertions=10)
def test_every_kinematic_parameter_sets_its_own_limit() -> None:
    # Coarse steps too: at these speeds and the default granularities DWB would roll out ten
    # million poses a cycle, which our reader refuses; upstream's handler rolls nothing out.
    settings = dwb_settings(VALUES | {"linear_granularity": 100.0, "angular_granularity": 100.0})
    assert {name: getattr(settings, name) for name in VALUES} == VALUES
