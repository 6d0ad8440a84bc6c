"""The `lasertest` command: `plan` finds placements, `explain` shows which beams read one of them,
`profile` shows the laser the gate reads from a robot description, `catalogue` lists scanner
models, `doctor` checks the installation."""

from __future__ import annotations

import argparse
import dataclasses
import importlib.metadata
import importlib.util
import json
import math
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.route import NominalPath
from pytest_lasertest.model.sensor import LaserProfile
from pytest_lasertest.pairsfile import Pair, PairsFile, SpecError, load_pairs_file
from pytest_lasertest.pairsfile.bundled import bundled_robots
from pytest_lasertest.pairsfile.catalogue import load_catalogue
from pytest_lasertest.pairsfile.controller import default_controller
from pytest_lasertest.descriptions.gitref import GitError
from pytest_lasertest.pairsfile.robot import load_robot_file

# Distribution name -> module name, for the packages the plugin runs on.
DEPENDENCIES = {
    "pytest": "pytest",
    "numpy": "numpy",
    "pyyaml": "yaml",
    "hypothesis": "hypothesis",
    "z3-solver": "z3",
    "pybullet": "pybullet",
    "xacro": "xacro",
}


def main(argv: Sequence[str] | None = None) -> int:
    """Run one subcommand; the exit status is 0 on success."""
    parser = argparse.ArgumentParser(prog="lasertest", description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)
    plan = commands.add_parser("plan", help="find the placements that tell each pair apart")
    plan.add_argument("pairs_file", type=Path, metavar="PAIRS.yaml")
    plan.add_argument("--json", action="store_true", help="print the JSON contract")
    explain = commands.add_parser("explain", help="show which beams read one witness's obstacle")
    explain.add_argument("pairs_file", type=Path, metavar="PAIRS.yaml")
    explain.add_argument("pair", metavar="PAIR", help="a pair's name in the pairs file")
    explain.add_argument("witness", metavar="WITNESS", help="an id `lasertest plan` prints")
    explain.add_argument("--json", action="store_true", help="print JSON instead of text")
    add_profile_parser(commands)
    catalogue = commands.add_parser("catalogue", help="list the scanner models `model:` can name")
    catalogue.add_argument("--json", action="store_true", help="print JSON instead of a table")
    commands.add_parser("doctor", help="check the installation and say what to fix")
    args = parser.parse_args(argv)
    try:
        if args.command == "plan":
            return print_plan(args.pairs_file, as_json=args.json)
        if args.command == "explain":
            return print_explain(args.pairs_file, args.pair, args.witness, as_json=args.json)
        if args.command == "profile":
            return print_profile(args)
        if args.command == "catalogue":
            return print_catalogue(as_json=args.json)
        return run_doctor()
    except (SpecError, GitError) as error:
        print(f"lasertest: {error}", file=sys.stderr)
        return 2


def add_profile_parser(commands: Any) -> None:
    """`lasertest profile FILE [--sensor] [--ref] [--xacro-arg ...] [--package ...] [--json]`."""
    profile = commands.add_parser(
        "profile", help="print the laser profile the gate reads from a URDF, xacro or SDF file"
    )
    profile.add_argument("file", type=Path, metavar="FILE")
    profile.add_argument(
        "--sensor", metavar="NAME", help="the laser to read, when there are several"
    )
    profile.add_argument("--ref", metavar="REF", help="read the file at this git revision")
    profile.add_argument(
        "--xacro-arg",
        action="append",
        default=[],
        type=parse_xacro_arg,
        metavar="NAME:=VALUE",
        help="a xacro arg (repeatable)",
    )
    profile.add_argument(
        "--package",
        action="append",
        default=[],
        type=parse_package,
        metavar="NAME=DIR",
        help="where $(find NAME) points (repeatable)",
    )
    profile.add_argument("--json", action="store_true", help="print JSON instead of text")


def parse_xacro_arg(text: str) -> tuple[str, str]:
    """`NAME:=VALUE`, as xacro's command line takes it."""
    name, separator, value = text.partition(":=")
    if not separator or not name:
        raise argparse.ArgumentTypeError(f"{text!r} is not NAME:=VALUE, e.g. laser_enabled:=1")
    return name, value


def parse_package(text: str) -> tuple[str, Path]:
    """`NAME=DIR`: the directory `$(find NAME)` stands for."""
    name, separator, directory = text.partition("=")
    if not separator or not name or not directory:
        raise argparse.ArgumentTypeError(f"{text!r} is not NAME=DIR, e.g. lms1xx=src/LMS1xx")
    return name, Path(directory).absolute()


def print_profile(args: argparse.Namespace) -> int:
    """Print the laser a description holds, as the gate reads it."""
    from pytest_lasertest.reports.description import profile_read_json, profile_read_text, read_profile

    read = read_profile(
        args.file,
        sensor=args.sensor,
        ref=args.ref,
        args=dict(args.xacro_arg),
        packages=dict(args.package),
    )
    print(json.dumps(profile_read_json(read), indent=2) if args.json else profile_read_text(read))
    return 0


@dataclass(frozen=True)
class ModelFigures:
    """One catalogue model as `lasertest catalogue` shows it."""

    model: str
    name: str
    fov_deg: float
    beams: int
    step_deg: float
    range_min_m: float
    range_max_m: float
    update_rate_hz: float
    noise_stddev_m: float | None

    @classmethod
    def of(cls, model: str, name: str, profile: LaserProfile) -> ModelFigures:
        return cls(
            model=model,
            name=name,
            fov_deg=round(math.degrees(profile.max_angle - profile.min_angle), 2),
            beams=profile.beam_count,
            step_deg=round(math.degrees(profile.angle_increment), 4),
            range_min_m=profile.range_min,
            range_max_m=profile.range_max,
            update_rate_hz=profile.update_rate,
            noise_stddev_m=profile.noise.stddev if profile.noise else None,
        )

    def cells(self) -> tuple[str, ...]:
        noise = "-" if self.noise_stddev_m is None else f"{self.noise_stddev_m * 1e3:g}"
        return (
            self.model,
            f"{self.fov_deg:g}",
            str(self.beams),
            f"{self.step_deg:.3f}",
            f"{self.range_min_m:g}-{self.range_max_m:g}",
            f"{self.update_rate_hz:g}",
            noise,
            self.name,
        )


CATALOGUE_HEADER = (
    "model",
    "FOV deg",
    "beams",
    "step deg",
    "range m",
    "rate Hz",
    "noise mm",
    "name",
)


def _driven_path(spec: PairsFile, pair: Pair) -> NominalPath:
    """The path the gate's items plan on: the route timed by the baseline's obstacle-free run,
    with the pairs file's controller or the default (conftest hooks need pytest, and are not
    asked). That run reads nothing, so its scan noise, and the seed, make no difference to it."""
    from pytest_lasertest.search.drives import drive, solver_path

    controller = spec.controller or default_controller(spec.path)
    control = drive(spec, pair.baseline.profile, (), 0, controller.factory)
    return solver_path(spec, control)


def print_plan(path: Path, *, as_json: bool) -> int:
    """Solve every pair of a pairs file and print the verified witnesses."""
    from pytest_lasertest.reports.plan import plan_json, plan_text
    from pytest_lasertest.solver.plan import plan_pair

    spec = load_pairs_file(path)
    plans = [plan_pair(spec, pair, _driven_path(spec, pair)) for pair in spec.pairs]
    if as_json:
        print(json.dumps({"pairs": [plan_json(plan) for plan in plans]}, indent=2))
    else:
        print("\n".join(plan_text(plan) for plan in plans))
    return 0


def print_explain(path: Path, pair_name: str, witness_id: str, *, as_json: bool) -> int:
    """Plan one pair and print which beams of each scanner read one witness's obstacle."""
    from pytest_lasertest.reports.explain import (
        explain_json,
        explain_scans,
        explain_text,
        find_witness,
        witness_ids,
    )
    from pytest_lasertest.solver.plan import plan_pair

    spec = load_pairs_file(path)
    pair = next((pair for pair in spec.pairs if pair.name == pair_name), None)
    if pair is None:
        names = ", ".join(pair.name for pair in spec.pairs)
        return _usage_error(f"no pair {pair_name!r} in {path}; pairs: {names}")
    plan = plan_pair(spec, pair, _driven_path(spec, pair))
    witness = find_witness(plan, witness_id)
    if witness is None:
        ids = ", ".join(witness_ids(plan)) or "none"
        return _usage_error(f"pair {pair_name!r} has no witness {witness_id!r}; witnesses: {ids}")
    scans = explain_scans(plan.scene, witness)
    if as_json:
        print(json.dumps(explain_json(pair_name, witness, scans), indent=2))
    else:
        print(explain_text(pair_name, witness, scans))
    return 0


def _usage_error(message: str) -> int:
    print(f"lasertest: {message}", file=sys.stderr)
    return 2


def print_catalogue(*, as_json: bool) -> int:
    """Print every catalogue model with the figures that matter for a 2D scan."""
    rows = [
        ModelFigures.of(key, entry.name, entry.profile(Pose3D()))
        for key, entry in load_catalogue().entries.items()
    ]
    if as_json:
        print(json.dumps([dataclasses.asdict(row) for row in rows], indent=2))
    else:
        print(_table([CATALOGUE_HEADER, *(row.cells() for row in rows)]))
    return 0


def _table(lines: list[tuple[str, ...]]) -> str:
    widths = [max(len(line[column]) for line in lines) for column in range(len(lines[0]))]
    return "\n".join(
        "  ".join(cell.ljust(width) for cell, width in zip(line, widths, strict=True)).rstrip()
        for line in lines
    )


@dataclass(frozen=True)
class Check:
    """One thing the plugin needs, how to test it, and what to do when it is broken."""

    name: str
    run: Callable[[], str]
    fix: str


def run_doctor() -> int:
    """Run every check, print one line each, and return 1 if any failed."""
    failures = 0
    for check in CHECKS:
        try:
            print(f"ok    {check.name}: {check.run()}")
        except Exception as error:  # noqa: BLE001  (the doctor reports every failure as text)
            failures += 1
            print(f"FAIL  {check.name}: {type(error).__name__}: {error}\n      fix: {check.fix}")
    print("all checks passed" if not failures else f"{failures} check(s) failed")
    return 1 if failures else 0


def _python() -> str:
    return f"{sys.implementation.name} {sys.version.split()[0]} at {sys.executable}"


def _packages() -> str:
    found, missing = [], []
    for distribution, module in DEPENDENCIES.items():
        try:
            version = importlib.metadata.version(distribution)
        except importlib.metadata.PackageNotFoundError:
            version = None
        if version is None or importlib.util.find_spec(module) is None:
            missing.append(distribution)
        else:
            found.append(f"{distribution} {version}")
    if missing:
        raise RuntimeError(f"not installed: {', '.join(missing)}")
    return ", ".join(found)


def _z3() -> str:
    from pytest_lasertest.solver import self_test

    return self_test()


def _pybullet() -> str:
    from pytest_lasertest.sim import self_test

    return self_test()


def _robots() -> str:
    robots = bundled_robots()
    if not robots:
        raise RuntimeError("no bundled robot found")
    return ", ".join(f"{name} ({load_robot_file(path).name})" for name, path in robots.items())


def _catalogue() -> str:
    entries = load_catalogue().entries
    if not entries:
        raise RuntimeError("the scanner catalogue is empty")
    return f"{len(entries)} models load and validate"


def _entry_point() -> str:
    for entry_point in importlib.metadata.entry_points(group="pytest11"):
        if entry_point.value == "pytest_lasertest.plugin":
            return f"pytest loads it as {entry_point.name!r}"
    raise RuntimeError("no pytest11 entry point names pytest_lasertest.plugin")


CHECKS = (
    Check("python", _python, "install Python 3.11 or newer"),
    Check("packages", _packages, "pip install pytest-lasertest, which brings its dependencies"),
    Check("z3", _z3, "pip install --force-reinstall z3-solver"),
    Check("pybullet", _pybullet, "pip install --force-reinstall pybullet"),
    Check("bundled robots", _robots, "reinstall pytest-lasertest: its package data is incomplete"),
    Check("scanner catalogue", _catalogue, "reinstall pytest-lasertest: its catalogue is damaged"),
    Check(
        "pytest plugin", _entry_point, "reinstall pytest-lasertest so pytest finds its entry point"
    ),
)


if __name__ == "__main__":
    sys.exit(main())
