"""Xacro files expanded with the `xacro` package, as `xacro FILE NAME:=VALUE` would.

Two things differ from the command. Every file xacro opens (the top file, its includes, YAML it
loads) is read through a `FileReader`, so a description at a git revision includes its files at
that same revision; each XML file is first read by `parse_xml`, which refuses entity bombs and
names the line of any syntax error. And `$(find PKG)` resolves through the `packages:` mapping
the pairs file gives, not through a ROS installation, so the gate runs without ROS.

xacro keeps its state in module globals and opens files with the built-in `open`; `_patched`
swaps both for the length of one expansion. That ties this module to xacro 2.1's internals, which
is why pyproject pins xacro below 2.2.
"""

from __future__ import annotations

import contextlib
import errno
import io
import os
import re
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Protocol
from xml.sax.saxutils import quoteattr

from pytest_lasertest.descriptions.xmlfile import XmlElement, parse_xml
from pytest_lasertest.inputs.errors import Location, SpecError

XACRO_FIX = "run `xacro FILE` by hand to see the problem, then fix the description"
# The attribute that marks each element xacro reads with the file and line that wrote it.
ORIGIN = "lasertest-origin"


class FileReader(Protocol):
    """Where a description's files come from: the working tree, or a git revision."""

    def read(self, path: Path) -> bytes:
        """The file's bytes; FileNotFoundError when there is no such file."""
        ...

    def name(self, path: Path) -> str:
        """How messages name the file (with the revision, when there is one)."""
        ...


@dataclass(frozen=True)
class Expansion:
    """A description as xacro expanded it, and the files it was made from."""

    root: XmlElement  # its lines are those of the expanded text, not of any file written
    # Every file xacro read, the top file first; None for a file that is not XML (YAML).
    sources: Mapping[Path, XmlElement | None]


class _MissingPackage(LookupError):
    """`$(find PKG)` names a package the `packages:` mapping does not give."""

    def __init__(self, package: str) -> None:
        super().__init__(package)
        self.package = package


def expand_xacro(
    path: Path, reader: FileReader, args: Mapping[str, str], packages: Mapping[str, Path]
) -> Expansion:
    """The description at `path` expanded with xacro `args` (NAME:=VALUE); SpecError naming the
    file and line when xacro cannot expand it."""
    import xacro

    opened: dict[Path, XmlElement | None] = {}
    try:
        with _patched(xacro, _opener(reader, opened), _finder(packages)):
            document = xacro.process_file(str(path), mappings=dict(args))
    except SpecError:
        raise
    except Exception as error:  # noqa: BLE001  (xacro raises bare errors from user expressions)
        # xacro names no lines, but its stack says which file it was reading.
        reading = Path(os.path.abspath((xacro.filestack or [None])[-1] or path))
        raise _xacro_error(error, reading, opened, reader) from None
    text = document.toxml(encoding="utf-8")
    root = parse_xml(text, path)
    return Expansion(root, opened)


@contextlib.contextmanager
def _patched(xacro: object, opener: object, finder: object) -> Iterator[None]:
    """xacro's `open` and `$(find)` replaced, its include list emptied, for one expansion."""
    from xacro import substitution_args

    saved_find = substitution_args._eval_find
    xacro.all_includes = []  # type: ignore[attr-defined]
    xacro.open = opener  # type: ignore[attr-defined]  # shadows the built-in inside xacro
    substitution_args._eval_find = finder
    try:
        with contextlib.redirect_stderr(io.StringIO()):  # its warnings are not ours to print
            yield
    finally:
        del xacro.open  # type: ignore[attr-defined]
        substitution_args._eval_find = saved_find


def _opener(reader: FileReader, opened: dict[Path, XmlElement | None]) -> object:
    def open_for_xacro(name: str, mode: str = "r", *_: object, **__: object) -> IO[bytes]:
        if "r" not in mode:
            raise PermissionError(errno.EACCES, "expanding a description writes nothing", name)
        path = Path(os.path.abspath(name))
        data = reader.read(path)
        # Only XML goes through the checks; a YAML file loaded by xacro.load_yaml does not.
        if not _looks_like_xml(data):
            opened[path] = None
            return io.BytesIO(data)
        root = opened[path] = parse_xml(data, path)
        return io.BytesIO(_with_origins(data, root))

    return open_for_xacro


def _with_origins(data: bytes, root: XmlElement) -> bytes:
    """The file with every plain element (not the root, not a xacro directive) marked with the
    file and line that write it, in the attribute ORIGIN; xacro copies it through macros and
    includes, so each expanded element still says where it was written."""
    marks = sorted(
        (
            element.offset + 1 + len(element.tag.encode()),
            f" {ORIGIN}={quoteattr(f'{element.location.path}:{element.location.line}')}",
        )
        for element in root.walk()
        if element is not root and ":" not in element.tag
    )
    pieces, start = [], 0
    for offset, mark in marks:
        pieces += [data[start:offset], mark.encode()]
        start = offset
    return b"".join([*pieces, data[start:]])


def origin(element: XmlElement) -> Location | None:
    """Where the files xacro read write an element of its expansion, when they say."""
    mark = element.get(ORIGIN)
    if mark is None:
        return None
    path, _, line = mark.rpartition(":")
    return Location(Path(path), int(line))


def _looks_like_xml(data: bytes) -> bool:
    return data.lstrip(b"\xef\xbb\xbf \t\r\n")[:1] == b"<"


def _finder(packages: Mapping[str, Path]) -> object:
    def find(package: str) -> str:
        if package not in packages:
            raise _MissingPackage(package)
        return str(packages[package])

    return find


def _xacro_error(
    error: Exception,
    here: Path,
    opened: Mapping[Path, XmlElement | None],
    reader: FileReader,
) -> SpecError:
    cause = _root_cause(error)
    if isinstance(cause, SpecError):
        return cause
    if isinstance(cause, _MissingPackage):
        return SpecError(
            _where(here, opened, f"$(find {cause.package})"),
            "",
            f"the description needs the ROS package {cause.package!r} ($(find "
            f"{cause.package})), which the pairs file does not map to a directory",
            f"map it under the scanner's `packages:`, e.g. `packages: {{{cause.package}: "
            f"path/to/{cause.package}}}` (or `--package {cause.package}=DIR` on the command line)",
        )
    if isinstance(cause, FileNotFoundError) and cause.filename:
        missing = Path(os.path.abspath(cause.filename))
        return SpecError(
            _where(here, opened, missing.name),
            "",
            f"it includes {reader.name(missing)}, which does not exist",
            "check the include's path, or map the package it lives in under `packages:`",
        )
    message = " ".join(str(error).split())
    unknown = re.search(r"unknown macro name: (\S+)", message)
    needle = f"<{unknown.group(1)}" if unknown else _first_name(message)
    return SpecError(
        _where(here, opened, needle), "", f"xacro cannot expand it: {message}", XACRO_FIX
    )


def _root_cause(error: BaseException) -> BaseException:
    """The exception xacro wrapped, however deep."""
    seen = error
    while getattr(seen, "exc", None) is not None:
        seen = seen.exc  # type: ignore[attr-defined]
    return seen


def _first_name(message: str) -> str | None:
    quoted = re.search(r"'([^']+)'", message)
    return quoted.group(1) if quoted else None


def _where(path: Path, opened: Mapping[Path, XmlElement | None], needle: str | None) -> Location:
    """The first element whose tag, attributes or text hold `needle`: in `path` (the file
    xacro was reading; it reports no lines), else in the other files it read (a macro's body
    is evaluated where it is called, but written where it is defined)."""
    if not needle:
        return Location(path, 1)
    others = [root for key, root in opened.items() if key != path]
    for root in [opened.get(path), *others]:
        for element in root.walk() if root is not None else ():
            written = " ".join([f"<{element.tag}", *element.attributes.values(), element.text])
            if needle in written:
                return element.location
    return Location(path, 1)
