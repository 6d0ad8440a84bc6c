"""A Nav2 params file, as ROS 2 writes one: each node's parameters under `ros__parameters`,
nodes perhaps within a namespace (`local_costmap: {local_costmap: {ros__parameters: ...}}`).

Read with the line of every value, handed to `pytest_lasertest.nav.nav2.params` to make Nav2's
settings, whose problems come back here as errors naming file, line and parameter.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from pathlib import Path

from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.inputs.node import SpecNode, describe, read_root
from pytest_lasertest.inputs.yamlfile import YamlList, YamlMap
from pytest_lasertest.model.robot import ParameterValue, Robot
from pytest_lasertest.nav.nav2.node_parameters import ParameterProblem
from pytest_lasertest.nav.nav2.params import WILDCARD, Parameter, configured
from pytest_lasertest.nav.nav2.settings import RELEASES, marking_of

PARAMETERS = "ros__parameters"
RELEASE_FIX = (
    f"write one of {', '.join(RELEASES)}, or a Jazzy release number from 1.3.0 to 1.3.13 "
    "(1.3.11 marks by cells without the pre-filter 1.3.12 added)"
)


# The keys that name Nav2's configuration: in a robot file, and in a pairs file's navigation:.
NAV2_KEYS = ("nav2", "nav2_version")


def read_nav2(fields: Mapping[str, SpecNode], robot: Robot) -> Robot:
    """The robot with the Nav2 params file and release `fields` name, over its own: a params
    file replaces the robot's whole, as a launch's params_file does."""
    release = robot.nav2_release
    if "nav2_version" in fields:
        release = read_release(fields["nav2_version"])
    if "nav2" not in fields:
        return dataclasses.replace(robot, nav2_release=release)
    parameters = load_nav2_file(fields["nav2"], release)
    path = nav2_path(fields["nav2"])
    return dataclasses.replace(robot, nav2=parameters, nav2_release=release, nav2_file=str(path))


def read_release(node: SpecNode) -> str:
    """`nav2_version:` a release whose marking rule we know."""
    release = str(node.value) if isinstance(node.value, int | float | str) else ""
    if marking_of(release) is None:
        raise node.error(f"{describe(node.value)} is not a Nav2 release we imitate", RELEASE_FIX)
    return release


def nav2_path(node: SpecNode) -> Path:
    """The params file `nav2:` names, relative to the file it is written in."""
    return node.location.path.parent / node.text(what="a path to a Nav2 params file")


def load_nav2_file(node: SpecNode, release: str) -> tuple[Parameter, ...]:
    """The params file `node` names, relative to the file it is written in, checked by making
    Nav2's settings from it."""
    path = nav2_path(node)
    if not path.is_file():
        raise node.error(
            f"{path} does not exist",
            "give the path of a Nav2 params YAML file (as nav2_bringup's nav2_params.yaml) "
            "relative to this file",
        )
    root = read_root(
        path, what="Nav2 params file", needs="nodes with ros__parameters", ros_params=True
    )
    where: dict[tuple[str, str], SpecNode] = {}
    for name, node_parameters in ros2_nodes(root):
        for key, value in _flattened(node_parameters, "").items():
            where[(name, key)] = value
    parameters = tuple((name, key, _value(value)) for (name, key), value in where.items())
    try:
        configured(parameters, release)
    except ParameterProblem as problem:
        raise _located(problem, where, root) from None
    return parameters


def ros2_nodes(root: SpecNode) -> list[tuple[str, SpecNode]]:
    """Each node's `ros__parameters`, by the node's name, its namespace dropped, as rcl's
    parser joins the keys above them (`robot1: {controller_server: ...}`, or
    `/robot1/controller_server:`; rcl_yaml_param_parser/src/parse.c parse_key at ros2/rcl
    bef8bd17); "/**" and a node named "*" stand for every node (`WILDCARD`). The gate drives
    one robot: a node set under two namespaces is an error."""
    found = _nodes_under(root, ())
    seen: dict[str, str] = {}
    for name, namespace, node in found:
        if name != WILDCARD and seen.setdefault(name, namespace) != namespace:
            raise node.error(
                f"{name} is set under two namespaces ({seen[name]} and {namespace}): the gate "
                "drives one robot",
                "keep the nodes of the robot the pairs file drives, in one namespace",
            )
    return [(name, node) for name, _, node in found]


def _nodes_under(node: SpecNode, parts: tuple[str, ...]) -> list[tuple[str, str, SpecNode]]:
    """(node name, namespace, its ros__parameters) for each node under `node`."""
    found = []
    for key, child in node.entries(what="nodes").items():
        entries = child.entries(what=f"{key}'s parameters or nodes")
        path = (*parts, *(part for part in key.split("/") if part))
        if PARAMETERS in entries:
            found.append((_node_name(path), "/" + "/".join(path[:-1]), entries[PARAMETERS]))
        elif _holds_nodes(child.value):
            found += _nodes_under(child, path)  # a namespace: each entry a node, or more
        else:
            raise child.missing(
                PARAMETERS,
                f"write each node's parameters under it: `{key}:` then, indented, "
                f"`{PARAMETERS}:` and the parameters below (a namespace holds such nodes)",
            )
    return found


def _holds_nodes(value: object) -> bool:
    """Whether a mapping is a namespace: each entry a node or a namespace, some node within."""
    if not isinstance(value, YamlMap) or not value:
        return False
    if PARAMETERS in value:
        return True
    return all(_holds_nodes(inner) for inner in value.values())


def _node_name(path: tuple[str, ...]) -> str:
    """The node a key path names: its last part, or every node for "/**" and "*"."""
    if not path or path[-1] in ("*", "**"):
        return WILDCARD
    return path[-1]


def _flattened(node: SpecNode, prefix: str) -> dict[str, SpecNode]:
    """A node's parameters by dotted name: nested mappings are names' parts."""
    flat: dict[str, SpecNode] = {}
    for key, child in node.entries(what="parameters").items():
        if isinstance(child.value, YamlMap):
            flat.update(_flattened(child, f"{prefix}{key}."))
        else:
            flat[f"{prefix}{key}"] = child
    return flat


def _value(node: SpecNode) -> ParameterValue:
    """A parameter's value: a number, true or false, a string, or a list of them."""
    value = node.value
    if isinstance(value, YamlList):
        return tuple(_value(item) for item in node.items(what="values"))
    if isinstance(value, bool | int | float | str):
        return value
    raise node.error(
        f"a parameter's value is a number, true or false, a string or a list, not "
        f"{describe(value)}",
        "write a value, or leave the parameter out to keep Nav2's default",
    )


def _located(
    problem: ParameterProblem, where: dict[tuple[str, str], SpecNode], root: SpecNode
) -> SpecError:
    """The problem at its parameter's line, or at its node's when the parameter is not set."""
    node = where.get((problem.node, problem.name)) or where.get((WILDCARD, problem.name))
    if node is not None:
        return node.error(problem.problem, problem.fix)
    field = f"{problem.node}.{problem.name}"
    in_node = next((n for (name, _), n in where.items() if name == problem.node), None)
    if in_node is None:
        missing = f"the file has no {problem.node} node: Nav2 runs it on its defaults"
        why = f"{problem.problem} ({missing})"
        return SpecError(root.location, field, why, problem.fix)
    return SpecError(in_node.location, field, problem.problem, problem.fix)
