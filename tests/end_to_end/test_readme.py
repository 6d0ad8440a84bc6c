"""The README's and the documentation's promises: the annotated pairs file is valid and the same
in both, the quickstart is two commands, the gate on a recording loads, the README stays short,
and every relative link names a file that exists."""

from __future__ import annotations

import math
import re
from pathlib import Path

import yaml

from pytest_lasertest.pairsfile import load_pairs_file
from tests.helpers import REPO
from tests.helpers.bags import laser_scans, write_bag

README = (REPO / "README.md").read_text()
DOCS = REPO / "docs"


def first_yaml_block(text: str) -> str:
    block = re.search(r"```yaml\n(.*?)```", text, re.DOTALL)
    assert block is not None
    return block.group(1)


def test_the_annotated_pairs_file_in_the_readme_loads(tmp_path: Path) -> None:
    path = tmp_path / "annotated.lasertest.yaml"
    path.write_text(first_yaml_block(README))
    spec = load_pairs_file(path)
    assert [pair.name for pair in spec.pairs] == ["blind_spot"]
    assert spec.pairs[0].candidate.model == "clearpath_lms1xx_gazebo"


def test_the_docs_annotate_the_same_pairs_file_as_the_readme() -> None:
    docs = first_yaml_block((DOCS / "how-to" / "pairs-file.md").read_text())
    assert yaml.safe_load(docs) == yaml.safe_load(first_yaml_block(README))


def test_the_quickstart_is_one_command_for_the_main_job_and_one_for_the_tests() -> None:
    quickstart = README.split("## Quickstart")[1].split("\n## ")[0]
    commands = re.findall(r"```bash\n(.*?)\n```", quickstart, re.DOTALL)
    assert len(commands) == 2
    assert commands[0].endswith("pytest examples/")
    # The tests run on every core, each documentation page's commands on one worker, in order,
    # and the slowest are listed.
    assert commands[1].endswith("pytest -n auto --dist loadgroup --durations=25 tests/")
    assert all("\n" not in command for command in commands)


def test_the_docs_gate_on_a_recording_loads_with_the_recording_as_its_candidate(
    tmp_path: Path,
) -> None:
    page = (DOCS / "how-to" / "recordings.md").read_text()
    recordings = page.split("## Recordings")[1].split("\n## ")[0]
    gate = re.search(r"```yaml\n(.*?)```", recordings, re.DOTALL)
    assert gate is not None
    write_bag(tmp_path / "new_scanner", laser_scans(no_return=math.nan))
    path = tmp_path / "gate.lasertest.yaml"
    path.write_text(gate.group(1))
    candidate = load_pairs_file(path).pairs[0].candidate
    assert candidate.label == "bag new_scanner /scan"
    assert candidate.profile.driver.no_return == "nan"


def test_the_ci_how_to_quotes_the_workflows_step_as_the_workflow_has_it() -> None:
    page = (DOCS / "how-to" / "ci.md").read_text()
    steps = [
        block for block in re.findall(r"```yaml\n(.*?)```", page, re.DOTALL) if "- name:" in block
    ]
    assert len(steps) == 1
    assert steps[0] in (REPO / "examples" / "ci" / "lasertest.yml").read_text()


# A Markdown link's target; code blocks and code spans are left out first (they hold no links).
LINK = re.compile(r"\]\(([^)\s]+)\)")
CODE = re.compile(r"^```.*?^```|`[^`\n]*`", re.DOTALL | re.MULTILINE)


def relative_links(page: Path) -> list[str]:
    targets = LINK.findall(CODE.sub("", page.read_text()))
    return [target for target in targets if not re.match(r"[a-z]+:|#", target)]


# The schema the site serves, written as it is built (docs/hooks/reference.py).
GENERATED = (DOCS / "pairs-file.schema.json").resolve()


def test_the_readme_stays_under_250_lines_and_every_relative_link_resolves() -> None:
    assert len(README.splitlines()) < 250
    pages = [REPO / "README.md", *sorted(DOCS.rglob("*.md"))]
    checked, broken = 0, []
    for page in pages:
        for target in relative_links(page):
            resolved = (page.parent / target.split("#")[0]).resolve()
            checked += 1
            if resolved == GENERATED:
                continue
            if not resolved.is_file() or not resolved.is_relative_to(REPO):
                broken.append(f"{page.relative_to(REPO)}: {target}")
    assert broken == []
    assert checked > 100  # the README's links to the pages and the pages' links to each other
