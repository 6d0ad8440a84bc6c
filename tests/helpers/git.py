"""git repositories made for a test, without the user's configuration."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path


def git(directory: Path, *args: str) -> str:
    """Run git with an argument list, without the user's configuration."""
    done = subprocess.run(
        ["git", "-c", "user.name=t", "-c", "user.email=t@t", "-C", str(directory), *args],
        check=True,
        capture_output=True,
        env={**os.environ, "GIT_CONFIG_GLOBAL": os.devnull, "GIT_CONFIG_NOSYSTEM": "1"},
    )
    return done.stdout.decode().strip()


def commit_everything(directory: Path) -> None:
    """Make `directory` a repository (branch main) whose one commit holds all its files."""
    git(directory, "-c", "init.defaultBranch=main", "init", "-q")
    git(directory, "add", "-A")
    git(directory, "commit", "-q", "-m", "everything")
