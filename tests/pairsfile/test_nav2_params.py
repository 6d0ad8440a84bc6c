"""A team's Nav2 params file, named by a pairs file's `navigation: {nav2: ...}`: read in the ROS 2
format, its values set on the Nav2 imitation, what it does not read listed, and every problem
one error naming the params file, its line, the parameter and the fix."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.nav.nav2.obstacle_layer import Marking
from pytest_lasertest.nav.nav2.params import configure
from pytest_lasertest.nav.nav2.settings import Nav2Settings
from pytest_lasertest.pairsfile.pairs import load_pairs_file
from tests.helpers import REPO
from tests.helpers.runs import Case

BRINGUP = REPO / "tests" / "data" / "nav2" / "nav2_params.yaml"
PAIRS = """\
robot: husky
controller: nav2
navigation:
  nav2: team.nav2.yaml
  nav2_version: jazzy
world: {start: {x: 0, y: 0}, goal: {x: 3, y: 0}, time_limit: 30}
pairs:
  longer: {baseline: {model: hokuyo_ust_10lx}, candidate: {model: hokuyo_ust_20lx}}
"""
# Line numbers matter: the cases below break one line of it.
TEAM = """\
controller_server:
  ros__parameters:
    controller_frequency: 40.0
    controller_plugins: ["FollowPath"]
    FollowPath:
      plugin: "nav2_mppi_controller::MPPIController"
      batch_size: 1000
      critics: ["ConstraintCritic", "CostCritic", "GoalCritic"]
      CostCritic:
        cost_weight: 4.0
local_costmap:
  local_costmap:
    ros__parameters:
      width: 4
      height: 4
      footprint: "[[0.55, 0.45], [0.55, -0.45], [-0.55, -0.45], [-0.55, 0.45]]"
      plugins: ["obstacle_layer", "inflation_layer"]
      inflation_layer: {plugin: "nav2_costmap_2d::InflationLayer", inflation_radius: 0.8}
      obstacle_layer:
        plugin: "nav2_costmap_2d::ObstacleLayer"
        observation_sources: scan
        scan: {data_type: "LaserScan", obstacle_max_range: 2.0, inf_is_valid: true}
planner_server:
  ros__parameters:
    GridBased: {plugin: "nav2_navfn_planner/NavfnPlanner", use_astar: false}
amcl:
  ros__parameters: {alpha1: 0.2}
velocity_smoother:
  ros__parameters: {max_decel: [-2.5, 0.0, -3.2]}
collision_monitor:
  ros__parameters:
    FootprintApproach: {type: "polygon", action_type: "approach"}
    polygons: ["FootprintApproach"]
    observation_sources: ["scan"]
global_costmap:
  global_costmap:
    ros__parameters:
      plugins: ["obstacle_layer", "inflation_layer"]
      inflation_layer: {plugin: "nav2_costmap_2d::InflationLayer"}
      obstacle_layer:
        plugin: "nav2_costmap_2d::ObstacleLayer"
        observation_sources: scan
        scan: {data_type: "LaserScan", max_obstacle_height: 2.0, clearing: true}
"""


def load(tmp_path: Path, team: str = TEAM, pairs: str = PAIRS) -> object:
    (tmp_path / "team.nav2.yaml").write_text(team)
    (tmp_path / "gate.lasertest.yaml").write_text(pairs)
    return load_pairs_file(tmp_path / "gate.lasertest.yaml")


def test_a_teams_params_file_sets_the_nav2_imitation_and_nav2s_code_defaults_the_rest(
    tmp_path: Path,
) -> None:
    robot = load(tmp_path).robot  # type: ignore[attr-defined]
    config = configure(robot.nav2, robot.nav2_release)
    s = config.settings
    assert s.controller_frequency == 40.0
    assert s.mppi.batch_size == 1000
    assert s.mppi.time_steps == 56
    assert [type(critic).__name__ for critic in s.critics] == [
        "ConstraintCritic",
        "CostCritic",
        "GoalCritic",
    ]
    assert s.critics[1].weight == 4.0
    assert s.local.costmap.size == 4.0
    assert s.local.costmap.inflation_radius == 0.8
    assert s.local.costmap.inf_is_valid
    assert s.local.source.obstacle_max_range == 2.0
    # footprint_padding's default 0.01 m pads it, as costmap_2d does.
    # Read at a float's precision, as parseVVF reads it, then padded by 0.01 m.
    assert s.local.footprint is not None
    assert np.allclose(
        s.local.footprint, [(0.56, 0.46), (0.56, -0.46), (-0.56, -0.46), (-0.56, 0.46)]
    )
    # What the file leaves out takes Nav2's code default, not nav2_params.yaml's:
    assert s.local.costmap.cost_scaling_factor == 10.0  # inflation_layer.cpp:94
    assert s.local.costmap.resolution == 0.1  # costmap_2d_ros.cpp:126
    assert not s.local.source.clearing  # obstacle_layer.cpp:153
    assert s.local.source.max_obstacle_height == 0.0  # obstacle_layer.cpp:150
    assert s.prune_distance == 1.5  # path_handler.cpp:38
    assert not s.mppi.regenerate_noises  # noise_generator.cpp:35
    assert s.smoother.max_velocity == (0.5, 2.5)  # velocity_smoother.cpp:64-65
    assert s.collision_monitor is not None
    assert (s.collision_monitor.min_points, s.collision_monitor.time_before_collision) == (4, 2.0)
    # No footprint and no robot_radius: robot_radius's 0.1 m circle, padded.
    assert s.global_.footprint is not None
    assert len(s.global_.footprint) == 16
    assert s.global_.footprint[0][0] == pytest.approx(0.11)
    assert s.marking is Marking.CELLS_PREFILTERED
    assert config.unmodelled == ("amcl: every parameter (1)",)


def test_nav2_version_picks_the_obstacle_layers_marking_rule(tmp_path: Path) -> None:
    for release, marking in [
        ("jazzy", Marking.CELLS_PREFILTERED),
        ("kilted", Marking.EUCLIDEAN),
        ("humble", Marking.CELLS),
        ('"1.3.10"', Marking.EUCLIDEAN),
        ('"1.3.11"', Marking.CELLS),
        ('"1.3.12"', Marking.CELLS_PREFILTERED),
    ]:
        pairs = PAIRS.replace("nav2_version: jazzy", f"nav2_version: {release}")
        robot = load(tmp_path, pairs=pairs).robot  # type: ignore[attr-defined]
        assert configure(robot.nav2, robot.nav2_release).settings.marking is marking, release


GLOBAL = """\
global_costmap:
  global_costmap:
    ros__parameters:
      track_unknown_space: true
      plugins: {plugins}
      static_layer: {{plugin: "nav2_costmap_2d::StaticLayer"}}
      obstacle_layer:
        plugin: "nav2_costmap_2d::ObstacleLayer"
        observation_sources: scan
        scan: {{data_type: "LaserScan"}}
"""


@pytest.mark.parametrize(
    ("plugins", "unknown"),
    [
        ('["static_layer", "obstacle_layer"]', False),
        ('["obstacle_layer"]', True),
    ],
    ids=["with-a-map", "without-a-map"],
)
def test_the_global_costmap_keeps_unknown_space_only_without_a_static_layer(
    tmp_path: Path, plugins: str, unknown: bool
) -> None:
    # With a static layer the open world's map is known free; without one (Nav2's
    # nav2_no_map_params.yaml) only what a scan clears is known.
    team = TEAM[: TEAM.index("global_costmap:")] + GLOBAL.format(plugins=plugins)
    robot = load(tmp_path, team=team).robot  # type: ignore[attr-defined]
    settings = configure(robot.nav2, robot.nav2_release).settings
    assert settings.global_.costmap.track_unknown_space is unknown


def test_nav2_bringups_own_params_file_sets_jazzys_values() -> None:
    from pytest_lasertest.inputs.errors import Location
    from pytest_lasertest.inputs.node import SpecNode
    from pytest_lasertest.pairsfile.nav2_params import load_nav2_file

    node = SpecNode(BRINGUP.name, Location(BRINGUP.parent / "gate.lasertest.yaml", 1), "nav2")
    config = configure(load_nav2_file(node, "jazzy"))
    s = config.settings
    assert s.local.costmap.size == 3.0
    assert s.local.costmap.resolution == 0.05
    # robot_radius 0.22 m: costmap_2d's 16-point circle.
    assert len(s.local.footprint or ()) == 16
    # The voxel layer's column is 16 x 0.05 m: a scan above 0.8 m marks nothing locally.
    assert s.local.source.layer_max_obstacle_height == pytest.approx(0.8)
    assert s.global_.source.layer_max_obstacle_height == 2.0
    assert s.collision_monitor is not None
    assert s.collision_monitor.min_points == 6
    assert s.smoother.max_velocity == (0.5, 2.0)
    assert "amcl: every parameter (37)" in config.unmodelled
    assert any(line.startswith("controller_server: ") for line in config.unmodelled)


CASES = {
    "a word where a number belongs": Case(
        "controller_frequency: 40.0",
        "controller_frequency: fast",
        3,
        "controller_server.ros__parameters.controller_frequency",
        "is a number, not 'fast'",
        "write a number",
    ),
    "a zero rate": Case(
        "controller_frequency: 40.0",
        "controller_frequency: 0",
        3,
        "controller_server.ros__parameters.controller_frequency",
        "must be above zero, not 0.0",
        "write a positive controller_frequency",
    ),
    "a batch no controller could run": Case(
        "batch_size: 1000",
        "batch_size: 2000000",
        7,
        "controller_server.ros__parameters.FollowPath.batch_size",
        "2e+06 is beyond any Nav2 configuration (at most 100000)",
        "check the figure",
    ),
    "MPPI at a period longer than its model_dt": Case(
        "controller_frequency: 40.0",
        "controller_frequency: 10.0",
        3,
        "controller_server.ros__parameters.controller_frequency",
        "10 Hz is a period longer than MPPI's model_dt (0.05 s)",
        "write controller_frequency: 20, or a shorter model_dt",
    ),
    "a smoother that speeds up to slow down": Case(
        "max_decel: [-2.5, 0.0, -3.2]",
        "max_decel: [2.5, 0.0, -3.2]",
        29,
        "velocity_smoother.ros__parameters.max_decel",
        "has a positive value [2.5, 0.0, -3.2]: Nav2's velocity smoother refuses to start",
        "write each of max_decel zero or less",
    ),
    "a collision monitor polygon of a type Nav2 does not know": Case(
        'type: "polygon"',
        'type: "square"',
        32,
        "collision_monitor.ros__parameters.FootprintApproach.type",
        "'square' is not a type Nav2's collision monitor knows (polygon, circle, velocity_polygon)",
        "write polygon",
    ),
    "a collision monitor circle": Case(
        'type: "polygon"',
        'type: "circle"',
        32,
        "collision_monitor.ros__parameters.FootprintApproach.type",
        "'circle' is not imitated: the monitor here has one footprint polygon on the scan",
        "write polygon",
    ),
    "a controller the imitation does not have": Case(
        "nav2_mppi_controller::MPPIController",
        "nav2_regulated_pure_pursuit_controller::RegulatedPurePursuitController",
        6,
        "controller_server.ros__parameters.FollowPath.plugin",
        "RegulatedPurePursuitController is a controller the Nav2 imitation does not have",
        "use nav2_mppi_controller::MPPIController",
    ),
    "a critic the imitation does not have": Case(
        '"GoalCritic"]',
        '"ObstaclesCritic"]',
        8,
        "controller_server.ros__parameters.FollowPath.critics",
        "ObstaclesCritic is a critic the MPPI imitation does not have",
        "leave it out, or use those it has",
    ),
    "a rectangular rolling window": Case(
        "height: 4",
        "height: 5",
        15,
        "local_costmap.local_costmap.ros__parameters.height",
        "differs from width",
        "write the same width and height",
    ),
    "a footprint that is not a polygon": Case(
        '"[[0.55, 0.45], [0.55, -0.45], [-0.55, -0.45], [-0.55, 0.45]]"',
        '"[[0.55, 0.45], [0.55]]"',
        16,
        "local_costmap.local_costmap.ros__parameters.footprint",
        "is not a polygon of three or more [x, y] points",
        'write e.g. "[[0.5, 0.4]',
    ),
    "a footprint with a NaN (JSON would read it)": Case(
        '"[[0.55, 0.45], [0.55, -0.45], [-0.55, -0.45], [-0.55, 0.45]]"',
        '"[[NaN, 0.45], [0.55, -0.45], [-0.55, -0.45], [-0.55, 0.45]]"',
        16,
        "local_costmap.local_costmap.ros__parameters.footprint",
        "cannot be read as a list of [x, y] points: 'NaN, 0.45]",
        'write e.g. "[[0.5, 0.4]',
    ),
    "a footprint without its last bracket": Case(
        '"[[0.55, 0.45], [0.55, -0.45], [-0.55, -0.45], [-0.55, 0.45]]"',
        '"[[0.55, 0.45], [0.55, -0.45], [-0.55, -0.45], [-0.55, 0.45]"',
        16,
        "local_costmap.local_costmap.ros__parameters.footprint",
        "cannot be read as a list of [x, y] points: an unterminated list",
        'write e.g. "[[0.5, 0.4]',
    ),
    "a footprint of numbers outside the points' brackets": Case(
        '"[[0.55, 0.45], [0.55, -0.45], [-0.55, -0.45], [-0.55, 0.45]]"',
        '"[0.55, 0.45, 0.55, -0.45, -0.55, -0.45]"',
        16,
        "local_costmap.local_costmap.ros__parameters.footprint",
        "cannot be read as a list of [x, y] points: '0' outside an inner [...]",
        'write e.g. "[[0.5, 0.4]',
    ),
    "two observation sources": Case(
        "observation_sources: scan",
        "observation_sources: scan rear_scan",
        21,
        "local_costmap.local_costmap.ros__parameters.obstacle_layer.observation_sources",
        "names 2 sources; the imitation feeds its layer one laser scan",
        "name one LaserScan source",
    ),
    "a point cloud source": Case(
        'data_type: "LaserScan"',
        'data_type: "PointCloud2"',
        22,
        "local_costmap.local_costmap.ros__parameters.obstacle_layer.scan.data_type",
        "must be LaserScan",
        "write LaserScan",
    ),
    "A* asked of NavFn": Case(
        "use_astar: false",
        "use_astar: true",
        25,
        "planner_server.ros__parameters.GridBased.use_astar",
        "A* is not imitated",
        "write false",
    ),
    "a node without ros__parameters": Case(
        "amcl:\n  ros__parameters: {alpha1: 0.2}",
        "amcl:\n  parameters: {alpha1: 0.2}",
        26,
        "amcl.ros__parameters",
        "ros__parameters is missing",
        "write each node's parameters under it: `amcl:` then, indented, `ros__parameters:`",
    ),
    "a parameter with no value": Case(
        "batch_size: 1000",
        "batch_size:",
        7,
        "controller_server.ros__parameters.FollowPath.batch_size",
        "a parameter's value is a number, true or false, a string or a list, not",
        "leave the parameter out to keep Nav2's default",
    ),
    # What Nav2's code leaves without a default, or gives one only for its default list.
    "FollowPath left to its default plugin, DWB, with MPPI's critics": Case(
        'plugin: "nav2_mppi_controller::MPPIController"',
        "# plugin: left to the default",
        8,
        "controller_server.ros__parameters.FollowPath.critics",
        "ConstraintCritic is a critic the DWB imitation does not have",
        "leave it out, or use those it has",
    ),
    "a collision monitor without polygons": Case(
        '    polygons: ["FootprintApproach"]',
        "    # polygons: left out",
        32,
        "collision_monitor.polygons",
        "is not set: Nav2's collision monitor refuses to configure without it",
        "or leave the collision_monitor node out of the file to run none",
    ),
    "a layer of a list other than the default without its plugin": Case(
        '      inflation_layer: {plugin: "nav2_costmap_2d::InflationLayer"}',
        "      inflation_layer: {cost_scaling_factor: 3.0}",
        38,
        "global_costmap.inflation_layer.plugin",
        "is not set: Nav2 refuses to configure without it",
        "write inflation_layer.plugin: nav2_costmap_2d::ObstacleLayer or",
    ),
    # Resources: each figure within its bounds, not together.
    "MPPI samples no cycle could score": Case(
        "batch_size: 1000",
        "batch_size: 100000",
        7,
        "controller_server.ros__parameters.FollowPath.batch_size",
        "100,000 samples of 56 steps are 5,600,000 points every cycle",
        "lower batch_size or time_steps",
    ),
    "a costmap of more cells than any run marks": Case(
        "      width: 4\n      height: 4",
        "      width: 4000\n      height: 4000",
        14,
        "local_costmap.resolution",
        "4000 m at 0.1 m a cell is 40,000 cells a side, more than the 4000",
        "coarsen resolution to at least 1 m, or narrow the costmap",
    ),
    "a footprint 2 km long": Case(
        '"[[0.55, 0.45], [0.55, -0.45], [-0.55, -0.45], [-0.55, 0.45]]"',
        '"[[2000, 0.45], [2000, -0.45], [-0.55, -0.45], [-0.55, 0.45]]"',
        16,
        "local_costmap.local_costmap.ros__parameters.footprint",
        "reaches 2000.01 m from the robot's origin",
        "within 20 m of its origin",
    ),
    "a footprint whose edges cross (a bow tie)": Case(
        '"[[0.55, 0.45], [0.55, -0.45], [-0.55, -0.45], [-0.55, 0.45]]"',
        '"[[0.55, 0.45], [-0.55, -0.45], [0.55, -0.45], [-0.55, 0.45]]"',
        16,
        "local_costmap.local_costmap.ros__parameters.footprint",
        "has edges that cross each other, from (0.55, 0.45) to (-0.55, -0.45) and from "
        "(0.55, -0.45) to (-0.55, 0.45): it outlines no body",
        "list the corners in order round the robot",
    ),
    "a footprint of more corners than costmaps test": Case(
        '"[[0.55, 0.45], [0.55, -0.45], [-0.55, -0.45], [-0.55, 0.45]]"',
        '"[' + ", ".join(["[0.5, 0.0]"] * 101) + ']"',
        16,
        "local_costmap.local_costmap.ros__parameters.footprint",
        "has 101 corners, more than the 100 the gate accepts",
        "give the robot's outline with fewer corners",
    ),
    "a robot_radius of a kilometre": Case(
        '      footprint: "[[0.55, 0.45], [0.55, -0.45], [-0.55, -0.45], [-0.55, 0.45]]"',
        "      robot_radius: 1000",
        16,
        "local_costmap.local_costmap.ros__parameters.robot_radius",
        "reaches 1000.01 m from the robot's origin",
        "within 20 m of its origin",
    ),
}


@pytest.mark.parametrize("case", CASES.values(), ids=CASES.keys())
def test_a_broken_params_file_is_one_error_naming_its_line_parameter_and_fix(
    tmp_path: Path, case: Case
) -> None:
    assert case.old in TEAM
    with pytest.raises(SpecError) as raised:
        load(tmp_path, team=TEAM.replace(case.old, case.new, 1))
    error = raised.value
    assert error.location.path.name == "team.nav2.yaml"
    assert (error.location.line, error.field) == (case.line, case.field)
    assert case.problem in error.problem
    assert case.fix in error.fix


def test_a_file_without_the_controller_server_node_is_an_error_saying_nav2_would_run_dwb(
    tmp_path: Path,
) -> None:
    team = TEAM[TEAM.index("local_costmap:") :]
    with pytest.raises(SpecError) as raised:
        load(tmp_path, team=team)
    error = raised.value
    assert (error.location.line, error.field) == (1, "controller_server.FollowPath.critics")
    assert "the file has no controller_server node: Nav2 runs it on its defaults" in error.problem


def test_a_file_without_the_collision_monitor_node_runs_none(tmp_path: Path) -> None:
    team = TEAM[: TEAM.index("collision_monitor:")] + TEAM[TEAM.index("global_costmap:") :]
    robot = load(tmp_path, team=team).robot  # type: ignore[attr-defined]
    assert configure(robot.nav2, robot.nav2_release).settings.collision_monitor is None


def test_humbles_collision_monitor_without_polygons_runs_none_and_jazzys_refuses(
    tmp_path: Path,
) -> None:
    team = TEAM.replace('    polygons: ["FootprintApproach"]\n', "")
    humble = PAIRS.replace("nav2_version: jazzy", "nav2_version: humble")
    robot = load(tmp_path, team=team, pairs=humble).robot  # type: ignore[attr-defined]
    assert configure(robot.nav2, robot.nav2_release).settings.collision_monitor is None
    with pytest.raises(SpecError, match="polygons"):
        load(tmp_path, team=team)


def test_a_costmap_without_plugins_runs_nav2s_default_layers(tmp_path: Path) -> None:
    # static_layer, obstacle_layer and inflation_layer, of their default types: the
    # obstacle_layer's and inflation_layer's parameters the file sets are read.
    team = TEAM.replace('      plugins: ["obstacle_layer", "inflation_layer"]\n', "", 1)
    robot = load(tmp_path, team=team).robot  # type: ignore[attr-defined]
    local = configure(robot.nav2, robot.nav2_release).settings.local
    assert local.costmap.inflation_radius == 0.8
    assert local.source.obstacle_max_range == 2.0


def test_humbles_progress_checker_is_named_by_progress_checker_plugin(tmp_path: Path) -> None:
    # controller_server.cpp:53 at humble 3c3db59d: one name, not Jazzy's list.
    team = TEAM.replace(
        "    controller_frequency: 40.0\n",
        "    controller_frequency: 40.0\n    progress_checker_plugin: slow\n"
        "    slow: {plugin: nav2_controller::SimpleProgressChecker,"
        " movement_time_allowance: 20.0}\n",
    )
    humble = PAIRS.replace("nav2_version: jazzy", "nav2_version: humble")
    robot = load(tmp_path, team=team, pairs=humble).robot  # type: ignore[attr-defined]
    assert configure(robot.nav2, robot.nav2_release).settings.movement_time_allowance == 20.0


def test_a_global_costmap_rolls_at_its_width_only_where_rolling_window_says_so(
    tmp_path: Path,
) -> None:
    unique = '      inflation_layer: {plugin: "nav2_costmap_2d::InflationLayer"}\n'
    rolling = TEAM.replace(unique, f"      rolling_window: true\n      width: 20\n{unique}")
    for team, size in ((TEAM, Nav2Settings().global_.costmap.size), (rolling, 20.0)):
        robot = load(tmp_path, team=team).robot  # type: ignore[attr-defined]
        assert configure(robot.nav2, robot.nav2_release).settings.global_.costmap.size == size


@pytest.mark.parametrize(
    ("old", "new", "line", "problem"),
    [
        ("nav2: team.nav2.yaml", "nav2: missing.yaml", 4, "missing.yaml does not exist"),
        ("nav2_version: jazzy", "nav2_version: iron", 5, "'iron' is not a Nav2 release"),
        ("nav2_version: jazzy", 'nav2_version: "1.3.14"', 5, "'1.3.14' is not a Nav2 release"),
    ],
)
def test_a_pairs_file_naming_a_missing_params_file_or_an_unknown_release_is_an_error_at_its_line(
    tmp_path: Path, old: str, new: str, line: int, problem: str
) -> None:
    with pytest.raises(SpecError) as raised:
        load(tmp_path, pairs=PAIRS.replace(old, new))
    assert raised.value.location.line == line
    assert problem in raised.value.problem


def test_a_pairs_file_naming_nav2_bringups_params_file_collects_runs_and_lists_what_is_unread(
    pytester: pytest.Pytester,
) -> None:
    shutil.copy(BRINGUP, pytester.path / "nav2_params.yaml")
    pairs = PAIRS.replace("team.nav2.yaml", "nav2_params.yaml").replace(
        "hokuyo_ust_20lx", "rplidar_a1"
    )
    (pytester.path / "gate.lasertest.yaml").write_text(pairs)
    result = pytester.runpytest("-k", "no-obstacle", "-rA", "--laser-seed=1")
    result.assert_outcomes(passed=1, deselected=result.parseoutcomes()["deselected"])
    result.stdout.fnmatch_lines(
        [
            "*UnreadParametersWarning: the Nav2 imitation does not read these parameters*",
            "    amcl: every parameter (37)",
        ]
    )


def test_the_bundled_husky_runs_clearpaths_a200_parameters_with_dwb(tmp_path: Path) -> None:
    pairs = PAIRS.replace("  nav2: team.nav2.yaml\n", "")
    robot = load(tmp_path, pairs=pairs).robot  # type: ignore[attr-defined]
    config = configure(robot.nav2, robot.nav2_release)
    s = config.settings
    assert s.dwb is not None
    assert (s.dwb.max_vel_x, s.dwb.acc_lim_x, s.dwb.slowing_factor) == (1.0, 0.5, 12.0)
    assert s.dwb.path_align_scale == 32.0
    assert s.xy_goal_tolerance == 0.3
    assert s.local.costmap.resolution == 0.06
    assert s.local.costmap.size == 5.0
    assert s.global_.costmap.size == 20.0
    assert s.collision_monitor is not None
    assert (s.collision_monitor.time_before_collision, s.collision_monitor.min_points) == (0.3, 12)
    assert s.smoother.max_accel == (0.5, 0.5)
    assert (s.behaviors.min_rotational_vel, s.behaviors.rotational_acc_lim) == (0.2, 0.5)
    # Left unread: what Nav2 Jazzy does not read either. It reads progress_checker_plugins,
    # where Clearpath's file writes Humble's singular name; DWB has no `stateful`; a scan
    # source has no heights (only a point cloud's, pointcloud.cpp:151 at jazzy f4108e5b).
    assert config.unmodelled == (
        "controller_server: progress_checker_plugin (did you mean progress_checker_plugins?), "
        "FollowPath.stateful",
        "collision_monitor: scan.min_height, scan.max_height",
    )


@pytest.mark.parametrize(
    ("edits", "problem"),
    [
        pytest.param(
            (('"RotateToGoal", ', '"RotateToGoal", "Twirling", '),),
            "Twirling is a critic the DWB imitation does not have",
            id="unknown-dwb-critic",
        ),
        pytest.param(
            (("RotateToGoal.lookahead_time: -1.0", "RotateToGoal.lookahead_time: 1.0"),),
            "only a negative lookahead_time",
            id="positive-lookahead",
        ),
        pytest.param(
            (("max_vel_y: 0.0", "max_vel_y: 0.5"), ("acc_lim_y: 0.0", "acc_lim_y: 2.5")),
            "DWB would sample lateral speeds from 0 to 0.5 m/s",
            id="sideways-dwb",
        ),
        pytest.param(
            (("velocity_timeout: 1.0", "velocity_timeout: 0.02"),),
            "0.02 s is no longer than the controller's cycle (0.05 s)",
            id="smoother-timing-out",
        ),
        pytest.param(
            (('"assisted_teleop", "wait"]', '"assisted_teleop"]'),),
            "does not list wait, which the behaviour tree's recoveries call",
            id="no-wait-behavior",
        ),
        pytest.param(
            (('plugin: "nav2_behaviors/Spin"', 'plugin: "nav2_behaviors/Wait"'),),
            "is nav2_behaviors::Wait, but the behaviour tree's recoveries call spin for "
            "nav2_behaviors::Spin",
            id="spin-as-wait",
        ),
        pytest.param(
            (('plugin: "nav2_behaviors/AssistedTeleop"', 'plugin: "team_behaviors/Dance"'),),
            "team_behaviors::Dance is a behavior the Nav2 imitation does not have",
            id="unknown-behavior",
        ),
    ],
)
def test_a_dwb_or_behavior_setting_the_imitation_cannot_run_is_an_error_at_its_line(
    tmp_path: Path, edits: tuple[tuple[str, str], ...], problem: str
) -> None:
    husky = (REPO / "pytest_lasertest" / "robots" / "husky" / "nav2.yaml").read_text()
    for old, new in edits:
        assert husky.count(old) == 1
        husky = husky.replace(old, new)
    with pytest.raises(SpecError) as raised:
        load(tmp_path, team=husky)
    first = next(i for i, line in enumerate(husky.splitlines(), 1) if edits[0][1] in line)
    assert raised.value.location.line == first
    assert problem in raised.value.problem


def _nested(team: str, namespace: str) -> str:
    """TEAM with every node under `namespace:`, indented a level."""
    return f"{namespace}:\n" + "".join(f"  {line}\n" for line in team.splitlines())


@pytest.mark.parametrize(
    "team",
    [
        TEAM.replace("controller_server:\n", "/controller_server:\n", 1),
        TEAM.replace("controller_server:\n", "/robot1/controller_server:\n", 1),
        _nested(TEAM, "robot1"),
    ],
    ids=["fully-qualified", "namespaced-key", "namespace-mapping"],
)
def test_fully_qualified_and_namespaced_node_names_are_read_as_ros_2_reads_them(
    tmp_path: Path, team: str
) -> None:
    # rcl joins the keys above ros__parameters into the node's name, a leading / or not
    # (ros2 param dump writes /controller_server:).
    robot = load(tmp_path, team=team).robot  # type: ignore[attr-defined]
    assert configure(robot.nav2, robot.nav2_release).settings.controller_frequency == 40.0


def test_a_node_set_under_two_namespaces_is_an_error_at_the_second(tmp_path: Path) -> None:
    team = TEAM + "/robot2/controller_server:\n  ros__parameters: {controller_frequency: 10.0}\n"
    team = team.replace("controller_server:\n", "/robot1/controller_server:\n", 1)
    with pytest.raises(SpecError) as raised:
        load(tmp_path, team=team)
    assert (
        raised.value.location.line
        == team.splitlines().index("  ros__parameters: {controller_frequency: 10.0}") + 1
    )
    assert "controller_server is set under two namespaces (/robot1 and /robot2)" in (
        raised.value.problem
    )


def test_parameters_for_every_node_reach_each_node_the_later_winning(tmp_path: Path) -> None:
    # rclcpp applies "/**" to every node, and of two entries for one parameter the later.
    before = "/**:\n  ros__parameters: {controller_frequency: 25.0, use_sim_time: true}\n"
    robot = load(tmp_path, team=before + TEAM).robot  # type: ignore[attr-defined]
    config = configure(robot.nav2, robot.nav2_release)
    assert config.settings.controller_frequency == 40.0
    assert config.unmodelled[-1] == "/**: use_sim_time"
    after = "/**:\n  ros__parameters: {controller_frequency: 25.0}\n"
    robot = load(tmp_path, team=TEAM + after).robot  # type: ignore[attr-defined]
    assert configure(robot.nav2, robot.nav2_release).settings.controller_frequency == 25.0


def test_a_yaml_alias_is_refused_at_its_line_as_ros_2_refuses_it(tmp_path: Path) -> None:
    # Aliases of aliases would also make a few hundred bytes billions of values.
    team = TEAM.replace(
        "    controller_frequency: 40.0\n",
        "    controller_frequency: &rate 40.0\n    failure_tolerance: *rate\n",
    )
    with pytest.raises(SpecError) as raised:
        load(tmp_path, team=team)
    assert raised.value.location.line == 4
    assert "ROS 2's parameter parser refuses one" in raised.value.problem
    bomb = "a: &a [1, 1]\nb: &b [*a, *a]\nc: &c [*b, *b]\n" + "".join(
        f"{chr(100 + i)}: &{chr(100 + i)} [*{chr(99 + i)}, *{chr(99 + i)}]\n" for i in range(20)
    )
    with pytest.raises(SpecError, match="Will not support aliasing"):
        load(tmp_path, team=bomb)


@pytest.mark.parametrize(
    ("old", "new", "problem"),
    [
        ("controller_frequency: 40.0", "controller_frequency: .inf", "must be a finite number"),
        ("controller_frequency: 40.0", "controller_frequency: .nan", "must be a finite number"),
        ("controller_frequency: 40.0", "controller_frequency: 1.0e+9", "beyond any navigation"),
        (
            "max_decel: [-2.5, 0.0, -3.2]",
            "smoothing_frequency: 1.0e+9, max_decel: [-2.5, 0.0, -3.2]",
            "beyond any navigation",
        ),
        (
            "batch_size: 1000",
            "batch_size: " + "9" * 401,
            "9999... (401 digits) is beyond any Nav2 configuration",
        ),
        (
            "max_decel: [-2.5, 0.0, -3.2]",
            "max_decel: [-.inf, 0.0, -3.2]",
            "holds a figure that is not a finite number",
        ),
        # The goal checker goes in on the line of `old`, which moves down one.
        (
            'controller_plugins: ["FollowPath"]',
            'goal_checker: {xy_goal_tolerance: .inf}\n    controller_plugins: ["FollowPath"]',
            "must be a finite number",
        ),
        (
            'controller_plugins: ["FollowPath"]',
            'goal_checker: {xy_goal_tolerance: .nan}\n    controller_plugins: ["FollowPath"]',
            "must be a finite number",
        ),
    ],
    ids=[
        "infinite-rate",
        "nan-rate",
        "gigahertz-rate",
        "gigahertz-smoothing",
        "401-digits",
        "infinite-limit",
        "infinite-tolerance",
        "nan-tolerance",
    ],
)
def test_figures_no_configuration_holds_are_errors_at_their_line(
    tmp_path: Path, old: str, new: str, problem: str
) -> None:
    with pytest.raises(SpecError) as raised:
        load(tmp_path, team=TEAM.replace(old, new, 1))
    assert (
        raised.value.location.line
        == TEAM.splitlines().index(next(line for line in TEAM.splitlines() if old in line)) + 1
    )
    assert problem in raised.value.problem


def test_a_number_with_an_exponent_and_no_dot_is_a_number_as_ros_2_reads_it(
    tmp_path: Path,
) -> None:
    # rcl's get_value reads a plain 4e1 with strtod; YAML 1.1 would read it as text.
    team = TEAM.replace("controller_frequency: 40.0", "controller_frequency: 4e1")
    robot = load(tmp_path, team=team).robot  # type: ignore[attr-defined]
    assert configure(robot.nav2, robot.nav2_release).settings.controller_frequency == 40.0
    quoted = TEAM.replace("controller_frequency: 40.0", 'controller_frequency: "4e1"')
    with pytest.raises(SpecError, match="is a number, not '4e1'"):
        load(tmp_path, team=quoted)


def test_a_misspelt_node_or_parameter_is_listed_unread_with_the_name_meant(
    tmp_path: Path,
) -> None:
    team = TEAM.replace("      batch_size: 1000", "      batch_sise: 1000").replace(
        "amcl:", "controler_server:"
    )
    robot = load(tmp_path, team=team).robot  # type: ignore[attr-defined]
    unread = configure(robot.nav2, robot.nav2_release).unmodelled
    assert "controller_server: FollowPath.batch_sise (did you mean FollowPath.batch_size?)" in (
        unread
    )
    assert "controler_server: every parameter (1) (did you mean controller_server?)" in unread


def test_dwb_rolling_out_more_poses_than_any_cycle_scores_is_an_error_at_vx_samples() -> None:
    from pytest_lasertest.nav.nav2.dwb_settings import CRITICS
    from pytest_lasertest.nav.nav2.node_parameters import ParameterProblem
    from tests.helpers.nav2_params import nav2_settings

    server = {
        "FollowPath.plugin": "dwb_core::DWBLocalPlanner",
        "FollowPath.critics": CRITICS,
        "FollowPath.max_vel_x": 0.5,
        "FollowPath.vx_samples": 1000,
        "FollowPath.vtheta_samples": 1000,
    }
    with pytest.raises(ParameterProblem) as raised:
        nav2_settings({"controller_server": server})
    assert raised.value.name == "FollowPath.vx_samples"
    assert "more than the 200,000 the gate accepts" in raised.value.problem
