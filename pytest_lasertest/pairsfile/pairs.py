"""Pairs files: a robot, a world, settings, constraints, the controller, and named
baseline/candidate pairs, each with optional pinned placements (recorded failures kept as
regression tests)."""

from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass, field
from pathlib import Path

from pytest_lasertest.inputs.errors import Location, SpecError
from pytest_lasertest.inputs.node import Bounds, SpecNode, read_root
from pytest_lasertest.inputs.profile import build_profile
from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.robot import Robot
from pytest_lasertest.model.route import nominal_path
from pytest_lasertest.nav.laser_filters import ScanFilterChain
from pytest_lasertest.pairsfile.catalogue import Catalogue, load_catalogue
from pytest_lasertest.pairsfile.constraints import Constraint, read_constraints
from pytest_lasertest.pairsfile.controller import ControllerChoice, read_controller
from pytest_lasertest.pairsfile.described import DESCRIPTION_KEYS, is_described, read_described
from pytest_lasertest.pairsfile.nav2_params import NAV2_KEYS, read_nav2
from pytest_lasertest.pairsfile.navigation import read_navigation
from pytest_lasertest.pairsfile.placements import PinnedPlacement, read_placements
from pytest_lasertest.pairsfile.recorded import read_recorded
from pytest_lasertest.pairsfile.robot import read_robot
from pytest_lasertest.pairsfile.scan_filters import SCAN_FILTERS, read_scan_filters
from pytest_lasertest.pairsfile.scanners import PROFILE_KEYS, Scanner, read_fields
from pytest_lasertest.pairsfile.world import World, read_world

SECTIONS = ("robot", "world", "settings", "constraints", "controller", "navigation", "pairs")
REQUIRED_SECTIONS = ("robot", "world", "pairs")
SETTINGS_KEYS = ("min_obstacle_size", "max_obstacle_size", "witnesses", "solver_rlimit")
PAIR_KEYS = ("baseline", "candidate", "placements")
# Each witness is a test item of its own, with a solver search and a round of driving.
MAX_WITNESSES = 20
# Scans of one scanner along the route (a run, or the path the solver plans along): each is ray
# cast and checked. 50 Hz for an hour is 180,000.
MAX_SCANS = 2_000_000
# The verifier wants a beam 5 mm inside an obstacle (REQUIRED_MARGIN), so a thinner one than
# this can never be confirmed; a wider one than the largest is a wall, not an obstacle.
OBSTACLE_SIZE = Bounds(
    0.01,
    10.0,
    "m",
    "the verifier confirms a reading only 5 mm inside an obstacle, so a thinner one is never read",
    "an obstacle that wide is a wall, and the solver searches sizes up to it",
)
# Z3's resource limit per query (`settings.solver_rlimit`): a count of its own steps, the same on
# every machine, where wall time would make the plan depend on the machine's load.
RLIMIT = Bounds(
    1,
    5_000_000_000,
    "",
    "Z3 stops every query at once",
    "at a thousand times the default (5000000) one query can take hours",
)
# Pair names become part of test ids (`file::NAME[...]`), which `::`, `[` and spaces would break.
PAIR_NAME = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.-]*\Z")


@dataclass(frozen=True)
class Settings:
    """How a pairs file tunes the gate."""

    min_obstacle_size: float = 0.05  # m, the thinnest obstacle the robot must see
    max_obstacle_size: float = 1.0  # m, the widest obstacle placed
    witnesses: int = 3  # per pair and direction: one test item each
    solver_rlimit: int | None = None  # Z3's resource limit per query; None: the solver's own

    @property
    def obstacle_sizes(self) -> tuple[float, float]:
        """The thinnest obstacle the robot must see and the widest one placed (m)."""
        return self.min_obstacle_size, self.max_obstacle_size


@dataclass(frozen=True)
class Pair:
    """A named hardware change: the baseline scanner, the candidate that replaces it, and the
    placements the pair is always tested on besides the solver's."""

    name: str
    location: Location
    baseline: Scanner
    candidate: Scanner
    placements: tuple[PinnedPlacement, ...] = ()  # from `placements:`, in the order written


@dataclass(frozen=True)
class PairsFile:
    """Everything one pairs file asks the gate to check."""

    path: Path
    robot: Robot
    world: World
    pairs: tuple[Pair, ...]
    settings: Settings = field(default_factory=Settings)
    constraints: tuple[Constraint, ...] = ()
    # The file's `controller:`; None leaves the choice to conftest hooks, then the default.
    controller: ControllerChoice | None = None
    # The move_base parameters its own `navigation:` sets (over the robot's).
    move_base_overrides: tuple[tuple[str, str, float | bool], ...] = ()
    # The laser_filters chain its `navigation: {scan_filters: FILE}` runs in front of the stack.
    scan_filters: ScanFilterChain | None = None


def load_pairs_file(path: Path) -> PairsFile:
    """Read and validate a pairs file; any problem is a SpecError naming file, line and field."""
    root = read_root(
        path,
        what="pairs file",
        needs="robot, world and pairs; start from the annotated example in the README",
    )
    sections = root.mapping(SECTIONS, what="pairs-file sections")
    for key in REQUIRED_SECTIONS:
        if key not in sections:
            raise root.missing(
                key, "a pairs file needs robot, world and pairs; see the example in the README"
            )
    robot = read_robot(sections["robot"])
    overrides: tuple[tuple[str, str, float | bool], ...] = ()
    scan_filters: ScanFilterChain | None = None
    if "navigation" in sections:
        navigation = sections["navigation"]
        # The file's own parameters come after the robot's, and so win.
        overrides = read_navigation(navigation, robot.navigation, (*NAV2_KEYS, SCAN_FILTERS))
        robot = dataclasses.replace(robot, navigation=robot.navigation + overrides)
        fields = navigation.entries(what="navigation sections")
        robot = read_nav2(fields, robot)
        if SCAN_FILTERS in fields:
            scan_filters = read_scan_filters(fields[SCAN_FILTERS])
    world = read_world(sections["world"], robot)
    pairs = _read_pairs(sections["pairs"], load_catalogue(), robot.laser_mount)
    _check_scans(sections["pairs"], pairs, scanned_time(world, robot))
    return PairsFile(
        path=path,
        robot=robot,
        world=world,
        pairs=pairs,
        settings=_read_settings(sections.get("settings")),
        constraints=read_constraints(sections["constraints"]) if "constraints" in sections else (),
        controller=read_controller(sections["controller"]) if "controller" in sections else None,
        move_base_overrides=overrides,
        scan_filters=scan_filters,
    )


def scanned_time(world: World, robot: Robot) -> float:
    """The longest stretch of time the gate judges scans over (s): a run lasts up to the time
    limit, and the path the solver plans along lasts as long as the robot's nominal pace takes."""
    path = nominal_path(world.start, world.route, robot.nominal_speed, robot.nominal_turn_rate)
    return max(world.time_limit, path.duration)


def _check_scans(node: SpecNode, pairs: tuple[Pair, ...], seconds: float) -> None:
    """Refuse a scanner that would take more than MAX_SCANS scans along the route."""
    for pair in pairs:
        for side in ("baseline", "candidate"):
            profile = getattr(pair, side).profile
            scans = profile.update_rate * seconds
            if scans > MAX_SCANS:
                written = node.entries(what="pairs")[pair.name].entries(what="scanners")[side]
                raise written.error(
                    f"at {profile.update_rate:g} Hz over the {seconds:g} s the gate judges this "
                    f"route (its time limit, or its nominal duration), the {side} scanner takes "
                    f"{scans:,.0f} scans, more than the {MAX_SCANS:,} the gate judges: each is "
                    "ray cast and checked",
                    f"lower the scanner's update_rate to at most {MAX_SCANS / seconds:g} Hz, "
                    "or the world's time_limit",
                )


def _read_settings(node: SpecNode | None) -> Settings:
    if node is None:
        return Settings()
    fields = node.mapping(SETTINGS_KEYS, what="settings")
    defaults = Settings()
    smallest = _size(fields.get("min_obstacle_size"), defaults.min_obstacle_size)
    largest = _size(fields.get("max_obstacle_size"), defaults.max_obstacle_size)
    if largest < smallest:
        raise fields.get("max_obstacle_size", node).error(
            f"max_obstacle_size {largest} m is below min_obstacle_size {smallest} m",
            "make max_obstacle_size at least as large as min_obstacle_size",
        )
    count = fields.get("witnesses")
    witnesses = defaults.witnesses
    if count is not None:
        witnesses = count.whole_number()
        if not 1 <= witnesses <= MAX_WITNESSES:
            raise count.error(
                f"{witnesses} witnesses per direction: each is a test item of its own, and more "
                f"than {MAX_WITNESSES} would each cost a solver search and a round of driving",
                f"write a number from 1 to {MAX_WITNESSES}",
            )
    return Settings(smallest, largest, witnesses, _rlimit(fields.get("solver_rlimit")))


def _rlimit(node: SpecNode | None) -> int | None:
    """Z3's resource limit per query, if the pairs file sets one."""
    return None if node is None else node.whole_number_in(RLIMIT)


def _size(node: SpecNode | None, default: float) -> float:
    if node is None:
        return default
    if node.number("m") <= 0:
        raise node.error(f"{node.value} m is no obstacle", "write a positive width in m, e.g. 0.05")
    return node.number_in(OBSTACLE_SIZE)


def _read_pairs(node: SpecNode, catalogue: Catalogue, mount: Pose3D) -> tuple[Pair, ...]:
    entries = node.entries(what="pairs, each `NAME: {baseline: ..., candidate: ...}`")
    if not entries:
        raise node.error("there are no pairs", "add one: `NAME: {baseline: ..., candidate: ...}`")
    return tuple(_read_pair(name, entry, catalogue, mount) for name, entry in entries.items())


def _read_pair(name: str, node: SpecNode, catalogue: Catalogue, mount: Pose3D) -> Pair:
    if not PAIR_NAME.match(name):
        raise node.error(
            f"the pair name {name!r} cannot be part of a test id",
            "use letters, digits, '_', '-' and '.' only, e.g. `blind_spot`",
        )
    sides = node.mapping(PAIR_KEYS, what="the two scanners of the pair, and its placements")
    for side in ("baseline", "candidate"):
        if side not in sides:
            raise node.missing(side, f"give the {side} scanner: a profile, or `model: NAME`")
    return Pair(
        name,
        node.location,
        _read_scanner(sides["baseline"], catalogue, mount),
        _read_scanner(sides["candidate"], catalogue, mount),
        read_placements(sides["placements"]) if "placements" in sides else (),
    )


def _read_scanner(node: SpecNode, catalogue: Catalogue, mount: Pose3D) -> Scanner:
    fields = read_fields(node, ("model", "bag", *DESCRIPTION_KEYS, *PROFILE_KEYS, "pose"))
    if "bag" in fields:
        return read_recorded(node, fields, mount)
    if is_described(fields):
        described = read_described(node, fields)
        return Scanner(described.profile, None, described.label)
    for key in DESCRIPTION_KEYS:
        if key in fields:
            raise fields[key].error(
                f"`{key}:` belongs to a scanner read from a robot description",
                "add `urdf: PATH` (or `sdf: PATH`) to read one, or drop it",
            )
    model = fields.pop("model", None)
    if model is None:
        return Scanner(build_profile(fields, node, mount), None)
    entry = catalogue.find(model)
    try:
        return Scanner(build_profile({**entry.fields, **fields}, node, mount), entry.key)
    except SpecError as error:
        if error.location.path == node.location.path:
            raise
        # The overrides clash with a catalogue value: the fix belongs in the pairs file.
        raise SpecError(
            node.location,
            f"{node.field}.{error.field}",
            f"{error.problem} (model {entry.key!r} sets {error.field} at {error.location})",
            error.fix,
        ) from None
