"""The blocks of README.md and docs/ that show what a command prints, read with Sybil, and how
each is checked against what the command prints today.

A fenced block tagged `text`, or not tagged, shows output, and is one of:

- a session: lines beginning with `$ ` are commands, each followed by an excerpt of what it
  prints (nothing, for a command shown without output);
- after the comment `<!-- shown-output: COMMAND -->`: more of COMMAND's output, where the page
  shows it in parts (the output of the document's last run of COMMAND, run now if none ran);
- after `<!-- shown-file: NAME -->`: a file the reader saves as NAME (tagged with its language);
- after `<!-- not-output: WHY -->`: a sketch, checked by nothing.

An excerpt matches where its lines appear together, in order, in the output, trailing spaces
aside: a line of `...` stands for any number of lines, and `...` within a line for any text on
that line (doctest's ELLIPSIS, kept to its line). Commands run through bash in
the document's scratch directory, which holds a copy of examples/ (the pages run them from a
checkout), of inputs/ (the broken files whose errors the pages show, for commands in comments)
and the document's files; outputs show that directory as /tmp/my_robot. They run with
this interpreter's scripts first on PATH, 80 columns, and not as on a CI service.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from sybil import Document, Example, Region
from sybil.parsers.markdown.lexers import RawFencedCodeBlockLexer

from tests.helpers import EXAMPLES, REPO

DOCUMENTS = (REPO / "README.md", *sorted((REPO / "docs").rglob("*.md")))
INPUTS = Path(__file__).parent / "inputs"
SHOWN_DIRECTORY = "/tmp/my_robot"
# s: a command the docs show runs a gate of a few items at most.
TIMEOUT = 600.0
FENCES = RawFencedCodeBlockLexer(info_pattern=re.compile(r"(?P<language>[\w-]*)$\n", re.M))
DIRECTIVE = re.compile(r"<!-- (?P<kind>shown-output|shown-file|not-output): (?P<argument>.+?) -->")
OUTPUT_LANGUAGES = ("text", "")


@dataclass(frozen=True)
class Shown:
    """A command and the excerpt of its output a page shows under it."""

    command: str
    excerpt: str
    fresh: bool  # run it now (a session), or reuse the document's last run of it


@dataclass(frozen=True)
class SavedFile:
    """A file a page asks the reader to save."""

    name: str
    text: str


def examples(path: Path) -> list[Example]:
    """The checked blocks of one page, in order."""
    return list(Document.parse(str(path), parse))


def parse(document: Document) -> Iterable[Region]:
    """Sybil's parser: a region for each block to check."""
    for block in FENCES(document):
        region = _checked(document, block)
        if region is not None:
            yield region


def unchecked_text_blocks(path: Path) -> list[int]:
    """The lines of the output blocks of a page that nothing checks or marks as a sketch."""
    document = Document(path.read_text(), str(path))
    return [
        document.text.count("\n", 0, block.start) + 1
        for block in FENCES(document)
        if block.lexemes["language"] in OUTPUT_LANGUAGES
        and _checked(document, block) is None
        and _directive_before(document.text, block.start) is None
    ]


def _checked(document: Document, block: Region) -> Region | None:
    """The region that checks a fenced block, if it is one to check."""
    source, language = str(block.lexemes["source"]), block.lexemes["language"]
    directive = _directive_before(document.text, block.start)
    if directive is not None and directive[0] == "shown-file":
        return Region(block.start, block.end, SavedFile(directive[1], source), _save)
    if directive is not None and directive[0] == "shown-output":
        return Region(block.start, block.end, [Shown(directive[1], source, False)], _check)
    if language in OUTPUT_LANGUAGES and source.startswith("$ "):
        return Region(block.start, block.end, _session(source), _check)
    return None


def scratch_directory(path: Path) -> Path:
    """`path`, holding a copy of the examples and of the inputs the pages' hidden commands
    read (`inputs/`: the broken files whose errors they show), for one page's commands."""
    shutil.copytree(EXAMPLES, path / "examples")
    shutil.copytree(INPUTS, path / "inputs")
    return path


def _directive_before(text: str, start: int) -> tuple[str, str] | None:
    """The directive on the line just before a block, if any: (kind, argument)."""
    before = text[:start].rstrip("\n").rsplit("\n", 1)[-1]
    match = DIRECTIVE.fullmatch(before.strip())
    return None if match is None else (match["kind"], match["argument"])


def _session(source: str) -> list[Shown]:
    """A session's commands, each with the lines under it."""
    shown: list[Shown] = []
    for part in re.split(r"^\$ ", source, flags=re.M)[1:]:
        command, _, excerpt = part.partition("\n")
        shown.append(Shown(command, excerpt, fresh=True))
    return shown


def replay(example: Example) -> None:
    """What `example` does to its document's directory, unchecked, once: a test run alone
    first replays the examples before it, whose own tests check them. Once only, because a
    second run of a gate in the same directory replays the failures the first one stored."""
    done: set[int] = example.namespace.setdefault("done", set())
    if example.start in done:
        return
    done.add(example.start)
    if isinstance(example.parsed, SavedFile):
        saved: SavedFile = example.parsed
        (example.namespace["cwd"] / saved.name).write_text(saved.text)
        return
    outputs: dict[str, str] = example.namespace.setdefault("outputs", {})
    for shown in example.parsed:
        if shown.fresh or shown.command not in outputs:
            outputs[shown.command] = _run(shown.command, example.namespace["cwd"])


def _save(example: Example) -> None:
    replay(example)


def _check(example: Example) -> str | None:
    """None if every excerpt is in its command's output; else what differs."""
    replay(example)
    outputs: dict[str, str] = example.namespace["outputs"]
    for shown in example.parsed:
        output = outputs[shown.command]
        if not contains(output, shown.excerpt):
            return (
                f"the page shows under `{shown.command}`:\n{shown.excerpt}\n"
                f"which is not in what it prints:\n{output}"
            )
    return None


def _run(command: str, cwd: Path) -> str:
    """What `command` prints, stdout and stderr together, with `cwd` shown as on the page."""
    env = {key: value for key, value in os.environ.items() if key != "CI"}
    env.pop("PYTEST_ADDOPTS", None)
    scripts = str(Path(sys.executable).parent)
    env.update(COLUMNS="80", PATH=f"{scripts}{os.pathsep}{env.get('PATH', '')}")
    done = subprocess.run(
        ["bash", "-c", command],
        cwd=cwd,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        timeout=TIMEOUT,
        check=False,
    )
    return done.stdout.replace(str(cwd), SHOWN_DIRECTORY)


def contains(output: str, excerpt: str) -> bool:
    """Whether the excerpt's lines appear together, in order, in the output: a line of `...`
    stands for any number of lines, `...` within a line for any text on it."""
    if not excerpt.strip():
        return True
    return _pattern(_rstripped(excerpt)).search(_rstripped(output) + "\n") is not None


def _pattern(excerpt: str) -> re.Pattern[str]:
    lines = []
    for line in excerpt.split("\n"):
        if line.strip() == "...":
            lines.append(r"(?:[^\n]*\n)*?")
        else:
            lines.append(".*".join(re.escape(part) for part in line.split("...")) + "\n")
    return re.compile("^" + "".join(lines), re.M)


def _rstripped(text: str) -> str:
    return "\n".join(line.rstrip() for line in text.strip("\n").splitlines())
