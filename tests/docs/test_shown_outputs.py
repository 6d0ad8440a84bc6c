"""Every command output README.md and docs/ show is what the command prints today.

Sybil reads the Markdown (`shown.py` says which blocks it takes and how it compares them). Each
document's commands run in order, once each, in a scratch directory of its own, on one xdist
worker: the README's test command distributes with `--dist loadgroup`, and each document is one
group, so that the tutorial's replay finds the artifacts its run wrote (pytest-xdist 3.8 under
pytest 9.2 would spread a group over the workers, pytest-xdist#1386, so tests/conftest.py
schedules the pages itself). A test run alone (`-k`) first runs the commands its page shows
before it.
"""

from __future__ import annotations

import pytest
from sybil import Example

from tests.docs.shown import (
    DOCUMENTS,
    examples,
    replay,
    scratch_directory,
    unchecked_text_blocks,
)
from tests.helpers import REPO
from tests.helpers.scheduling import SHOWN_OUTPUTS, page_of


def _params() -> list[object]:
    params: list[object] = []
    for path in DOCUMENTS:
        name = str(path.relative_to(REPO))
        for example in examples(path):
            group = pytest.mark.xdist_group(name)
            params.append(pytest.param(example, id=f"{name}:{example.line}", marks=group))
    return params


@pytest.mark.parametrize("example", _params())
def test_the_docs_show_what_each_command_prints(
    example: Example, tmp_path_factory: pytest.TempPathFactory
) -> None:
    if "cwd" not in example.namespace:
        example.namespace["cwd"] = scratch_directory(tmp_path_factory.mktemp("my_robot"))
    for earlier in example.document.examples():
        if earlier.start >= example.start:
            break
        replay(earlier)  # what its page did before it, where this worker has not done it yet
    example.evaluate()


def test_every_output_block_of_the_docs_is_checked() -> None:
    # A block that shows a command's output but is neither a `$` session nor marked would go
    # stale unseen: every `text` block must be one of them.
    unchecked = [
        f"{path.relative_to(REPO)}:{line}"
        for path in DOCUMENTS
        for line in unchecked_text_blocks(path)
    ]
    assert unchecked == []


def test_each_page_is_one_group_of_the_readme_s_loadgroup_schedule() -> None:
    tests = [
        f"{SHOWN_OUTPUTS}{page}:{line}]"
        for page in ("README.md", "docs/tutorial.md")
        for line in (3, 40)
    ]
    assert [page_of(nodeid) for nodeid in tests] == ["README.md"] * 2 + ["docs/tutorial.md"] * 2
    # Every other test is scheduled as pytest-xdist schedules it.
    assert (
        page_of("tests/docs/test_shown_outputs.py::test_every_output_block_of_the_docs_is_checked")
        is None
    )
    assert page_of("tests/test_suite.py::test_x[README.md:3]") is None
