"""Command-line options, each parsed by a pure function that names the bad value and the choices."""

from __future__ import annotations

import secrets
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path

import pytest

from pytest_lasertest.model.policy import POLICIES, Policy
from pytest_lasertest.search.budgets import BUDGET_NAMES, BUDGETS, MAX_EXAMPLES, Budget, BudgetName

MAX_SEED = 2**32 - 1
PAIRS_SUFFIXES = (".lasertest.yaml", ".lasertest.yml")


@dataclass(frozen=True)
class LaserOptions:
    """The run's settings: everything needed to replay it."""

    seed: int
    profile: BudgetName  # --laser-profile
    policy: Policy
    artifacts: Path | None
    pairs: tuple[Path, ...]  # pairs files named on the command line, absolute
    examples: int | None = None  # overrides the profile's

    @property
    def budget(self) -> Budget:
        """The profile's budget, with `--laser-examples` if given."""
        return BUDGETS[self.profile].with_examples(self.examples)

    def recorded(self) -> dict[str, object]:
        """The run's seed, profile and policy, as the artifacts record them."""
        return {"seed": self.seed, "profile": self.profile, "policy": self.policy}

    def replay_options(self) -> str:
        """The options that reproduce this run."""
        examples = f" --laser-examples={self.examples}" if self.examples is not None else ""
        return (
            f"--laser-seed={self.seed} --laser-profile={self.profile} --laser-policy={self.policy}"
            f"{examples}"
        )


def parse_seed(text: str) -> int | None:
    """An explicit seed, or None for 'random' (a fresh seed per run)."""
    if text == "random":
        return None
    try:
        seed = int(text, 10)
    except ValueError:
        seed = -1
    if not 0 <= seed <= MAX_SEED:
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
    return "ci" if environ.get("CI", "").lower() not in ("", "0", "false", "no") else "dev"


def parse_policy(text: str) -> Policy:
    """What fails an item: any failure of the candidate, or only one the baseline does not share."""
    if text not in POLICIES:
        raise pytest.UsageError(
            f"--laser-policy={text!r} is not a policy: choose 'candidate' (fail whenever the "
            "candidate fails) or 'regression' (fail only where the baseline did not)"
        )
    return text


def parse_artifacts(text: str, base: Path) -> Path:
    """The directory that receives failure artifacts; created when the first one is written."""
    path = base / text
    if not text or (path.exists() and not path.is_dir()):
        raise pytest.UsageError(
            f"--laser-artifacts={text!r} is not a directory: give a directory path "
            "(it is created if missing)"
        )
    return path


def parse_pairs(texts: Iterable[str], base: Path, source: str) -> tuple[Path, ...]:
    """Pairs files from `source` (an option or ini name), each an existing file."""
    paths = []
    for text in texts:
        path = (base / text).resolve()
        if not path.is_file():
            what = "a directory" if path.is_dir() else "missing"
            raise pytest.UsageError(
                f"{source}: {text!r} is {what}; it takes the path of a pairs file "
                f"(relative to {base}); to collect every *{PAIRS_SUFFIXES[0]} in a directory, "
                "pass the directory to pytest as an argument"
            )
        paths.append(path)
    return tuple(paths)


def is_pairs_file(path: Path, named: frozenset[Path]) -> bool:
    """Whether pytest should collect `path` (any file it visits) as a pairs file."""
    return path.name.endswith(PAIRS_SUFFIXES) or (bool(named) and path.resolve() in named)
