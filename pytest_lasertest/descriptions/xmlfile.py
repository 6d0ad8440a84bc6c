"""XML read safely and with line numbers: robot descriptions (URDF, xacro, SDF).

Entity declarations are refused before anything is expanded: a ten-line "billion laughs" file
expands to gigabytes, and an external entity reads files the description has no business
reading. Namespace prefixes are kept as written (`xacro:macro`), so a prefix used without its
`xmlns` declaration, as in SDFormat's own test files, is not an error.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from xml.parsers import expat

from pytest_lasertest.inputs.errors import Location, SpecError

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


class _Builder:
    """Expat callbacks that build XmlElements and refuse entities."""

    def __init__(self, path: Path, parser: expat.XMLParserType) -> None:
        self.path = path
        self.parser = parser
        self.stack: list[_Open] = []
        self.root: XmlElement | None = None

    def start(self, tag: str, attributes: dict[str, str]) -> None:
        parser = self.parser
        self.stack.append(_Open(tag, attributes, parser.CurrentLineNumber, parser.CurrentByteIndex))

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


def parse_xml(data: bytes, path: Path) -> XmlElement:
    """The root element of an XML document; SpecError at the line where it is not well formed
    or where it declares an entity."""
    parser = expat.ParserCreate()
    builder = _Builder(path, parser)
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
        raise SpecError(
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
