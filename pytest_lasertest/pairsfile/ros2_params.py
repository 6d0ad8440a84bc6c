"""ROS 2's parameters under one name, as rclcpp reads a params file: nested keys and dotted keys
alike (`filter1: {name: x}` and `filter1.name: x`), each member a value or a group, with the
line it is written on.
"""

from __future__ import annotations

from dataclasses import dataclass

from pytest_lasertest.inputs.node import SpecNode, describe
from pytest_lasertest.inputs.yamlfile import YamlMap


@dataclass(frozen=True)
class Group:
    """Parameters under one name, as ROS 2 reads nested keys and dotted keys alike
    (`filter1: {name: x}` and `filter1.name: x`): where the group is first written, and its
    members, each a value or a group."""

    node: SpecNode
    members: dict[str, SpecNode | Group]


def group_of(node: SpecNode) -> Group:
    """A mapping's parameters, nested keys and dotted keys alike (`Group`)."""
    group = Group(node, {})
    for key, child in node.entries(what="parameters").items():
        _insert(group, key.split("."), child)
    return group


def _insert(group: Group, parts: list[str], child: SpecNode) -> None:
    head, existing = parts[0], group.members.get(parts[0])
    if len(parts) == 1 and not isinstance(child.value, YamlMap):
        if existing is not None:
            raise child.error(f"{head} is set twice in this group", "set each parameter once")
        group.members[head] = child
        return
    if existing is not None and not isinstance(existing, Group):
        raise child.error(
            f"{head} is set both as a value and as a group of parameters", "set it once"
        )
    inner = existing if isinstance(existing, Group) else Group(child, {})
    group.members[head] = inner
    if len(parts) > 1:
        _insert(inner, parts[1:], child)
        return
    for key, grandchild in child.entries(what="parameters").items():
        _insert(inner, key.split("."), grandchild)


def as_group(member: SpecNode | Group, key: str) -> Group:
    if isinstance(member, Group):
        return member
    raise member.error(
        f"expected a mapping of {key}'s parameters, got {describe(member.value)}",
        "write `key: value` pairs, indented below this line",
    )


def as_value(member: SpecNode | Group, key: str) -> SpecNode:
    if isinstance(member, SpecNode):
        return member
    raise member.node.error(
        f"{key} is a mapping where a value belongs", f"write {key}: VALUE on one line"
    )


def node_of(member: SpecNode | Group) -> SpecNode:
    return member if isinstance(member, SpecNode) else member.node
