"""Nav2 params files as the tests set them up: Jazzy's nav2_params.yaml (tests/data/nav2/) with
the nodes a test is about replaced by the parameters the test gives, the rest of such a node at
Nav2's code defaults, as a team's file that sets only those would leave them. An upstream unit
test builds its one node alone; the other nodes here are nav2_bringup's, so that the file is one
Nav2 runs."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import yaml

from pytest_lasertest.model.robot import ParameterValue
from pytest_lasertest.nav.nav2.params import Parameter, configure
from pytest_lasertest.nav.nav2.settings import Nav2Settings
from tests.helpers import REPO

BRINGUP = REPO / "tests" / "data" / "nav2" / "nav2_params.yaml"
Nodes = Mapping[str, Mapping[str, ParameterValue]]


def params_file(nodes: Nodes) -> tuple[Parameter, ...]:
    """nav2_params.yaml's parameters with each node of `nodes` set to its parameters alone."""
    kept = [(node, name, value) for node, name, value in _bringup() if node not in nodes]
    given = [
        (node, name, value) for node, values in nodes.items() for name, value in values.items()
    ]
    return (*kept, *given)


def nav2_settings(nodes: Nodes, release: str = "jazzy") -> Nav2Settings:
    """Nav2's settings from `params_file(nodes)` for `release`."""
    return configure(params_file(nodes), release).settings


def local_footprint(parameters: Mapping[str, ParameterValue]) -> tuple[tuple[float, float], ...]:
    """The local costmap's footprint (m) that a params file makes whose local_costmap sets
    `parameters` and nav2_params.yaml's layers (an upstream costmap test has Nav2's default
    layers, whose obstacle layer reads no source: one our reader refuses)."""
    layers = {name: value for name, value in bringup_node("local_costmap").items() if "." in name}
    local = {"plugins": bringup_node("local_costmap")["plugins"], **layers, **parameters}
    footprint = nav2_settings({"local_costmap": local}).local.footprint
    assert footprint is not None  # a params file's costmap has one
    return footprint


def bringup_node(node: str, drop: tuple[str, ...] = ()) -> dict[str, ParameterValue]:
    """nav2_params.yaml's parameters of `node`, less those named in `drop`: the rest of a node
    a test sets a few parameters of."""
    return {name: value for n, name, value in _bringup() if n == node and name not in drop}


def _bringup() -> list[Parameter]:
    text = yaml.safe_load(BRINGUP.read_text())
    parameters: list[Parameter] = []
    for key, section in text.items():
        inner = section if "ros__parameters" in section else section[key]
        for name, value in _flattened(inner["ros__parameters"], "").items():
            parameters.append((key, name, value))
    return parameters


def _flattened(values: dict[str, Any], prefix: str) -> dict[str, ParameterValue]:
    flat: dict[str, ParameterValue] = {}
    for key, value in values.items():
        if isinstance(value, dict):
            flat.update(_flattened(value, f"{prefix}{key}."))
        else:
            flat[f"{prefix}{key}"] = tuple(value) if isinstance(value, list) else value
    return flat
