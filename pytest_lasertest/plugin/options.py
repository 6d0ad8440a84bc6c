"""Command-line options, each parsed by a pure function that names the bad value and the choices."""

from __future__ import annotations

import hashlib
import os
import secrets
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from pytest_lasertest.model.policy import POLICIES, Policy
from pytest_lasertest.model.seeds import MAX_SEED, whole_seed
from pytest_lasertest.search.budgets import BUDGET_NAMES, BUDGETS, MAX_EXAMPLES, Budget, BudgetName

if TYPE_CHECKING:
    from pytest_lasertest.reports.formats import Replay

PAIRS_SUFFIXES = (".lasertest.yaml", ".lasertest.yml")


@dataclass(frozen=True)
class LaserOptions:
    """The run's settings: everything needed to replay it."""

    # --laser-seed; None: each pairs file's own seed, derived from its path (`derived_seed`),
    # as on a CI service where no seed is given, so that a commit gets the same verdict twice.
    seed: int | None
    profile: BudgetName  # --laser-profile
    policy: Policy
    artifacts: Path | None
    pairs: tuple[Path, ...]  # pairs files named on the command line, absolute
    examples: int | None = None  # overrides the profile's
    summary: Path | None = None  # --laser-summary: a Markdown file the table is appended to
    root: Path = Path()  # the rootdir, against which a derived seed names a pairs file

    def seed_of(self, path: Path) -> int:
        """The seed of the pairs file at `path`: the run's, else the file's own."""
        if self.seed is not None:
            return self.seed
        return derived_seed(item_path(path, self.root))

    @property
    def budget(self) -> Budget:
        """The profile's budget, with `--laser-examples` if given."""
        return BUDGETS[self.profile].with_examples(self.examples)

    def recorded(self, path: Path) -> dict[str, object]:
        """The seed of the pairs file at `path`, the profile and the policy, as the artifacts
        record them."""
        return {"seed": self.seed_of(path), "profile": self.profile, "policy": self.policy}

    def replay(self, nodeid: str, path: Path, here: Path) -> Replay:
        """How to run the item `nodeid`, of the pairs file at `path`, again as this run ran it,
        from `here`, where pytest was started: the node id's path is relative to the rootdir,
        which need not be `here`."""
        # Only items replay, and they have loaded the reports (and numpy) already.
        from pytest_lasertest.reports.formats import Replay, shell_word

        _, _, name = nodeid.partition("::")
        file = item_path(path, here)
        options = self.replay_options(self.seed_of(path))
        if not path.name.endswith(PAIRS_SUFFIXES):
            # pytest collects a pairs file of another name only when --laser-pairs names it.
            options = f"--laser-pairs={shell_word(file)} {options}"
        return Replay(f"{file}::{name}", options, here)

    def replay_options(self, seed: int | None) -> str:
        """The options that reproduce this run of a pairs file seeded `seed` (None: of any
        pairs file, each with its own seed, as the run took them)."""
        examples = f" --laser-examples={self.examples}" if self.examples is not None else ""
        seeded = f"--laser-seed={seed} " if seed is not None else ""
        return f"{seeded}--laser-profile={self.profile} --laser-policy={self.policy}{examples}"

    def seed_line(self) -> str:
        """How the run is seeded, for the report header."""
        if self.seed is not None:
            return f"seed {self.seed}"
        return "seed fixed per pairs file, from its path (on CI; --laser-seed=random explores)"


def item_path(path: Path, here: Path) -> str:
    """The pairs file at `path` as pytest, started in `here`, takes it: relative, with `..` where
    it lies elsewhere (absolute only when no relative path leads there)."""
    try:
        return os.path.relpath(path.resolve(), here.resolve())
    except ValueError:  # another drive, on Windows
        return str(path.resolve())


def derived_seed(name: str) -> int:
    """The seed of the pairs file `name` (its path relative to the rootdir, as node ids name
    it) where no seed is given on CI: the same file gets the same seed on every run, every
    machine and every pytest-xdist worker, whatever else the run collects."""
    digest = hashlib.sha256(f"lasertest-seed:{Path(name).as_posix()}".encode()).digest()
    return int.from_bytes(digest[:4], "big")


def on_ci(environ: Mapping[str, str]) -> bool:
    """Whether the run is on a CI service, which sets CI (GitHub Actions, GitLab, ...)."""
    return environ.get("CI", "").lower() not in ("", "0", "false", "no")


def parse_seed(text: str) -> int | None:
    """An explicit seed, or None for 'random' (a fresh seed per run)."""
    if text == "random":
        return None
    seed = whole_seed(text)
    if seed is None:
        raise pytest.UsageError(
            f"--laser-seed={text!r} is not a seed: give a whole number from 0 to {MAX_SEED}, "
            "or 'random' for a fresh one (the report header prints it for replay)"
        )
    return seed


def fresh_seed() -> int:
    """A seed drawn from the operating system, not from any global random state."""
    return secrets.randbelow(MAX_SEED + 1)


def parse_profile(text: str) -> BudgetName:
    """A budget profile name."""
    if text not in BUDGET_NAMES:
        raise pytest.UsageError(
            f"--laser-profile={text!r} is not a budget profile: choose one of "
            f"{', '.join(BUDGET_NAMES)}"
        )
    return text


def parse_examples(text: str) -> int:
    """How many perturbations each placement item tries."""
    try:
        examples = int(text, 10)
    except ValueError:
        examples = 0
    if not 1 <= examples <= MAX_EXAMPLES:
        raise pytest.UsageError(
            f"--laser-examples={text!r} is not a number of examples: give a whole number from 1 "
            f"to {MAX_EXAMPLES} (the witness itself is the first)"
        )
    return examples


def default_profile(environ: Mapping[str, str]) -> BudgetName:
    """`ci` on a CI service (which sets CI), else `dev`."""
    return "ci" if on_ci(environ) else "dev"


def parse_policy(text: str) -> Policy:
    """What fails the run: only a regression (the default), or any failure of the candidate."""
    if text not in POLICIES:
        raise pytest.UsageError(
            f"--laser-policy={text!r} is not a policy: choose 'regression' (the default: fail "
            "only where the candidate fails and the baseline passes, under every further draw of "
            "the scan noise and of where each obstacle stands within 1 cm) "
            "or 'candidate' (fail whenever the candidate fails, pre-existing and marginal "
            "failures and losses of coverage included)"
        )
    return text


def parse_artifacts(text: str, base: Path, beside_report: bool = False) -> Path:
    """The directory that receives failure artifacts; created when the first one is written.
    `beside_report`: it is pytest-html's, not one `--laser-artifacts` named, and the errors say so.

    Refused up front: an empty path, a path at a file or below one, and a directory this user
    cannot create or write to. What only writing can tell (a full disk, a folder where an
    artifact goes) is reported beside each failure instead.
    """
    path = base / text
    if beside_report:
        where = f"--html puts the failure artifacts beside its report, in {text!r}, which"
        fix = "move what is there, or give --laser-artifacts=DIR to put them elsewhere"
    else:
        where = f"--laser-artifacts={text!r}"
        fix = "give a directory this user can write to (it is created if missing)"
    if not text or (_nearest_existing(path) == path and not path.is_dir()):
        raise pytest.UsageError(f"{where} is not a directory: {fix}")
    problem = unwritable(path)
    if problem is not None:
        raise pytest.UsageError(f"{where}: {problem}: {fix}")
    return path


def parse_summary(text: str, base: Path) -> Path:
    """The Markdown file the run's summary is appended to (GitHub Actions' job summary, say);
    refused up front where no file can be written."""
    path = base / text
    if not text or path.is_dir():
        raise pytest.UsageError(
            f"--laser-summary={text!r} is not a file: give a file path, such as "
            '"$GITHUB_STEP_SUMMARY" (it is created if missing, and appended to)'
        )
    problem = unwritable(path.parent)
    if problem is not None:
        raise pytest.UsageError(
            f"--laser-summary={text!r}: {problem}: give a file in a directory this user can "
            "write to"
        )
    return path


def unwritable(directory: Path) -> str | None:
    """Why no file can be written in `directory` (made if missing), or None if it can be."""
    existing = _nearest_existing(directory)
    if existing.is_symlink() and not existing.exists():
        return f"{existing} is a link to {os.readlink(existing)}, which does not exist"
    if not existing.is_dir():
        return f"{existing} is a file, so no directory can be made below it"
    if not os.access(existing, os.W_OK | os.X_OK):
        return f"this user cannot write to {existing}"
    return None


def _nearest_existing(path: Path) -> Path:
    """`path` if it exists (a dangling link too), else its nearest parent that does and that
    this user can look at: the access check then refuses a parent it cannot look into."""
    for folder in (path, *path.parents):
        try:
            folder.lstat()
        except OSError:  # missing, below a file, or in a folder this user cannot look into
            continue
        return folder
    return Path(path.anchor)


def parse_pairs(texts: Iterable[str], base: Path, source: str) -> tuple[Path, ...]:
    """Pairs files from `source` (an option or ini name), each an existing file."""
    paths = []
    for text in texts:
        path = (base / text).resolve()
        if not path.is_file():
            what = _not_a_file(path)
            raise pytest.UsageError(
                f"{source}: {text!r} is {what}; it takes the path of a pairs file "
                f"(relative to {base}); to collect every *{PAIRS_SUFFIXES[0]} in a directory, "
                "pass the directory to pytest as an argument"
            )
        paths.append(path)
    return tuple(paths)


def _not_a_file(path: Path) -> str:
    """What `path`, which is no regular file, is instead."""
    if path.is_dir():
        return "a directory"
    # A pipe or a device: reading it could wait for ever, or never end.
    return "not a regular file (a pipe, socket or device)" if path.exists() else "missing"


def is_pairs_file(path: Path, named: frozenset[Path]) -> bool:
    """Whether pytest should collect `path` (any file it visits) as a pairs file."""
    return path.name.endswith(PAIRS_SUFFIXES) or (bool(named) and path.resolve() in named)
