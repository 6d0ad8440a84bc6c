"""The plugin tests' pairs files in the pytester directory: two pairs that plan in a moment, and
the paper's."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from tests.helpers import EXAMPLES
from tests.helpers.texts import PLACEMENT_PAIRS


@pytest.fixture
def placement_pairs(pytester: pytest.Pytester) -> Path:
    """PLACEMENT_PAIRS as `gate.lasertest.yaml` in the pytester directory."""
    path = pytester.path / "gate.lasertest.yaml"
    path.write_text(PLACEMENT_PAIRS)
    return path


@pytest.fixture
def paper(pytester: pytest.Pytester) -> Path:
    """The paper's pairs file, whose size pair puts the thin pole in the 16-beam robot's way."""
    path = pytester.path / "paper.lasertest.yaml"
    shutil.copy(EXAMPLES / "paper.lasertest.yaml", path)
    return path
