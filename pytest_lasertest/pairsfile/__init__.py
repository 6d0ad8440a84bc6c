"""Spec files: pairs files, the scanner catalogue and robots, read with line numbers."""

from __future__ import annotations

from pytest_lasertest.inputs.errors import Location, SpecError
from pytest_lasertest.pairsfile.pairs import Pair, PairsFile, Settings, load_pairs_file
from pytest_lasertest.inputs.profile import Scanner

__all__ = [
    "Location",
    "Pair",
    "PairsFile",
    "Scanner",
    "Settings",
    "SpecError",
    "load_pairs_file",
]
