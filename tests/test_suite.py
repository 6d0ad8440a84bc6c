"""The suite itself: a test that edits one of the shared texts of tests/helpers/texts.py edits
something that is there. `VALID_PAIRS.replace(old, new)` with an `old` the text no longer holds
returns the text unchanged, and the test goes on to test the unedited file: when the shared
goal moved from 10 m to 9 m, twelve tests kept passing locally on texts they no longer
edited, until their assertions on the edit's effect failed in CI."""

from __future__ import annotations

import ast
from pathlib import Path

import tests.helpers.texts as texts

TESTS = Path(__file__).parent
SHARED = {name: value for name, value in vars(texts).items() if isinstance(value, str)}


def imported_texts(tree: ast.Module) -> dict[str, str]:
    """The shared texts a test module imports, by the name it uses, where it does not bind that
    name again itself."""
    imported = {
        alias.asname or alias.name: SHARED[alias.name]
        for node in tree.body
        if isinstance(node, ast.ImportFrom) and node.module == "tests.helpers.texts"
        for alias in node.names
        if alias.name in SHARED
    }
    bound = {
        target.id
        for node in tree.body
        if isinstance(node, ast.Assign)
        for target in node.targets
        if isinstance(target, ast.Name)
    }
    return {name: text for name, text in imported.items() if name not in bound}


def stale_edits(path: Path) -> list[str]:
    """`path:line` for each `TEXT.replace("...", ...)` whose old string TEXT lacks."""
    tree = ast.parse(path.read_text())
    shared = imported_texts(tree)
    return [
        f"{path.relative_to(TESTS)}:{node.lineno}: {node.func.value.id} lacks {old.value!r}"
        for node in ast.walk(tree)
        if isinstance(node, ast.Call)
        and isinstance(node.func, ast.Attribute)
        and node.func.attr == "replace"
        and isinstance(node.func.value, ast.Name)
        and node.func.value.id in shared
        and node.args
        and isinstance(old := node.args[0], ast.Constant)
        and isinstance(old.value, str)
        and old.value not in shared[node.func.value.id]
    ]


def test_every_edit_of_a_shared_test_text_finds_what_it_replaces() -> None:
    modules = sorted(TESTS.rglob("*.py"))
    assert len(modules) > 100
    assert [stale for path in modules for stale in stale_edits(path)] == []
