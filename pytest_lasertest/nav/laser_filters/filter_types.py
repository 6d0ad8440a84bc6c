"""The filter types the gate imitates, by their laser_filters names: each one's parameters in
ROS 1 and in ROS 2 (`params.py` says how a parameter is declared and what a file that leaves it
out gets), with the upstream line that sets each default, and how it makes the filter of them;
the filter types refused, with the reason, and those not imitated.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping

from pytest_lasertest.nav.laser_filters.params import (
    ROS1,
    ROS2,
    FilterProblem,
    FilterType,
    Param,
    Params,
    Refusal,
    Value,
    as_chain,
    as_flag,
    as_number,
    as_span,
    as_whole,
    check_ordered,
    ros1,
    ros2,
)
from pytest_lasertest.nav.laser_filters.scan_filters import (
    AngularBoundsFilter,
    AngularBoundsFilterInPlace,
    BoxFilter,
    FootprintFilter,
    InterpolationFilter,
    RangeFilter,
    Ros,
    ShadowDetector,
    ShadowsFilter,
    SpeckleFilter,
)
from pytest_lasertest.nav.laser_filters.temporal import ArrayFilter, ChannelFilter, Statistic

__all__ = [
    "BASE_FRAMES",
    "CHANNEL_TYPES",
    "FILTER_TYPES",
    "NOT_IMITATED",
    "REFUSED",
    "ScanFilter",
]

# A filter of a scan, as a chain runs it: one of the types below.
ScanFilter = (
    RangeFilter
    | AngularBoundsFilter
    | AngularBoundsFilterInPlace
    | BoxFilter
    | FootprintFilter
    | InterpolationFilter
    | SpeckleFilter
    | ShadowsFilter
    | ArrayFilter
)

# LaserScanRangeFilter: ROS 1's dynamic_reconfigure defaults (cfg/RangeFilter.cfg:43-53, the
# filter's config_ at range_filter.h:56); ROS 2's zeros over the code's (range_filter.h:60-77).
_RANGE: Params = {
    "ros1": {
        "lower_threshold": ros1("double", 0.0, "cfg/RangeFilter.cfg:43-44"),
        "upper_threshold": ros1("double", 100000.0, "cfg/RangeFilter.cfg:45-46"),
        "use_message_range_limits": ros1("bool", False, "cfg/RangeFilter.cfg:47"),
        "lower_replacement_value": ros1("double", 0.0, "cfg/RangeFilter.cfg:49-50", True),
        "upper_replacement_value": ros1("double", 100000.0, "cfg/RangeFilter.cfg:52-53", True),
    },
    "ros2": {
        "lower_threshold": ros2("double"),
        "upper_threshold": ros2("double", "100000 range_filter.h:75 sets"),
        "use_message_range_limits": ros2("bool"),
        "lower_replacement_value": ros2("double", "NaN range_filter.h:64 sets", True),
        "upper_replacement_value": ros2("double", "NaN range_filter.h:69 sets", True),
    },
}


def _range(ros: Ros, values: Mapping[str, Value]) -> RangeFilter:
    made = RangeFilter(
        as_number(values, "lower_threshold"),
        as_number(values, "upper_threshold"),
        as_flag(values, "use_message_range_limits"),
        as_number(values, "lower_replacement_value"),
        as_number(values, "upper_replacement_value"),
    )
    if not made.use_message_range_limits:
        why = "every reading is replaced, one at or below the lower, the rest at or above the upper"
        check_ordered(values, "lower_threshold", "upper_threshold", "m", why)
    return made


def _angles(lines: str) -> Params:
    """lower_angle and upper_angle: without either ROS 1's filter does not configure (`lines`);
    ROS 2's makes the same check, which never fails, as its getParam always answers."""
    return {
        "ros1": {name: ros1("double", None, lines) for name in ("lower_angle", "upper_angle")},
        "ros2": {name: ros2("double") for name in ("lower_angle", "upper_angle")},
    }


def _bounds(values: Mapping[str, Value], effect: str) -> tuple[float, float]:
    for name in ("lower_angle", "upper_angle"):
        if abs(as_number(values, name)) > 2 * math.pi:
            raise FilterProblem(
                (name,),
                f"{name} {as_number(values, name):g} rad is beyond a full turn",
                "write an angle in rad of the laser frame, within ±2π",
            )
    check_ordered(values, "lower_angle", "upper_angle", "rad", effect)
    return as_number(values, "lower_angle"), as_number(values, "upper_angle")


def _cut(ros: Ros, values: Mapping[str, Value]) -> AngularBoundsFilter:
    return AngularBoundsFilter(*_bounds(values, "the filter keeps at most one beam"))


def _in_place(ros: Ros, values: Mapping[str, Value]) -> AngularBoundsFilterInPlace:
    return AngularBoundsFilterInPlace(*_bounds(values, "the filter replaces no reading"))


# LaserScanBoxFilter: ROS 1's dynamic_reconfigure defaults (cfg/BoxFilter.cfg:7-21, the
# filter's config_ at box_filter.h:94); ROS 2 logs each left out (box_filter.h:75-121) but its
# getParam never fails, so the box is the zeros.
_AXES = ("min_x", "max_x", "min_y", "max_y", "min_z", "max_z")
_BOX: Params = {
    "ros1": {
        "box_frame": ros1("string", "base_link", "cfg/BoxFilter.cfg:7-8"),
        **{
            name: ros1("double", -1.0 if name.startswith("min") else 1.0, "cfg/BoxFilter.cfg:9-20")
            for name in _AXES
        },
        "invert": ros1("bool", False, "cfg/BoxFilter.cfg:21"),
    },
    "ros2": {
        "box_frame": ros2("string"),
        **{name: ros2("double") for name in _AXES},
        "invert": ros2("bool"),
    },
}
# The frames the gate knows the box may be in: the robot's base (base_footprint, at ground
# level, where the bundled robots' base_link also lies).
BASE_FRAMES = ("base_link", "base_footprint")


def _box(ros: Ros, values: Mapping[str, Value]) -> BoxFilter:
    frame = values["box_frame"]
    if frame not in BASE_FRAMES:
        missing = "the filter finds no transform to it, fails every update and the chain "
        missing += "publishes no scan (box_filter.h:137-147 at laser_filters ros2 905f5e9a)"
        why = missing if frame == "" else "the gate knows the robot's base frame alone"
        raise FilterProblem(("box_frame",), f"box_frame {frame!r}: {why}", "write base_link")
    for axis in "xyz":
        effect = "the box is empty: the filter removes no reading (with invert, every one)"
        check_ordered(values, f"min_{axis}", f"max_{axis}", "m", effect)
    low_x, high_x, low_y, high_y, low_z, high_z = (as_number(values, name) for name in _AXES)
    return BoxFilter(low_x, high_x, low_y, high_y, low_z, high_z, as_flag(values, "invert"))


_FOOTPRINT: Params = {
    "ros1": {"inscribed_radius": ros1("double", None, "footprint_filter.h:62-66")},
    "ros2": {"inscribed_radius": ros2("double")},
}


def _footprint(ros: Ros, values: Mapping[str, Value]) -> FootprintFilter:
    radius = as_number(values, "inscribed_radius")
    if radius <= 0:
        raise FilterProblem(
            ("inscribed_radius",),
            f"inscribed_radius {radius:g} m: the filter removes no reading",
            "write the radius (m) of the circle the robot's footprint holds",
        )
    return FootprintFilter(radius)


# LaserScanSpeckleFilter: ROS 1's dynamic_reconfigure defaults (cfg/SpeckleFilter.cfg:49-52,
# the filter's config_ at speckle_filter.h:170); ROS 2's zeros (speckle_filter.h:183-199).
_SPECKLE: Params = {
    "ros1": {
        "filter_type": ros1("int", 0, "cfg/SpeckleFilter.cfg:49"),
        "max_range": ros1("double", 2.0, "cfg/SpeckleFilter.cfg:50"),
        "max_range_difference": ros1("double", 0.4, "cfg/SpeckleFilter.cfg:51"),
        "filter_window": ros1("int", 4, "cfg/SpeckleFilter.cfg:52"),
    },
    "ros2": {
        "filter_type": ros2("int"),
        "max_range": ros2("double"),
        "max_range_difference": ros2("double"),
        "filter_window": ros2("int"),
    },
}


def _speckle(ros: Ros, values: Mapping[str, Value]) -> SpeckleFilter:
    kind = as_whole(values, "filter_type")
    if kind not in (0, 1):
        crash = ": the filter has no validator, and its first update crashes the node"
        raise FilterProblem(
            ("filter_type",),
            f"filter_type {kind} is neither 0 (distance) nor 1 (radius outlier)"
            + (crash if ros == "ros2" else ""),
            "write filter_type: 0 or 1",
        )
    window = as_span(values, "filter_window", 1, "marks no reading valid: every one becomes NaN")
    # ROS 1 picks its validator in the dynamic_reconfigure callback, which runs before the
    # filter reads its params (speckle_filter.cpp:63-69 at noetic-devel): filter_type from the
    # chain's params never takes effect, and the filter runs the default, distance (0).
    used = 0 if ros == "ros1" else kind
    return SpeckleFilter(ros, used, *_speckle_distances(values), window)


def _speckle_distances(values: Mapping[str, Value]) -> tuple[float, float]:
    """max_range and max_range_difference (m), each of a use."""
    reach, difference = as_number(values, "max_range"), as_number(values, "max_range_difference")
    if reach <= 0:
        raise FilterProblem(
            ("max_range",),
            f"max_range {reach:g} m: every reading lies beyond it and stays, so the filter "
            "removes nothing",
            "write the range (m) within which speckles are looked for, e.g. 2.0",
        )
    if difference < 0:
        raise FilterProblem(
            ("max_range_difference",),
            f"max_range_difference {difference:g} m is below zero: no two readings agree",
            "write a distance (m) of zero or more, e.g. 0.1",
        )
    return reach, difference


# ScanShadowsFilter: ROS 1 refuses to configure without the angles and window
# (scan_shadows_filter.cpp:54-68), defaults neighbors and remove_shadow_start_point
# (:69, :74); ROS 2's reads the same but its getParam never fails (scan_shadows_filter.h:75-94)
# and it has no remove_shadow_start_point.
_NEED = "scan_shadows_filter.cpp:54-68"
_SHADOWS: Params = {
    "ros1": {
        "min_angle": ros1("double", None, _NEED),
        "max_angle": ros1("double", None, _NEED),
        "window": ros1("int", None, _NEED),
        "neighbors": ros1("int", 0, "scan_shadows_filter.cpp:69"),
        "remove_shadow_start_point": ros1("bool", False, "scan_shadows_filter.cpp:74"),
    },
    "ros2": {
        "min_angle": ros2("double"),
        "max_angle": ros2("double"),
        "window": ros2("int"),
        "neighbors": ros2("int"),
    },
}


def _shadows(ros: Ros, values: Mapping[str, Value]) -> ShadowsFilter:
    detector = ShadowDetector(*(math.radians(angle) for angle in _shadow_angles(values)))
    window = as_span(values, "window", 1, "compares no readings: the filter removes nothing")
    neighbors = as_span(values, "neighbors", 0, "is below zero: the filter removes nothing")
    remove = ros == "ros1" and as_flag(values, "remove_shadow_start_point")
    if neighbors == 0 and not remove:
        raise FilterProblem(
            ("neighbors",),
            "neighbors 0: a shadow deletes only farther readings within 0 beams of it, none, "
            "and the filter removes nothing",
            "write neighbors: 1 or more"
            + (", or remove_shadow_start_point: true" if ros == "ros1" else ""),
        )
    return ShadowsFilter(detector, window, neighbors, remove)


def _shadow_angles(values: Mapping[str, Value]) -> tuple[float, float]:
    """min_angle and max_angle (degrees), where laser_filters keeps them."""
    for name, low, high in (("min_angle", 0.0, 90.0), ("max_angle", 90.0, 180.0)):
        angle = as_number(values, name)
        if not low <= angle <= high:
            forced = low if angle < low else high
            raise FilterProblem(
                (name,),
                f"{name} {angle:g}° is outside {low:g}-{high:g}°: laser_filters logs an error "
                f"and forces it to {forced:g}° (scan_shadows_filter.cpp:78-97 at {ROS1}; "
                f"scan_shadows_filter.h:96-115 at {ROS2})",
                f"write {name} from {low:g} to {high:g} (degrees)",
            )
    return as_number(values, "min_angle"), as_number(values, "max_angle")


_NONE: Params = {"ros1": {}, "ros2": {}}


def _interpolation(ros: Ros, values: Mapping[str, Value]) -> InterpolationFilter:
    return InterpolationFilter()


# LaserArrayFilter: ROS 1 calls both chains on every scan and crashes on one left out
# (array_filter.cpp:44-51, :106-107); ROS 2 configures each from its params, none if left out.
_CRASH = "array_filter.cpp:44-51, :106-107"
_CALLED = "calls both chains on every scan, and crashes on the one left out"
_ARRAY: Params = {
    "ros1": {
        name: ros1("chain", None, _CRASH, need=_CALLED)
        for name in ("range_filter_chain", "intensity_filter_chain")
    },
    "ros2": {"range_filter_chain": ros2("chain"), "intensity_filter_chain": ros2("chain")},
}


def _array(ros: Ros, values: Mapping[str, Value]) -> ArrayFilter:
    return ArrayFilter(as_chain(values, "range_filter_chain"))


_MEDIAN: Params = {
    "ros1": {"internal_filter": ros1("chain", None, "median_filter.cpp:44-48")},
    "ros2": (
        "ROS 2's LaserMedianFilter logs its deprecation through a logger it does not have yet "
        f"(median_filter.h:56 at laser_filters {ROS2}): making it crashes the node",
        "use laser_filters/LaserArrayFilter with a filters/MultiChannelMedianFilterFloat in its "
        "range_filter_chain",
    ),
}


def _median(ros: Ros, values: Mapping[str, Value]) -> ArrayFilter:
    return ArrayFilter(as_chain(values, "internal_filter"))


FILTER_TYPES: dict[str, FilterType[ScanFilter]] = {
    "laser_filters/LaserScanRangeFilter": FilterType(_RANGE, _range),
    "laser_filters/LaserScanAngularBoundsFilter": FilterType(
        _angles("angular_bounds_filter.h:56-59"), _cut
    ),
    "laser_filters/LaserScanAngularBoundsFilterInPlace": FilterType(
        _angles("angular_bounds_filter_in_place.h:56-59"), _in_place
    ),
    "laser_filters/LaserScanBoxFilter": FilterType(_BOX, _box),
    "laser_filters/LaserScanFootprintFilter": FilterType(_FOOTPRINT, _footprint),
    "laser_filters/LaserScanSpeckleFilter": FilterType(_SPECKLE, _speckle),
    "laser_filters/ScanShadowsFilter": FilterType(_SHADOWS, _shadows),
    "laser_filters/InterpolationFilter": FilterType(_NONE, _interpolation),
    "laser_filters/LaserArrayFilter": FilterType(_ARRAY, _array),
    "laser_filters/LaserMedianFilter": FilterType(_MEDIAN, _median),
}

# The filters the gate refuses in both ROSes, and why.
REFUSED: dict[str, Refusal] = {
    "laser_filters/LaserScanIntensityFilter": (
        "it keeps or removes readings by their intensities, and the simulated scanner publishes "
        "no intensities",
        "leave it out of the chain the gate runs: the simulated readings are what the scanner "
        "returns, with no intensity to judge them by",
    )
}

# laser_filters' other scan filters (laser_filters_plugins.xml at noetic-devel and ros2).
NOT_IMITATED = (
    "laser_filters/LaserScanMaskFilter",
    "laser_filters/LaserScanPolygonFilter",
    "laser_filters/StaticLaserScanPolygonFilter",
    "laser_filters/LaserScanSectorFilter",
    "laser_filters/ScanBlobFilter",
)

_OBSERVATIONS: Params = {
    "ros1": {
        "number_of_observations": Param(
            "int",
            None,
            "without it ROS 1's filter does not configure (mean.hpp:176-180, median.hpp:227-231 "
            "at ros/filters noetic-devel 310202ed)",
        )
    },
    "ros2": {"number_of_observations": ros2("int")},
}


def _channel(statistic: Statistic) -> Callable[[Ros, Mapping[str, Value]], ChannelFilter]:
    def build(ros: Ros, values: Mapping[str, Value]) -> ChannelFilter:
        why = "keeps no observation, and the filter fails every update"
        return ChannelFilter(statistic, as_span(values, "number_of_observations", 1, why))

    return build


_STATISTICS: tuple[tuple[str, Statistic], ...] = (("Mean", "mean"), ("Median", "median"))
# The filters package's multi-channel filters a LaserArrayFilter's chains may hold
# (default_plugins.xml at ros/filters ros2 and noetic-devel); Float and Double alike here.
CHANNEL_TYPES: dict[str, FilterType[ChannelFilter]] = {
    f"filters/MultiChannel{name}Filter{width}": FilterType(_OBSERVATIONS, _channel(statistic))
    for name, statistic in _STATISTICS
    for width in ("Float", "Double")
}
