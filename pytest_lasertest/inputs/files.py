"""A file the user named, read from disk, refused before it can hang the run or fill memory:
every description file, and every YAML file (pairs, robot, navigation, scanner).

Only a regular file of at most its kind's limit is read. It is opened without blocking and
checked on the open descriptor, so a FIFO (which would wait for a writer for ever), a device such
as /dev/zero (which never ends) or a file swapped for one between a check and the open is never
read. Every other reason the system gives (a symlink loop, no permission) is said in words.
"""

from __future__ import annotations

import errno
import os
import stat
from dataclasses import dataclass
from pathlib import Path

from pytest_lasertest.inputs.errors import display_path

# The largest description file read, the top file or one it includes: the real descriptions
# the gate is tested on are under 25 kB, a large generated URDF a few MB.
MAX_FILE_BYTES = 16 * 1024 * 1024  # bytes
_KINDS = {
    stat.S_IFIFO: "a FIFO (named pipe), which would wait for a writer for ever",
    stat.S_IFCHR: "a character device, which may never end",
    stat.S_IFBLK: "a block device",
    stat.S_IFSOCK: "a socket",
}


@dataclass(frozen=True)
class FileKind:
    """What kind of file is read, the most of it read, and the fixes a refusal gives."""

    name: str  # "a description file"
    limit: int  # bytes
    fix: str  # when it is no regular file, or cannot be read
    large: str  # when it is larger than `limit`


DESCRIPTION = FileKind(
    "a description file",
    MAX_FILE_BYTES,
    "point `urdf:` (or the include) at the description file itself",
    "point `urdf:` at the robot's description; a description this large is not one (robot "
    "descriptions are kilobytes; meshes belong in their own files)",
)


class UnreadableFile(OSError):
    """A file that exists but is not read: `problem` says why, naming the file;
    `fix` how to fix it. An OSError, so that xacro reports it as the include it could not
    open."""

    def __init__(self, path: Path, problem: str, fix: str) -> None:
        super().__init__(errno.EINVAL, problem, str(path))
        self.problem = problem
        self.fix = fix


def _refused(path: Path, phrase: str, fix: str) -> UnreadableFile:
    return UnreadableFile(path, f"{display_path(path)} {phrase}", fix)


def read_regular_file(path: Path, kind: FileKind = DESCRIPTION) -> bytes:
    """The bytes of the regular file at `path`, at most `kind.limit`; FileNotFoundError when
    there is none, UnreadableFile when it is something else (a directory, a FIFO), too large, or
    cannot be read."""
    fix = kind.fix
    try:
        descriptor = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except (FileNotFoundError, NotADirectoryError):
        raise FileNotFoundError(errno.ENOENT, f"{path} does not exist", str(path)) from None
    except OSError as error:
        raise _unopenable(path, error, fix) from None
    except ValueError:  # a NUL character in the name
        raise _refused(path, "names no file: its name holds a NUL character", fix) from None
    try:
        _check_kind(path, os.fstat(descriptor).st_mode, fix)
        # One byte past the limit tells a file that grew after the check from one that fits.
        data = _read_at_most(descriptor, kind.limit + 1)
    finally:
        os.close(descriptor)
    if len(data) > kind.limit:
        size = _size_text(kind.limit)
        raise _refused(
            path, f"is larger than {size}, the most the gate reads of {kind.name}", kind.large
        )
    return data


def _check_kind(path: Path, mode: int, fix: str) -> None:
    if stat.S_ISDIR(mode):
        raise _refused(path, "is a directory, not a file", fix)
    if not stat.S_ISREG(mode):
        kind = _KINDS.get(stat.S_IFMT(mode), "not a regular file")
        raise _refused(path, f"is {kind}", fix)


def _size_text(limit: int) -> str:
    return f"{limit // (1024 * 1024)} MB" if limit >= 1024 * 1024 else f"{limit:,} bytes"


def _read_at_most(descriptor: int, size: int) -> bytes:
    chunks: list[bytes] = []
    left = size
    while left > 0:
        chunk = os.read(descriptor, min(left, 1024 * 1024))
        if not chunk:
            break
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)


def _unopenable(path: Path, error: OSError, fix: str) -> UnreadableFile:
    if error.errno == errno.ELOOP:
        return _refused(
            path,
            "is a symbolic link that leads round in a loop (or through too many links)",
            "point the link at the description file itself: `ls -l` shows where each link goes",
        )
    if error.errno == errno.EACCES:
        return _refused(
            path,
            "cannot be read: permission denied",
            "let the user who runs the gate read it (`chmod a+r`)",
        )
    return _refused(path, f"cannot be read: {error.strerror}", fix)
