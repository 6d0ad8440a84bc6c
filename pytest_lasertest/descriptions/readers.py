"""Where a description's files are read from: the working tree, or a git revision."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from pytest_lasertest.descriptions.gitref import GitError, GitRevision, revision_holding
from pytest_lasertest.inputs.errors import display_path
from pytest_lasertest.inputs.files import UnreadableFile, read_regular_file


@dataclass(frozen=True)
class WorkingTree:
    """Files as they are on disk."""

    def read(self, path: Path) -> bytes:
        """The file's bytes; FileNotFoundError when it is missing, UnreadableFile when it is
        not a regular file of at most MAX_FILE_BYTES or cannot be read."""
        return read_regular_file(path)

    def name(self, path: Path) -> str:
        """The path as messages show it."""
        return display_path(path)


@dataclass(frozen=True)
class AtRevision:
    """Files inside the repository as the revision holds them; files outside it (an installed
    ROS package, say) as they are on disk."""

    revision: GitRevision

    def read(self, path: Path) -> bytes:
        """The file's bytes at the revision; FileNotFoundError when it has no such file,
        UnreadableFile when git cannot read it or it is too large."""
        if not self.revision.holds(path):
            return WorkingTree().read(path)
        try:
            return self.revision.read(path)
        except GitError as error:
            raise UnreadableFile(path, error.problem, error.fix) from None

    def name(self, path: Path) -> str:
        """The path, and the revision it is read at."""
        if self.revision.holds(path):
            return f"{display_path(path)} at {self.revision.label}"
        return display_path(path)


def reader_at(ref: str | None, path: Path) -> WorkingTree | AtRevision:
    """The working tree, or revision `ref` of the git repository that holds the description
    file `path` (absolute). GitError when there is no such revision, or the file lies in no
    repository: a ref must never quietly read the working tree instead."""
    return WorkingTree() if ref is None else AtRevision(revision_holding(path, ref))
