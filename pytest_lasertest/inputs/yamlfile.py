"""Safe YAML loading that keeps the line of every key and item, and refuses duplicate keys."""

from __future__ import annotations

from pathlib import Path

import yaml
from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from pytest_lasertest.inputs.errors import Location, SpecError

_MERGE_TAG = "tag:yaml.org,2002:merge"


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


_LocatingLoader.add_constructor("tag:yaml.org,2002:map", _construct_map)
_LocatingLoader.add_constructor("tag:yaml.org,2002:seq", _construct_list)


def load_yaml(path: Path) -> object:
    """Parse one YAML file into YamlMap, YamlList and scalars; None when it holds nothing."""
    text = read_text(path)
    loader = _LocatingLoader(text, path)
    try:
        return loader.get_single_data()
    except yaml.MarkedYAMLError as error:
        raise _syntax_error(path, error) from None
    except yaml.YAMLError as error:
        raise SpecError(
            Location(path, 1), "", f"this is not valid YAML: {error}", "fix the syntax"
        ) from None
    finally:
        loader.dispose()


def _syntax_error(path: Path, error: yaml.MarkedYAMLError) -> SpecError:
    mark = error.problem_mark or error.context_mark
    line = mark.line + 1 if mark is not None else 1
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


def read_text(path: Path) -> str:
    """The file's text as UTF-8, or a SpecError that says why it cannot be read."""
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise SpecError(
            Location(path, 1), "", "the file does not exist", "check the path and its spelling"
        ) from None
    except OSError as error:
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
