"""The conformance page shows the table the conformance tests write: its counts come from the
run, not from hand."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from tests.helpers import REPO

PAGE = REPO / "docs" / "explanation" / "conformance.md"
BEGIN, END = "<!-- conformance table: begin -->\n", "<!-- conformance table: end -->"


def test_the_conformance_page_shows_the_table_of_a_run_of_the_conformance_tests(
    tmp_path: Path,
) -> None:
    table = tmp_path / "table.md"
    command = [sys.executable, "-m", "pytest", "tests/conformance", "-n", "0", "-q"]
    command += ["-p", "no:cacheprovider", f"--conformance-table={table}"]
    run = subprocess.run(command, cwd=REPO, capture_output=True, text=True, check=False)
    assert run.returncode == 0, run.stdout[-2000:]
    page = PAGE.read_text()
    shown = page[page.index(BEGIN) + len(BEGIN) : page.index(END)]
    assert shown == table.read_text(), (
        "docs/explanation/conformance.md is stale: paste the table that "
        "`pytest tests/conformance -n 0 --conformance-table=FILE` writes between its markers"
    )
