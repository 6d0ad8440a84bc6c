"""How laser_filters reads a filter's `params`, in ROS 1 and in ROS 2: a parameter's type and
the value a file that leaves it out gets, with the upstream line that sets it, the readers of
the values a filter type makes its filter of (`filter_types.py` holds each type's), and the
problems that make a filter useless or stop its node (`FilterProblem`, which the file's reader
places at the parameter's line).

ROS 1 is ros-perception/laser_filters noetic-devel 75913d51 on ros/filters noetic-devel
310202ed; ROS 2 is laser_filters ros2 905f5e9a on ros/filters ros2 e33463ae. They differ in
what a left-out parameter becomes: ROS 1's getParam leaves the filter's own default (its
dynamic_reconfigure default, or its code's), or fails the filter's configure; ROS 2's getParam
declares a left-out parameter with its type's zero, whatever the filter set before calling
it (filter_base.hpp:123-146, :160-194 at ros/filters e33463ae; laser_filters issue #172), so
that, say, a range filter without upper_threshold replaces every reading.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Generic, Literal, TypeVar

from pytest_lasertest.model.robot import ParameterValue
from pytest_lasertest.nav.laser_filters.scan_filters import Ros
from pytest_lasertest.nav.laser_filters.temporal import ChannelFilter

__all__ = [
    "FilterProblem",
    "FilterType",
    "Param",
    "Params",
    "Refusal",
    "Value",
]

Kind = Literal["double", "int", "bool", "string", "chain"]
Value = ParameterValue | tuple[ChannelFilter, ...]
T = TypeVar("T")

ROS1 = "noetic-devel 75913d51"
ROS2 = "ros2 905f5e9a"
# The type's zero ROS 2's getParam declares a left-out parameter with, and where.
_ZERO: dict[Kind, tuple[Value, str]] = {
    "double": (0.0, "filter_base.hpp:181-184"),
    "int": (0, "filter_base.hpp:191-194"),
    "bool": (False, "filter_base.hpp:171-174"),
    "string": ("", "filter_base.hpp:160-164"),
    "chain": ((), "filter_chain.hpp:104-106, a chain of no filters"),
}
# The most a window, a neighbourhood or a filter's memory may span: each beam or scan of it is a
# pass over every scan, and ROS 1's dynamic_reconfigure bounds window, neighbors and
# filter_window at 100 too (cfg/ScanShadowsFilter.cfg:45-46, cfg/SpeckleFilter.cfg:52).
MAX_SPAN = 100


class FilterProblem(Exception):
    """A filter's parameters that make it useless or stop its node: the parameters at fault
    (the last one the file sets is where the error points), what is wrong, and the fix."""

    def __init__(self, params: tuple[str, ...], problem: str, fix: str) -> None:
        super().__init__(problem)
        self.params, self.problem, self.fix = params, problem, fix


@dataclass(frozen=True)
class Param:
    """One parameter a filter reads: its ROS type, and what a file that leaves it out gets."""

    kind: Kind
    default: Value | None  # None: without it the filter does not configure
    source: str  # the upstream line that sets the default, or refuses the filter without it
    special: bool = False  # NaN and the infinities are values (a replacement value)


# Why the gate refuses a filter type, and what to write instead.
Refusal = tuple[str, str]
# By ROS: a filter type's parameters there, or why the gate refuses it there.
Params = Mapping[Ros, Mapping[str, Param] | Refusal]


@dataclass(frozen=True)
class FilterType(Generic[T]):
    """A filter type the gate imitates: its parameters in each ROS (or why it refuses it
    there), and how it makes the filter from them, the left-out ones at their defaults."""

    params: Params
    build: Callable[[Ros, Mapping[str, Value]], T]


def ros1(
    kind: Kind,
    default: Value | None,
    source: str,
    special: bool = False,
    need: str = "does not configure",
) -> Param:
    """A parameter as ROS 1's filter reads it: `default` where `source` (a file of laser_filters
    at noetic-devel 75913d51) sets it, or, with no default, what the filter does without it."""
    where = f"{source} at laser_filters {ROS1}"
    if default is None:
        return Param(kind, None, f"without it ROS 1's filter {need} ({where})", special)
    return Param(kind, default, f"ROS 1 takes {default!r} ({where})", special)


def ros2(kind: Kind, meant: str = "", special: bool = False) -> Param:
    """A parameter as ROS 2's filter reads it: its type's zero where left out; `meant`, what
    the filter's code set before getParam overwrote it, if anything."""
    zero, line = _ZERO[kind]
    where = f"{line} at ros/filters ros2 e33463ae"
    if kind == "chain":
        return Param(kind, zero, where)
    instead = f", not the {meant}" if meant else ""
    return Param(kind, zero, f"ROS 2's getParam declares it {zero!r} ({where}){instead}", special)


def as_number(values: Mapping[str, Value], name: str) -> float:
    value = values[name]
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise TypeError(f"{name} is {value!r}: the reader hands on numbers alone")
    return float(value)


def as_whole(values: Mapping[str, Value], name: str) -> int:
    value = values[name]
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"{name} is {value!r}: the reader hands on integers alone")
    return value


def as_flag(values: Mapping[str, Value], name: str) -> bool:
    value = values[name]
    if not isinstance(value, bool):
        raise TypeError(f"{name} is {value!r}: the reader hands on true or false alone")
    return value


def as_chain(values: Mapping[str, Value], name: str) -> tuple[ChannelFilter, ...]:
    value = values[name]
    if not isinstance(value, tuple):
        raise TypeError(f"{name} is {value!r}: the reader hands on a chain")
    return tuple(item for item in value if isinstance(item, ChannelFilter))


def as_span(values: Mapping[str, Value], name: str, least: int, why: str) -> int:
    """An integer parameter from `least` to MAX_SPAN."""
    value = as_whole(values, name)
    if value < least:
        raise FilterProblem((name,), f"{name} {value} {why}", f"write {name}: {least} or more")
    if value > MAX_SPAN:
        raise FilterProblem(
            (name,),
            f"{name} {value} is above {MAX_SPAN}, the most the gate runs: each one is a pass "
            "over every scan, and ROS 1's dynamic_reconfigure allows no more",
            f"write {name} from {least} to {MAX_SPAN}",
        )
    return value


def check_ordered(values: Mapping[str, Value], low: str, high: str, unit: str, why: str) -> None:
    """A problem where the `low` parameter is not below the `high` one."""
    if as_number(values, low) >= as_number(values, high):
        raise FilterProblem(
            (low, high),
            f"{low} {as_number(values, low):g} {unit} is not below {high} "
            f"{as_number(values, high):g} {unit}: {why}",
            f"make {low} less than {high}",
        )
