"""What the MPPI conformance tests (tests/conformance/test_mppi_*.py) build alike: Nav2's settings
from a params file's controller_server parameters, a critic as such a file makes it, one cycle's
critic data, and the costmap nav2_mppi_controller's tests score on."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from pytest_lasertest.model.robot import ParameterValue
from pytest_lasertest.nav.nav2.controller_params import MPPI
from pytest_lasertest.nav.nav2.mppi import F32, CostGrid, Critic, CriticData, Optimizer
from pytest_lasertest.nav.nav2.nav2 import _follow_path
from pytest_lasertest.nav.nav2.settings import Nav2Settings
from tests.helpers import nav2_params as params

NO_PARAMETERS: Mapping[str, ParameterValue] = {}


def nav2_settings(controller_server: Mapping[str, ParameterValue]) -> Nav2Settings:
    """The settings of a params file whose controller_server runs MPPI and sets only these
    parameters ("controller_frequency", "FollowPath.vx_max", ...): each one it leaves out
    takes Nav2's code default, as a team's file that omits it would."""
    server = {"FollowPath.plugin": MPPI, **controller_server}
    return params.nav2_settings({"controller_server": server})


def critic(name: str, controller_server: Mapping[str, ParameterValue] = NO_PARAMETERS) -> Critic:
    """MPPI's critic `name` as Nav2 here runs it from a params file listing only that critic and
    setting only `controller_server` ("FollowPath.PathAngleCritic.mode", "FollowPath.vy_max")."""
    (made,) = optimizer({"FollowPath.critics": (name,), **controller_server}).critics
    return made


def optimizer(controller_server: Mapping[str, ParameterValue]) -> Optimizer:
    """MPPI as Nav2 here builds it from a params file setting only `controller_server`."""
    made = _follow_path(nav2_settings(controller_server), seed=0)
    assert isinstance(made, Optimizer)
    return made


def critic_data(
    batch: int,
    steps: int,
    *,
    pose: tuple[float, float, float] = (0.0, 0.0, 0.0),
    goal: tuple[float, float] = (0.0, 0.0),
    path: F32 | None = None,
    costmap: CostGrid | None = None,
    model_dt: float = 0.1,
) -> CriticData:
    """One cycle's data as nav2_mppi_controller's tests make it: `batch` trajectories of `steps`
    steps, speeds, controls and poses all zero, no cost yet, and an empty path unless given."""

    def zeros() -> F32:
        return np.zeros((batch, steps), dtype=np.float32)

    route = np.zeros((0, 2), dtype=np.float32) if path is None else path
    costs = np.zeros(batch, dtype=np.float32)
    return CriticData(
        pose=pose,
        goal=goal,
        path=route,
        cvx=zeros(),
        cwz=zeros(),
        vx=zeros(),
        wz=zeros(),
        x=zeros(),
        y=zeros(),
        yaw=zeros(),
        model_dt=model_dt,
        costs=costs,
        costmap=costmap,
    )


def path_along_x(xs: list[float]) -> F32:
    """A path (P, 2) m through (x, 0) for each x."""
    return np.column_stack([xs, np.zeros(len(xs))]).astype(np.float32)


def dummy_costmap() -> CostGrid:
    """The costmap of the tests' Costmap2DROS("dummy_costmap") with its defaults
    (costmap_2d_ros.cpp: width and height 5 m, resolution 0.1 m, origin (0, 0),
    track_unknown_space false), all free; its costs, indexed [y, x], may be written."""
    return CostGrid(np.zeros((50, 50), dtype=np.uint8), (0.0, 0.0), 0.1, tracking_unknown=False)
