"""Nav2 given the world's map: its global costmap's static layer holds it (as
nav2_costmap_2d's StaticLayer in a rolling window), tracks unknown space as the params file
says, and NavFn plans round a wall no scan has seen; a costmap without a static layer, and the
local costmap, take no map."""

from __future__ import annotations

import math

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, Point2D
from pytest_lasertest.model.obstacles import Box
from pytest_lasertest.model.occupancy import OccupancyGrid, rasterised
from pytest_lasertest.nav.move_base.cost_values import FREE, LETHAL, UNKNOWN
from pytest_lasertest.nav.move_base.static_layer import StaticLayerSettings
from pytest_lasertest.nav.nav2.nav2 import Nav2
from pytest_lasertest.nav.nav2.params import configure
from pytest_lasertest.nav.nav2.settings import Nav2Settings
from pytest_lasertest.nav.protocol import LaserScan, Odometry
from pytest_lasertest.pairsfile import load_pairs_file
from tests.helpers import EXAMPLES
from tests.helpers.costmap import cost_at
from tests.helpers.nav2_params import bringup_node, nav2_settings, params_file

PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
SCANNER = next(pair for pair in PAPER.pairs if pair.name == "distance").baseline.profile
GOAL = Point2D(6.0, 0.0)
# 4 m of wall across the straight line to the goal, 3 m ahead, in a map drawn as a pairs file's
# walls are (1 m of free cells round it).
ACROSS = Box(3.0, 0.0, 0.0, 0.2, 4.0, 2.0)
ACROSS_MAP = rasterised((ACROSS,), 0.05, 1.0)


def after_one_scan(robot_map: OccupancyGrid | None, settings: Nav2Settings | None = None) -> Nav2:
    """The Husky's Nav2 (Clearpath's a200 params) heading for GOAL, given `robot_map`, after
    one scan in which it sees nothing: its global costmap made and its first plan planned."""
    nav2 = Nav2(PAPER.robot, (GOAL,), settings)
    if robot_map is not None:
        nav2.receive_map(robot_map)
    nothing = np.full(SCANNER.beam_count, np.inf)
    scan = LaserScan(0.0, nothing, SCANNER.to_laserscan_meta(), SCANNER.pose)
    nav2.observe(scan, Odometry(0.0, 0.0, 0.0, 0.0, 0.0), 0.0)
    return nav2


def distance_to(box: Box, points: FloatArray) -> FloatArray:
    """How far each point (P, 2) lies outside the axis-aligned box (0 inside), (P,) m."""
    along = np.abs(points[:, 0] - box.x) - box.length / 2.0
    across = np.abs(points[:, 1] - box.y) - box.width / 2.0
    gap: FloatArray = np.hypot(np.maximum(along, 0.0), np.maximum(across, 0.0))
    return gap


def test_nav2_given_a_map_with_a_wall_across_its_way_plans_round_the_wall() -> None:
    plan = after_one_scan(ACROSS_MAP).plan
    assert len(plan)
    assert math.dist(plan[-1], (GOAL.x, GOAL.y)) < 0.1
    # It keeps out of the wall's inscribed cells (the a200 footprint's radius is 0.46 m).
    assert distance_to(ACROSS, plan).min() > 0.46
    assert np.abs(plan[:, 1]).max() > ACROSS.width / 2.0


def test_nav2_without_the_map_plans_straight_through_the_wall_it_has_not_seen() -> None:
    plan = after_one_scan(None).plan
    assert np.abs(plan[:, 1]).max() < 0.1
    assert distance_to(ACROSS, plan).min() == 0.0


def test_given_a_map_the_global_costmap_tracks_unknown_space_as_the_params_file_says() -> None:
    # Clearpath's a200 file: track_unknown_space true. Without a map the static layer stands
    # for an open field's, all free; with one, off the map is unknown until scanned.
    costmap = after_one_scan(ACROSS_MAP).global_costmap
    assert costmap.settings.track_unknown_space is True
    costs = costmap.costs()
    assert cost_at(costmap, 3.0, 0.0, costs) == LETHAL  # the wall
    assert cost_at(costmap, 2.0, 2.8, costs) == FREE  # the map's free cells round it
    assert cost_at(costmap, -3.0, -3.0, costs) == UNKNOWN  # off the map, never scanned
    mapless = after_one_scan(None).global_costmap
    assert mapless.settings.track_unknown_space is False
    assert mapless.static is None
    assert cost_at(mapless, -3.0, -3.0, mapless.costs()) == FREE


def test_only_the_global_costmap_takes_the_map() -> None:
    # The a200 file names static_layer in the local costmap too; the imitation's has none.
    nav2 = after_one_scan(ACROSS_MAP)
    assert nav2.global_costmap.static is not None
    assert nav2.local.static is None


def test_a_global_costmap_without_a_static_layer_takes_no_map() -> None:
    # nav2_no_map_params.yaml's global costmap: an obstacle and an inflation layer.
    layers = [
        ("plugins", ("obstacle_layer", "inflation_layer")),
        ("obstacle_layer.plugin", "nav2_costmap_2d::ObstacleLayer"),
        ("obstacle_layer.observation_sources", "scan"),
        ("obstacle_layer.scan.data_type", "LaserScan"),
        ("inflation_layer.plugin", "nav2_costmap_2d::InflationLayer"),
        ("track_unknown_space", True),
    ]
    settings = nav2_settings({"global_costmap": dict(layers)})
    assert settings.global_.static_layer is None
    nav2 = after_one_scan(ACROSS_MAP, settings)
    assert nav2.global_costmap.static is None
    assert np.abs(nav2.plan[:, 1]).max() < 0.1


def test_the_static_layers_parameters_are_read_from_the_costmap_node() -> None:
    values = {
        "track_unknown_space": True,
        "lethal_cost_threshold": 65,
        "unknown_cost_value": -1,
        "trinary_costmap": False,
        "use_maximum": False,
        "inscribed_obstacle_cost_value": 90,  # main's (a3a97043), no release's imitated
    }
    layers = bringup_node("global_costmap", drop=("track_unknown_space",))
    config = configure(params_file({"global_costmap": {**layers, **values}}))
    assert config.settings.global_.static_layer == StaticLayerSettings(
        track_unknown_space=True,
        lethal_cost_threshold=65,
        unknown_cost_value=-1,
        trinary_costmap=False,
        use_maximum=False,
    )
    # Without a map the costmap stands for an open field's, as before.
    assert config.settings.global_.costmap.track_unknown_space is False
    (unread,) = [line for line in config.unmodelled if line.startswith("global_costmap: ")]
    assert "inscribed_obstacle_cost_value" in unread


def test_nav2s_default_global_costmap_has_a_static_layer_that_tracks_unknown_space() -> None:
    # Jazzy's nav2_params.yaml: plugins static, obstacle, inflation; track_unknown_space true.
    static = Nav2Settings().global_.static_layer
    assert static == StaticLayerSettings.nav2(track_unknown_space=True)
    assert Nav2Settings().local.static_layer is None
