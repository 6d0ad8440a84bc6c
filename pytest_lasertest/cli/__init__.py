"""The `lasertest` command: `plan` finds placements, `explain` shows which beams read one of them
(or one both scanners read, an `avoid-K` item's), `profile` shows the laser the gate reads from a
robot description (or infers from a bag), `catalogue` lists scanner models, `schema` prints the
pairs file's JSON Schema, `doctor` checks the installation."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from pytest_lasertest.cli.commands import (
    print_catalogue,
    print_explain,
    print_plan,
    print_profile,
    print_schema,
)
from pytest_lasertest.cli.doctor import run_doctor
from pytest_lasertest.cli.errors import (
    EXIT_ERROR,
    ArgumentError,
    CommandError,
    Parser,
    report_error,
)
from pytest_lasertest.descriptions.gitref import GitError
from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.model.seeds import MAX_SEED, whole_seed

PAIRS = "robots/husky/gate.lasertest.yaml"  # the pairs file the fixes' examples name


def main(argv: Sequence[str] | None = None) -> int:
    """Run one subcommand; the exit status is 0 on success and 2 on an error, which is printed
    on stderr (and with --json as a JSON object on stdout too, `errors.py`)."""
    arguments = list(sys.argv[1:] if argv is None else argv)
    try:
        status = _run(_parsed(arguments))
        sys.stdout.flush()  # here, where a reader that went away can still be caught
    except BrokenPipeError:
        # The reader stopped early (`| head`): stop quietly, as other Unix tools do, and keep
        # Python from complaining when it flushes stdout at exit.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1
    except (ArgumentError, CommandError, SpecError, GitError) as error:
        report_error(error, as_json="--json" in arguments)
        return EXIT_ERROR
    return status


def _parsed(arguments: list[str]) -> argparse.Namespace:
    """The command line, parsed; words no parser takes are the subcommand's error, whose fix
    shows that subcommand's usage rather than the top level's."""
    parser = _parser()
    args, unknown = parser.parse_known_args(arguments)
    if unknown:
        parser.commands()[args.command].error(f"unrecognized arguments: {' '.join(unknown)}")
    return args


def _parser() -> Parser:
    """`lasertest` and its subcommands, each with an example its errors' fix shows."""
    parser = Parser(prog="lasertest", description=__doc__, example=f"lasertest plan {PAIRS}")
    commands = parser.add_subparsers(dest="command", required=True)
    plan = commands.add_parser(
        "plan",
        help="find the placements that tell each pair apart",
        example=f"lasertest plan {PAIRS}",
    )
    plan.add_argument("pairs_file", type=Path, metavar="PAIRS.yaml")
    plan.add_argument("--json", action="store_true", help="print the JSON contract")
    add_explain_parser(commands)
    add_profile_parser(commands)
    add_installation_parsers(commands)
    return parser


def add_installation_parsers(commands: Any) -> None:
    """`lasertest catalogue [--json]`, `lasertest schema [--path]`, `lasertest doctor`: what the
    installed package holds, and whether it works."""
    catalogue = commands.add_parser(
        "catalogue",
        help="list the scanner models `model:` can name",
        example="lasertest catalogue --json",
    )
    catalogue.add_argument("--json", action="store_true", help="print JSON instead of a table")
    schema = commands.add_parser(
        "schema", help="print the pairs file's JSON Schema", example="lasertest schema --path"
    )
    schema.add_argument(
        "--path", action="store_true", help="print where the installed schema file is instead"
    )
    commands.add_parser(
        "doctor", help="check the installation and say what to fix", example="lasertest doctor"
    )


def add_explain_parser(commands: Any) -> None:
    """`lasertest explain PAIRS.yaml PAIR WITNESS [--seed SEED] [--json]`."""
    explain = commands.add_parser(
        "explain",
        help="show which beams read one witness's obstacle",
        example=f"lasertest explain {PAIRS} size candidate-misses-0",
    )
    explain.add_argument("pairs_file", type=Path, metavar="PAIRS.yaml")
    explain.add_argument("pair", metavar="PAIR", help="a pair's name in the pairs file")
    explain.add_argument(
        "witness",
        metavar="WITNESS",
        help="an id `lasertest plan` prints, or avoid-K for the pair's K-th placement both "
        "scanners read (its item PAIR[avoid-K])",
    )
    explain.add_argument(
        "--seed",
        type=parse_seed,
        default=0,
        metavar="SEED",
        help="for avoid-K: the run's --laser-seed, whose scan noise the baseline drives past "
        "each placement with (default 0)",
    )
    explain.add_argument("--json", action="store_true", help="print JSON instead of text")


def _run(args: argparse.Namespace) -> int:
    """The subcommand `args` names."""
    if args.command == "plan":
        return print_plan(args.pairs_file, as_json=args.json)
    if args.command == "explain":
        return print_explain(
            args.pairs_file, args.pair, args.witness, seed=args.seed, as_json=args.json
        )
    if args.command == "profile":
        return print_profile(args)
    if args.command == "catalogue":
        return print_catalogue(as_json=args.json)
    if args.command == "schema":
        return print_schema(path=args.path)
    return run_doctor()


def add_profile_parser(commands: Any) -> None:
    """`lasertest profile FILE [--sensor] [--ref] [--xacro-arg ...] [--package ...] [--json]`,
    or `lasertest profile --bag PATH [--topic TOPIC] [--json]`."""
    profile = commands.add_parser(
        "profile",
        help="print the laser profile the gate reads from a URDF, xacro or SDF file, or the "
        "profile a recording of the scanner (a bag) shows",
        example="lasertest profile robots/mybot/robot.urdf.xacro",
    )
    profile.add_argument("file", type=Path, metavar="FILE", nargs="?")
    profile.add_argument(
        "--bag",
        type=Path,
        metavar="PATH",
        help="infer the profile from a bag's LaserScan messages: a rosbag2 directory, an .mcap "
        "or .db3 file, or a ROS 1 .bag",
    )
    profile.add_argument(
        "--topic", metavar="TOPIC", help="the bag's LaserScan topic, when it has several"
    )
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


def parse_seed(text: str) -> int:
    """A seed as `--laser-seed` takes one: a whole number from 0 to MAX_SEED."""
    seed = whole_seed(text)
    if seed is None:
        raise argparse.ArgumentTypeError(
            f"{text!r} is not a seed: give a whole number from 0 to {MAX_SEED}, as the run's "
            "report header prints it (lasertest: --laser-seed=N ...)"
        )
    return seed


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
    path = Path(directory).absolute()
    if not path.is_dir():
        what = "a file" if path.exists() else "missing"
        raise argparse.ArgumentTypeError(
            f"{text!r}: {directory!r} is {what}; DIR is the directory `$(find {name})` stands for"
        )
    return name, path


if __name__ == "__main__":
    sys.exit(main())
