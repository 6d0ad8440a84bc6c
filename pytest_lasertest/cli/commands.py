"""The `lasertest` verbs that read files and print what they find: `plan`, `explain`, `profile`,
`catalogue` and `schema`. Each returns the command's exit status; what it prints comes from
`reports/`."""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING

from pytest_lasertest.cli.errors import CommandError, check_file
from pytest_lasertest.inputs.errors import display_path
from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.plan import AVOID, PairPlan, Witness
from pytest_lasertest.model.verify import Scene
from pytest_lasertest.pairsfile import Pair, PairsFile, load_pairs_file
from pytest_lasertest.pairsfile.catalogue import load_catalogue
from pytest_lasertest.pairsfile.controller import ControllerChoice, default_controller
from pytest_lasertest.pairsfile.scan_filters import with_scan_filters
from pytest_lasertest.pairsfile.schema import SHIPPED, schema_text
from pytest_lasertest.reports.catalogue import ModelFigures, catalogue_table
from pytest_lasertest.reports.formats import json_text

if TYPE_CHECKING:
    from pytest_lasertest.search.trials import Setting
    from pytest_lasertest.sim.client import PhysicsClient
    from pytest_lasertest.sim.scenario import ControllerError, Run

DESCRIPTION = "a URDF, xacro or SDF file"
BOTH = (
    "lasertest profile robots/mybot/robot.urdf.xacro [--sensor NAME ...] reads a description; "
    "lasertest profile --bag rosbag2_2024_05_01 [--topic /scan] reads a recording"
)


def print_plan(path: Path, *, as_json: bool) -> int:
    """Solve every pair of a pairs file and print the verified witnesses."""
    from pytest_lasertest.reports.plan import plan_json, plan_text

    spec = load_pairs_file(_pairs_file(path, "plan"))
    plans = [_driven_plan(spec, pair) for pair in spec.pairs]
    if as_json:
        print(json_text({"pairs": [plan_json(plan) for plan in plans]}))
    else:
        print("\n".join(plan_text(plan) for plan in plans))
    return 0


def print_explain(
    path: Path, pair_name: str, witness_id: str, *, seed: int = 0, as_json: bool
) -> int:
    """Plan one pair and print which beams of each scanner read one witness's obstacle: one
    `lasertest plan` prints, or `avoid-K`, the placement both scanners read of the pair's item
    `PAIR[avoid-K]`, as a run with `--laser-seed=seed` finds it."""
    from pytest_lasertest.reports.explain import explain_json, explain_scans, explain_text

    spec = load_pairs_file(_pairs_file(path, "explain"))
    pair = _named_pair(spec, pair_name)
    if witness_id.startswith(f"{AVOID}-"):
        scene, witness = _avoid_witness(spec, pair, witness_id, seed)
    else:
        plan = _driven_plan(spec, pair)
        scene, witness = plan.scene, _planned_witness(spec, plan, witness_id)
    scans = explain_scans(scene, witness)
    if as_json:
        print(json_text(explain_json(pair_name, witness, scans)))
    else:
        print(explain_text(pair_name, witness, scans, scene=scene))
    return 0


def _named_pair(spec: PairsFile, name: str) -> Pair:
    """The pair of that name, or an error naming the pairs there are."""
    pair = next((pair for pair in spec.pairs if pair.name == name), None)
    if pair is None:
        names = ", ".join(pair.name for pair in spec.pairs)
        raise CommandError(
            f"no pair {name!r} in {spec.path}", f"give one of its pairs: {names}", spec.path
        )
    return pair


def _planned_witness(spec: PairsFile, plan: PairPlan, witness_id: str) -> Witness:
    """The plan's witness of that id, or an error naming the ids there are."""
    witness = plan.find(witness_id)
    if witness is None:
        ids = ", ".join(witness.id for witness in plan.witnesses()) or "none"
        raise CommandError(
            f"pair {plan.name!r} has no witness {witness_id!r}",
            f"give one of the witnesses `lasertest plan` prints for it ({ids}), or "
            f"{_avoid_ids(spec)} for its {_placements(spec)} both scanners read",
            spec.path,
        )
    return witness


def _avoid_witness(
    spec: PairsFile, pair: Pair, witness_id: str, seed: int
) -> tuple[Scene, Witness]:
    """The pair's `avoid-K` placement, found as its item finds it: on the path the baseline's
    obstacle-free run times, among the placements the baseline robot passes with `seed`'s scan
    noise (`LaserSession.avoid`)."""
    from pytest_lasertest.search.plans import avoid_for, pair_scene
    from pytest_lasertest.search.witness import passed_by_baseline
    from pytest_lasertest.sim.scenario import ControllerError

    index = _avoid_index(spec, pair, witness_id)
    with _setting(spec, pair, seed) as setting:
        scene = pair_scene(spec, pair, _control_run(spec, pair, setting.client))
        try:
            found = passed_by_baseline(setting, avoid_for(spec, scene), spec.settings.witnesses)
        except ControllerError as error:
            raise _broken(error, pair, "a drive past its placements both scanners read") from None
    if index >= len(found):
        raise _not_passed(spec, pair, witness_id, found, seed)
    return scene, found[index]


def _avoid_index(spec: PairsFile, pair: Pair, witness_id: str) -> int:
    """K of `avoid-K`, refused unless the pair has that item."""
    index = witness_id.removeprefix(f"{AVOID}-")
    if index.isdigit() and int(index) < spec.settings.witnesses:
        return int(index)
    raise CommandError(
        f"pair {pair.name!r} has no witness {witness_id!r}: its {_placements(spec)} both "
        f"scanners read {'are' if spec.settings.witnesses > 1 else 'is'} {_avoid_ids(spec)}, "
        "as many as settings.witnesses asks",
        f"give {_avoid_ids(spec)}, or a witness `lasertest plan` prints for it",
        spec.path,
    )


def _avoid_ids(spec: PairsFile) -> str:
    """`avoid-0`, or `avoid-0 to avoid-2`: the ids of a pair's items `PAIR[avoid-K]`."""
    last = spec.settings.witnesses - 1
    return f"{AVOID}-0" if last == 0 else f"{AVOID}-0 to {AVOID}-{last}"


def _placements(spec: PairsFile) -> str:
    return "placements" if spec.settings.witnesses > 1 else "placement"


def _not_passed(
    spec: PairsFile, pair: Pair, witness_id: str, found: tuple[Witness, ...], seed: int
) -> CommandError:
    """An `avoid-K` the baseline robot does not get to: its item skips, as there is no K-th
    placement both scanners read that the baseline passes."""
    passed = ", ".join(witness.id for witness in found)
    give = f"give one it passes ({passed})" if found else "give a witness `lasertest plan` prints"
    return CommandError(
        f"pair {pair.name!r} has no witness {witness_id!r}: with seed {seed} the baseline robot "
        f"passes {len(found)} of its placements both scanners read, and its item "
        f"{pair.name}[{witness_id}] is skipped",
        f"{give}, or give the seed of the run (its --laser-seed) with --seed",
        spec.path,
    )


@contextlib.contextmanager
def _setting(spec: PairsFile, pair: Pair, seed: int) -> Iterator[Setting]:
    """Where the pair's drives go, as an item's would: the pairs file's controller, else the
    default (conftest hooks need pytest, and are not asked), in a physics client closed after."""
    from pytest_lasertest.search.drives import RunCache
    from pytest_lasertest.search.trials import Setting
    from pytest_lasertest.sim.client import PhysicsClient

    controller = _controller(spec)
    client = PhysicsClient()
    try:
        yield Setting(spec, pair, controller, seed, client, RunCache())
    finally:
        client.close()


def _controller(spec: PairsFile) -> ControllerChoice:
    """The pairs file's controller, else the default, behind the file's scan filter chain."""
    return with_scan_filters(spec.controller or default_controller(spec.path), spec.scan_filters)


def print_profile(args: argparse.Namespace) -> int:
    """Print the laser a description holds, as the gate reads it, or the profile a recording
    of the scanner shows."""
    from pytest_lasertest.descriptions.profile import read_profile
    from pytest_lasertest.reports.description import profile_read_json, profile_read_text

    _check_profile_source(args)
    if args.bag is not None:
        return print_bag_profile(args.bag, args.topic, as_json=args.json)
    if args.ref is None:  # at a revision, the working tree may well lack the file
        check_file(args.file, DESCRIPTION, "lasertest profile robots/mybot/robot.urdf.xacro")
    read = read_profile(
        args.file,
        sensor=args.sensor,
        ref=args.ref,
        args=dict(args.xacro_arg),
        packages=dict(args.package),
    )
    print(json_text(profile_read_json(read)) if args.json else profile_read_text(read))
    return 0


def print_bag_profile(path: Path, topic: str | None, *, as_json: bool) -> int:
    """Print the profile the LaserScan messages of a bag show, as YAML a pairs file pastes."""
    from pytest_lasertest.inputs.bags import BagError
    from pytest_lasertest.inputs.inferred import profile_from_bag
    from pytest_lasertest.reports.recording import recording_json, recording_yaml

    try:
        inferred = profile_from_bag(path, topic)
    except BagError as error:
        problem = f"{display_path(error.path)}: {error.problem}"
        raise CommandError(problem, error.fix, error.path, kind="input") from None
    print(json_text(recording_json(inferred, path)) if as_json else recording_yaml(inferred, path))
    return 0


def _check_profile_source(args: argparse.Namespace) -> None:
    """`lasertest profile` reads a description FILE or a --bag, and each its own options."""
    if args.bag is None and args.file is None:
        raise CommandError("give a description FILE, or a recording with --bag PATH", BOTH)
    if args.bag is not None and args.file is not None:
        raise CommandError("give a description FILE or --bag PATH, not both", BOTH)
    if args.bag is None and args.topic is not None:
        raise CommandError("--topic names a topic of a bag, and no --bag was given", BOTH)
    described = {
        "--sensor": args.sensor is not None,
        "--ref": args.ref is not None,
        "--xacro-arg": bool(args.xacro_arg),
        "--package": bool(args.package),
    }
    given = [option for option, used in described.items() if used]
    if args.bag is not None and given:
        raise CommandError(f"only a description FILE takes {', '.join(given)}, not --bag", BOTH)


def print_catalogue(*, as_json: bool) -> int:
    """Print every catalogue model with the figures that matter for a 2D scan."""
    rows = [
        ModelFigures.of(key, entry.name, entry.profile(Pose3D()))
        for key, entry in load_catalogue().entries.items()
    ]
    if as_json:
        print(json_text([dataclasses.asdict(row) for row in rows]))
    else:
        print(catalogue_table(rows))
    return 0


def print_schema(*, path: bool) -> int:
    """Print the pairs file's JSON Schema, or where the installed package keeps it."""
    if path:
        print(SHIPPED)
    else:
        print(schema_text(), end="")  # the text ends in its own newline
    return 0


def _driven_plan(spec: PairsFile, pair: Pair) -> PairPlan:
    """The pair planned as the gate's items plan it: along the route timed by the baseline's
    obstacle-free run."""
    from pytest_lasertest.search.plans import plan_for

    return plan_for(spec, pair, _control_run(spec, pair))


def _control_run(spec: PairsFile, pair: Pair, client: PhysicsClient | None = None) -> Run:
    """The baseline's obstacle-free run, which times the path the gate plans on, with the pairs
    file's controller or the default (conftest hooks need pytest, and are not asked). That run
    reads nothing, so its scan noise, and the seed, make no difference to it."""
    from pytest_lasertest.search.drives import drive
    from pytest_lasertest.sim.scenario import ControllerError

    controller = _controller(spec)
    try:
        return drive(spec, pair.baseline.profile, (), 0, controller.factory, client)
    except ControllerError as error:
        raise _broken(error, pair) from None


def _broken(
    error: ControllerError, pair: Pair, drive: str = "the obstacle-free drive that times"
) -> CommandError:
    """A controller that broke `drive` of `pair`: what it did, where in its code, and the fix
    (`sim/guard.py`)."""
    fault = error.fault
    frame = fault.frames[0] if fault.frames else None  # the controller's own call
    file = Path(frame.path) if frame else None
    where = f" (at {display_path(file)}:{frame.line} in {frame.function})" if frame and file else ""
    problem = (
        f"the controller {error.controller} broke {drive} pair "
        f"{pair.name!r}: {fault.describe()}{where}"
    )
    line = frame.line if frame else None
    return CommandError(problem, fault.fix, file, kind="controller", line=line)


def _pairs_file(path: Path, verb: str) -> Path:
    """`path`, checked to be a readable pairs file before it is read."""
    check_file(path, "a pairs file", f"lasertest {verb} robots/husky/gate.lasertest.yaml")
    return path
