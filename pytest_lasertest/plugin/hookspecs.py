"""The hooks pytest-lasertest adds, for conftest files and plugins to implement.

The entry point (`plugin/__init__.py`) registers them in `pytest_addhooks`. They are called
through the pairs file's own hook proxy, so a conftest file's implementation applies to the pairs
files in its directory and below, as pytest scopes conftest hooks. A pairs file's `controller:`
wins over the hook, which wins over the default: the hook is not called for a pairs file that
names its controller.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import pytest

if TYPE_CHECKING:
    from pytest_lasertest.nav.protocol import ControllerFactory
    from pytest_lasertest.pairsfile import PairsFile


@pytest.hookspec(firstresult=True)
def pytest_lasertest_make_controller(
    config: pytest.Config, spec: PairsFile
) -> ControllerFactory | None:
    """The controller factory to drive this pairs file's robots with, or None for the default."""
