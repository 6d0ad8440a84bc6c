"""DWB's settings as the conformance tests of nav2_dwb_controller build them: from a params file
that names DWB as FollowPath and sets only the given FollowPath parameters, read as humble's
(our DWB imitates humble 3c3db59d)."""

from __future__ import annotations

from collections.abc import Mapping

from pytest_lasertest.model.robot import ParameterValue
from pytest_lasertest.nav.nav2.dwb import DwbSettings
from pytest_lasertest.nav.nav2.params import DWB, configure


def dwb_settings(follow_path: Mapping[str, ParameterValue]) -> DwbSettings:
    """DWB's settings from a params file setting `follow_path` ("sim_time", "max_vel_x", ...)
    under FollowPath; each one it leaves out keeps our default."""
    parameters: list[tuple[str, str, ParameterValue]] = [
        ("controller_server", "FollowPath.plugin", DWB)
    ]
    parameters += [
        ("controller_server", f"FollowPath.{name}", value) for name, value in follow_path.items()
    ]
    settings = configure(parameters, "humble").settings.dwb
    assert settings is not None
    return settings
