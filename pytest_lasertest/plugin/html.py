"""pytest-html: a failing item's picture inline in the HTML report, and a link to each of its
other artifacts (the repro, the Gazebo world, the numbers, the rosbag2).

Imported only when a failing item wrote artifacts, and it does nothing without pytest-html:
pytest-html is no dependency of the gate.
"""

from __future__ import annotations

import base64
from pathlib import Path

import pytest


def add_extras(report: pytest.TestReport, artifacts: tuple[Path, ...]) -> None:
    """Add the artifacts to the report's `extras`, which pytest-html shows, if it is there."""
    try:
        from pytest_html import extras
    except ImportError:
        return
    entries = list(getattr(report, "extras", []))
    for path in artifacts:
        if path.suffix == ".png":
            try:
                picture = base64.b64encode(path.read_bytes()).decode("ascii")
            except OSError:  # removed since it was written: the report still has its path
                continue
            entries.append(extras.png(picture, name=path.name))
        else:
            entries.append(extras.url(path.resolve().as_uri(), name=path.name))
    report.extras = entries  # type: ignore[attr-defined]  # pytest-html reads it
