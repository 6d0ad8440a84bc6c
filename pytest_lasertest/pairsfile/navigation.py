"""`navigation:` parameters: a robot's navigation.yaml, and a pairs file's overrides of it.

Both are written the same way, one mapping per section of `pytest_lasertest.nav.move_base.settings`,
with ROS's parameter names; a pairs file's may also name a Nav2 params file and release
(`nav2_params.py`) and a laser_filters params file (`scan_filters.py`):

    navigation:
      move_base: {back_up_recovery: true}
      dwa: {min_vel_x: -0.1}
      nav2: nav2_params.yaml
      nav2_version: jazzy
      scan_filters: laser_filters.yaml
"""

from __future__ import annotations

from pytest_lasertest.inputs.node import Bounds, SpecNode, read_root
from pytest_lasertest.nav.move_base.settings import (
    LIMITS,
    NavigationSettings,
    Parameter,
    clashes,
    parameter_types,
)
from pytest_lasertest.pairsfile.nav2_params import NAV2_KEYS

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


def read_navigation(
    node: SpecNode, under: tuple[Parameter, ...] = (), elsewhere: tuple[str, ...] = NAV2_KEYS
) -> tuple[Parameter, ...]:
    """The parameters a `navigation:` mapping sets, each checked against its section and its
    limits, and all of them, set over `under` (the robot's), checked together. The keys
    `elsewhere` (Nav2's, and a pairs file's scan_filters) are accepted and read by others."""
    types = parameter_types()
    sections = node.mapping((*types, *elsewhere), what="navigation sections")
    read: list[tuple[Parameter, SpecNode]] = []
    for section, values in sections.items():
        if section in elsewhere:
            continue  # read by read_nav2, or read_scan_filters
        known = types[section]
        for name, value in values.mapping(known, what=f"{section} parameters").items():
            read.append(((section, name, _value(value, known[name], section)), value))
    parameters = tuple(parameter for parameter, _ in read)
    for clash in clashes(NavigationSettings.from_parameters(under + parameters)):
        # The last of the clashing parameters this mapping sets; the robot's were checked alone.
        culprits = [child for (section, name, _), child in read if (section, name) in clash.names]
        raise (culprits[-1] if culprits else node).error(clash.problem, clash.fix)
    return parameters


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


def _value(node: SpecNode, kind: type, section: str) -> float | bool:
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
    limit = LIMITS[section][name]
    bounds = Bounds(limit.low, limit.high, limit.unit, limit.below, limit.why)
    bounds.check(node, value)
    return value
