"""Driving in items: the pair's control item, `PAIR[no-obstacle]`, and the drive failure that
both it and the placement items report.

The control item drives both robots through the empty world. A candidate that fails there fails
everywhere, so the pair's placement items then say so in one line and leave the report to it.
The baseline's run also times the path the solver places the pair's witnesses along.
Each process drives a pair's control run once and keeps it for the session; the runs are
deterministic, so pytest-xdist workers that drive the same pair get the same runs.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from _pytest._code.code import TerminalRepr, TracebackStyle

from pytest_lasertest.search.drives import PairDrive, RunCache, drive_lines, drive_pair
from pytest_lasertest.plugin.options import OPTIONS_KEY
from pytest_lasertest.plugin.items.base import PairItem
from pytest_lasertest.sim.client import PhysicsClient
from pytest_lasertest.pairsfile import Pair, PairsFile
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.inputs.errors import display_path

CONTROLS_KEY = pytest.StashKey[dict[tuple[Path, str], PairDrive]]()
PHYSICS_KEY = pytest.StashKey[PhysicsClient]()
CACHE_KEY = pytest.StashKey[RunCache]()
CONTROL = "no-obstacle"


class DriveFailed(Exception):
    """The policy fails a drive: the candidate failed an oracle (under `regression`, one the
    baseline passed)."""

    def __init__(self, headline: str, drives: PairDrive, details: list[str]) -> None:
        super().__init__(headline)
        self.headline = headline
        self.drives = drives
        self.details = details


def physics_client(config: pytest.Config) -> PhysicsClient:
    """The process's physics client, which every drive resets and builds its world in (see
    `PhysicsClient` for what a client of its own would cost each run)."""
    if PHYSICS_KEY not in config.stash:
        client = PhysicsClient()
        config.stash[PHYSICS_KEY] = client
        config.add_cleanup(client.close)
    return config.stash[PHYSICS_KEY]


def run_cache(config: pytest.Config) -> RunCache:
    """The process's runs, by scenario: no scenario is simulated twice in a session."""
    if CACHE_KEY not in config.stash:
        config.stash[CACHE_KEY] = RunCache()
    return config.stash[CACHE_KEY]


def control_drive(
    config: pytest.Config, spec: PairsFile, pair: Pair, controller: ControllerChoice
) -> PairDrive:
    """The pair's obstacle-free runs, driven once per process. Every item of a pairs file
    drives with the same controller, so the pairs file and the pair key them."""
    controls = config.stash.setdefault(CONTROLS_KEY, {})
    key = (spec.path, pair.name)
    if key not in controls:
        seed = config.stash[OPTIONS_KEY].seed
        client = physics_client(config)
        cache = run_cache(config)
        controls[key] = drive_pair(spec, pair, (), seed, controller, client, cache)
    return controls[key]


def drive_report(
    item: pytest.Item, pair: Pair, controller: ControllerChoice, failed: DriveFailed
) -> str:
    """The failure report of a drive: the controller, what happened to each robot, and how to
    replay it."""
    options = item.config.stash[OPTIONS_KEY]
    lines = [
        failed.headline,
        f"  pair       {pair.name} ({pair.location})",
        f"  controller {controller.name} ({controller.source})",
        *failed.details,
        *drive_lines(failed.drives, pair),
        f"  policy     {options.policy}",
        f"  replay     pytest '{item.nodeid}' {options.replay_options()}",
    ]
    return "\n".join(lines)


class ControlItem(PairItem):
    """Both robots through the empty world: the candidate must still reach the goal there."""

    kind = "control"

    def __init__(self, *, controller: ControllerChoice, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.controller = controller

    def runtest(self) -> None:
        drives = control_drive(self.config, self.spec, self.pair, self.controller)
        self.user_properties += [
            ("lasertest.seed", self.options.seed),
            ("lasertest.controller", self.controller.name),
            *drives.properties(),
        ]
        if drives.fails(self.options.policy):
            raise DriveFailed(
                "the candidate fails without any obstacle: the change breaks the robot "
                "everywhere, not only where the scanners differ",
                drives,
                [f"  artifact   {display_path(path)}" for path in self._write_evidence(drives)],
            )

    def _write_evidence(self, drives: PairDrive) -> tuple[Path, ...]:
        """The failure's picture, empty Gazebo world and numbers, if the run asked for them."""
        options = self.options
        if options.artifacts is None:
            return ()
        from pytest_lasertest.artifacts.evidence import write_control_evidence

        return write_control_evidence(
            options.artifacts, self.nodeid, self.spec, self.pair, drives, options.recorded()
        )

    def repr_failure(
        self, excinfo: pytest.ExceptionInfo[BaseException], style: TracebackStyle | None = None
    ) -> str | TerminalRepr:
        if isinstance(excinfo.value, DriveFailed):
            return drive_report(self, self.pair, self.controller, excinfo.value)
        return super().repr_failure(excinfo, style)
