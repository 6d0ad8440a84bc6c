"""What every item of a pair shares: its pairs file and pair, its markers, the run's options,
and a report location at the pair's line."""

from __future__ import annotations

from pathlib import Path
from typing import Any, ClassVar

import pytest

from pytest_lasertest.plugin.options import OPTIONS_KEY, LaserOptions
from pytest_lasertest.pairsfile import Pair, PairsFile


class PairItem(pytest.Item):
    """An item of one pair; `kind` is its marker besides `lasertest`."""

    kind: ClassVar[str]

    def __init__(self, *, spec: PairsFile, pair: Pair, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.spec = spec
        self.pair = pair
        self.add_marker("lasertest")
        self.add_marker(self.kind)

    @property
    def options(self) -> LaserOptions:
        return self.config.stash[OPTIONS_KEY]

    def reportinfo(self) -> tuple[Path, int, str]:
        return self.path, self.pair.location.line - 1, self.name
