"""`navigation:` parameters: a robot's navigation.yaml, and a pairs file's overrides of it.

Both are written the same way, one mapping per section of `pytest_lasertest.nav.move_base.settings`,
with ROS's parameter names:

    navigation:
      move_base: {back_up_recovery: true}
      dwa: {min_vel_x: -0.1}
"""

from __future__ import annotations

from pytest_lasertest.inputs.node import SpecNode, read_root
from pytest_lasertest.nav.move_base.settings import Parameter, parameter_types

# A speed that may be negative: DWA's least forward speed reverses below zero.
MAY_BE_NEGATIVE = frozenset({"min_vel_x"})
# Rates, sizes and sample counts that must be above zero: the rest may also be zero.
MUST_BE_POSITIVE = frozenset(
    {
        "controller_frequency",
        "update_frequency",
        "size",
        "resolution",
        "sim_time",
        "sim_granularity",
        "angular_sim_granularity",
        "vx_samples",
        "vth_samples",
        "neutral_cost",
        "max_vel_x",
        "max_trans_vel",
        "back_up_speed",
    }
)


def read_navigation(node: SpecNode) -> tuple[Parameter, ...]:
    """The parameters a `navigation:` mapping sets, each checked against its section."""
    types = parameter_types()
    sections = node.mapping(types, what="navigation sections")
    parameters: list[Parameter] = []
    for section, values in sections.items():
        known = types[section]
        for name, value in values.mapping(known, what=f"{section} parameters").items():
            parameters.append((section, name, _value(value, known[name])))
    return tuple(parameters)


def load_navigation_file(node: SpecNode) -> tuple[Parameter, ...]:
    """The parameters of the navigation file a robot file names, relative to the robot file."""
    path = node.location.path.parent / node.text(what="a path to a navigation file")
    if not path.is_file():
        raise node.error(
            f"{path} does not exist",
            "give the path of a navigation YAML file relative to this robot file",
        )
    return read_navigation(
        read_root(path, what="navigation file", needs="sections such as move_base or dwa")
    )


def _value(node: SpecNode, kind: type) -> float | bool:
    """One parameter's value, of its type and in its range."""
    name = node.field.rsplit(".", 1)[-1]
    if kind is bool:
        if not isinstance(node.value, bool):
            raise node.error(f"{name} is true or false, not {node.value!r}", "write true or false")
        return node.value
    value: float = (
        node.whole_number() if kind is int else node.number("the unit ROS gives it (m, s, Hz, rad)")
    )
    if name in MUST_BE_POSITIVE and value <= 0:
        raise node.error(f"{name} must be above zero, not {value}", f"write a positive {name}")
    if name not in MAY_BE_NEGATIVE and value < 0:
        raise node.error(f"{name} cannot be negative ({value})", "write zero or more")
    return value
