"""The one error a file the user wrote can raise: where, which field, what is wrong, and how to
fix it."""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class Location:
    """A line in a file the user wrote."""

    path: Path
    line: int  # 1-based

    def __str__(self) -> str:
        return f"{display_path(self.path)}:{self.line}"


class SpecError(Exception):
    """A file the user wrote (a pairs file, robot, catalogue model or description) cannot be
    used as written."""

    def __init__(self, location: Location, field: str, problem: str, fix: str) -> None:
        super().__init__(location, field, problem, fix)
        self.location = location
        self.field = field
        self.problem = problem
        self.fix = fix

    def __str__(self) -> str:
        where = f"{self.location}: {self.field}" if self.field else str(self.location)
        return f"{where}: {self.problem}\n  fix: {self.fix}"


def display_path(path: Path) -> str:
    """The path relative to the working directory when it lies below it, else as given."""
    # os.path.realpath, not Path.resolve: it raises RuntimeError on a symbolic link loop.
    try:
        return str(Path(os.path.realpath(path)).relative_to(Path.cwd().resolve()))
    except ValueError:
        return os.fspath(path)
