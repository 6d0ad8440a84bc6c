"""Safe YAML loading that keeps the line of every key and item, and refuses duplicate keys."""

from __future__ import annotations

import re
from pathlib import Path

import yaml
from yaml.events import AliasEvent
from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from pytest_lasertest.inputs.errors import Location, SpecError
from pytest_lasertest.inputs.files import FileKind, UnreadableFile, read_regular_file

_MERGE_TAG = "tag:yaml.org,2002:merge"
# The files read here (pairs files, robots, navigation parameters, catalogue models) are a page
# or two. Beyond these, a file is not one of them, and parsing it would take long or recurse
# past Python's stack.
MAX_BYTES = 1_000_000  # about 20,000 lines
# A pipe or a device named as a pairs, robot or navigation file is refused before it is read.
YAML_FILE = FileKind(
    "a YAML file",
    MAX_BYTES,
    "name the YAML file itself, saved on disk",
    "check that this is the file you meant: a pairs, robot, navigation or scanner file",
)
MAX_DEPTH = 50  # mappings and lists nested in each other; a pairs file needs about 6


class YamlMap(dict[str, object]):
    """A YAML mapping that remembers the line of each of its keys."""

    def __init__(self, line: int) -> None:
        super().__init__()
        self.line = line
        self.key_lines: dict[str, int] = {}


class YamlList(list[object]):
    """A YAML sequence that remembers the line of each of its items."""

    def __init__(self, line: int) -> None:
        super().__init__()
        self.line = line
        self.item_lines: list[int] = []


class _LocatingLoader(yaml.SafeLoader):
    """SafeLoader building YamlMap and YamlList, tracking the field path for error messages."""

    def __init__(self, text: str, path: Path) -> None:
        super().__init__(text)
        self.path = path
        self.field_path: list[str] = []
        self.depth = 0  # how many nodes deep the composer is

    def compose_node(self, parent: Node | None, index: int) -> Node | None:
        """Compose one node, refusing nesting deeper than MAX_DEPTH where it begins."""
        self.depth += 1
        try:
            if self.depth > MAX_DEPTH:
                line = self.get_mark().line + 1  # where the reader is: the deepest node begins
                raise SpecError(
                    Location(self.path, line),
                    "",
                    f"mappings and lists are nested more than {MAX_DEPTH} deep here",
                    "no file the gate reads nests that deep; check the brackets around this line",
                )
            return super().compose_node(parent, index)
        finally:
            self.depth -= 1

    def located(self, node: Node) -> Location:
        return Location(self.path, node.start_mark.line + 1)

    def field_name(self, key: str | None = None) -> str:
        parts = [*self.field_path, *([key] if key is not None else [])]
        return ".".join(parts).replace(".[", "[")


def _construct_map(loader: _LocatingLoader, node: MappingNode) -> YamlMap:
    _refuse_duplicate_keys(loader, node)
    loader.flatten_mapping(node)  # resolves `<<: *anchor`; later keys override merged ones
    result = YamlMap(node.start_mark.line + 1)
    for key_node, value_node in node.value:
        key = loader.construct_object(key_node, deep=True)
        if not isinstance(key, str):
            raise SpecError(
                loader.located(key_node),
                loader.field_name(),
                f"the key {key!r} is not text (YAML reads it as {type(key).__name__})",
                f"quote it: '{key_node.value}'",
            )
        loader.field_path.append(key)
        result[key] = loader.construct_object(value_node, deep=True)
        loader.field_path.pop()
        result.key_lines[key] = key_node.start_mark.line + 1
    return result


def _refuse_duplicate_keys(loader: _LocatingLoader, node: MappingNode) -> None:
    first_lines: dict[str, int] = {}
    for key_node, _ in node.value:
        if key_node.tag == _MERGE_TAG or not isinstance(key_node, ScalarNode):
            continue
        line = key_node.start_mark.line + 1
        if key_node.value in first_lines:
            raise SpecError(
                loader.located(key_node),
                loader.field_name(key_node.value),
                f"'{key_node.value}' appears twice here (first on line "
                f"{first_lines[key_node.value]}); YAML would silently keep only the last",
                "rename or remove one of them",
            )
        first_lines[key_node.value] = line


def _construct_list(loader: _LocatingLoader, node: SequenceNode) -> YamlList:
    result = YamlList(node.start_mark.line + 1)
    for index, child in enumerate(node.value):
        loader.field_path.append(f"[{index}]")
        result.append(loader.construct_object(child, deep=True))
        loader.field_path.pop()
        result.item_lines.append(child.start_mark.line + 1)
    return result


def _construct_int(loader: _LocatingLoader, node: ScalarNode) -> int:
    _refuse_surprising_number(loader, node)
    value: int = loader.construct_yaml_int(node)
    return value


def _construct_float(loader: _LocatingLoader, node: ScalarNode) -> float:
    _refuse_surprising_number(loader, node)
    value: float = loader.construct_yaml_float(node)
    return value


def _refuse_surprising_number(loader: _LocatingLoader, node: ScalarNode) -> None:
    """YAML 1.1 (PyYAML's) reads `0720` as octal 464 and `1:30` as base 60, 90: numbers nobody
    writes on purpose in these files, which would be used silently as something else."""
    digits = node.value.replace("_", "").lstrip("+-")
    if ":" in digits:
        value = _read_as(loader, node, digits)
        raise SpecError(
            loader.located(node),
            loader.field_name(),
            f"YAML 1.1 reads {node.value} as the base-60 (sexagesimal) number {value}",
            f"write the number you mean as plain digits ({value} if that is it), "
            "or quote it if it is text",
        )
    if len(digits) > 1 and digits[0] == "0" and digits.isdigit():
        sign = node.value[0] if node.value[0] in "+-" else ""
        raise SpecError(
            loader.located(node),
            loader.field_name(),
            f"YAML 1.1 reads {node.value}, with its leading zero, as the octal number "
            f"{_read_as(loader, node, digits)}",
            f"write it without the leading zero: {sign}{digits.lstrip('0') or 0}",
        )


def _read_as(loader: _LocatingLoader, node: ScalarNode, digits: str) -> int | float:
    """What PyYAML makes of the scalar."""
    value: int | float = (
        loader.construct_yaml_float(node) if "." in digits else loader.construct_yaml_int(node)
    )
    return value


_LocatingLoader.add_constructor("tag:yaml.org,2002:map", _construct_map)
_LocatingLoader.add_constructor("tag:yaml.org,2002:seq", _construct_list)
_LocatingLoader.add_constructor("tag:yaml.org,2002:int", _construct_int)
_LocatingLoader.add_constructor("tag:yaml.org,2002:float", _construct_float)


class _Ros2ParamsLoader(_LocatingLoader):
    """A ROS 2 params file as rcl's parser reads it (rcl_yaml_param_parser/src/parse.c at
    ros2/rcl bef8bd17): an alias refused ("Will not support aliasing"), and a plain scalar that
    strtod reads whole, such as 5e-1, a number (get_value), where YAML 1.1 reads it as text."""

    def compose_node(self, parent: Node | None, index: int) -> Node | None:
        if self.check_event(AliasEvent):
            line = self.peek_event().start_mark.line + 1  # type: ignore[no-untyped-call]
            raise SpecError(
                Location(self.path, line),
                "",
                "a YAML alias (*name): ROS 2's parameter parser refuses one (\"Will not "
                'support aliasing"), so the nodes would not start with this file',
                "write the value out in full where the alias stands",
            )
        return super().compose_node(parent, index)


_Ros2ParamsLoader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^[-+]?([0-9]+(\.[0-9]*)?|\.[0-9]+)[eE][-+]?[0-9]+$"),
    list("-+0123456789."),
)


def load_yaml(path: Path, ros_params: bool = False) -> object:
    """Parse one YAML file into YamlMap, YamlList and scalars; None when it holds nothing.
    `ros_params`: the file is a ROS 2 params file, read as ROS 2 reads one."""
    size = _size(path)
    if size > MAX_BYTES:
        raise SpecError(
            Location(path, 1),
            "",
            f"the file holds {size:,} bytes, more than the {MAX_BYTES:,} any file the gate "
            "reads as YAML needs",
            "check that this is the file you meant: a pairs, robot, navigation or scanner file",
        )
    text = read_text(path)
    loader = (_Ros2ParamsLoader if ros_params else _LocatingLoader)(text, path)
    try:
        return loader.get_single_data()
    except yaml.MarkedYAMLError as error:
        raise _syntax_error(path, error, text) from None
    except yaml.YAMLError as error:
        raise SpecError(
            Location(path, 1), "", f"this is not valid YAML: {error}", "fix the syntax"
        ) from None
    finally:
        loader.dispose()


# YAML takes a key written without `? ` to be at most this long (the spec's 1024 characters).
MAX_IMPLICIT_KEY = 1024


def _syntax_error(path: Path, error: yaml.MarkedYAMLError, text: str) -> SpecError:
    mark = error.problem_mark or error.context_mark
    line = mark.line + 1 if mark is not None else 1
    written = text.splitlines()[line - 1] if 0 < line <= len(text.splitlines()) else ""
    key = written.split(":", 1)[0].strip()
    if len(key) > MAX_IMPLICIT_KEY:
        return SpecError(
            Location(path, line),
            "",
            f"the key on this line is {len(key):,} characters long: YAML reads a key of at most "
            f"{MAX_IMPLICIT_KEY:,} as one",
            "give it a shorter name; a pair's or a node's name is a word or two",
        )
    problem = f"this is not valid YAML: {error.problem or error.context}"
    if error.problem and error.context and error.context_mark is not None:
        # Where the parser gave up is often a line after the mistake; name where it began.
        problem += f" ({error.context} that starts on line {error.context_mark.line + 1})"
    return SpecError(
        Location(path, line),
        "",
        problem,
        f"check the indentation (spaces, not tabs) and the quoting around line {line}",
    )


def _size(path: Path) -> int:
    """The file's size in bytes; 0 when it cannot be read, as read_text then says why."""
    try:
        return path.stat().st_size
    except OSError:
        return 0


def read_text(path: Path) -> str:
    """The file's text as UTF-8, or a SpecError that says why it cannot be read."""
    try:
        data = read_regular_file(path, YAML_FILE)
    except FileNotFoundError:
        raise SpecError(
            Location(path, 1), "", "the file does not exist", "check the path and its spelling"
        ) from None
    except UnreadableFile as error:
        raise SpecError(Location(path, 1), "", error.problem, error.fix) from None
    except OSError as error:  # failing while reading, past the checks
        raise SpecError(
            Location(path, 1), "", f"the file cannot be read: {error.strerror}", "check the path"
        ) from None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        line = data[: error.start].count(b"\n") + 1
        raise SpecError(
            Location(path, line), "", "the file is not UTF-8 text", "save it as UTF-8"
        ) from None
