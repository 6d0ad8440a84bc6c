"""A team's laser_filters params file, named by a pairs file's `navigation: {scan_filters:
...}`: read as the team's ROS 1 or ROS 2 chain node reads it, every filter made with what that
ROS gives a left-out parameter, and every problem one error naming the params file, its line,
the parameter and the fix."""

from __future__ import annotations

from pathlib import Path

import pytest

from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.nav.laser_filters.scan_filters import (
    AngularBoundsFilter,
    BoxFilter,
    FootprintFilter,
    RangeFilter,
    ShadowsFilter,
    SpeckleFilter,
)
from pytest_lasertest.nav.laser_filters.temporal import ArrayFilter, ChannelFilter
from pytest_lasertest.pairsfile.pairs import PairsFile, load_pairs_file
from tests.helpers.runs import Case

PAIRS = """\
robot: husky
controller: move_base
navigation:
  scan_filters: filters.yaml
world: {start: {x: 0, y: 0}, goal: {x: 3, y: 0}, time_limit: 30}
pairs:
  longer: {baseline: {model: hokuyo_ust_10lx}, candidate: {model: hokuyo_ust_20lx}}
"""
# Line numbers matter: the cases below break one line of these.
ROS2 = """\
scan_to_scan_filter_chain:
  ros__parameters:
    tf_message_filter_target_frame: base_link
    filter1:
      name: range
      type: laser_filters/LaserScanRangeFilter
      params:
        lower_threshold: 0.3
        upper_threshold: 30.0
        lower_replacement_value: -.inf
        upper_replacement_value: .inf
    filter2:
      name: shadows
      type: laser_filters/ScanShadowsFilter
      params: {min_angle: 10.0, max_angle: 170.0, window: 1, neighbors: 20}
    filter3:
      name: box
      type: laser_filters/LaserScanBoxFilter
      params:
        box_frame: base_link
        min_x: -0.6
        max_x: 0.6
        min_y: -0.4
        max_y: 0.4
        min_z: 0.0
        max_z: 1.0
    filter4:
      name: median
      type: laser_filters/LaserArrayFilter
      params:
        range_filter_chain:
          filter1:
            name: median_3
            type: filters/MultiChannelMedianFilterFloat
            params: {number_of_observations: 3}
"""
ROS1 = """\
scan_filter_chain:
- name: range
  type: laser_filters/LaserScanRangeFilter
  params:
    lower_threshold: 0.3
- name: angles
  type: laser_filters/LaserScanAngularBoundsFilter
  params:
    lower_angle: -1.5
    upper_angle: 1.5
- name: speckle
  type: laser_filters/LaserScanSpeckleFilter
  params: {filter_type: 1, max_range: 2.0, max_range_difference: 0.1, filter_window: 2}
- name: footprint
  type: laser_filters/LaserScanFootprintFilter
  params: {inscribed_radius: 0.5}
- name: median
  type: laser_filters/LaserMedianFilter
  params:
    internal_filter:
      - name: median_5
        type: filters/MultiChannelMedianFilterFloat
        params: {number_of_observations: 5}
"""
NODE = "scan_to_scan_filter_chain.ros__parameters"


def load(tmp_path: Path, filters: str, pairs: str = PAIRS) -> PairsFile:
    (tmp_path / "filters.yaml").write_text(filters)
    (tmp_path / "gate.lasertest.yaml").write_text(pairs)
    return load_pairs_file(tmp_path / "gate.lasertest.yaml")


def test_a_ros_2_chain_runs_its_filters_in_the_order_of_their_numbers(tmp_path: Path) -> None:
    chain = load(tmp_path, ROS2).scan_filters
    assert chain is not None
    assert (chain.ros, chain.file, chain.describe()) == (
        "ros2",
        "filters.yaml",
        "scan filters: filters.yaml (4 filters)",
    )
    assert [named.name for named in chain.filters] == ["range", "shadows", "box", "median"]
    assert chain.filters[0].filter == RangeFilter(0.3, 30.0, False, float("-inf"), float("inf"))
    shadows = chain.filters[1].filter
    assert isinstance(shadows, ShadowsFilter)
    assert (shadows.window, shadows.neighbors, shadows.remove_shadow_start_point) == (1, 20, False)
    assert chain.filters[2].filter == BoxFilter(-0.6, 0.6, -0.4, 0.4, 0.0, 1.0, False)
    assert chain.filters[3].filter == ArrayFilter((ChannelFilter("median", 3),))


def test_a_ros_1_chain_takes_its_filters_dynamic_reconfigure_defaults(tmp_path: Path) -> None:
    chain = load(tmp_path, ROS1).scan_filters
    assert chain is not None
    assert chain.ros == "ros1"
    # cfg/RangeFilter.cfg: upper_threshold 100000, replacement values 0 and 100000.
    assert chain.filters[0].filter == RangeFilter(0.3, 100000.0, False, 0.0, 100000.0)
    assert chain.filters[1].filter == AngularBoundsFilter(-1.5, 1.5)
    # ROS 1 chooses its validator before it reads filter_type: distance (0), whatever is set.
    assert chain.filters[2].filter == SpeckleFilter("ros1", 0, 2.0, 0.1, 2)
    assert chain.filters[3].filter == FootprintFilter(0.5)
    assert chain.filters[4].filter == ArrayFilter((ChannelFilter("median", 5),))


def test_ros_2_reads_dotted_names_and_a_namespaced_node_as_nested_ones(tmp_path: Path) -> None:
    dotted = """\
/robot1/scan_filter:
  ros__parameters:
    filter1.name: range
    filter1.type: laser_filters/LaserScanRangeFilter
    filter1.params.lower_threshold: 0.3
    filter1.params:
      upper_threshold: 30.0
"""
    chain = load(tmp_path, dotted).scan_filters
    assert chain is not None
    assert chain.filters[0].filter == RangeFilter(0.3, 30.0, False, 0.0, 0.0)


def test_a_ros_2_speckle_filter_runs_the_validator_its_filter_type_names(tmp_path: Path) -> None:
    speckle = """\
scan_to_scan_filter_chain:
  ros__parameters:
    filter1:
      name: speckle
      type: laser_filters/LaserScanSpeckleFilter
      params: {filter_type: 1, max_range: 2.0, max_range_difference: 0.1, filter_window: 2}
"""
    chain = load(tmp_path, speckle).scan_filters
    assert chain is not None
    assert chain.filters[0].filter == SpeckleFilter("ros2", 1, 2.0, 0.1, 2)


def test_a_pairs_file_without_scan_filters_runs_no_chain(tmp_path: Path) -> None:
    pairs = PAIRS.replace("navigation:\n  scan_filters: filters.yaml\n", "")
    assert load(tmp_path, ROS2, pairs).scan_filters is None


def test_a_missing_params_file_is_an_error_at_the_pairs_files_line(tmp_path: Path) -> None:
    (tmp_path / "gate.lasertest.yaml").write_text(PAIRS)
    with pytest.raises(SpecError) as raised:
        load_pairs_file(tmp_path / "gate.lasertest.yaml")
    error = raised.value
    assert (error.location.path.name, error.location.line) == ("gate.lasertest.yaml", 4)
    assert error.field == "navigation.scan_filters"
    assert "filters.yaml does not exist" in error.problem


def test_a_robots_navigation_file_has_no_scan_filters(tmp_path: Path) -> None:
    # The chain belongs to the pairs file's navigation: a robot's navigation file sets
    # move_base's sections alone.
    from pytest_lasertest.inputs.errors import Location
    from pytest_lasertest.inputs.node import SpecNode
    from pytest_lasertest.pairsfile.navigation import load_navigation_file

    (tmp_path / "navigation.yaml").write_text("scan_filters: filters.yaml\n")
    node = SpecNode("navigation.yaml", Location(tmp_path / "robot.yaml", 1), "navigation")
    with pytest.raises(SpecError, match="unknown key 'scan_filters'"):
        load_navigation_file(node)


SECOND_NODE = """
other_chain:
  ros__parameters:
    filter1: {name: r, type: laser_filters/LaserScanRangeFilter}
"""
ROS2_CASES = {
    "a misspelt filter type": Case(
        "type: laser_filters/LaserScanRangeFilter",
        "type: laser_filters/LaserScanRangeFilterr",
        6,
        f"{NODE}.filter1.type",
        "'laser_filters/LaserScanRangeFilterr' is no filter type the gate imitates",
        "did you mean 'laser_filters/LaserScanRangeFilter'?",
    ),
    "a filter type without its package": Case(
        "type: laser_filters/LaserScanRangeFilter",
        "type: LaserScanRangeFilter",
        6,
        f"{NODE}.filter1.type",
        "(a type is package/Filter, with one '/')",
        "did you mean 'laser_filters/LaserScanRangeFilter'?",
    ),
    "a filter the gate does not imitate": Case(
        "type: laser_filters/LaserScanRangeFilter",
        "type: laser_filters/LaserScanMaskFilter",
        6,
        f"{NODE}.filter1.type",
        "laser_filters/LaserScanMaskFilter is a laser_filters filter the gate does not imitate",
        "leave it out; the gate imitates laser_filters/InterpolationFilter",
    ),
    "a filter of intensities": Case(
        "type: laser_filters/LaserScanRangeFilter",
        "type: laser_filters/LaserScanIntensityFilter",
        6,
        f"{NODE}.filter1.type",
        "LaserScanIntensityFilter is refused: it keeps or removes readings by their intensities, "
        "and the simulated scanner publishes no intensities",
        "leave it out of the chain the gate runs",
    ),
    "ROS 2's LaserMedianFilter, which crashes its node": Case(
        "type: laser_filters/LaserArrayFilter",
        "type: laser_filters/LaserMedianFilter",
        29,
        f"{NODE}.filter4.type",
        "LaserMedianFilter is refused: ROS 2's LaserMedianFilter logs its deprecation through a "
        "logger it does not have yet (median_filter.h:56",
        "use laser_filters/LaserArrayFilter with a filters/MultiChannelMedianFilterFloat",
    ),
    "a misspelt parameter": Case(
        "lower_threshold: 0.3",
        "lower_treshold: 0.3",
        8,
        f"{NODE}.filter1.params.lower_treshold",
        "LaserScanRangeFilter reads no parameter 'lower_treshold': ROS 2 ignores it",
        "did you mean 'lower_threshold'?",
    ),
    "an integer where ROS 2 declares a double": Case(
        "upper_threshold: 30.0",
        "upper_threshold: 30",
        9,
        f"{NODE}.filter1.params.upper_threshold",
        "upper_threshold is the integer 30: ROS 2 declares upper_threshold a double",
        "write 30.0",
    ),
    "a double where ROS 2 declares an integer": Case(
        "window: 1,",
        "window: 1.0,",
        15,
        f"{NODE}.filter2.params.window",
        "window is the double 1: ROS 2 declares it an integer",
        "write 1",
    ),
    "a word where a number belongs": Case(
        "min_x: -0.6",
        "min_x: left",
        21,
        f"{NODE}.filter3.params.min_x",
        "min_x is a number, not the text 'left'",
        "write a number",
    ),
    "a number where true or false belongs": Case(
        "        lower_replacement_value: -.inf\n",
        "        lower_replacement_value: -.inf\n        use_message_range_limits: 1\n",
        11,
        f"{NODE}.filter1.params.use_message_range_limits",
        "use_message_range_limits is true or false, not 1: ROS 2 refuses it",
        "write true or false",
    ),
    "a parameter of another filter": Case(
        "params: {min_angle",
        "params: {invert: true, min_angle",
        15,
        f"{NODE}.filter2.params.invert",
        "ScanShadowsFilter reads no parameter 'invert': ROS 2 ignores it",
        "known keys here: max_angle, min_angle, neighbors, window",
    ),
    "NaN as a threshold": Case(
        "lower_threshold: 0.3",
        "lower_threshold: .nan",
        8,
        f"{NODE}.filter1.params.lower_threshold",
        "lower_threshold is nan: the filter compares readings with it",
        "write a finite number",
    ),
    "infinity as a side of the box": Case(
        "max_x: 0.6",
        "max_x: .inf",
        22,
        f"{NODE}.filter3.params.max_x",
        "max_x is inf: the filter compares readings with it",
        "write a finite number",
    ),
    "a figure beyond any scanner's reach": Case(
        "max_x: 0.6",
        "max_x: 6.0e+9",
        22,
        f"{NODE}.filter3.params.max_x",
        "max_x is 6e+09, beyond ±1e+06",
        "check the figure",
    ),
    "thresholds the wrong way round": Case(
        "lower_threshold: 0.3",
        "lower_threshold: 40.0",
        9,
        f"{NODE}.filter1.params.upper_threshold",
        "lower_threshold 40 m is not below upper_threshold 30 m: every reading is replaced",
        "make lower_threshold less than upper_threshold",
    ),
    "upper_threshold left out, which ROS 2 reads as 0": Case(
        "        upper_threshold: 30.0\n",
        "",
        8,
        f"{NODE}.filter1.params.lower_threshold",
        "lower_threshold 0.3 m is not below upper_threshold 0 m: every reading is replaced, "
        "one at or below the lower, the rest at or above the upper (upper_threshold is left "
        "out: ROS 2's getParam declares it 0.0 (filter_base.hpp:181-184 at ros/filters ros2 "
        "e33463ae), not the 100000 range_filter.h:75 sets)",
        "set upper_threshold in the filter's params (make lower_threshold less than",
    ),
    "an empty box": Case(
        "min_x: -0.6",
        "min_x: 0.8",
        22,
        f"{NODE}.filter3.params.max_x",
        "min_x 0.8 m is not below max_x 0.6 m: the box is empty: the filter removes no reading "
        "(with invert, every one)",
        "make min_x less than max_x",
    ),
    "a box in the laser's frame": Case(
        "box_frame: base_link",
        "box_frame: laser",
        20,
        f"{NODE}.filter3.params.box_frame",
        "box_frame 'laser': the gate knows the robot's base frame alone",
        "write base_link",
    ),
    "a box without its frame, which ROS 2 reads as ''": Case(
        "        box_frame: base_link\n",
        "",
        16,
        f"{NODE}.filter3.params.box_frame",
        "box_frame '': the filter finds no transform to it, fails every update and the chain "
        "publishes no scan",
        "set box_frame in the filter's params (write base_link)",
    ),
    "a shadow angle laser_filters would force": Case(
        "min_angle: 10.0",
        "min_angle: 95.0",
        15,
        f"{NODE}.filter2.params.min_angle",
        "min_angle 95° is outside 0-90°: laser_filters logs an error and forces it to 90°",
        "write min_angle from 0 to 90 (degrees)",
    ),
    "shadows that delete no neighbour": Case(
        "neighbors: 20",
        "neighbors: 0",
        15,
        f"{NODE}.filter2.params.neighbors",
        "neighbors 0: a shadow deletes only farther readings within 0 beams of it, none",
        "write neighbors: 1 or more",
    ),
    "remove_shadow_start_point, which ROS 2's filter does not have": Case(
        "neighbors: 20}",
        "neighbors: 20, remove_shadow_start_point: true}",
        15,
        f"{NODE}.filter2.params.remove_shadow_start_point",
        "ScanShadowsFilter reads no parameter 'remove_shadow_start_point': ROS 2 ignores it",
        "known keys here",
    ),
    "a window no scan is worth": Case(
        "window: 1,",
        "window: 500,",
        15,
        f"{NODE}.filter2.params.window",
        "window 500 is above 100, the most the gate runs",
        "write window from 1 to 100",
    ),
    "a gap in the filters' numbers": Case(
        "    filter3:",
        "    filter5:",
        16,
        f"{NODE}.filter5",
        "filter5 follows no filter3: ROS 2's chain stops at the first filterN it does not find",
        "number the filters filter1, filter2, ... without a gap",
    ),
    "a filter without its type": Case(
        "      type: laser_filters/LaserScanRangeFilter\n",
        "",
        4,
        f"{NODE}.filter1.type",
        "type is missing",
        "write filter1.name and filter1.type, both required",
    ),
    "two filters of one name": Case(
        "name: shadows",
        "name: range",
        13,
        f"{NODE}.filter2.name",
        "a filter before this one is named 'range' too",
        "give each filter of the chain its own name",
    ),
    "a misspelt node parameter": Case(
        "tf_message_filter_target_frame:",
        "tf_message_filter_target:",
        3,
        f"{NODE}.tf_message_filter_target",
        "unknown parameter 'tf_message_filter_target' of the chain node",
        "did you mean 'tf_message_filter_target_frame'?",
    ),
    "a misspelt key of a filter": Case(
        "      params:\n        lower",
        "      parmas:\n        lower",
        7,
        f"{NODE}.filter1.parmas",
        "unknown key 'parmas' of a filter's name, type and params",
        "did you mean 'params'?",
    ),
    "a median of no observation": Case(
        "number_of_observations: 3",
        "number_of_observations: 0",
        35,
        f"{NODE}.filter4.params.range_filter_chain.filter1.params.number_of_observations",
        "number_of_observations 0 keeps no observation",
        "write number_of_observations: 1 or more",
    ),
    "a scan filter in a median's chain": Case(
        "type: filters/MultiChannelMedianFilterFloat",
        "type: laser_filters/LaserScanRangeFilter",
        34,
        f"{NODE}.filter4.params.range_filter_chain.filter1.type",
        "'laser_filters/LaserScanRangeFilter' is no filter type the gate imitates",
        "the gate imitates filters/MultiChannelMeanFilterDouble",
    ),
    "a second chain node": Case(
        "            params: {number_of_observations: 3}\n",
        "            params: {number_of_observations: 3}\n" + SECOND_NODE,
        38,
        "other_chain.ros__parameters",
        "other_chain sets a filter chain beside scan_to_scan_filter_chain's",
        "keep the node that filters the scan your stack reads",
    ),
}
ROS1_CASES = {
    "angular bounds without lower_angle, which ROS 1 needs": Case(
        "    lower_angle: -1.5\n",
        "",
        6,
        "scan_filter_chain[1].params.lower_angle",
        "lower_angle is missing: without it ROS 1's filter does not configure "
        "(angular_bounds_filter.h:56-59 at laser_filters noetic-devel 75913d51)",
        "write lower_angle in the filter's params",
    ),
    "a double where ROS 1 reads an integer": Case(
        "filter_window: 2}",
        "filter_window: 2.0}",
        13,
        "scan_filter_chain[2].params.filter_window",
        "filter_window is the double 2: ROS 1 reads it only from an integer",
        "write 2",
    ),
    "a speckle filter of no type": Case(
        "filter_type: 1,",
        "filter_type: 2,",
        13,
        "scan_filter_chain[2].params.filter_type",
        "filter_type 2 is neither 0 (distance) nor 1 (radius outlier)",
        "write filter_type: 0 or 1",
    ),
    "a footprint of no size": Case(
        "inscribed_radius: 0.5",
        "inscribed_radius: 0.0",
        16,
        "scan_filter_chain[3].params.inscribed_radius",
        "inscribed_radius 0 m: the filter removes no reading",
        "write the radius (m)",
    ),
    "a median of unsaid length": Case(
        "params: {number_of_observations: 5}",
        "params: {}",
        21,
        "scan_filter_chain[4].params.internal_filter[0].params.number_of_observations",
        "number_of_observations is missing: without it ROS 1's filter does not configure",
        "write number_of_observations in the filter's params",
    ),
    "an array filter without its intensity chain": Case(
        "  type: laser_filters/LaserMedianFilter\n  params:\n    internal_filter:",
        "  type: laser_filters/LaserArrayFilter\n  params:\n    range_filter_chain:",
        17,
        "scan_filter_chain[4].params.intensity_filter_chain",
        "intensity_filter_chain is missing: without it ROS 1's filter calls both chains on "
        "every scan, and crashes on the one left out (array_filter.cpp:44-51, :106-107",
        "write intensity_filter_chain in the filter's params",
    ),
    "the deprecated filter_chain beside scan_filter_chain": Case(
        "        params: {number_of_observations: 5}\n",
        "        params: {number_of_observations: 5}\nfilter_chain: []\n",
        1,
        "scan_filter_chain",
        "scan_filter_chain is set beside filter_chain: ROS 1's node runs the deprecated "
        "filter_chain alone",
        "keep one chain, under scan_filter_chain",
    ),
    "a filter without its name": Case(
        "- name: speckle\n  type",
        "- type",
        11,
        "scan_filter_chain[2].name",
        "name is missing",
        "write each filter's name, type and params",
    ),
    "a chain that is no list": Case(
        ROS1,
        "scan_filter_chain: {name: range, type: laser_filters/LaserScanRangeFilter}\n",
        1,
        "scan_filter_chain",
        "expected a list of filters",
        "write one `- item` per line",
    ),
    "a chain of no filter": Case(
        ROS1,
        "scan_filter_chain: []\n",
        1,
        "scan_filter_chain",
        "the chain holds no filter: it passes every scan on unchanged",
        "leave scan_filters out",
    ),
    "a file of neither ROS": Case(
        ROS1,
        "laser_filter:\n  chain: []\n",
        1,
        "",
        "this is neither a ROS 1 chain (scan_filter_chain: a list of filters) nor a ROS 2 "
        "params file",
        "write the file your chain node loads",
    ),
}


def assert_case(tmp_path: Path, base: str, case: Case) -> None:
    assert case.old in base
    with pytest.raises(SpecError) as raised:
        load(tmp_path, base.replace(case.old, case.new, 1))
    error = raised.value
    assert error.location.path.name == "filters.yaml"
    assert (error.location.line, error.field) == (case.line, case.field)
    assert case.problem in error.problem
    assert case.fix in error.fix


@pytest.mark.parametrize("case", ROS2_CASES.values(), ids=ROS2_CASES.keys())
def test_a_broken_ros_2_chain_is_one_error_naming_its_line_parameter_and_fix(
    tmp_path: Path, case: Case
) -> None:
    assert_case(tmp_path, ROS2, case)


@pytest.mark.parametrize("case", ROS1_CASES.values(), ids=ROS1_CASES.keys())
def test_a_broken_ros_1_chain_is_one_error_naming_its_line_parameter_and_fix(
    tmp_path: Path, case: Case
) -> None:
    assert_case(tmp_path, ROS1, case)
