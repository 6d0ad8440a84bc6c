"""XML read safely and with line numbers: robot descriptions (URDF, xacro, SDF).

Entity declarations are refused before anything is expanded: a ten-line "billion laughs" file
expands to gigabytes, and an external entity reads files the description has no business
reading. Namespace prefixes are kept as written (`xacro:macro`), so a prefix used without its
`xmlns` declaration, as in SDFormat's own test files, is not an error.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from xml.parsers import expat

from pytest_lasertest.inputs.errors import Location, SpecError

# Bounds on a document: real descriptions nest about 12 deep (an SDF world's nested models)
# and hold at most some thousands of elements. Deeper or larger is refused before the reading
# (which recurses once per level) runs out of stack or memory.
MAX_DEPTH = 100  # elements nested in one another
MAX_ELEMENTS = 250_000  # elements in one document
ENTITY_FIX = (
    "remove the <!DOCTYPE ...> block and its <!ENTITY ...> declarations; robot descriptions "
    "need none (write the values, or use xacro properties)"
)


@dataclass(frozen=True)
class XmlElement:
    """One element: its tag as written, attributes, direct text, children and line."""

    tag: str
    attributes: Mapping[str, str]
    text: str  # the element's own character data, comments left out
    children: tuple[XmlElement, ...]
    location: Location
    offset: int = 0  # bytes from the start of the file to the element's `<`

    def get(self, name: str) -> str | None:
        """An attribute's value, or None."""
        return self.attributes.get(name)

    def child(self, tag: str) -> XmlElement | None:
        """The first direct child with this tag."""
        return next((child for child in self.children if child.tag == tag), None)

    def all(self, tag: str) -> tuple[XmlElement, ...]:
        """Every direct child with this tag, in document order."""
        return tuple(child for child in self.children if child.tag == tag)

    def walk(self) -> Iterator[XmlElement]:
        """This element and every element below it, in document order."""
        yield self
        for child in self.children:
            yield from child.walk()


@dataclass
class _Open:
    """An element whose end tag has not been read yet."""

    tag: str
    attributes: dict[str, str]
    line: int
    offset: int
    text: list[str] = field(default_factory=list)
    children: list[XmlElement] = field(default_factory=list)


_WIDE_BOMS = (b"\xff\xfe", b"\xfe\xff")  # UTF-16 and UTF-32 files, which hold NUL bytes
_DECLARED_ENCODING = re.compile(rb"(?:\xef\xbb\xbf)?\s*<\?xml[^>]*?encoding=[\"']([A-Za-z0-9._-]+)")
# Where an element with these attributes was written, when they say (an expansion's elements).
Located = Callable[[Mapping[str, str]], Location | None]


class _Builder:
    """Expat callbacks that build XmlElements and refuse entities and runaway documents."""

    def __init__(self, path: Path, parser: expat.XMLParserType, located: Located) -> None:
        self.path = path
        self.parser = parser
        self.located = located
        self.stack: list[_Open] = []
        self.root: XmlElement | None = None
        self.count = 0

    def start(self, tag: str, attributes: dict[str, str]) -> None:
        parser = self.parser
        self.count += 1
        if len(self.stack) >= MAX_DEPTH or self.count > MAX_ELEMENTS:
            raise self._too_big(attributes)
        self.stack.append(_Open(tag, attributes, parser.CurrentLineNumber, parser.CurrentByteIndex))

    def _too_big(self, attributes: Mapping[str, str]) -> SpecError:
        where = self.located(attributes) or Location(self.path, self.parser.CurrentLineNumber)
        if self.count > MAX_ELEMENTS:
            return SpecError(
                where,
                "",
                f"the document holds more than {MAX_ELEMENTS} XML elements",
                "point `urdf:` at the robot's description; robot descriptions hold some "
                "thousands of elements",
            )
        return SpecError(
            where,
            "",
            f"elements nest more than {MAX_DEPTH} deep here",
            "robot descriptions nest about a dozen levels: close the elements left open above "
            "this line",
        )

    def end(self, tag: str) -> None:
        done = self.stack.pop()
        element = XmlElement(
            done.tag,
            done.attributes,
            "".join(done.text),
            tuple(done.children),
            Location(self.path, done.line),
            done.offset,
        )
        if self.stack:
            self.stack[-1].children.append(element)
        else:
            self.root = element

    def characters(self, data: str) -> None:
        if self.stack:
            self.stack[-1].text.append(data)

    def entity(self, name: str, *_: object) -> None:
        raise SpecError(
            Location(self.path, self.parser.CurrentLineNumber),
            "",
            f"the file declares the XML entity {name!r}; entities are refused, not expanded, "
            "because a few nested ones can expand to gigabytes (an 'entity bomb')",
            ENTITY_FIX,
        )

    def external(self, *_: object) -> int:
        raise SpecError(
            Location(self.path, self.parser.CurrentLineNumber),
            "",
            "the file refers to an external XML entity, which would read another file",
            ENTITY_FIX,
        )


def parse_xml(data: bytes, path: Path, *, located: Located = lambda _: None) -> XmlElement:
    """The root element of an XML document; SpecError at the line where it is not well formed,
    declares an entity, or passes MAX_DEPTH or MAX_ELEMENTS (at the line `located` gives, when
    it gives one)."""
    parser = expat.ParserCreate()
    builder = _Builder(path, parser, located)
    parser.StartElementHandler = builder.start
    parser.EndElementHandler = builder.end
    parser.CharacterDataHandler = builder.characters
    parser.EntityDeclHandler = builder.entity
    parser.ExternalEntityRefHandler = builder.external
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    parser.buffer_text = True
    try:
        parser.Parse(data, True)
    except expat.ExpatError as error:
        raise _not_text(data, path) or SpecError(
            Location(path, error.lineno),
            "",
            f"this is not well-formed XML: {expat.ErrorString(error.code)} "
            f"(line {error.lineno}, column {error.offset + 1})",
            _syntax_fix(error.code),
        ) from None
    if builder.root is None:  # pragma: no cover - expat reports "no element found" first
        raise SpecError(Location(path, 1), "", "the file holds no XML element", "check the path")
    return builder.root


def _syntax_fix(code: int) -> str:
    if expat.ErrorString(code) == expat.errors.XML_ERROR_MISPLACED_XML_PI:
        return "keep exactly one <?xml ...?> declaration, on the file's first line"
    return "fix the XML at that line: every tag closed, attributes quoted, `&` written `&amp;`"


def _not_text(data: bytes, path: Path) -> SpecError | None:
    """Why a file expat cannot read is no XML text at all, when that is why: a binary file (a
    mesh, an image), or one in another encoding than the UTF-8 it is read as."""
    if b"\x00" in data and not data.startswith(_WIDE_BOMS):
        return SpecError(
            Location(path, 1),
            "",
            "this is not a text file: it holds NUL bytes (is it a mesh, an image or an archive?)",
            "point `urdf:` (or the include) at the robot's URDF, xacro or SDF file",
        )
    declared = _DECLARED_ENCODING.match(data)
    if declared and declared.group(1).lower().replace(b"_", b"-") not in (b"utf-8", b"utf8"):
        return None  # expat read it in the encoding it names
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as error:
        return SpecError(
            Location(path, data.count(b"\n", 0, error.start) + 1),
            "",
            f"this file is not UTF-8: byte 0x{data[error.start]:02x} on this line is no UTF-8 "
            "character (the file may be Latin-1 or Windows-1252)",
            'save it as UTF-8, or name its encoding on its first line: <?xml version="1.0" '
            'encoding="ISO-8859-1"?>',
        )
    return None
