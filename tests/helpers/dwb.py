"""DWB's settings as the conformance tests of nav2_dwb_controller build them: from a params file
whose controller_server names DWB as FollowPath with its critics and sets only the given
FollowPath parameters, read as humble's (our DWB imitates humble 3c3db59d)."""

from __future__ import annotations

from collections.abc import Mapping

from pytest_lasertest.model.robot import ParameterValue
from pytest_lasertest.nav.nav2.controller_params import DWB
from pytest_lasertest.nav.nav2.dwb_settings import CRITICS, DwbSettings
from tests.helpers.nav2_params import nav2_settings


def dwb_settings(follow_path: Mapping[str, ParameterValue]) -> DwbSettings:
    """DWB's settings from a params file setting `follow_path` ("sim_time", "max_vel_x", ...)
    under FollowPath, and DWB's critics; each one it leaves out takes DWB's code default."""
    server = {"FollowPath.plugin": DWB, "FollowPath.critics": CRITICS}
    server |= {f"FollowPath.{name}": value for name, value in follow_path.items()}
    settings = nav2_settings({"controller_server": server}, "humble").dwb
    assert settings is not None
    return settings
