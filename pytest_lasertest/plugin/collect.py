"""Collection: a pairs file, and the items it yields for each pair.

Each pair yields `PAIR[coverage]`, its control item `PAIR[no-obstacle]` and its placement items;
a pair that pins placements yields only its pinned items; a pair whose scanners read alike
yields none, and the run's summary names it. The pairs file chooses the controller its items
drive with: its own `controller:`, else a conftest's `pytest_lasertest_make_controller`, else
the default.
"""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path
from typing import TYPE_CHECKING

import pytest

from pytest_lasertest.inputs.errors import Location, SpecError
from pytest_lasertest.inputs.node import SpecNode, read_root
from pytest_lasertest.model.sensor import same_sensing
from pytest_lasertest.pairsfile import Pair, PairsFile, load_pairs_file
from pytest_lasertest.pairsfile.bundled import ROBOTS_DIR
from pytest_lasertest.pairsfile.controller import (
    ControllerChoice,
    checked_factory,
    default_controller,
)
from pytest_lasertest.pairsfile.scan_filters import with_scan_filters
from pytest_lasertest.plugin.items.control import ControlItem
from pytest_lasertest.plugin.items.coverage import CoverageItem
from pytest_lasertest.plugin.items.pinned import pinned_items
from pytest_lasertest.plugin.items.placement import placement_items
from pytest_lasertest.plugin.session import LaserSession

if TYPE_CHECKING:
    from pytest_lasertest.nav.nav2.settings import Nav2Settings

HOOK = "pytest_lasertest_make_controller"


class UnreadParametersWarning(UserWarning):
    """A Nav2 params file sets parameters the Nav2 imitation does not read."""


class PairFile(pytest.File):
    """A pairs file; a file that cannot be used is one collection error naming file and line."""

    spares_the_run = True  # a broken pairs file does not stop the other files (LaserSession)

    def collect(self) -> list[pytest.Item]:
        try:
            spec = load_pairs_file(self.path)
            controller = self._controller(spec)
        except SpecError as error:
            raise self.CollectError(str(error)) from None
        unread: tuple[str, ...] = ()
        if controller.name == "nav2":
            controller, unread = self._nav2(spec, controller)
        # The team's laser_filters chain stands in front of whichever stack drives.
        controller = with_scan_filters(controller, spec.scan_filters)
        items = self._items(spec, controller)
        if items and unread:  # a file that yields no items drives no Nav2: nothing to warn of
            self._note_unread(spec, unread)
        return items

    def _items(self, spec: PairsFile, controller: ControllerChoice) -> list[pytest.Item]:
        """Each pair's items: none where its scanners read alike, its pinned items where it pins
        placements, else its coverage, control and placement items."""
        items: list[pytest.Item] = []
        for pair in spec.pairs:
            if same_sensing(pair.baseline.profile, pair.candidate.profile):
                # An edit that changes nothing the scanner reads (the usual URDF change) costs
                # the gate nothing; the summary says so.
                self._note_unchanged(pair)
            elif pair.placements:
                items += pinned_items(self, spec, pair, controller)
            else:
                items += self._pair_items(spec, pair, controller)
        return items

    def _pair_items(
        self, spec: PairsFile, pair: Pair, controller: ControllerChoice
    ) -> list[pytest.Item]:
        """The coverage and control items of a pair, then its placement items."""
        return [
            CoverageItem.from_parent(self, name=f"{pair.name}[coverage]", spec=spec, pair=pair),
            ControlItem.from_parent(
                self, name=ControlItem.name_of(pair), spec=spec, pair=pair, controller=controller
            ),
            *placement_items(self, spec, pair, controller),
        ]

    def _nav2(
        self, spec: PairsFile, controller: ControllerChoice
    ) -> tuple[ControllerChoice, tuple[str, ...]]:
        """Nav2's choice, saying what it runs, and the parameters the robot's params file sets
        that the imitation does not read (`_note_unread` warns of them)."""
        from pytest_lasertest.nav.nav2.params import configured
        from pytest_lasertest.nav.nav2.settings import describe

        config = configured(spec.robot.nav2, spec.robot.nav2_release)
        self._check_reach(spec, config.settings)
        if spec.move_base_overrides:
            sections = sorted({section for section, _, _ in spec.move_base_overrides})
            self.warn(
                UnreadParametersWarning(
                    f"navigation: sets move_base parameters ({', '.join(sections)}), but the "
                    "robots drive Nav2, which does not read them: write `controller: move_base` "
                    "to drive move_base, or give Nav2's in `navigation: {nav2: FILE}`"
                )
            )
        return dataclasses.replace(controller, stack=describe(config.settings)), config.unmodelled

    def _check_reach(self, spec: PairsFile, settings: Nav2Settings) -> None:
        """A collection error where Nav2's rolling global costmap cannot hold the next
        waypoint from where the robot sets off for it: NavFn would plan no path, and every
        drive would fail alike."""
        from pytest_lasertest.nav.nav2.global_costmap import global_window, out_of_reach

        world = spec.world
        start = (world.start.x, world.start.y)
        index = out_of_reach(settings, start, world.route)
        if index is None:
            return
        point, window = world.route[index], global_window(settings.global_, start, world.route)
        raise self.CollectError(
            str(
                SpecError(
                    route_location(self.path),
                    "world.route",
                    f"the waypoint ({point.x:g}, {point.y:g}) lies {window / 2:g} m or more from "
                    f"where the robot sets off for it, beyond the half of Nav2's rolling global "
                    f"costmap ({window:g} m wide, global_costmap's width) that holds it: NavFn "
                    "would plan no path to it",
                    "put waypoints closer together along the route, or widen the global "
                    "costmap (width and height) in the Nav2 params file",
                )
            )
        )

    def _note_unread(self, spec: PairsFile, unread: tuple[str, ...]) -> None:
        """Warn, once per params file in the session, of the parameters it sets that the Nav2
        imitation does not read, as a warning pytest lists at the end. Its text names the params
        file and nothing else, so that pytest groups the same warning from every pairs file and
        every pytest-xdist worker as one."""
        name = params_file_name(spec, self.config.rootpath)
        params = f"the params file {name}" if name else f"the robot {spec.robot.name}'s params file"
        warned = LaserSession.of(self.config).unread_warned
        if params in warned:
            return
        warned.add(params)
        lines = "\n  ".join(unread)
        self.warn(
            UnreadParametersWarning(
                f"the Nav2 imitation does not read these parameters of {params} "
                f"(docs/explanation/navigation.md says what it imitates):\n  {lines}"
            )
        )

    def _note_unchanged(self, pair: Pair) -> None:
        LaserSession.of(self.config).unchanged.add(
            f"{self.nodeid}::{pair.name}",
            f"baseline {pair.baseline.label} and candidate {pair.candidate.label} "
            f"both read {pair.candidate.profile.describe()}",
        )

    def _controller(self, spec: PairsFile) -> ControllerChoice:
        """The pairs file's `controller:`, else the first factory a conftest (or plugin) returns
        from the hook, else the default. Collection chooses, so every pytest-xdist worker,
        collecting the same file under the same conftests, chooses the same."""
        if spec.controller is not None:
            return spec.controller
        # The file's own hook proxy: only conftests at or above the pairs file take part.
        factory: object = self.ihook.pytest_lasertest_make_controller(config=self.config, spec=spec)
        if factory is None:
            return default_controller(self.path)
        if not callable(factory):
            raise SpecError(
                Location(self.path, 1),
                "controller",
                f"the {HOOK} hook (in a conftest.py or plugin) returned {factory!r:.60}, not a "
                "controller factory",
                "return a callable that takes (robot, route) and returns a controller, or None "
                "for the default",
            )
        name = _qualified_name(factory)
        # Checked as a `controller:` is; the hook has no line of its own, so the error points
        # at the pairs file's first.
        node = SpecNode(factory, Location(self.path, 1), "controller")
        checked = checked_factory(node, factory, f"the {HOOK} hook's factory {name}")
        return ControllerChoice(name, f"from the {HOOK} hook", checked)


def route_location(path: Path) -> Location:
    """Where the pairs file at `path` writes its route (or goal)."""
    world = read_root(path, what="pairs file", needs="world").entries(what="sections")["world"]
    fields = world.entries(what="world fields")
    return fields.get("route", fields.get("goal", world)).location


def _qualified_name(factory: object) -> str:
    """`module:qualname` of a hook's factory, for reports."""
    module = getattr(factory, "__module__", None)
    name = getattr(factory, "__qualname__", None)
    return f"{module}:{name}" if module and name else repr(factory)


def params_file_name(spec: PairsFile, root: Path) -> str | None:
    """The Nav2 params file the pairs file's robots drive with, as warnings name it, the same
    from every pairs file and worker: a bundled robot's as `husky/nav2.yaml of the bundled
    robots`, else relative to the rootdir, else absolute; None for a robot without one."""
    if spec.robot.nav2_file is None:
        return None
    path = Path(os.path.realpath(spec.robot.nav2_file))
    if path.is_relative_to(ROBOTS_DIR.resolve()):
        return f"{path.relative_to(ROBOTS_DIR.resolve()).as_posix()} of the bundled robots"
    if path.is_relative_to(root.resolve()):
        return path.relative_to(root.resolve()).as_posix()
    return path.as_posix()
