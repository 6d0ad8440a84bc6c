"""Artifact paths derived from test ids, and atomic writes."""

from __future__ import annotations

import json
import os
import re
import tempfile
from pathlib import Path

_UNSAFE = re.compile(r"[^A-Za-z0-9_.-]+")


def artifact_path(directory: Path, nodeid: str, suffix: str) -> Path:
    """Where the artifact of `nodeid` goes: one folder per pairs file, one file per item."""
    file_part, _, item_part = nodeid.partition("::")
    folders = [_UNSAFE.sub("_", part).replace("..", "__") for part in Path(file_part).parts]
    return directory.joinpath(*folders, _UNSAFE.sub("_", item_part).strip("_") + suffix)


def write_json(path: Path, data: object) -> Path:
    """Write `data` as JSON at `path` atomically: readers never see half a file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    descriptor, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.")
    try:
        with os.fdopen(descriptor, "w", encoding="utf-8") as handle:
            json.dump(data, handle, indent=2, sort_keys=True)
            handle.write("\n")
        os.replace(temporary, path)
    except BaseException:
        os.unlink(temporary)
        raise
    return path
