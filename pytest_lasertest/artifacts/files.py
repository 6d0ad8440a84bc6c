"""Artifact paths derived from test ids, and atomic writes."""

from __future__ import annotations

import json
import os
import re
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import IO

_UNSAFE = re.compile(r"[^A-Za-z0-9_.-]+")


def artifact_path(directory: Path, nodeid: str, suffix: str) -> Path:
    """Where the artifact of `nodeid` goes: one folder per pairs file, one file per item."""
    file_part, _, item_part = nodeid.partition("::")
    folders = [_UNSAFE.sub("_", part).replace("..", "__") for part in Path(file_part).parts]
    return directory.joinpath(*folders, _UNSAFE.sub("_", item_part).strip("_") + suffix)


def write_atomically(path: Path, write: Callable[[IO[bytes]], None]) -> Path:
    """Let `write` fill a temporary file beside `path`, then rename it to `path`; returns `path`.

    Readers never see half a file, and a write that raises leaves the previous file (if any) in
    place and no temporary behind. Creates the parent directories.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    # Same directory, so the rename stays on one file system and is atomic; the dot hides it.
    descriptor, temporary = tempfile.mkstemp(
        dir=path.parent, prefix=f".{path.name}.", suffix=path.suffix
    )
    try:
        with os.fdopen(descriptor, "wb") as handle:
            # mkstemp makes the file 0o600; an artifact gets the mode any new file would get.
            os.chmod(temporary, 0o666 & ~_umask())
            write(handle)
        os.replace(temporary, path)
    except BaseException:
        os.unlink(temporary)
        raise
    return path


def write_text(path: Path, text: str) -> Path:
    """Write `text` as UTF-8 at `path` atomically; returns `path`."""
    data = text.encode("utf-8")

    def write(handle: IO[bytes]) -> None:
        handle.write(data)

    return write_atomically(path, write)


def write_json(path: Path, data: object) -> Path:
    """Write `data` as JSON at `path` atomically: readers never see half a file."""
    return write_text(path, json.dumps(data, indent=2, sort_keys=True) + "\n")


def _umask() -> int:
    """The process's file mode creation mask."""
    # The only way to read it is to set it; set it straight back.
    mask = os.umask(0o022)
    os.umask(mask)
    return mask
