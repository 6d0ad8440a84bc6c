"""A scanner a pairs file reads from a recording of the real scanner:
`{bag: {path: recordings/front.mcap, topic: /scan}}`, the profile its LaserScan messages show
(`inputs/inferred.py`), optionally with profile fields and `pose:` that override it, as they
override a catalogue `model:`."""

from __future__ import annotations

import os
from pathlib import Path

from pytest_lasertest.inputs.bags import BagError
from pytest_lasertest.inputs.inferred import profile_fields, profile_from_bag
from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.inputs.profile import build_profile
from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.pairsfile.described import DESCRIPTION_KEYS
from pytest_lasertest.pairsfile.scanners import Scanner

BAG_KEYS = ("path", "topic")
BAG_FIX = "write `bag: {path: recordings/front.mcap, topic: /scan}`, the path relative to this file"


def read_recorded(node: SpecNode, fields: dict[str, SpecNode], mount: Pose3D) -> Scanner:
    """The scanner `fields["bag"]` names; the scanner's other fields override what the bag
    shows. A bag that gives no profile is an error at the `bag:` line (or its `topic:`)."""
    bag = fields.pop("bag")
    _refuse_other_sources(fields)
    if isinstance(bag.value, str):
        raise bag.error("`bag:` takes the bag's path and its topic", BAG_FIX)
    entries = bag.mapping(BAG_KEYS, what="the bag's path and topic")
    if "path" not in entries:
        raise bag.missing("path", BAG_FIX)
    path_node, topic_node = entries["path"], entries.get("topic")
    path = _path(path_node, node.location.path.parent)
    topic = topic_node.text(what="a topic name", fix=BAG_FIX) if topic_node else None
    try:
        inferred = profile_from_bag(path, topic)
    except BagError as error:
        culprit = topic_node if error.about == "topic" and topic_node else bag
        raise culprit.error(f"{path_node.value}: {error.problem}", error.fix) from None
    shown = {
        key: SpecNode(value, bag.location, bag.field)
        for key, value in profile_fields(inferred.profile).items()
    }
    profile = build_profile({**shown, **fields}, node, mount)
    return Scanner(profile, None, f"bag {path_node.value} {inferred.topic}")


def _refuse_other_sources(fields: dict[str, SpecNode]) -> None:
    for key in ("model", *DESCRIPTION_KEYS):
        if key in fields:
            raise fields[key].error(
                f"a scanner read from a `bag:` takes no `{key}:`",
                "read the scanner from a bag, a catalogue `model:` or a description, one of them",
            )


def _path(node: SpecNode, here: Path) -> Path:
    """The bag's path as the pairs file writes it, relative to its directory."""
    text = node.text(what="a bag's path", fix=BAG_FIX)
    if "\x00" in text:
        raise node.error(
            f"the path {text!r} holds a NUL character, which no file name can hold",
            "write the path as it is on disk",
        )
    return Path(os.path.abspath(here / text))
