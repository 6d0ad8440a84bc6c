"""Xacro files expanded with the `xacro` package, as `xacro FILE NAME:=VALUE` would.

Three things differ from the command. Every file xacro opens (the top file, its includes, YAML
it loads) is read through a `FileReader`, so a description at a git revision includes its files
at that same revision; each XML file is first read by `parse_xml`, which refuses entity bombs and
names the line of any syntax error. `$(find PKG)` resolves through the `packages:` mapping the
pairs file gives, not through a ROS installation, so the gate runs without ROS. And the expansion
is bounded (`xacro_guard.py`): a runaway macro, include or block is an error at the line that
calls it, not a hang.

xacro keeps its state in module globals, opens files with the built-in `open` and edits its DOM
through three module functions; `_patched` swaps them for the length of one expansion. That ties
this module to xacro 2.1's internals, which is why pyproject pins xacro below 2.2.
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
from typing import IO, Any, Protocol
from xml.sax.saxutils import quoteattr

from pytest_lasertest.descriptions.xacro_guard import ExpansionGuard
from pytest_lasertest.descriptions.xmlfile import XmlElement, parse_xml
from pytest_lasertest.inputs.errors import Location, SpecError
from pytest_lasertest.inputs.files import UnreadableFile

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
    guard = ExpansionGuard(xacro, opened)
    try:
        with _patched(xacro, guard, _opener(reader, opened, guard), _finder(packages)):
            document = xacro.process_file(str(path), mappings=dict(args))
            text = document.toxml(encoding="utf-8")
    except SpecError:
        raise
    except RecursionError:
        raise guard.nested_too_deep() from None
    except Exception as error:  # noqa: BLE001  (xacro raises bare errors from user expressions)
        # xacro names no lines, but its stack says which file it was reading.
        reading = Path(os.path.abspath((xacro.filestack or [None])[-1] or path))
        raise _xacro_error(error, reading, opened, reader) from None
    root = parse_xml(text, path, located=_origin_of)
    return Expansion(root, opened)


@contextlib.contextmanager
def _patched(xacro: Any, guard: ExpansionGuard, opener: object, finder: object) -> Iterator[None]:
    """xacro's `open` and `$(find)` replaced, its macro calls and insertions guarded, its include
    list emptied, for one expansion."""
    from xacro import substitution_args

    names = ("handle_macro_call", "replace_node", "remove_previous_comments")
    saved = substitution_args._eval_find, {name: getattr(xacro, name) for name in names}
    xacro.all_includes = []
    xacro.open = opener  # shadows the built-in inside xacro
    substitution_args._eval_find = finder
    xacro.handle_macro_call = guard.macro_call(xacro.handle_macro_call)
    xacro.replace_node = guard.replace_node
    xacro.remove_previous_comments = guard.splicer.remove_previous_comments
    try:
        with contextlib.redirect_stderr(io.StringIO()):  # its warnings are not ours to print
            yield
    finally:
        del xacro.open
        substitution_args._eval_find = saved[0]
        for name, function in saved[1].items():
            setattr(xacro, name, function)


def _opener(
    reader: FileReader, opened: dict[Path, XmlElement | None], guard: ExpansionGuard
) -> object:
    def open_for_xacro(name: str, mode: str = "r", *_: object, **__: object) -> IO[bytes]:
        if "r" not in mode:
            raise PermissionError(errno.EACCES, "expanding a description writes nothing", name)
        path = Path(os.path.abspath(name))
        guard.check_include(path)
        data = reader.read(path)
        # Every file xacro parses as XML goes through the checks, whatever its first bytes;
        # a YAML file loaded by xacro.load_yaml does not.
        if not guard.parsing(path):
            opened[path] = None
            return io.BytesIO(data)
        data = _utf8(data)
        root = opened[path] = parse_xml(data, path)
        guard.read_top(root)
        return io.BytesIO(_with_origins(data, root))

    return open_for_xacro


def _utf8(data: bytes) -> bytes:
    """A UTF-16 file as UTF-8, its declaration saying so: the origin marks are UTF-8 bytes."""
    if not data.startswith((b"\xff\xfe", b"\xfe\xff")):
        return data
    try:
        text = data.decode("utf-16")
    except UnicodeDecodeError:
        return data  # parse_xml says where it breaks
    declared = re.sub(r"""^(\s*<\?xml[^>]*?encoding=["'])[^"']*""", r"\1UTF-8", text, count=1)
    return declared.encode("utf-8")


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
    return _origin_of(element.attributes)


def _origin_of(attributes: Mapping[str, str]) -> Location | None:
    """Where the files xacro read write an element with these attributes, when they say."""
    mark = attributes.get(ORIGIN)
    if mark is None:
        return None
    path, _, line = mark.rpartition(":")
    return Location(Path(path), int(line))


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
    if isinstance(cause, UnreadableFile):
        return SpecError(
            _where(here, opened, Path(cause.filename).name),
            "",
            f"it includes a file that cannot be used: {cause.problem}",
            cause.fix,
        )
    message = _message(error)
    unset = re.search(r"environment variable '([^']+)' is not set", message)
    if unset:
        return SpecError(
            _where(here, opened, f"$(env {unset.group(1)})"),
            "",
            f"the description reads the environment variable {unset.group(1)} ($(env "
            f"{unset.group(1)})), which is not set",
            f"set {unset.group(1)} where the gate runs, or give it a default in the description "
            f"with $(optenv {unset.group(1)} DEFAULT)",
        )
    unknown = re.search(r"unknown macro name: (\S+)", message)
    needle = f"<{unknown.group(1)}" if unknown else _first_name(message)
    return SpecError(
        _where(here, opened, needle), "", f"xacro cannot expand it: {message}", XACRO_FIX
    )


def _message(error: BaseException) -> str:
    """xacro's message, each part once: it wraps a cause in an exception whose own text may
    repeat the cause's (`$(env X)`'s names the cause's class, then its text, then the text again
    from the cause)."""
    parts: list[str] = []
    suffixes: list[str] = []
    seen = error
    while (inner := getattr(seen, "exc", None)) is not None:
        own = str(seen.args[0]) if seen.args and seen.args[0] is not None else ""
        if own and str(inner) not in own:
            parts.append(own)
        suffixes.insert(0, str(getattr(seen, "suffix", None) or ""))
        seen = inner
    return " ".join(" ".join([*parts, str(seen), *suffixes]).split())


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
