"""The pairs file's field reference, in Markdown, written from its JSON Schema: one table per
mapping (the file's sections, then each mapping inside them, by its dotted path), each field's
type, whether it is required, the values it takes and what it means. The docs site's reference
page is this text (`docs/hooks/reference.py`)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

Term = Mapping[str, Any]


def schema_reference(schema: Term) -> str:
    """One Markdown table per mapping of `schema`, the whole file's first, then those of its
    definitions (which `$ref` names)."""
    tables: list[str] = []
    _tables(schema, "", tables)
    for name, definition in schema.get("definitions", {}).items():
        _tables(definition, name, tables)
    return "\n".join(tables)


def _tables(term: Term, path: str, tables: list[str]) -> None:
    for name, mapping in _mappings(term, path):
        tables.append(_table(name, mapping))
        for key, child in mapping["properties"].items():
            _tables(child, f"{name}.{key}" if name else key, tables)


def _mappings(term: Term, path: str) -> list[tuple[str, Term]]:
    """The mappings `term` is or holds: itself, its list's items, its alternatives, the values
    of a mapping whose keys are names (`pairs.NAME`)."""
    if "properties" in term:
        return [(path, term)]
    if term.get("type") == "array":
        return _mappings(term["items"], f"{path}[]")
    if isinstance(term.get("additionalProperties"), Mapping):
        return _mappings(term["additionalProperties"], f"{path}.NAME")
    return [
        found for alternative in term.get("oneOf", ()) for found in _mappings(alternative, path)
    ]


def _table(path: str, mapping: Term) -> str:
    required = set(mapping.get("required", ()))
    rows = [
        f"| `{key}` | {_kind(child)} | {'yes' if key in required else ''} | {_meaning(child)} |"
        for key, child in mapping["properties"].items()
    ]
    heading = f"## `{path}`" if path else "## The pairs file"
    introduction = [_sentence(mapping.get("description", "")), *_alternatives(mapping)]
    table = ["| field | type | required | meaning |", "|---|---|---|---|", *rows]
    return "\n\n".join([heading, *introduction, "\n".join(table)]) + "\n"


def _alternatives(mapping: Term) -> list[str]:
    """The mapping's rule on which keys go together, where it has one."""
    choices = mapping.get("anyOf") or mapping.get("oneOf")
    if not choices:
        return []
    which = "one" if "oneOf" in mapping else "at least one"
    written = [" and ".join(f"`{key}`" for key in choice["required"]) for choice in choices]
    return [f"It needs {which} of: {'; '.join(written)}."]


def _kind(term: Term, *, many: bool = False) -> str:
    """A field's type, as a reader says it; `many` for a list's items."""
    plural = "s" if many else ""
    if "enum" in term:
        return "one of " + ", ".join(f"`{value}`" for value in term["enum"])
    if "$ref" in term:
        name = term["$ref"].rsplit("/", 1)[-1]
        return f"[`{name}`{plural}](#{name})"
    if "properties" in term:
        return f"mapping{plural}"
    if "oneOf" in term:
        kinds = [_kind(alternative, many=many) for alternative in term["oneOf"]]
        return " or ".join(dict.fromkeys(kinds))
    kind = term.get("type", "")
    if kind == "array":
        return f"list{plural} of {_kind(term['items'], many=True)}"
    named = term.get("additionalProperties")
    if kind == "object" and isinstance(named, Mapping):
        return f"mapping{plural} of names to {_kind(named, many=True)}"
    kinds = kind if isinstance(kind, list) else [kind]
    return " or ".join(f"{name}{plural}" for name in kinds)


def _meaning(term: Term) -> str:
    """What a field means, then the values it takes."""
    limits = [part for part in (_range(term), _count(term), _examples(term)) if part]
    text = _sentence(term.get("description", ""))
    return " ".join([text, *(f"{part}." for part in limits)]).replace("|", "\\|")


def _range(term: Term) -> str:
    low = term.get("minimum", term.get("exclusiveMinimum"))
    high = term.get("maximum")
    above = "above" if "exclusiveMinimum" in term else "from"
    if low is not None and high is not None:
        return f"{above.capitalize()} {_figure(low)} to {_figure(high)}"
    if low is not None:
        return f"{above.capitalize()} {_figure(low)}"
    if "pattern" in term:
        return f"Matching `{term['pattern']}`"
    return ""


def _count(term: Term) -> str:
    least, most = term.get("minItems"), term.get("maxItems")
    if term.get("type") != "array" or (least is None and most is None):
        return "At most {} characters".format(term["maxLength"]) if "maxLength" in term else ""
    if least == most:
        return f"Exactly {least} items"
    if most is None:
        return f"At least {least} items"
    return f"{least or 0} to {most} items"


def _examples(term: Term) -> str:
    examples = term.get("examples", ())
    return "E.g. " + ", ".join(f"`{example}`" for example in examples) if examples else ""


def _figure(value: float) -> str:
    """A bound as a reader writes it: whole numbers in full (a seed's 4294967295), others
    to six figures."""
    return str(int(value)) if float(value).is_integer() else f"{value:g}"


def _sentence(text: str) -> str:
    return text if not text or text.endswith(".") else f"{text}."
