"""The README's promises: its annotated pairs file is valid, its quickstart is two commands."""

from __future__ import annotations

import math
import re
from pathlib import Path

from pytest_lasertest.pairsfile import load_pairs_file
from tests.helpers import REPO
from tests.helpers.bags import laser_scans, write_bag

README = (REPO / "README.md").read_text()


def test_the_annotated_pairs_file_in_the_readme_loads(tmp_path: Path) -> None:
    annotated = re.search(r"```yaml\n(.*?)```", README, re.DOTALL)
    assert annotated is not None
    path = tmp_path / "annotated.lasertest.yaml"
    path.write_text(annotated.group(1))
    spec = load_pairs_file(path)
    assert [pair.name for pair in spec.pairs] == ["blind_spot"]
    assert spec.pairs[0].candidate.model == "clearpath_lms1xx_gazebo"


def test_the_quickstart_is_one_command_for_the_main_job_and_one_for_the_tests() -> None:
    quickstart = README.split("## Quickstart")[1].split("\n## ")[0]
    commands = re.findall(r"```bash\n(.*?)\n```", quickstart, re.DOTALL)
    assert len(commands) == 2
    assert commands[0].endswith("pytest examples/")
    assert commands[1].endswith("pytest -n auto tests/")  # the tests run on every core
    assert all("\n" not in command for command in commands)


def test_the_readmes_gate_on_a_recording_loads_with_the_recording_as_its_candidate(
    tmp_path: Path,
) -> None:
    recordings = README.split("### Recordings")[1].split("\n### ")[0]
    gate = re.search(r"```yaml\n(.*?)```", recordings, re.DOTALL)
    assert gate is not None
    write_bag(tmp_path / "new_scanner", laser_scans(no_return=math.nan))
    path = tmp_path / "gate.lasertest.yaml"
    path.write_text(gate.group(1))
    candidate = load_pairs_file(path).pairs[0].candidate
    assert candidate.label == "bag new_scanner /scan"
    assert candidate.profile.driver.no_return == "nan"
