"""A filter parameter's value as each ROS reads it from a params file: a double, an integer or
true or false, each refused where that ROS refuses it (the chain's node does not start) or
ignores it (the filter keeps its default), at the value's line.
"""

from __future__ import annotations

import math

from pytest_lasertest.inputs.node import SpecNode, describe
from pytest_lasertest.nav.laser_filters.params import Param
from pytest_lasertest.nav.laser_filters.scan_filters import Ros

# The largest magnitude of a number a filter reads: beyond any scanner's reach in m, any angle.
MAX_MAGNITUDE = 1e6


def double_value(ros: Ros, key: str, param: Param, node: SpecNode) -> float:
    """A double parameter: finite and within MAX_MAGNITUDE unless it is a replacement value."""
    value = node.value
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise node.error(f"{key} is a number, not {describe(value)}", "write a number, e.g. 0.5")
    if isinstance(value, int) and ros == "ros2":
        raise node.error(
            f"{key} is the integer {value}: ROS 2 declares {key} a double (filter_base.hpp:181-184 "
            "at ros/filters ros2 e33463ae) and refuses an integer for it, so the chain's node "
            "does not start",
            f"write {value}.0",
        )
    number = float(value)
    if not math.isfinite(number) and not param.special:
        raise node.error(
            f"{key} is {describe(value)}: the filter compares readings with it, and NaN or "
            "infinity is meant only as a replacement value",
            "write a finite number",
        )
    if math.isfinite(number) and abs(number) > MAX_MAGNITUDE:
        raise node.error(
            f"{key} is {number:g}, beyond ±{MAX_MAGNITUDE:g}: no scanner reads that far, and no "
            "angle is that wide",
            "check the figure",
        )
    return number


def int_value(ros: Ros, key: str, node: SpecNode) -> int:
    """An integer parameter: a double, even a whole one, is refused (ROS 2) or ignored (ROS 1)."""
    value = node.value
    if isinstance(value, int) and not isinstance(value, bool):
        return value
    if isinstance(value, float) and value.is_integer():
        refused = (
            "ROS 1 reads it only from an integer (filter_base.hpp:184-200 at ros/filters "
            "noetic-devel 310202ed) and keeps its default"
            if ros == "ros1"
            else "ROS 2 declares it an integer (filter_base.hpp:191-194 at ros/filters ros2 "
            "e33463ae) and refuses a double for it, so the chain's node does not start"
        )
        raise node.error(f"{key} is the double {value:g}: {refused}", f"write {int(value)}")
    raise node.error(f"{key} is a whole number, not {describe(value)}", "write an integer, e.g. 1")


def bool_value(ros: Ros, key: str, node: SpecNode) -> bool:
    """A true-or-false parameter."""
    if isinstance(node.value, bool):
        return node.value
    reads = "ROS 1 reads it only from true or false" if ros == "ros1" else "ROS 2 refuses it"
    raise node.error(
        f"{key} is true or false, not {describe(node.value)}: {reads}", "write true or false"
    )
