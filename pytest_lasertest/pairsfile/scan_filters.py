"""`navigation: {scan_filters: FILE}`: a team's laser_filters params file, the chain its
scan_to_scan_filter_chain node runs on every scan before the stack sees it.

The file is read as the team's node reads it, in either ROS:

    scan_filter_chain:                      # ROS 1: a list (or the deprecated filter_chain)
      - name: range
        type: laser_filters/LaserScanRangeFilter
        params: {lower_threshold: 0.3, upper_threshold: 30.0}

    scan_to_scan_filter_chain:              # ROS 2: one node, filter1, filter2, ... in order
      ros__parameters:
        filter1:
          name: range
          type: laser_filters/LaserScanRangeFilter
          params: {lower_threshold: 0.3, upper_threshold: 30.0}

with the line of every value. A filter the gate does not imitate, a parameter the filter does
not read, a value of the wrong type, NaN or infinity where a number belongs, bounds that leave
the filter useless, or a file its node would not start with, is an error naming the file's
line, the parameter and the fix; a parameter left out takes what that ROS's laser_filters gives
it (`pytest_lasertest.nav.laser_filters.params`, which cites where).
"""

from __future__ import annotations

import dataclasses
import difflib
import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Generic, TypeVar

from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.inputs.node import SpecNode, read_root, suggest_key
from pytest_lasertest.inputs.yamlfile import YamlMap
from pytest_lasertest.nav.laser_filters import Filtered, NamedFilter, ScanFilterChain
from pytest_lasertest.nav.laser_filters.chain import ROS_NAMES
from pytest_lasertest.nav.laser_filters.filter_types import (
    CHANNEL_TYPES,
    FILTER_TYPES,
    NOT_IMITATED,
    REFUSED,
    ScanFilter,
)
from pytest_lasertest.nav.laser_filters.params import FilterProblem, FilterType, Param, Value
from pytest_lasertest.nav.laser_filters.scan_filters import Ros
from pytest_lasertest.nav.laser_filters.temporal import ChannelFilter
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.pairsfile.filter_values import bool_value, double_value, int_value
from pytest_lasertest.pairsfile.nav2_params import ros2_nodes
from pytest_lasertest.pairsfile.ros2_params import Group, as_group, as_value, group_of, node_of

SCAN_FILTERS = "scan_filters"
# ROS 1's chain parameter; the deprecated one wins where both are set
# (scan_to_scan_filter_chain.cpp:78-84 at laser_filters noetic-devel 75913d51).
ROS1_CHAINS = ("scan_filter_chain", "filter_chain")
# The node's own parameters beside the chain, which change nothing here: the simulated tf
# always has the laser's transform.
NODE_PARAMETERS = ("tf_message_filter_target_frame", "tf_message_filter_tolerance", "use_sim_time")
# The greatest number of filters one chain runs: each is a pass over every scan.
MAX_FILTERS = 100
_FILTER_KEY = re.compile(r"filter(\d+)\Z")
_FILTER_FIELDS = ("name", "type", "params")
T = TypeVar("T")


@dataclass(frozen=True)
class Made(Generic[T]):
    """One filter of a chain as read: its name's node, its type, and the filter made."""

    name: SpecNode
    type: str
    filter: T


def read_scan_filters(node: SpecNode) -> ScanFilterChain:
    """The chain of the laser_filters params file `node` names, relative to the file it is
    written in."""
    written = node.text(what="a path to a laser_filters params file")
    path = node.location.path.parent / written
    if not path.is_file():
        raise node.error(
            f"{path} does not exist",
            "give the path of the laser_filters params file your scan_to_scan_filter_chain node "
            "loads, relative to this file",
        )
    needs = "scan_filter_chain: (ROS 1) or a node's ros__parameters with filter1: (ROS 2)"
    root = read_root(path, what="laser_filters params file", needs=needs)
    if isinstance(root.value, YamlMap) and any(key in root.value for key in ROS1_CHAINS):
        ros: Ros = "ros1"
        filters = _ros1_chain(root)
    elif _holds_parameters(root.value):
        ros = "ros2"
        ros2_root = read_root(path, what="laser_filters params file", needs=needs, ros_params=True)
        filters = _ros2_chain(ros2_root)
    else:
        raise root.error(
            "this is neither a ROS 1 chain (scan_filter_chain: a list of filters) nor a ROS 2 "
            "params file (a node's ros__parameters)",
            f"write the file your chain node loads; it holds {needs}",
        )
    return ScanFilterChain(written, str(path.resolve()), ros, filters)


def with_scan_filters(choice: ControllerChoice, chain: ScanFilterChain | None) -> ControllerChoice:
    """The controller choice with `chain` in front of each controller it makes (the reports
    name the chain after the stack); `choice` itself where there is no chain."""
    if chain is None:
        return choice
    return dataclasses.replace(choice, factory=Filtered(choice.factory, chain), scan_filters=chain)


def without_scan_filters(choice: ControllerChoice) -> ControllerChoice:
    """The controller choice `with_scan_filters` made, with its chain taken out again."""
    if choice.scan_filters is None or not isinstance(choice.factory, Filtered):
        return choice
    return dataclasses.replace(choice, factory=choice.factory.inner, scan_filters=None)


def _ros1_chain(root: SpecNode) -> tuple[NamedFilter, ...]:
    fields = root.mapping((*ROS1_CHAINS, *NODE_PARAMETERS), what="the chain node's parameters")
    if all(key in fields for key in ROS1_CHAINS):
        raise fields["scan_filter_chain"].error(
            "scan_filter_chain is set beside filter_chain: ROS 1's node runs the deprecated "
            "filter_chain alone (scan_to_scan_filter_chain.cpp:78-84 at laser_filters "
            "noetic-devel 75913d51)",
            "keep one chain, under scan_filter_chain",
        )
    chain = fields.get("filter_chain") or fields["scan_filter_chain"]
    return _named(_ros1_filters(chain, FILTER_TYPES, "ros1"), chain)


def _ros1_filters(chain: SpecNode, types: Mapping[str, FilterType[T]], ros: Ros) -> list[Made[T]]:
    """Each filter of a ROS 1 chain, a list of {name, type, params}
    (filter_chain.hpp:142-252 at ros/filters noetic-devel 310202ed), by its name's node."""
    entries = chain.items(what="filters, each `{name: ..., type: ..., params: {...}}`")
    made: list[Made[T]] = []
    for entry in entries:
        fields = entry.mapping(_FILTER_FIELDS, what="a filter's name, type and params")
        for key in ("name", "type"):
            if key not in fields:
                raise entry.missing(key, "write each filter's name, type and params")
        params = fields["params"].entries(what="the filter's params") if "params" in fields else {}
        made.append(_filter(ros, fields["name"], fields["type"], params, entry, types))
    _check_names(ros, [filter.name for filter in made])
    return made


def _ros2_chain(root: SpecNode) -> tuple[NamedFilter, ...]:
    found = [(name, node) for name, node in ros2_nodes(root) if _holds_filters(node)]
    if not found:
        raise root.error(
            "no node of this file sets filter1: neither a ROS 1 chain (scan_filter_chain: a "
            "list) nor a ROS 2 scan_to_scan_filter_chain node",
            "write the file your chain node loads: `scan_to_scan_filter_chain:` then "
            "`ros__parameters:` then `filter1: {name: ..., type: ..., params: {...}}`",
        )
    if len(found) > 1:
        raise found[1][1].error(
            f"{found[1][0]} sets a filter chain beside {found[0][0]}'s: the gate runs one "
            "chain, in front of its one laser",
            "keep the node that filters the scan your stack reads",
        )
    group = group_of(found[0][1])
    _check_node_keys(group)
    return _named(_ros2_filters(group, FILTER_TYPES, "ros2"), group.node)


def _holds_parameters(value: object) -> bool:
    """Whether a YAML mapping holds a ROS 2 node's ros__parameters, at any depth."""
    if not isinstance(value, YamlMap):
        return False
    return "ros__parameters" in value or any(_holds_parameters(inner) for inner in value.values())


def _holds_filters(node: SpecNode) -> bool:
    keys = node.value.keys() if isinstance(node.value, YamlMap) else ()
    return any(_FILTER_KEY.match(key.split(".", 1)[0]) for key in keys)


def _ros2_filters(group: Group, types: Mapping[str, FilterType[T]], ros: Ros) -> list[Made[T]]:
    """Each filter of a ROS 2 chain, filter1, filter2, ... until the first missing one
    (filter_chain.hpp:62-165 at ros/filters ros2 e33463ae), by its name's node."""
    made: list[Made[T]] = []
    while f"filter{len(made) + 1}" in group.members:
        key = f"filter{len(made) + 1}"
        made.append(_ros2_filter(as_group(group.members[key], key), key, types, ros))
    for key, member in group.members.items():
        match = _FILTER_KEY.match(key)
        if match and int(match[1]) > len(made):
            raise node_of(member).error(
                f"{key} follows no filter{len(made) + 1}: ROS 2's chain stops at the first "
                "filterN it does not find (filter_chain.hpp:73-106 at ros/filters ros2 "
                f"e33463ae), so {key} never runs",
                "number the filters filter1, filter2, ... without a gap",
            )
    _check_names(ros, [filter.name for filter in made])
    return made


def _ros2_filter(entry: Group, key: str, types: Mapping[str, FilterType[T]], ros: Ros) -> Made[T]:
    """One `filterN` of a ROS 2 chain: its name, type and params."""
    _check_keys(entry, _FILTER_FIELDS, "a filter's name, type and params")
    fields = {field: entry.members[field] for field in _FILTER_FIELDS if field in entry.members}
    for field in ("name", "type"):
        if field not in fields:
            raise entry.node.missing(field, f"write {key}.name and {key}.type, both required")
    name, kind = as_value(fields["name"], "name"), as_value(fields["type"], "type")
    params = as_group(fields["params"], "params").members if "params" in fields else {}
    return _filter(ros, name, kind, params, entry.node, types)


def _named(made: list[Made[ScanFilter]], where: SpecNode) -> tuple[NamedFilter, ...]:
    """The chain's filters, in order; none, or too many, is an error at `where`."""
    if not made:
        raise where.error(
            "the chain holds no filter: it passes every scan on unchanged",
            "add the filters your chain node runs, or leave scan_filters out",
        )
    if len(made) > MAX_FILTERS:
        raise made[MAX_FILTERS].name.error(
            f"{len(made)} filters: more than the {MAX_FILTERS} one chain may run here, each a "
            "pass over every scan",
            f"keep at most {MAX_FILTERS} filters",
        )
    return tuple(NamedFilter(str(one.name.value), one.type, one.filter) for one in made)


def _filter(
    ros: Ros,
    name: SpecNode,
    kind: SpecNode,
    params: Mapping[str, SpecNode | Group],
    where: SpecNode,
    types: Mapping[str, FilterType[T]],
) -> Made[T]:
    """One filter, made of its params as `ros` reads them; the problem its params make is an
    error at the parameter's line (`_located`)."""
    name.text(what="the filter's name", fix="write a name, e.g. range")
    text = kind.text(
        what="the filter's type, package/Filter",
        fix="write e.g. laser_filters/LaserScanRangeFilter",
    )
    spec = _spec(ros, kind, text, types)
    values = _values(ros, _short(text), spec, params, where)
    try:
        return Made(name, text, types[text].build(ros, values))
    except FilterProblem as problem:
        raise _located(problem, params, spec, where) from None


def _values(
    ros: Ros,
    short: str,
    spec: Mapping[str, Param],
    params: Mapping[str, SpecNode | Group],
    where: SpecNode,
) -> dict[str, Value]:
    """Each parameter the filter reads: as the file sets it, else at its ROS's default; one the
    filter does not read, or one it cannot do without, is an error."""
    values: dict[str, Value] = {}
    for key, value in params.items():
        if key not in spec:
            raise node_of(value).error(
                f"{short} reads no parameter {key!r}: {ROS_NAMES[ros]} ignores it",
                suggest_key(key, spec, {}),
            )
        values[key] = _typed(ros, key, spec[key], value)
    for key, param in spec.items():
        if key in values:
            continue
        if param.default is None:
            raise SpecError(
                where.location,
                f"{where.field}.params.{key}",
                f"{key} is missing: {param.source}",
                f"write {key} in the filter's params",
            )
        values[key] = param.default
    return values


def _spec(
    ros: Ros, node: SpecNode, text: str, types: Mapping[str, FilterType[T]]
) -> Mapping[str, Param]:
    """The parameters `ros` reads for the filter type `text`; an error at `node` for a type
    the gate refuses or does not know."""
    refusal = REFUSED.get(text)
    kind = types.get(text)
    spec = kind.params[ros] if kind is not None else refusal
    if spec is None:
        raise _unknown(ros, node, text, types)
    if isinstance(spec, tuple):
        problem, fix = spec
        raise node.error(f"{_short(text)} is refused: {problem}", fix)
    return spec


def _unknown(ros: Ros, node: SpecNode, text: str, types: Mapping[str, object]) -> SpecError:
    imitated = ", ".join(sorted(types))
    if text in NOT_IMITATED:
        return node.error(
            f"{text} is a laser_filters filter the gate does not imitate",
            f"leave it out; the gate imitates {imitated}",
        )
    known = [*types, *(REFUSED if types is FILTER_TYPES else ()), *NOT_IMITATED]
    close = difflib.get_close_matches(text, known, n=1, cutoff=0.6)
    close += [name for name in known if "/" not in text and name.endswith(f"/{text}")]
    hint = f"did you mean {close[-1]!r}? " if close else ""
    form = "" if text.count("/") == 1 else " (a type is package/Filter, with one '/')"
    return node.error(
        f"{text!r} is no filter type the gate imitates{form}: {ROS_NAMES[ros]}'s chain does not "
        "start with it",
        f"{hint}the gate imitates {imitated}",
    )


def _typed(ros: Ros, key: str, param: Param, written: SpecNode | Group) -> Value:
    """The value of the parameter `key` as `ros` reads it, or an error at its line."""
    if param.kind == "chain":
        return _channel_chain(ros, key, written)
    node = as_value(written, key)
    if param.kind == "double":
        return double_value(ros, key, param, node)
    if param.kind == "int":
        return int_value(ros, key, node)
    if param.kind == "bool":
        return bool_value(ros, key, node)
    return node.text(what=f"{key}, a name", fix="write a frame's name, e.g. base_link")


def _channel_chain(ros: Ros, key: str, written: SpecNode | Group) -> tuple[ChannelFilter, ...]:
    """A LaserArrayFilter's (or LaserMedianFilter's) chain of multi-channel filters."""
    if ros == "ros1":
        made = _ros1_filters(as_value(written, key), CHANNEL_TYPES, ros)
    else:
        made = _ros2_filters(as_group(written, key), CHANNEL_TYPES, ros)
    return tuple(one.filter for one in made)


def _located(
    problem: FilterProblem,
    params: Mapping[str, SpecNode | Group],
    spec: Mapping[str, Param],
    where: SpecNode,
) -> SpecError:
    """The problem at the line of the last of its parameters the file sets, saying what each
    it leaves out was taken as; at the filter's line where it sets none of them."""
    given = [name for name in problem.params if name in params]
    left = [name for name in problem.params if name not in params]
    notes = "".join(f" ({name} is left out: {spec[name].source})" for name in left)
    fix = (
        f"set {' and '.join(left)} in the filter's params ({problem.fix})" if left else problem.fix
    )
    if given:
        return node_of(params[given[-1]]).error(problem.problem + notes, fix)
    field = f"{where.field}.params.{problem.params[-1]}"
    return SpecError(where.location, field, problem.problem + notes, fix)


def _check_keys(group: Group, allowed: tuple[str, ...], what: str) -> None:
    for key, member in group.members.items():
        if key not in allowed:
            raise node_of(member).error(
                f"unknown key {key!r} of {what}: ROS 2's chain reads name, type and params "
                "alone, and ignores it",
                suggest_key(key, allowed, {}),
            )


def _check_node_keys(group: Group) -> None:
    """The chain node's parameters: filter1, filter2, ... and its own (NODE_PARAMETERS)."""
    for key, member in group.members.items():
        if not _FILTER_KEY.match(key) and key not in NODE_PARAMETERS:
            raise node_of(member).error(
                f"unknown parameter {key!r} of the chain node: it reads filter1, filter2, ... "
                f"and {', '.join(NODE_PARAMETERS)}",
                suggest_key(key, ("filter1", *NODE_PARAMETERS), {}),
            )


def _check_names(ros: Ros, names: list[SpecNode]) -> None:
    seen: set[object] = set()
    for name in names:
        if name.value in seen:
            raise name.error(
                f"a filter before this one is named {name.value!r} too: {ROS_NAMES[ros]}'s chain "
                "refuses two filters of one name (filter_chain.hpp at ros/filters)",
                "give each filter of the chain its own name",
            )
        seen.add(name.value)


def _short(text: str) -> str:
    """`LaserScanRangeFilter` of `laser_filters/LaserScanRangeFilter`."""
    return text.rsplit("/", 1)[-1]
