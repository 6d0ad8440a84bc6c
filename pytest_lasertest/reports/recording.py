"""What `lasertest profile --bag` prints: the profile a recording of the real scanner shows, as
YAML a pairs file can paste below `baseline:` or `candidate:`, with how it was read as comments.

The JSON (`--json`) holds the same fields, nested as the YAML nests them:
`{"bag", "topic", "messages", "arrival_age", "profile": {samples, min_angle, max_angle,
range: {min, max}, update_rate, driver: {...}}, "notes": [...]}`; `arrival_age` (s) is null when
the stamps tell nothing, `driver` holds only the traits that are not Gazebo's.
"""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import yaml

from pytest_lasertest.inputs.errors import display_path
from pytest_lasertest.inputs.inferred import InferredProfile, profile_fields

WIDTH = 100  # columns of a comment line


def recording_json(inferred: InferredProfile, path: Path) -> dict[str, object]:
    """The JSON `lasertest profile --bag --json` prints."""
    return {
        "bag": display_path(path),
        "topic": inferred.topic,
        "messages": inferred.messages,
        "arrival_age": inferred.arrival_age,
        "profile": _nested(profile_fields(inferred.profile)),
        "notes": list(inferred.notes),
    }


def recording_yaml(inferred: InferredProfile, path: Path) -> str:
    """The profile as pasteable YAML, the notes above it as comments."""
    shown = display_path(path)
    header = [
        f"A scanner profile inferred from {inferred.messages} LaserScan messages on "
        f"{inferred.topic} in {shown}. Paste it below `baseline:` or `candidate:` in a pairs "
        f"file, or let the pairs file read the bag: `bag: {{path: {shown}, topic: "
        f"{inferred.topic}}}` (its path relative to the pairs file).",
    ]
    comments = [_comment(text, "# ", "# ") for text in header]
    comments += [_comment(note, "# - ", "#   ") for note in inferred.notes]
    # Groups in flow style (`range: {min: 0.1, max: 30.0}`), as pairs files write them; PyYAML
    # writes floats that it reads back as floats (1.0e-05, where 1e-05 would read as text).
    body = yaml.safe_dump(
        _nested(profile_fields(inferred.profile)),
        default_flow_style=None,
        sort_keys=False,
        width=math.inf,
    )
    return "\n".join([*comments, body.rstrip("\n")])


def _nested(flat: dict[str, object]) -> dict[str, object]:
    """`{"range.min": 0.1}` as `{"range": {"min": 0.1}}`."""
    nested: dict[str, object] = {}
    groups: dict[str, dict[str, object]] = {}
    for key, value in flat.items():
        group, dot, name = key.partition(".")
        if dot:
            inner = groups.setdefault(group, {})
            nested.setdefault(group, inner)  # where the group's first field stands
            inner[name] = value
        else:
            nested[key] = value
    return nested


def _comment(text: str, first: str, rest: str) -> str:
    return "\n".join(
        textwrap.wrap(
            text,
            WIDTH,
            initial_indent=first,
            subsequent_indent=rest,
            break_on_hyphens=False,
            break_long_words=False,
        )
    )
