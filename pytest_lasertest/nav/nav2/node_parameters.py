"""One node's parameters from a Nav2 params file, read typed: each read checked (its type,
its sign, figures beyond any real configuration) and marked used, so that what no read asked
for can be listed as not read."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from pytest_lasertest.model.figures import shown
from pytest_lasertest.model.robot import ParameterValue

# Rates, sizes, counts and times that must be above zero; the rest may be zero.
POSITIVE = frozenset(
    {
        "controller_frequency",
        "cycle_frequency",
        "update_frequency",
        "width",
        "height",
        "resolution",
        "time_steps",
        "model_dt",
        "batch_size",
        "iteration_count",
        "temperature",
        "vx_max",
        "wz_max",
        "smoothing_frequency",
        "time_before_collision",
        "simulation_time_step",
        "min_points",
        "robot_radius",
        "sim_time",
        "linear_granularity",
        "angular_granularity",
    }
)
# Lower limits and decelerations, negative by nature.
MAY_BE_NEGATIVE = frozenset(
    {
        "vx_min",
        "ax_min",
        "ay_min",
        "min_velocity",
        "max_decel",
        "min_vel_x",
        "min_vel_y",
        "decel_lim_x",
        "decel_lim_y",
        "decel_lim_theta",
        "lookahead_time",
        "unknown_cost_value",  # -1, as a map's int8 writes unknown, reads 255 as a byte
        # DWB's speed limits: a negative one is no limit (XYThetaIterator::isValidSpeed,
        # dwb_plugins/src/xy_theta_iterator.cpp:99-104 at humble 3c3db59d).
        "max_speed_xy",
        "min_speed_xy",
        "min_speed_theta",
    }
)
# Past these a figure is a typo, and the cycle would take seconds and gigabytes.
LARGEST = {"batch_size": 100_000, "time_steps": 1_000, "iteration_count": 100}
# Hz: no navigation stack's clock runs faster; the simulation steps at 50 Hz.
FASTEST = 1_000.0
# Beyond this any figure of these files is a typo: a kilometre-wide costmap is 1e3 m.
HUGE = 1e12
# The figures that may be infinite: ranges and heights, as "no limit".
MAY_BE_INFINITE = frozenset(
    {"obstacle_max_range", "raytrace_max_range", "max_obstacle_height", "transform_tolerance"}
)


class ParameterProblem(ValueError):
    """A parameter we cannot run as given: which, what is wrong and how to fix it."""

    def __init__(self, node: str, name: str, problem: str, fix: str) -> None:
        super().__init__(f"{node}: {name}: {problem}")
        self.node, self.name, self.problem, self.fix = node, name, problem, fix


class NodeParameters:
    """One node's parameters, read typed; each read is marked used."""

    def __init__(
        self,
        node: str,
        values: dict[str, ParameterValue],
        used: set[tuple[str, str]],
        asked: set[tuple[str, str]] | None = None,
    ) -> None:
        self.node, self.values, self.used = node, values, used
        self.asked = set() if asked is None else asked  # every name read for, set or not

    def problem(self, name: str, problem: str, fix: str) -> ParameterProblem:
        return ParameterProblem(self.node, name, problem, fix)

    def get(self, name: str) -> ParameterValue | None:
        self.asked.add((self.node, name))
        if name not in self.values:
            return None
        self.used.add((self.node, name))
        return self.values[name]

    def number(self, name: str, default: float, whole: bool = False) -> float:
        value = self.get(name)
        if value is None:
            return default
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.problem(name, f"is a number, not {value!r}", "write a number")
        if isinstance(value, int) and abs(value) > HUGE:
            raise self.problem(
                name, f"{shown(value)} is beyond any Nav2 configuration", "check the figure"
            )
        if whole and value != int(value):
            raise self.problem(name, f"is a whole number, not {value}", "write a whole number")
        return _checked(self, name, float(value))

    def flag(self, name: str, default: bool) -> bool:
        value = self.get(name)
        if value is None:
            return default
        if not isinstance(value, bool):
            raise self.problem(name, f"is true or false, not {value!r}", "write true or false")
        return value

    def text(self, name: str, default: str) -> str:
        value = self.get(name)
        if value is None:
            return default
        if not isinstance(value, str):
            raise self.problem(name, f"is a string, not {value!r}", "write a string")
        return value

    def names(self, name: str, default: tuple[str, ...]) -> tuple[str, ...]:
        """A list of names, or one string of them separated by spaces (as
        observation_sources is written)."""
        value = self.get(name)
        if value is None:
            return default
        if isinstance(value, str):
            return tuple(value.split())
        if isinstance(value, tuple) and all(isinstance(item, str) for item in value):
            return tuple(str(item) for item in value)
        raise self.problem(name, f"is a list of names, not {value!r}", 'write e.g. ["FollowPath"]')

    def numbers(self, name: str, default: tuple[float, ...]) -> tuple[float, ...]:
        value = self.get(name)
        if value is None:
            return default
        if not (
            isinstance(value, tuple)
            and len(value) == len(default)
            and all(isinstance(v, int | float) and not isinstance(v, bool) for v in value)
        ):
            raise self.problem(
                name,
                f"is a list of {len(default)} numbers, not {value!r}",
                "write e.g. [0.5, 0.0, 2.0]",
            )
        if not all(abs(v) <= HUGE for v in value):  # type: ignore[arg-type]
            raise self.problem(
                name, f"holds a figure that is not a finite number: {value!r}", "check it"
            )
        return tuple(float(v) for v in value)  # type: ignore[arg-type]

    def plugin(self, name: str, imitated: tuple[str, ...], what: str, default: str | None) -> str:
        """`<name>.plugin` (`pkg::Class` or `pkg/Class`), which must be one we imitate; `default`
        where Nav2 declares one (for a plugin list left as its default), else the file must set
        it (nav2_util::get_plugin_type_param, node_utils.hpp:251-269 at jazzy f4108e5b)."""
        kind = self.text(f"{name}.plugin", default or "").replace("/", "::")
        if not kind:
            raise self.problem(
                f"{name}.plugin",
                "is not set: Nav2 refuses to configure without it (\"No 'plugin' param\")",
                f"write {name}.plugin: {' or '.join(imitated)}",
            )
        if kind not in imitated:
            raise self.problem(
                f"{name}.plugin",
                f"{kind} is a {what} the Nav2 imitation does not have",
                f"use {' or '.join(imitated)}, or drive with your own controller",
            )
        return kind

    def fields(
        self,
        prefix: str,
        values: Any,
        renamed: dict[str, str] | None = None,
        exclude: tuple[str, ...] = (),
    ) -> Any:
        """A dataclass with each of its fields the node sets under `prefix` read at its type;
        `renamed` maps the file's names to the fields' (a field renamed is read by those names
        alone); the fields in `exclude` are not the node's parameters."""
        names = {f.name: f.name for f in dataclasses.fields(values) if f.name not in exclude}
        for attribute in (renamed or {}).values():
            names.pop(attribute, None)
        names.update(renamed or {})
        changes: dict[str, float | bool] = {}
        for name, attribute in names.items():
            current = getattr(values, attribute)
            key = f"{prefix}{name}"
            if isinstance(current, bool):
                changes[attribute] = self.flag(key, current)
            elif isinstance(current, int | float):
                found = self.number(key, current, whole=isinstance(current, int))
                changes[attribute] = int(found) if isinstance(current, int) else found
        return dataclasses.replace(values, **changes)


def _checked(node: NodeParameters, name: str, value: float) -> float:
    leaf = name.rsplit(".", 1)[-1]
    if math.isnan(value) or (math.isinf(value) and leaf not in MAY_BE_INFINITE):
        raise node.problem(name, f"must be a finite number, not {value}", "write a number")
    if leaf.endswith("frequency") and value > FASTEST:
        raise node.problem(
            name,
            f"{value:g} Hz is beyond any navigation stack's clock (at most {FASTEST:g} Hz here)",
            "check the figure: Nav2's servers run at 1 to 100 Hz",
        )
    if leaf in POSITIVE and value <= 0.0:
        raise node.problem(name, f"must be above zero, not {value}", f"write a positive {leaf}")
    if leaf not in MAY_BE_NEGATIVE and value < 0.0:
        raise node.problem(name, f"cannot be negative ({value})", "write zero or more")
    if leaf in LARGEST and value > LARGEST[leaf]:
        raise node.problem(
            name,
            f"{value:g} is beyond any Nav2 configuration (at most {LARGEST[leaf]})",
            "check the figure: the controller would take seconds per cycle",
        )
    return value
