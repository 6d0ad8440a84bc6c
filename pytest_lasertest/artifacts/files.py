"""Artifact paths derived from test ids, atomic writes, and writing a failure's files best-effort:
a file the operating system refuses is reported beside the failure, never instead of it."""

from __future__ import annotations

import errno
import hashlib
import os
import re
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import IO

from pytest_lasertest.inputs.errors import SpecError, display_path
from pytest_lasertest.reports.formats import Artifacts, Unwritten, json_text

# A file or folder name kept as the id writes it: characters every file system takes.
_PLAIN = re.compile(r"[A-Za-z0-9_.-]+")
# An item `NAME[PARAM]`, written `NAME_PARAM`; no '_' in PARAM, so the split is unambiguous.
_ITEM = re.compile(r"([A-Za-z0-9_.-]+)\[([A-Za-z0-9.-]+)\]")
_UNSAFE = re.compile(r"[^A-Za-z0-9_.-]+")
# Characters of a name before its suffix. File systems take 255 bytes; the longest suffix
# (.lasertest.yaml) and the temporary file's dots and random part add 30.
NAME_LIMIT = 120
DIGEST = 8  # hex digits of the hash that keeps shortened and cleaned names apart


def artifact_path(directory: Path, nodeid: str, suffix: str) -> Path:
    """Where the artifact of `nodeid` goes: one folder per pairs file, one file per item.

    Names are kept as the id writes them where every file system takes them; any other name
    (too long, or with characters such as spaces or non-ASCII letters) is cleaned, cut to
    NAME_LIMIT and told apart from the others by a short hash of what it was.
    """
    file_part, _, item_part = nodeid.partition("::")
    folders = [_folder_name(part) for part in Path(file_part).parts]
    return directory.joinpath(*folders, _item_name(item_part) + suffix)


def _folder_name(part: str) -> str:
    if part == "..":  # a pairs file outside the rootdir: stay inside the directory
        return "__"
    plain = _PLAIN.fullmatch(part) is not None and part != "."
    return part if plain and len(part) <= NAME_LIMIT else _hashed(part)


def _item_name(part: str) -> str:
    item = _ITEM.fullmatch(part)
    name = f"{item[1]}_{item[2]}" if item else part
    plain = item is not None or _PLAIN.fullmatch(part) is not None
    return name if plain and len(name) <= NAME_LIMIT else _hashed(part)


def _hashed(text: str) -> str:
    """`text` cleaned to safe characters, cut short, and a hash of all of it."""
    digest = hashlib.sha256(text.encode("utf-8", "surrogatepass")).hexdigest()[:DIGEST]
    stem = _UNSAFE.sub("_", text).strip("_.")[: NAME_LIMIT - DIGEST - 1]
    return f"{stem}-{digest}" if stem else digest


def write_best_effort(writes: tuple[tuple[Path, Callable[[], object]], ...]) -> Artifacts:
    """Run each write of a failure's artifacts in turn; one the operating system refuses (or a
    repro whose pairs file changed since it was read) is recorded as unwritten, with the fix,
    and the others are still written."""
    written: list[Path] = []
    unwritten: list[Unwritten] = []
    for path, write in writes:
        try:
            write()
        except OSError as error:
            unwritten.append(refused(path, error))
        except SpecError as error:
            unwritten.append(Unwritten(path, f"{error.location}: {error.problem}", error.fix))
        else:
            written.append(path)
    return Artifacts(tuple(written), tuple(unwritten))


def refused(path: Path, error: OSError) -> Unwritten:
    """The artifact at `path` the operating system refused with `error`, and what to do."""
    code = error.errno if error.errno is not None else 0
    name = errno.errorcode.get(code)
    reason = error.strerror or str(error)
    return Unwritten(path, f"{reason} [{name}]" if name else reason, _fix(path, code))


def _fix(path: Path, code: int) -> str:
    folder = path.parent
    if code in (errno.EACCES, errno.EPERM):
        return (
            f"let this user write to {display_path(folder)}, or give --laser-artifacts another "
            "directory"
        )
    if code == errno.EROFS:
        return "give --laser-artifacts a directory on a writable file system"
    if code in (errno.ENOSPC, errno.EDQUOT):
        return "free space on that disk, or give --laser-artifacts a directory on another one"
    if code == errno.EISDIR:
        return "a folder has this file's name: remove or rename it"
    if code in (errno.EEXIST, errno.ENOTDIR):
        blocking = _file_in_the_way(folder)
        return f"{display_path(blocking)} is a file where a folder must go: remove or rename it"
    if code == errno.ENAMETOOLONG:
        return "give --laser-artifacts a shorter directory path"
    return "check that path, or give --laser-artifacts another directory"


def _file_in_the_way(folder: Path) -> Path:
    """The first of `folder` and its parents, from the top, that exists but is no folder."""
    for candidate in (*reversed(folder.parents), folder):
        if candidate.exists() and not candidate.is_dir():
            return candidate
    return folder


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
    """Write `data` as standard JSON (`json_text`) at `path` atomically: readers never see half
    a file."""
    return write_text(path, json_text(data, sort_keys=True) + "\n")


def _umask() -> int:
    """The process's file mode creation mask."""
    # The only way to read it is to set it; set it straight back.
    mask = os.umask(0o022)
    os.umask(mask)
    return mask
