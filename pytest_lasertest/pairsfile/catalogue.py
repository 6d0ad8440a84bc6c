"""The scanner catalogue: one YAML file of datasheet figures per real 2D scanner."""

from __future__ import annotations

import difflib
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache
from pathlib import Path

from pytest_lasertest.inputs.node import SpecNode, read_root
from pytest_lasertest.inputs.profile import build_profile
from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.pairsfile.bundled import LIDARS_DIR
from pytest_lasertest.pairsfile.scanners import PROFILE_KEYS, read_fields


@dataclass(frozen=True)
class CatalogueEntry:
    """One scanner model: its product name and its profile fields as written in its file."""

    key: str  # what `model:` names: the file's stem
    name: str
    fields: Mapping[str, SpecNode]
    node: SpecNode

    def profile(self, pose: Pose3D) -> LaserProfile:
        """The model's profile mounted at `pose`."""
        return build_profile(self.fields, self.node, pose)


@dataclass(frozen=True)
class Catalogue:
    """Scanner models by key."""

    entries: Mapping[str, CatalogueEntry]

    def find(self, node: SpecNode) -> CatalogueEntry:
        """The entry a `model:` value names, or an error with the closest names."""
        key = node.text(what="a model name", fix="`lasertest catalogue` lists the model names")
        if key in self.entries:
            return self.entries[key]
        close = difflib.get_close_matches(key, list(self.entries), n=3, cutoff=0.5)
        hint = f"did you mean {' or '.join(repr(c) for c in close)}? " if close else ""
        raise node.error(
            f"unknown scanner model {key!r}",
            f"{hint}`lasertest catalogue` lists the {len(self.entries)} models",
        )


@cache
def load_catalogue(directory: Path = LIDARS_DIR) -> Catalogue:
    """Every `*.yaml` model in `directory`, each checked to build a valid profile."""
    entries = {}
    for path in sorted(directory.glob("*.yaml")):
        node = read_root(path, what="scanner model file", needs="name and the profile fields")
        fields = read_fields(node, ("name", *PROFILE_KEYS))
        name_node = fields.pop("name", None)
        if name_node is None:
            raise node.missing("name", "write the product name, e.g. `name: SICK LMS111-10100`")
        entry = CatalogueEntry(path.stem, name_node.text(), fields, node)
        entry.profile(Pose3D())  # a broken model file fails where it is loaded, not where used
        entries[entry.key] = entry
    return Catalogue(entries)
