"""Whether the gate's verdict depends on the seed: pairs files run under several seeds, side by
side, each item's outcome compared across them.

Runs `pytest FILE --laser-seed=S --laser-profile=ci` for each pairs file and seed (in a copy of
the repository's examples and test data, with a fresh `.hypothesis/` for each run, so that no run
replays another's failures), reads each run's JUnit XML, and prints for each file:

    FILE: N items; K change with the seed; failed in every seed: ...; in some only: ...

then, for each item whose outcome changes, its outcome under each seed (F failed, . passed,
s skipped, p pre-existing, m marginal, c coverage-loss); and last

    items whose outcome changes between runs: K of N; failing items: F (in every run: A)

Give `--policy candidate` for the verdict before `regression` was the default, and `--pytest`
to run another checkout's code (a worktree of an older commit: its virtualenv's pytest, or this
one's with PYTHONPATH naming the worktree) with `--source` naming the worktree, whose examples
and test data are then the ones run. `--results DIR` keeps each run's JUnit XML in DIR and reads
a run found there instead of running it again: a sweep of all the examples under eight seeds
takes hours on two cores, and may be resumed, or reported from DIR alone. A run is kept by its
file and seed alone: give each sweep (each checkout, policy or -k) a DIR of its own.
`--ci RUNS` runs each file RUNS times as a CI service does instead (`CI=true`, no `--laser-seed`
or `--laser-profile`: each file's seed comes from its path, the profile is ci), to show that the
same commit gives the same verdict: no item may change between the runs.

    python benchmarks/verdicts.py [FILE ...] [--seeds 0-7 | --ci RUNS] [--workers 2]
                                  [--policy regression] [--pytest PATH] [-k EXPRESSION]
                                  [--source CHECKOUT] [--results DIR]

Without FILE, the harmless changes of tests/data/harmless/ (move_base and Nav2), which must
pass under every seed.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
HARMLESS = (
    "tests/data/harmless/move_base.lasertest.yaml",
    "tests/data/harmless/nav2.lasertest.yaml",
)
# A JUnit outcome as one letter: what pytest's progress line shows for it.
LETTERS = {"passed": ".", "failure": "F", "error": "E", "skipped": "s"}
# The expected failures lasertest notes, by their `lasertest.outcome` property.
NOTED = {"pre-existing": "p", "marginal": "m", "coverage-loss": "c"}


@dataclass(frozen=True)
class Sweep:
    """Each item's outcome letter under each seed, for one pairs file."""

    file: str
    seeds: tuple[int | None, ...]  # None: a run as on a CI service
    outcomes: dict[str, tuple[str, ...]]  # item -> one letter per seed

    def changing(self) -> list[str]:
        return [item for item, letters in self.outcomes.items() if len(set(letters)) > 1]

    def failing(self, every: bool) -> list[str]:
        """The items that failed under every seed, or under some but not every one."""
        return [
            item
            for item, letters in self.outcomes.items()
            if any(letter == "F" for letter in letters)
            and all(letter == "F" for letter in letters) == every
        ]

    @property
    def unit(self) -> str:
        """What the runs differ by: a seed, or nothing (runs as on a CI service)."""
        return "run" if all(seed is None for seed in self.seeds) else "seed"


def seeds_from(text: str) -> tuple[int, ...]:
    """`0-7` or `1,3,5`."""
    if "-" in text:
        low, high = (int(part) for part in text.split("-"))
        return tuple(range(low, high + 1))
    return tuple(int(part) for part in text.split(","))


def letter(case: ET.Element) -> str:
    """One JUnit test case's outcome as a letter."""
    ending = next((child for child in case if child.tag not in ("properties", "system-out")), None)
    if ending is None:
        return "."
    if ending.get("type") == "pytest.xfail":
        outcome = {prop.get("name"): prop.get("value") for prop in case.iter("property")}
        return NOTED.get(str(outcome.get("lasertest.outcome")), "x")
    return LETTERS.get(ending.tag, "?")


@dataclass(frozen=True)
class Runs:
    """How each run is made: which pytest, in which tree, with which options."""

    pytest: str
    tree: Path
    workers: int
    policy: str
    select: str | None  # -k

    def command(self, file: str, seed: int | None, report: Path) -> list[str]:
        """The run of `file` under `seed`; as on a CI service where `seed` is None."""
        command = [self.pytest, file]
        if seed is not None:
            command += [f"--laser-seed={seed}", "--laser-profile=ci"]
        command += ["-p", "no:randomly", "-p", "no:cacheprovider", "-q"]
        command += [f"--laser-policy={self.policy}", f"--junitxml={report}"]
        if self.workers > 1:
            command += ["-n", str(self.workers)]
        return command + (["-k", self.select] if self.select else [])


def run(runs: Runs, file: str, seed: int | None, kept: Path | None) -> dict[str, str]:
    """One run of `file` under `seed` (as on a CI service if None): each item's outcome letter.
    Read from `kept` where an earlier sweep kept it there."""
    if kept is not None and kept.exists():
        return outcomes_in(kept)
    tree = runs.tree
    shutil.rmtree(tree / ".hypothesis", ignore_errors=True)
    report = tree / "verdicts.xml"
    command = runs.command(file, seed, report)
    environment = {key: value for key, value in os.environ.items() if key != "CI"}
    if seed is None:
        environment["CI"] = "true"
    started = time.perf_counter()
    done = subprocess.run(command, cwd=tree, env=environment, capture_output=True, check=False)
    outcomes = outcomes_in(report)
    if kept is not None:
        shutil.copyfile(report, kept)
    # Progress, on stderr: a sweep of eight seeds takes hours.
    letters = "".join(sorted(outcomes.values()))
    seconds = time.perf_counter() - started
    how = f"seed {seed}" if seed is not None else "as on CI"
    print(
        f"{file} {how}: {letters}, exit status {done.returncode} ({seconds:.0f} s)",
        file=sys.stderr,
        flush=True,
    )
    return outcomes


def outcomes_in(report: Path) -> dict[str, str]:
    """Each item's outcome letter in one run's JUnit XML."""
    return {str(case.get("name")): letter(case) for case in ET.parse(report).iter("testcase")}


def kept_report(results: Path | None, file: str, seed: int | None, index: int) -> Path | None:
    """Where the JUnit XML of `file`'s run under `seed` (the `index`th run) is kept, if it is."""
    if results is None:
        return None
    how = f"seed{seed}" if seed is not None else f"ci{index}"
    return results / f"{file.replace('/', '.')}.{how}.xml"


def sweep_all(
    runs: Runs, files: Sequence[str], seeds: Sequence[int | None], results: Path | None
) -> list[Sweep]:
    """Every file under each seed, a seed at a time over all files, so that a sweep cut short
    has whole seeds in `results`."""
    by_seed = [
        {file: run(runs, file, seed, kept_report(results, file, seed, index)) for file in files}
        for index, seed in enumerate(seeds)
    ]
    return [sweep_of(file, seeds, [outcomes[file] for outcomes in by_seed]) for file in files]


def sweep_of(file: str, seeds: Sequence[int | None], by_seed: list[dict[str, str]]) -> Sweep:
    """`file`'s sweep from its runs' outcomes, one dictionary a seed."""
    items = sorted(set().union(*by_seed))
    outcomes = {item: tuple(run.get(item, "-") for run in by_seed) for item in items}
    return Sweep(file, tuple(seeds), outcomes)


def report(sweep: Sweep) -> list[str]:
    changing = sweep.changing()
    lines = [
        f"{sweep.file}: {len(sweep.outcomes)} items; {len(changing)} change with the "
        f"{sweep.unit}; failed in every {sweep.unit}: "
        f"{', '.join(sweep.failing(every=True)) or 'none'}; "
        f"in some only: {', '.join(sweep.failing(every=False)) or 'none'}"
    ]
    lines += [f"  {''.join(sweep.outcomes[item])}  {item}" for item in changing]
    return lines


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("files", nargs="*", default=list(HARMLESS))
    parser.add_argument("--seeds", type=seeds_from, default=tuple(range(8)))
    parser.add_argument("--ci", type=int, default=0, metavar="RUNS", help="run as CI does")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--policy", default="regression")
    # The pytest of the Python running this: the environment the benchmark was started in.
    parser.add_argument("--pytest", default=str(Path(sys.executable).with_name("pytest")))
    parser.add_argument("-k", dest="select", default=None, help="pytest's -k, to run fewer")
    parser.add_argument("--source", type=Path, default=REPO, help="the checkout whose files run")
    parser.add_argument("--results", type=Path, default=None, help="keep and reuse JUnit XML")
    args = parser.parse_args()
    if args.results is not None:
        args.results.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as scratch:
        tree = checkout(args.source, Path(scratch))
        runs = Runs(args.pytest, tree, args.workers, args.policy, args.select)
        seeds = (None,) * args.ci if args.ci else args.seeds
        sweeps = sweep_all(runs, args.files, seeds, args.results)
    for done in sweeps:
        print("\n".join(report(done)))
    total = sum(len(done.outcomes) for done in sweeps)
    changing = sum(len(done.changing()) for done in sweeps)
    failing = sum(len(done.failing(every=False)) for done in sweeps)
    always = sum(len(done.failing(every=True)) for done in sweeps)
    print(
        f"items whose outcome changes between runs: {changing} of {total}; "
        f"failing items: {failing} (in every run: {always})"
    )


def checkout(source: Path, tree: Path) -> Path:
    """The examples and test data of `source` in `tree`, committed: the CI gate example reads
    its description at HEAD."""
    for folder in ("examples", "tests/data"):
        shutil.copytree(source / folder, tree / folder)
    identity = ["-c", "user.name=lasertest", "-c", "user.email=lasertest@localhost"]
    for command in (["init", "-q"], ["add", "-A"], [*identity, "commit", "-qm", "sweep"]):
        subprocess.run(["git", *command], cwd=tree, check=True, capture_output=True)
    return tree


if __name__ == "__main__":
    main()
