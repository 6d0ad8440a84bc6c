"""The pairs-file reference the docs site prints: a table per mapping, written from the schema,
with every key the loader reads, the values it takes, and shared parts shown once."""

from __future__ import annotations

import re

import pytest

from pytest_lasertest.inputs.profile import DRIVER_KEYS
from pytest_lasertest.pairsfile.pairs import PAIR_KEYS, SECTIONS, SETTINGS_KEYS
from pytest_lasertest.pairsfile.scanners import PROFILE_KEYS
from pytest_lasertest.pairsfile.schema import pairs_file_schema
from pytest_lasertest.pairsfile.walls import BOX_KEYS, SEGMENT_KEYS
from pytest_lasertest.pairsfile.world import WORLD_KEYS
from pytest_lasertest.reports.reference import schema_reference

REFERENCE = schema_reference(pairs_file_schema())


def tables(heading: str) -> list[str]:
    """The tables under `## heading`, one for each alternative written there."""
    sections = re.split(r"^## ", REFERENCE, flags=re.MULTILINE)
    return [section for section in sections if section.split("\n", 1)[0] == heading]


def fields(table: str) -> list[str]:
    return re.findall(r"^\| `([^`]+)` \|", table, flags=re.MULTILINE)


@pytest.mark.parametrize(
    ("heading", "keys"),
    [
        ("The pairs file", SECTIONS),
        ("`world`", WORLD_KEYS),
        ("`settings`", SETTINGS_KEYS),
        ("`pairs.NAME`", PAIR_KEYS),
        ("`scanner.driver`", DRIVER_KEYS),
    ],
)
def test_each_mapping_s_table_lists_the_keys_the_loader_reads_in_its_order(
    heading: str, keys: tuple[str, ...]
) -> None:
    (table,) = tables(heading)
    assert fields(table) == list(keys)


def test_a_scanner_is_one_table_that_both_sides_of_a_pair_link_to() -> None:
    (scanner,) = tables("`scanner`")
    described = ["urdf", "sdf", "ref", "sensor", "args", "packages"]
    assert fields(scanner) == ["model", "bag", *described, *PROFILE_KEYS, "pose"]
    assert "| `baseline` | [`scanner`](#scanner) | yes |" in REFERENCE
    assert "| `candidate` | [`scanner`](#scanner) | yes |" in REFERENCE


def test_walls_have_a_table_for_a_box_and_one_for_a_segment() -> None:
    box, segment = tables("`world.walls[]`")
    assert fields(box) == list(BOX_KEYS)
    assert fields(segment) == list(SEGMENT_KEYS)


def test_a_row_says_the_unit_the_range_and_whether_the_field_is_required() -> None:
    assert (
        "| `time_limit` | number | yes | The time the robot has to reach the goal (s). "
        "From 1 to 3600. |"
    ) in REFERENCE
    assert "From 0 to 4294967295." in REFERENCE  # a seed, in full
    assert "| `samples` | integer |  | Beams per scan" in REFERENCE


def test_a_mapping_that_needs_one_key_of_several_says_which() -> None:
    (world,) = tables("`world`")
    assert "It needs one of: `goal`; `route`." in world
