"""The documentation site: it builds with --strict, its pairs-file reference is the schema's,
and it serves the schema an editor can point at."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from pytest_lasertest.pairsfile.schema import SHIPPED
from pytest_lasertest.pairsfile.world import WORLD_KEYS
from tests.helpers import REPO


def test_the_site_builds_strict_with_the_reference_written_from_the_schema(
    tmp_path: Path,
) -> None:
    site = tmp_path / "site"
    subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(site)],
        cwd=REPO,
        check=True,
        capture_output=True,
        env={**os.environ, "NO_MKDOCS_2_WARNING": "1"},
    )
    reference = (site / "reference" / "pairs-file" / "index.html").read_text()
    assert "lasertest: pairs-file schema" not in reference  # the marker was replaced
    for key in WORLD_KEYS:
        assert f"<code>{key}</code></td>" in reference
    assert (site / "pairs-file.schema.json").read_text() == SHIPPED.read_text()
