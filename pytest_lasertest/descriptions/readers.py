"""Where a description's files are read from: the working tree, or a git revision."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from pytest_lasertest.descriptions.gitref import GitRevision, open_revision
from pytest_lasertest.inputs.errors import display_path


@dataclass(frozen=True)
class WorkingTree:
    """Files as they are on disk."""

    def read(self, path: Path) -> bytes:
        """The file's bytes; FileNotFoundError when it is missing or is a directory."""
        if path.is_dir():
            raise FileNotFoundError(2, f"{path} is a directory", str(path))
        return path.read_bytes()

    def name(self, path: Path) -> str:
        """The path as messages show it."""
        return display_path(path)


@dataclass(frozen=True)
class AtRevision:
    """Files inside the repository as the revision holds them; files outside it (an installed
    ROS package, say) as they are on disk."""

    revision: GitRevision

    def read(self, path: Path) -> bytes:
        """The file's bytes at the revision; FileNotFoundError when it has no such file."""
        if self.revision.holds(path):
            return self.revision.read(path)
        return WorkingTree().read(path)

    def name(self, path: Path) -> str:
        """The path, and the revision it is read at."""
        if self.revision.holds(path):
            return f"{display_path(path)} at {self.revision.label}"
        return display_path(path)


def reader_at(ref: str | None, directory: Path) -> WorkingTree | AtRevision:
    """The working tree, or revision `ref` of the repository holding `directory` (GitError when
    there is no such revision)."""
    return WorkingTree() if ref is None else AtRevision(open_revision(directory, ref))
