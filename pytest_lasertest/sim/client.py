"""PyBullet physics clients in DIRECT mode: one per use, always disconnected, never global."""

from __future__ import annotations

import os
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from types import ModuleType


def load_pybullet() -> ModuleType:
    """The pybullet module, imported on first use without its build-time banner."""
    if "pybullet" not in sys.modules:
        with _banner_silenced():
            import pybullet  # noqa: F401
    return sys.modules["pybullet"]


@contextmanager
def direct_client() -> Iterator[int]:
    """A headless physics client id, disconnected on exit."""
    pybullet = load_pybullet()
    client: int = pybullet.connect(pybullet.DIRECT)
    if client < 0:
        raise RuntimeError("pybullet could not start a DIRECT physics client")
    try:
        yield client
    finally:
        pybullet.disconnect(physicsClientId=client)


def self_test() -> str:
    """Start a DIRECT client, step it once, disconnect; describe the pybullet that did it."""
    pybullet = load_pybullet()
    with direct_client() as client:
        pybullet.stepSimulation(physicsClientId=client)
        api = pybullet.getAPIVersion(physicsClientId=client)
    return f"pybullet API {api}: a DIRECT client started, stepped and disconnected"


@contextmanager
def _banner_silenced() -> Iterator[None]:
    # pybullet's C code prints its build time at import straight to file descriptor 2.
    sys.stderr.flush()
    saved = os.dup(2)
    try:
        with open(os.devnull, "w") as devnull:
            os.dup2(devnull.fileno(), 2)
            yield
    finally:
        os.dup2(saved, 2)
        os.close(saved)
