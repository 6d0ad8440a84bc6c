"""pytest-lasertest: a pytest gate for laser-scanner hardware changes on mobile robots."""

from __future__ import annotations

__version__ = "0.1.0"
