"""The YAML repro of a failing item: a pairs file with one pair and its one failing placement.

It is the user's own pairs file cut down to the failing case: the robot, world, controller and
navigation sections and the pair's two scanners are copied as written (so `model:` overrides read
as the user wrote them), and the placement is pinned. A scanner read from a robot description is
written out as the profile it read: its file moves on, and its `ref:` (a branch) moves too.
Paths to files beside the pairs file (the robot's, the world's `map:` and `sdf:`, and the Nav2
and laser_filters params files `navigation:` names) are rewritten to be found from wherever the
repro is written.
Committed, the repro replays the failure as a regression test on every run.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Sequence
from pathlib import Path
from typing import TypeGuard

import yaml

from pytest_lasertest.artifacts.files import write_text
from pytest_lasertest.inputs.errors import Location, SpecError, display_path
from pytest_lasertest.inputs.yamlfile import read_text
from pytest_lasertest.model.obstacles import Obstacle, placed
from pytest_lasertest.pairsfile.body import body_fields
from pytest_lasertest.pairsfile.bundled import bundled_robots
from pytest_lasertest.pairsfile.described import DESCRIPTION_KEYS
from pytest_lasertest.pairsfile.pairs import Pair, PairsFile
from pytest_lasertest.pairsfile.placements import PinnedPlacement, obstacle_fields
from pytest_lasertest.pairsfile.scanners import Scanner

# Settings and constraints only steer the solver, which a pinned placement never asks.
COPIED_SECTIONS = ("robot", "world", "controller", "navigation")
# The world's fields that name files, relative to the pairs file; a robot's written in place;
# and `navigation:`'s (a Nav2 params file, a laser_filters params file).
WORLD_FILES = ("map", "sdf")
ROBOT_FILES = ("navigation", "nav2")
NAVIGATION_FILES = ("nav2", "scan_filters")


class _ReproDumper(yaml.SafeDumper):
    """SafeDumper writing shared values out in full (`&id001` anchors read badly in a repro),
    and list items indented."""

    def ignore_aliases(self, data: object) -> bool:
        return True

    def increase_indent(self, flow: bool = False, indentless: bool = False) -> None:
        # List items indented below their key, as the examples write them.
        super().increase_indent(flow, False)


def repro_yaml(
    spec: PairsFile, pair: Pair, pinned: PinnedPlacement, destination: Path, header: Sequence[str]
) -> str:
    """A pairs file holding one pair with one pinned placement: the failing case, replayable on
    its own from `destination`."""
    written = _written(spec)
    document = {key: written[key] for key in COPIED_SECTIONS if key in written}
    robot = written["robot"]
    document["robot"] = (
        _robot_in_place(robot, spec, destination)
        if isinstance(robot, dict)
        else _robot_from(str(robot), spec.path, destination)
    )
    if "world" in document:
        document["world"] = _world_from(document["world"], spec.path, destination)
    navigation = document.get("navigation")
    if isinstance(navigation, dict):
        relocated = _files_relocated(navigation, NAVIGATION_FILES, spec.path, destination)
        document["navigation"] = relocated
    document["pairs"] = {pair.name: _pair_mapping(written, pair, pinned)}
    notes = [
        *header,
        *_described_notes(pair),
        *_robot_notes(robot),
        *_controller_notes(written.get("controller"), spec.path, destination),
    ]
    body = yaml.dump(
        document,
        Dumper=_ReproDumper,
        sort_keys=False,
        default_flow_style=None,  # innermost mappings on one line, as pairs files are written
        allow_unicode=True,
        width=100,
    )
    return _comments(notes) + body


def write_repro(
    path: Path, spec: PairsFile, pair: Pair, pinned: PinnedPlacement, header: Sequence[str]
) -> Path:
    """Write `repro_yaml` at `path` atomically; the temporary file's leading dot keeps a
    half-written repro out of `*.lasertest.yaml` collection."""
    return write_text(path, repro_yaml(spec, pair, pinned, path, header))


def _written(spec: PairsFile) -> dict[str, object]:
    """The pairs file's sections as the user wrote them (anchors and merge keys resolved)."""
    try:
        written = yaml.safe_load(read_text(spec.path))
    except yaml.YAMLError:
        # It parsed when it was collected: someone is editing it.
        written = None
    if not isinstance(written, dict):
        raise _changed(spec.path, "is no longer a mapping of sections")
    return written


def _changed(path: Path, problem: str) -> SpecError:
    """The pairs file, re-read to copy it into the repro, is not what the run read."""
    return SpecError(
        Location(path, 1),
        "",
        f"the pairs file changed since it was read and {problem}",
        "restore it, or run again",
    )


def _pair_mapping(
    written: dict[str, object], pair: Pair, pinned: PinnedPlacement
) -> dict[str, object]:
    """The pair's scanners as written, and `pinned` as its one placement."""
    pairs = written.get("pairs")
    sides = pairs.get(pair.name) if isinstance(pairs, dict) else None
    if not isinstance(sides, dict) or not {"baseline", "candidate"} <= sides.keys():
        raise SpecError(
            pair.location,
            f"pairs.{pair.name}",
            "the pair is gone from the file since it was read, or lost a scanner",
            "restore it, or run again",
        )
    placement: dict[str, object] = {"obstacle": _pinned_fields(pinned.obstacle)}
    placement["seed"] = int(pinned.seed)
    if pinned.direction is not None:
        placement["direction"] = pinned.direction
    return {
        "baseline": _scanner(sides["baseline"], pair.baseline),
        "candidate": _scanner(sides["candidate"], pair.candidate),
        "placements": [placement],
    }


def _pinned_fields(obstacle: Obstacle) -> dict[str, object]:
    """`obstacle_fields` of the obstacle as drives place it (`obstacles.placed`): the very
    numbers the failure drove, to a micrometre."""
    return obstacle_fields(placed(obstacle))


def _scanner(written: object, scanner: Scanner) -> object:
    """The scanner as written, or, read from a description, the profile it read."""
    if scanner.source is None:
        return written
    profile = scanner.profile
    fields: dict[str, object] = {
        "samples": profile.samples,
        "resolution": profile.resolution,
        "min_angle": profile.min_angle,
        "max_angle": profile.max_angle,
        "range": {
            "min": profile.range_min,
            "max": profile.range_max,
            "resolution": profile.range_resolution,
        },
        "update_rate": profile.update_rate,
        "pose": {"xyz": list(profile.pose.xyz), "rpy": list(profile.pose.rpy)},
    }
    if profile.noise is not None:
        fields["noise"] = {"type": "gaussian", **dataclasses.asdict(profile.noise)}
    return fields


def _robot_from(name: str, original: Path, destination: Path) -> str:
    """`robot:` as it resolves from the destination's directory: a bundled name or an absolute
    path as written, a relative path rewritten relative to where the repro goes."""
    if name in bundled_robots():
        return name
    relative = _relocated(name, original, destination)
    # A relative path that reads as a bundled name would load the bundled robot instead.
    return f"./{relative}" if relative in bundled_robots() else relative


def _robot_in_place(written: dict[str, object], spec: PairsFile, destination: Path) -> object:
    """A robot written in place, as written, its files' paths rewritten relative to where the
    repro goes; read around a description, with the mount (and name and body) it read pinned
    in place of the description, which moves on as a scanner's does."""
    robot = spec.robot
    kept = {key: value for key, value in written.items() if key not in DESCRIPTION_KEYS}
    kept = _files_relocated(kept, ROBOT_FILES, spec.path, destination)
    if not _around_description(written):
        return kept
    # Written in full (YAML round-trips a float's repr), so that the replay is the same robot.
    mount = robot.laser_mount
    kept.setdefault("name", robot.name)
    kept["laser_mount"] = {"xyz": [*map(float, mount.xyz)], "rpy": [*map(float, mount.rpy)]}
    kept.setdefault("body", body_fields(robot.body))
    return kept


def _world_from(world: object, original: Path, destination: Path) -> object:
    """`world:` as written, its `map:` and `sdf:` paths, if relative, rewritten relative to where
    the repro goes."""
    if not isinstance(world, dict):
        return world
    return _files_relocated(world, WORLD_FILES, original, destination)


def _files_relocated(
    section: dict[str, object], keys: Sequence[str], original: Path, destination: Path
) -> dict[str, object]:
    """`section` as written, the paths its `keys` give rewritten with `_relocated`."""
    return {
        key: _relocated(value, original, destination)
        if key in keys and isinstance(value, str)
        else value
        for key, value in section.items()
    }


def _relocated(path: str, original: Path, destination: Path) -> str:
    """A path written in the pairs file at `original`, as the file at `destination` must write
    it: an absolute path as written, a relative one rewritten relative to destination's
    directory."""
    if Path(path).is_absolute():
        return path
    target = original.parent.resolve() / path
    return Path(os.path.relpath(target, destination.parent.resolve())).as_posix()


def _around_description(written: object) -> TypeGuard[dict[str, object]]:
    """Whether `robot:` was written in place around the robot's description."""
    return isinstance(written, dict) and any(key in written for key in DESCRIPTION_KEYS)


def _robot_notes(written: object) -> list[str]:
    """Where a robot written around its description came from."""
    if not _around_description(written):
        return []
    source = written.get("urdf", written.get("sdf"))
    return [f"robot: its laser mount and body as read from {source}, pinned as read"]


def _described_notes(pair: Pair) -> list[str]:
    """Where the scanners read from descriptions came from."""
    return [
        f"{side}: {scanner.source}, pinned as read"
        for side, scanner in (("baseline", pair.baseline), ("candidate", pair.candidate))
        if scanner.source is not None
    ]


def _controller_notes(controller: object, original: Path, destination: Path) -> list[str]:
    """A note when `controller:` names a module next to the original pairs file, which the
    repro, written elsewhere, finds only if it is importable: controller.py has no path form."""
    if not isinstance(controller, str) or ":" not in controller:
        return []
    here = original.parent.resolve()
    if here == destination.parent.resolve():
        return []
    module = controller.split(":", 1)[0].strip()
    base = here.joinpath(*module.split("."))
    if not (base.with_suffix(".py").is_file() or (base / "__init__.py").is_file()):
        return []
    return [
        f"controller: {controller} is the module {module!r} next to {display_path(original)};"
        f" to replay this file, make it importable (copy it next to this file, or put"
        f" {display_path(here)} on sys.path)"
    ]


def _comments(lines: Sequence[str]) -> str:
    """`lines` as YAML comments, then a blank line; nothing when there are none."""
    if not lines:
        return ""
    split = [part for line in lines for part in line.splitlines() or [""]]
    return "".join(f"# {part}".rstrip() + "\n" for part in split) + "\n"
