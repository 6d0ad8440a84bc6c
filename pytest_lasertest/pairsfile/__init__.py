"""Pairs files, and what they name: robots, worlds, the scanner catalogue, navigation
parameters, constraints, the controller and pinned placements; YAML read with line numbers."""

from __future__ import annotations

from pytest_lasertest.pairsfile.pairs import Pair, PairsFile, Settings, load_pairs_file
from pytest_lasertest.pairsfile.scanners import Scanner

__all__ = ["Pair", "PairsFile", "Scanner", "Settings", "load_pairs_file"]
