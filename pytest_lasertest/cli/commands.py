"""The `lasertest` verbs that read files and print what they find: `plan`, `explain`, `profile`
and `catalogue`. Each returns the command's exit status; what it prints comes from `reports/`."""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
from pathlib import Path

from pytest_lasertest.model.geometry import Pose3D
from pytest_lasertest.model.plan import PairPlan
from pytest_lasertest.pairsfile import Pair, PairsFile, load_pairs_file
from pytest_lasertest.pairsfile.catalogue import load_catalogue
from pytest_lasertest.pairsfile.controller import default_controller
from pytest_lasertest.reports.catalogue import ModelFigures, catalogue_table


def print_plan(path: Path, *, as_json: bool) -> int:
    """Solve every pair of a pairs file and print the verified witnesses."""
    from pytest_lasertest.reports.plan import plan_json, plan_text

    spec = load_pairs_file(path)
    plans = [_driven_plan(spec, pair) for pair in spec.pairs]
    if as_json:
        print(json.dumps({"pairs": [plan_json(plan) for plan in plans]}, indent=2))
    else:
        print("\n".join(plan_text(plan) for plan in plans))
    return 0


def print_explain(path: Path, pair_name: str, witness_id: str, *, as_json: bool) -> int:
    """Plan one pair and print which beams of each scanner read one witness's obstacle."""
    from pytest_lasertest.reports.explain import explain_json, explain_scans, explain_text

    spec = load_pairs_file(path)
    pair = next((pair for pair in spec.pairs if pair.name == pair_name), None)
    if pair is None:
        names = ", ".join(pair.name for pair in spec.pairs)
        return _usage_error(f"no pair {pair_name!r} in {path}; pairs: {names}")
    plan = _driven_plan(spec, pair)
    witness = plan.find(witness_id)
    if witness is None:
        ids = ", ".join(witness.id for witness in plan.witnesses()) or "none"
        return _usage_error(f"pair {pair_name!r} has no witness {witness_id!r}; witnesses: {ids}")
    scans = explain_scans(plan.scene, witness)
    if as_json:
        print(json.dumps(explain_json(pair_name, witness, scans), indent=2))
    else:
        print(explain_text(pair_name, witness, scans))
    return 0


def print_profile(args: argparse.Namespace) -> int:
    """Print the laser a description holds, as the gate reads it."""
    from pytest_lasertest.descriptions.profile import read_profile
    from pytest_lasertest.reports.description import profile_read_json, profile_read_text

    read = read_profile(
        args.file,
        sensor=args.sensor,
        ref=args.ref,
        args=dict(args.xacro_arg),
        packages=dict(args.package),
    )
    print(json.dumps(profile_read_json(read), indent=2) if args.json else profile_read_text(read))
    return 0


def print_catalogue(*, as_json: bool) -> int:
    """Print every catalogue model with the figures that matter for a 2D scan."""
    rows = [
        ModelFigures.of(key, entry.name, entry.profile(Pose3D()))
        for key, entry in load_catalogue().entries.items()
    ]
    if as_json:
        print(json.dumps([dataclasses.asdict(row) for row in rows], indent=2))
    else:
        print(catalogue_table(rows))
    return 0


def _driven_plan(spec: PairsFile, pair: Pair) -> PairPlan:
    """The pair planned as the gate's items plan it: along the route timed by the baseline's
    obstacle-free run, with the pairs file's controller or the default (conftest hooks need
    pytest, and are not asked). That run reads nothing, so its scan noise, and the seed, make no
    difference to it."""
    from pytest_lasertest.search.drives import drive
    from pytest_lasertest.search.plans import plan_for

    controller = spec.controller or default_controller(spec.path)
    return plan_for(spec, pair, drive(spec, pair.baseline.profile, (), 0, controller.factory))


def _usage_error(message: str) -> int:
    print(f"lasertest: {message}", file=sys.stderr)
    return 2
