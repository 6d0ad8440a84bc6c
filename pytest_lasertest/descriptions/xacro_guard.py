"""Bounds on one xacro expansion, so that a description cannot expand until memory runs out.

xacro expands whatever it is given: a macro that calls another twice per level makes 2^n calls,
a macro or include that calls itself recurses until Python gives up, and a block inserted twice
per level doubles the document each time. The guard wraps xacro's macro calls and node
insertions for one expansion and stops it, at the line that calls the runaway macro or include,
when it passes one of these bounds. Real descriptions stay far below them: the Husky's, with
every laser on, makes 13 macro calls, 310 elements and nests includes 2 deep.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from pytest_lasertest.descriptions.xacro_dom import Node, Splicer
from pytest_lasertest.descriptions.xmlfile import XmlElement
from pytest_lasertest.inputs.errors import Location, SpecError

MAX_MACRO_CALLS = 10_000  # macro calls in one expansion
MAX_MACRO_DEPTH = 50  # macros expanding inside one another
MAX_INCLUDE_DEPTH = 32  # files including one another
# Elements of the top file and every element an expansion adds (an include's, a macro body's, a
# block's); a fifth of what a plain description may hold, because xacro's DOM work is slower.
MAX_EXPANDED_ELEMENTS = 50_000


@dataclass(frozen=True)
class _Call:
    """A macro call being expanded: its tag, the macro whose body holds it (None at a file's
    top level) and the file xacro was reading."""

    tag: str
    caller: str | None
    file: Path


class ExpansionGuard:
    """The counts of one expansion, and wrappers for xacro's functions that keep them."""

    def __init__(self, xacro: Any, opened: Mapping[Path, XmlElement | None]) -> None:
        self.xacro = xacro
        self.opened = opened  # every file xacro read so far, as parse_xml read it
        self.calls = 0
        self.elements = 0
        self.made: set[int] = set()  # ids of the DOM elements counted
        self.kept: list[Node] = []  # keeps them alive, so that no id is reused
        self.chain: list[_Call] = []
        self.splicer = Splicer(xacro._empty_text_node)

    def macro_call(self, handle: Callable[..., bool]) -> Callable[..., bool]:
        """xacro's handle_macro_call, counting calls and refusing runaway ones."""

        def guarded(node: Node, macros: object, symbols: object) -> bool:
            if not node.tagName.startswith("xacro:"):
                return handle(node, macros, symbols)
            stack = self.xacro.macrostack or []
            callers = [macro.body.getAttribute("name") for macro in stack]
            call = _Call(node.tagName, callers[-1] if callers else None, self._file())
            self.calls += 1
            if len(stack) >= MAX_MACRO_DEPTH:
                raise self._too_deep(call, callers)
            if self.calls > MAX_MACRO_CALLS:
                raise self._too_many(call)
            self.chain.append(call)
            expanded = handle(node, macros, symbols)
            # Left in place when xacro raises: the chain then says where it stopped.
            self.chain.pop()
            return expanded

        return guarded

    def replace_node(self, node: Node, by: Node, content_only: bool = False) -> None:
        """xacro's replace_node (`node` replaced by `by`, or by its children), counting the
        elements each insertion adds to the document."""
        if by is not None and by is not node:
            self._count(by if isinstance(by, list) else [by], node)
        self.splicer.replace(node, by, content_only)

    def parsing(self, path: Path) -> bool:
        """Whether xacro opens `path` to parse it as XML (the top file, an include), not to
        load it as YAML: it puts a file it parses on its stack before opening it."""
        files = self._files()
        return bool(files) and files[-1] == path

    def read_top(self, root: XmlElement) -> None:
        """Count the elements of a file xacro opens when it is the top file, which no
        insertion adds."""
        if len(self._files()) != 1:
            return
        self.elements += sum(1 for _ in root.walk())
        if self.elements > MAX_EXPANDED_ELEMENTS:
            raise self._too_large()

    def check_include(self, path: Path) -> None:
        """Refuse to open `path` when includes already nest MAX_INCLUDE_DEPTH deep."""
        files = self._files()
        includers = files[:-1] if files and files[-1] == path else files
        if len(includers) < MAX_INCLUDE_DEPTH:
            return
        names = [*(file.name for file in includers), path.name]
        if includers[-1] == path:
            problem = f"{path.name} includes itself, so the expansion would never end"
            fix = "remove the include of the file from itself"
        elif path in includers:
            last = len(includers) - 1 - includers[::-1].index(path)  # the shortest loop
            loop = " -> ".join(names[last:])
            problem = (
                f"it includes {path.name}, which is already being included: the includes "
                f"form a loop ({loop}), so the expansion would never end"
            )
            fix = "remove the include that leads back, or guard it with <xacro:if>"
        else:
            problem = f"includes nest more than {MAX_INCLUDE_DEPTH} files deep ({_chain(names)})"
            fix = "include the files a description needs from fewer levels"
        raise SpecError(self._include_site(includers[-1], path), "", problem, fix)

    def nested_too_deep(self) -> SpecError:
        """The error for a RecursionError in xacro: the document it builds nests deeper than
        Python's stack allows (xacro recurses once per element level)."""
        if self.chain:
            where = self._call_site(self.chain[-1])
            what = _chain([f"<{call.tag}>" for call in self.chain])
            problem = f"expanding {what} nests elements too deep for xacro to expand"
        else:
            where, problem = Location(self._file(), 1), "it nests elements too deep for xacro"
        return SpecError(
            where,
            "",
            problem,
            "a robot description nests a few levels: look for a macro whose body nests deep "
            "and that calls itself, or an include inside deeply nested elements",
        )

    def _files(self) -> list[Path]:
        """The files xacro is reading, each included by the one before it."""
        return [Path(os.path.abspath(name)) for name in self.xacro.filestack or [] if name]

    def _file(self) -> Path:
        files = self._files()
        return files[-1] if files else Path()

    def _count(self, roots: list[Node], node: Node) -> None:
        for element in _elements(roots):
            if id(element) in self.made:  # inserted before, into a body now inserted itself
                continue
            self.made.add(id(element))
            self.kept.append(element)
            self.elements += 1
            if self.elements > MAX_EXPANDED_ELEMENTS:
                raise self._too_large(node)

    def _too_deep(self, call: _Call, callers: list[str]) -> SpecError:
        name = call.tag.removeprefix("xacro:")
        if name in callers:
            start = len(callers) - 1 - callers[::-1].index(name)  # the shortest loop
            loop = " -> ".join([*callers[start:], name])
            problem = (
                f"the macro {name!r} calls itself without end ({loop}): macros nest more "
                f"than {MAX_MACRO_DEPTH} deep"
            )
        else:
            problem = f"macros nest more than {MAX_MACRO_DEPTH} deep ({_chain([*callers, name])})"
        return SpecError(
            self._call_site(call),
            "",
            problem,
            "give the recursion an end: make the call conditional (<xacro:if value=...>) on a "
            f"parameter that changes with each call, and reaches it in under {MAX_MACRO_DEPTH}",
        )

    def _too_many(self, call: _Call) -> SpecError:
        outer = self.chain[0] if self.chain else call
        inner = [f"<{step.tag}>" for step in [*self.chain, call]]
        return SpecError(
            self._call_site(outer),
            "",
            f"expanding <{outer.tag}> makes more than {MAX_MACRO_CALLS} macro calls (the "
            f"last through {_chain(inner)}): a macro that calls "
            "another several times, level after level, multiplies its calls with each level",
            f"a robot description needs far fewer calls: call each macro once per part it "
            f"makes; the gate stops at {MAX_MACRO_CALLS}",
        )

    def _too_large(self, node: Node = None) -> SpecError:
        """The error when the expansion passes MAX_EXPANDED_ELEMENTS, at the call (or the
        include, or the top file) that made it grow."""
        limit = f"more than {MAX_EXPANDED_ELEMENTS} XML elements"
        if self.chain:
            where = self._call_site(self.chain[0])
            problem = (
                f"expanding <{self.chain[0].tag}> makes {limit}: a block or macro inserted "
                "several times, level after level, doubles the document with each level"
            )
        elif node is not None and node.tagName == "xacro:include":
            written = node.getAttribute("filename")
            where = self._written(self._file(), "filename", written)
            problem = f"the includes bring in {limit} in all, the last of them {written!r}"
        else:
            where, problem = Location(self._file(), 1), f"the description holds {limit}"
        return SpecError(
            where,
            "",
            problem,
            "a robot description needs far fewer elements (a large one, some thousands); the "
            f"gate expands at most {MAX_EXPANDED_ELEMENTS}",
        )

    def _call_site(self, call: _Call) -> Location:
        """The line that writes the call: in its caller's definition, or in its file."""
        for root in self._sources(call.file):
            scope = _macro(root, call.caller) if call.caller else root
            found = _first(scope, call.tag) if scope is not None else None
            if found is not None:
                return found.location
        return Location(call.file, 1)

    def _include_site(self, includer: Path, path: Path) -> Location:
        root = self.opened.get(includer)
        for element in root.walk() if root is not None else ():
            if element.tag == "xacro:include" and path.name in (element.get("filename") or ""):
                return element.location
        return Location(includer, 1)

    def _written(self, file: Path, attribute: str, value: str) -> Location:
        """The first element of `file` whose `attribute` is written `value`."""
        root = self.opened.get(file)
        for element in root.walk() if root is not None else ():
            if element.get(attribute) == value:
                return element.location
        return Location(file, 1)

    def _sources(self, first: Path) -> Iterator[XmlElement]:
        """Every file read, `first` first: a macro is written where it is defined."""
        ordered = [self.opened.get(first), *(r for p, r in self.opened.items() if p != first)]
        return (root for root in ordered if root is not None)


def _elements(roots: list[Node]) -> Iterator[Node]:
    """Every element in the DOM trees below `roots`, without recursion."""
    pending = list(roots)
    while pending:
        node = pending.pop()
        if node.nodeType == node.ELEMENT_NODE:
            yield node
        pending.extend(node.childNodes)


def _macro(root: XmlElement, name: str) -> XmlElement | None:
    return next((e for e in root.walk() if e.tag == "xacro:macro" and e.get("name") == name), None)


def _first(scope: XmlElement, tag: str) -> XmlElement | None:
    return next((element for element in scope.walk() if element.tag == tag), None)


def _chain(names: list[str]) -> str:
    """`a -> b -> c`, its middle left out when it is long."""
    shown = names if len(names) <= 6 else [*names[:3], "...", *names[-3:]]
    return " -> ".join(shown)
