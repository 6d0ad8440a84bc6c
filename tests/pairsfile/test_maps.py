"""A map_server map named by a pairs file's `world: {map: ...}`: its YAML file and its image read
into the OccupancyGrid Nav2's map_server publishes (nav2_map_server/src/map_io.cpp at a3a97043),
and every problem one error naming the file, its line, the field and the fix."""

from __future__ import annotations

import io
from collections.abc import Callable
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest
from PIL import Image

from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.inputs.node import SpecNode, read_root
from pytest_lasertest.model.occupancy import FREE, OCCUPIED, UNKNOWN, OccupancyGrid
from pytest_lasertest.pairsfile.maps import read_map
from tests.helpers import WORLDS
from tests.helpers.runs import Case, assert_spec_error
from tests.helpers.texts import WALL_BESIDE_THE_GOAL, write

# Line numbers matter: the cases below break one line of each.
PAIRS = """\
robot: husky
world:
  map: maps/doorway.yaml
"""
MAP = """\
image: doorway.pgm
mode: trinary
resolution: 0.05
origin: [-1.0, -2.0, 0.0]
negate: 0
occupied_thresh: 0.65
free_thresh: 0.25
"""
BLACK, WHITE = 0, 254  # map_saver's occupied and free
WALL_ON_TOP = [[BLACK, BLACK, BLACK, BLACK], [WHITE] * 4, [WHITE] * 4]  # 3 rows of 4 pixels

Pixels = npt.ArrayLike


def map_node(tmp_path: Path, pairs: str = PAIRS) -> SpecNode:
    """The `map:` of the pairs file `pairs`, written to tmp_path."""
    root = read_root(write(tmp_path, pairs), what="pairs file", needs="world")
    return root.entries(what="sections")["world"].entries(what="world fields")["map"]


def write_map(tmp_path: Path, pixels: Pixels, text: str = MAP, image: str = "doorway.pgm") -> Path:
    """maps/doorway.yaml holding `text`, and the image `pixels` (rows of grey levels, or of
    [grey, alpha] or [r, g, b(, a)]) saved beside it as `image`, in the format its name says."""
    write(tmp_path / "maps", text, "doorway.yaml")
    Image.fromarray(np.array(pixels, dtype=np.uint8)).save(tmp_path / "maps" / image)
    return tmp_path / "maps" / image


def load(
    tmp_path: Path, pixels: Pixels, text: str = MAP, image: str = "doorway.pgm"
) -> OccupancyGrid:
    write_map(tmp_path, pixels, text, image)
    return read_map(map_node(tmp_path))


def values(grid: OccupancyGrid) -> list[list[int]]:
    return [[int(value) for value in row] for row in grid.data]


def test_a_wall_along_the_images_top_row_lies_along_the_grids_last_row(tmp_path: Path) -> None:
    grid = load(tmp_path, WALL_ON_TOP)
    assert (grid.width, grid.height) == (4, 3)
    assert values(grid) == [[FREE] * 4, [FREE] * 4, [OCCUPIED] * 4]


def test_a_pixel_in_the_images_top_left_corner_is_the_cell_at_the_maps_top_left(
    tmp_path: Path,
) -> None:
    pixels = np.full((3, 4), WHITE)
    pixels[0, 0] = BLACK
    grid = load(tmp_path, pixels)
    occupied = [(int(y), int(x)) for y, x in zip(*np.nonzero(grid.data == OCCUPIED), strict=True)]
    assert occupied == [(2, 0)]  # [y, x]: the top row, the first column


def test_the_grid_has_the_map_files_resolution_and_origin(tmp_path: Path) -> None:
    grid = load(tmp_path, WALL_ON_TOP)
    assert (grid.resolution, grid.origin) == (0.05, (-1.0, -2.0))
    # The bottom left pixel's centre lies half a cell from the origin; the wall along the top.
    assert grid.cell_centre(0, 0) == pytest.approx((-0.975, -1.975))
    assert grid.values_at(np.array([[-0.9, -1.99], [-0.9, -1.86]])).tolist() == [FREE, OCCUPIED]


@pytest.mark.parametrize("negate", ["1", "true"])
def test_negate_makes_white_occupied_and_black_free(tmp_path: Path, negate: str) -> None:
    grid = load(tmp_path, WALL_ON_TOP, MAP.replace("negate: 0", f"negate: {negate}"))
    assert values(grid) == [[OCCUPIED] * 4, [OCCUPIED] * 4, [FREE] * 4]


def test_a_map_without_negate_or_mode_is_read_as_trinary_without_negate(tmp_path: Path) -> None:
    text = MAP.replace("negate: 0\n", "").replace("mode: trinary\n", "")
    assert values(load(tmp_path, WALL_ON_TOP, text)) == values(load(tmp_path, WALL_ON_TOP))


@pytest.mark.parametrize(
    ("grey", "cell"),
    [
        (0, OCCUPIED),
        (89, OCCUPIED),  # occupancy 1 - 89/255 = 0.651, at least occupied_thresh 0.65
        (90, UNKNOWN),  # 0.647
        (128, UNKNOWN),
        (191, UNKNOWN),  # 0.251
        (192, FREE),  # 0.247, at most free_thresh 0.25
        (254, FREE),
        (255, FREE),
    ],
)
def test_trinary_mode_makes_dark_occupied_light_free_and_grey_between_unknown(
    tmp_path: Path, grey: int, cell: int
) -> None:
    assert values(load(tmp_path, [[grey]])) == [[cell]]


def test_map_savers_unknown_grey_is_unknown_under_ros_1s_free_thresh_and_free_under_nav2s(
    tmp_path: Path,
) -> None:
    # map_saver writes unknown cells as 205: occupancy 1 - 205/255 = 0.196, just above ROS 1's
    # free_thresh of 0.196 and below Nav2's 0.25, with which map_server reads it as free.
    ros1 = MAP.replace("free_thresh: 0.25", "free_thresh: 0.196")
    assert values(load(tmp_path, [[205]], ros1)) == [[UNKNOWN]]
    assert values(load(tmp_path, [[205]])) == [[FREE]]


def test_scale_mode_scales_grey_between_the_thresholds_from_0_to_100(tmp_path: Path) -> None:
    greys = [0, 89, 100, 128, 150, 191, 192, 255]
    grid = load(tmp_path, [greys], MAP.replace("mode: trinary", "mode: scale"))
    # (1 - grey / 255 - free_thresh) / (occupied_thresh - free_thresh) * 100, rounded: 100 is
    # 89.46, 128 is 62.01, 150 is 40.44 and 191 is 0.25.
    assert values(grid) == [[OCCUPIED, OCCUPIED, 89, 62, 40, 0, FREE, FREE]]


def test_raw_mode_takes_each_grey_level_as_the_cells_value_and_the_rest_as_unknown(
    tmp_path: Path,
) -> None:
    text = MAP.replace("mode: trinary", "mode: raw").replace("negate: 0", "negate: 1")
    grid = load(tmp_path, [[0, 37, 100, 101, 205, 255]], text)
    assert values(grid) == [[0, 37, 100, UNKNOWN, UNKNOWN, UNKNOWN]]  # negate does not apply


def test_the_mode_is_read_in_any_case(tmp_path: Path) -> None:
    grid = load(tmp_path, [[37]], MAP.replace("mode: trinary", "mode: Raw"))
    assert values(grid) == [[37]]


@pytest.mark.parametrize("mode", ["trinary", "scale"])
def test_a_pixel_less_than_opaque_is_unknown_in_trinary_and_scale_modes(
    tmp_path: Path, mode: str
) -> None:
    text = MAP.replace("mode: trinary", f"mode: {mode}").replace("doorway.pgm", "doorway.png")
    pixels = [[[BLACK, 255], [BLACK, 254], [BLACK, 0], [WHITE, 128]]]  # [grey, alpha]
    grid = load(tmp_path, pixels, text, "doorway.png")
    assert values(grid) == [[OCCUPIED, UNKNOWN, UNKNOWN, UNKNOWN]]


def test_alpha_does_not_apply_in_raw_mode(tmp_path: Path) -> None:
    text = MAP.replace("mode: trinary", "mode: raw").replace("doorway.pgm", "doorway.png")
    grid = load(tmp_path, [[[40, 255, 0, 0], [50, 50, 50, 0]]], text, "doorway.png")
    # (40, 255, 0) is 0.299 * 40 + 0.587 * 255 = 161.7: above 100, unknown.
    assert values(grid) == [[UNKNOWN, 50]]


def test_a_colour_image_is_read_as_its_rec_601_luma_as_graphicsmagick_makes_it_grey(
    tmp_path: Path,
) -> None:
    # In raw mode a cell is the pixel's grey level. Rec. 709 luma would make the red 54, the
    # green 122 (unknown) and the blue 18.
    text = MAP.replace("mode: trinary", "mode: raw").replace("doorway.pgm", "doorway.png")
    colours = [[255, 0, 0], [0, 170, 0], [0, 0, 255], [100, 100, 100]]
    grid = load(tmp_path, [colours], text, "doorway.png")
    assert values(grid) == [[76, 100, 29, 100]]


def test_a_16_bit_grey_image_is_read_as_its_nearest_8_bit_levels(tmp_path: Path) -> None:
    text = MAP.replace("mode: trinary", "mode: raw").replace("doorway.pgm", "doorway.png")
    write(tmp_path / "maps", text, "doorway.yaml")
    levels = np.array([[0, 50 * 257, 100 * 257 + 128, 100 * 257 + 129, 65535]], dtype=np.uint16)
    Image.fromarray(levels).save(tmp_path / "maps" / "doorway.png")
    assert values(read_map(map_node(tmp_path))) == [[0, 50, 100, UNKNOWN, UNKNOWN]]


def test_an_absolute_image_path_is_read_as_written(tmp_path: Path) -> None:
    elsewhere = tmp_path / "images" / "doorway.pgm"
    elsewhere.parent.mkdir()
    Image.fromarray(np.array(WALL_ON_TOP, dtype=np.uint8)).save(elsewhere)
    write(
        tmp_path / "maps", MAP.replace("image: doorway.pgm", f"image: {elsewhere}"), "doorway.yaml"
    )
    assert values(read_map(map_node(tmp_path)))[-1] == [OCCUPIED] * 4


MAP_CASES = {
    "no image": Case("image: doorway.pgm\n", "", 1, "image", "image is missing", "map_saver"),
    "no resolution": Case("resolution: 0.05\n", "", 1, "resolution", "resolution is missing", ""),
    "no origin": Case("origin: [-1.0, -2.0, 0.0]\n", "", 1, "origin", "origin is missing", ""),
    "no occupied_thresh": Case(
        "occupied_thresh: 0.65\n", "", 1, "occupied_thresh", "occupied_thresh is missing", ""
    ),
    "no free_thresh": Case(
        "free_thresh: 0.25\n", "", 1, "free_thresh", "free_thresh is missing", "0.25"
    ),
    "an image that is no path": Case(
        "image: doorway.pgm", "image: 5", 1, "image", "expected the path of the map's image", ""
    ),
    "a resolution that is no number": Case(
        "resolution: 0.05",
        "resolution: fine",
        3,
        "resolution",
        "expected a number in m, got the text 'fine'",
        "write a number in m",
    ),
    "a resolution of zero": Case(
        "resolution: 0.05",
        "resolution: 0",
        3,
        "resolution",
        "0 m is below 0.005 m: no laser scanner resolves 5 mm",
        "write a value from 0.005 to 1 m",
    ),
    "a resolution too coarse": Case(
        "resolution: 0.05",
        "resolution: 2.0",
        3,
        "resolution",
        "2 m is above 1 m, the most the gate accepts: a cell wider than a doorway",
        "write a value from 0.005 to 1 m",
    ),
    "an origin that is no list": Case(
        "origin: [-1.0, -2.0, 0.0]",
        "origin: -1.0",
        4,
        "origin",
        "expected a list of 3 numbers [x, y, yaw] (m, m, rad), got -1.0",
        "write one `- item` per line",
    ),
    "an origin of two numbers": Case(
        "origin: [-1.0, -2.0, 0.0]",
        "origin: [-1.0, -2.0]",
        4,
        "origin",
        "expected 3 numbers [x, y, yaw] (m, m, rad), got 2",
        "origin: [-10.0, -10.0, 0.0]",
    ),
    "an origin with text": Case(
        "origin: [-1.0, -2.0, 0.0]",
        "origin: [left, -2.0, 0.0]",
        4,
        "origin[0]",
        "expected a number in m, got the text 'left'",
        "write a number in m",
    ),
    "an origin far out": Case(
        "origin: [-1.0, -2.0, 0.0]",
        "origin: [-1.0, 20000.0, 0.0]",
        4,
        "origin[1]",
        "20000 m is above 10000 m",
        "write a value from -10000 to 10000 m",
    ),
    "a rotated origin": Case(
        "origin: [-1.0, -2.0, 0.0]",
        "origin: [-1.0, -2.0, 0.5]",
        4,
        "origin[2]",
        "the map's yaw is 0.5 rad: the gate's world frame is the map frame, and Nav2's static "
        "layer ignores a map's yaw",
        "rotate the image itself and write a yaw of 0.0",
    ),
    "negate of 2": Case(
        "negate: 0",
        "negate: 2",
        5,
        "negate",
        "negate is 0 or 1 (or false or true), not 2",
        "write 0 (black is occupied",
    ),
    "negate as text": Case(
        "negate: 0",
        "negate: no way",
        5,
        "negate",
        "negate is 0 or 1 (or false or true), not the text 'no way'",
        "write 0",
    ),
    "an occupied_thresh that is no number": Case(
        "occupied_thresh: 0.65",
        "occupied_thresh: high",
        6,
        "occupied_thresh",
        "expected a probability of occupancy from 0 to 1, got the text 'high'",
        "write a number from 0 to 1",
    ),
    "an occupied_thresh above 1": Case(
        "occupied_thresh: 0.65",
        "occupied_thresh: 65",
        6,
        "occupied_thresh",
        "65 is above 1, the most the gate accepts: a threshold is a probability of occupancy",
        "write a value from 0 to 1",
    ),
    "a free_thresh below 0": Case(
        "free_thresh: 0.25",
        "free_thresh: -0.1",
        7,
        "free_thresh",
        "-0.1 is below 0: a threshold is a probability of occupancy",
        "write a value from 0 to 1",
    ),
    "a free_thresh not below occupied_thresh": Case(
        "free_thresh: 0.25",
        "free_thresh: 0.65",
        7,
        "free_thresh",
        "free_thresh 0.65 is not below occupied_thresh 0.65: a cell would be free and occupied",
        "write a free_thresh below occupied_thresh; map_saver writes 0.25 and 0.65",
    ),
    "an unknown mode": Case(
        "mode: trinary",
        "mode: ternary",
        2,
        "mode",
        "'ternary' is not a map mode map_server knows",
        "write trinary (the default",
    ),
    "a mode that is no text": Case(
        "mode: trinary", "mode: 3", 2, "mode", "expected a map mode, got 3", "trinary, scale, raw"
    ),
    "a misspelt key": Case(
        "negate: 0",
        "negat: 1",
        5,
        "negat",
        "unknown key 'negat'",
        "did you mean 'negate'? map_server reads image, resolution",
    ),
    "a list, not a mapping": Case(
        MAP,
        "- image: doorway.pgm\n",
        1,
        "",
        "expected a mapping of map fields (image, resolution, origin, ...), got a list",
        "write `key: value` pairs",
    ),
    "unparseable YAML": Case(
        "origin: [-1.0, -2.0, 0.0]",
        "origin: [-1.0, -2.0, 0.0",
        5,
        "",
        "this is not valid YAML",
        "check the indentation",
    ),
    "an empty file": Case(MAP, "", 1, "", "the map file is empty", "it needs image, resolution"),
}


@pytest.mark.parametrize("case", MAP_CASES.values(), ids=MAP_CASES.keys())
def test_a_broken_map_file_is_one_error_naming_it_and_its_line_field_and_fix(
    tmp_path: Path, case: Case
) -> None:
    assert case.old in MAP
    write_map(tmp_path, WALL_ON_TOP, MAP.replace(case.old, case.new, 1))
    with pytest.raises(SpecError) as raised:
        read_map(map_node(tmp_path))
    assert_spec_error(raised.value, "doorway.yaml", case)


# Each spoils the image of a valid map; the error is at the map file's `image:` line.
IMAGE_CASES: dict[str, tuple[Callable[[Path], object], str, str]] = {
    "no image file": (
        lambda tmp_path: (tmp_path / "maps" / "doorway.pgm").unlink(),
        "doorway.pgm does not exist",
        "write its path relative to this map file's folder",
    ),
    "a text file for an image": (
        lambda tmp_path: (tmp_path / "maps" / "doorway.pgm").write_text("P5 not really\n"),
        "doorway.pgm is not an image Pillow can read",
        "save the map as PNG or PGM",
    ),
    "a PNG cut short": (
        lambda tmp_path: (tmp_path / "maps" / "doorway.pgm").write_bytes(png_bytes()[:60]),
        "doorway.pgm is not an image Pillow can read",
        "save the map as PNG or PGM",
    ),
    "a directory for an image": (
        lambda tmp_path: replace_with_directory(tmp_path / "maps" / "doorway.pgm"),
        "doorway.pgm is a directory, not a file",
        "point the map file's `image:` at the map's image file itself",
    ),
    "an image too wide": (
        lambda tmp_path: Image.new("L", (4001, 1), WHITE).save(tmp_path / "maps" / "doorway.pgm"),
        "doorway.pgm is 4001 x 1 pixels, more than the 4000 a side the gate accepts",
        "at most 4000 x 4000 pixels",
    ),
}


def png_bytes() -> bytes:
    buffer = io.BytesIO()
    Image.new("L", (64, 64), WHITE).save(buffer, "PNG")
    return buffer.getvalue()


def replace_with_directory(path: Path) -> None:
    path.unlink()
    path.mkdir()


@pytest.mark.parametrize(("spoil", "problem", "fix"), IMAGE_CASES.values(), ids=IMAGE_CASES.keys())
def test_an_image_that_cannot_be_read_is_an_error_at_the_map_files_image_line(
    tmp_path: Path, spoil: Callable[[Path], object], problem: str, fix: str
) -> None:
    write_map(tmp_path, WALL_ON_TOP)
    spoil(tmp_path)
    with pytest.raises(SpecError) as raised:
        read_map(map_node(tmp_path))
    assert_spec_error(raised.value, "doorway.yaml", Case("", "", 1, "image", problem, fix))


PAIRS_CASES = {
    "a map file that does not exist": Case(
        "map: maps/doorway.yaml",
        "map: maps/hallway.yaml",
        3,
        "world.map",
        "the map file maps/hallway.yaml does not exist",
        "give the path of a map_server map YAML file",
    ),
    "a directory for a map file": Case(
        "map: maps/doorway.yaml",
        "map: maps",
        3,
        "world.map",
        "maps is a directory, not a map YAML file",
        "name the map's YAML file in it",
    ),
    "a map that is no path": Case(
        "map: maps/doorway.yaml",
        "map: 5",
        3,
        "world.map",
        "expected a path to a map_server map YAML file, got 5",
        "relative to this file, e.g. maps/doorway.yaml",
    ),
}


@pytest.mark.parametrize("case", PAIRS_CASES.values(), ids=PAIRS_CASES.keys())
def test_a_map_the_pairs_file_cannot_name_is_an_error_at_the_pairs_files_line(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, case: Case
) -> None:
    monkeypatch.chdir(tmp_path)  # paths in messages are shown relative to the working directory
    write_map(tmp_path, WALL_ON_TOP)
    with pytest.raises(SpecError) as raised:
        read_map(map_node(tmp_path, PAIRS.replace(case.old, case.new)))
    assert_spec_error(raised.value, "gate.lasertest.yaml", case)


@pytest.mark.parametrize(
    ("name", "goal"), [("doorway", (8.5, 3.8)), ("aisle", (11.0, 3.0))], ids=["doorway", "aisle"]
)
def test_each_world_of_the_test_data_reads_its_map_as_walls(
    name: str, goal: tuple[float, float]
) -> None:
    from pytest_lasertest.pairsfile import load_pairs_file

    spec = load_pairs_file(WORLDS / f"{name}.lasertest.yaml")
    assert spec.world.walls
    last = spec.world.route[-1]
    assert (last.x, last.y) == pytest.approx(goal)


def _doorway(tmp_path: Path, old: str = "", new: str = "", pixels: Pixels | None = None) -> Path:
    """examples/worlds/doorway.lasertest.yaml and its map copied to tmp_path, `old` replaced by
    `new` in the pairs file, the map's image replaced by `pixels` if given."""
    for name in ("doorway.lasertest.yaml", "doorway.yaml", "doorway.pgm"):
        (tmp_path / name).write_bytes((WORLDS / name).read_bytes())
    pairs = tmp_path / "doorway.lasertest.yaml"
    pairs.write_text(pairs.read_text().replace(old, new))
    if pixels is not None and np.ndim(pixels) == 2:
        Image.fromarray(np.array(pixels, dtype=np.uint8)).save(tmp_path / "doorway.pgm")
    elif pixels is not None:
        # A PGM holds grey alone: pixels with colour or alpha go into a PNG the map names.
        Image.fromarray(np.array(pixels, dtype=np.uint8)).save(tmp_path / "doorway.png")
        map_file = tmp_path / "doorway.yaml"
        map_file.write_text(map_file.read_text().replace("doorway.pgm", "doorway.png"))
    return pairs


UNKNOWN_GREY = 205  # map_saver's unknown


@pytest.mark.parametrize(
    ("old", "new", "pixels", "line", "point"),
    [
        ("goal: {x: 8.5, y: 3.8}", "goal: {x: 28.5, y: 3.8}", None, 11, "(28.5, 3.8)"),
        ("", "", [[WHITE]], 10, "(1.5, 1.2)"),
        ("", "", np.full((120, 200), UNKNOWN_GREY), 10, "(1.5, 1.2)"),
        ("", "", np.full((100, 200, 4), [WHITE, WHITE, WHITE, 0]), 10, "(1.5, 1.2)"),
    ],
    ids=[
        "goal-20-m-off-the-map",
        "a-one-cell-map",
        "an-all-unknown-map",
        "a-fully-transparent-png",
    ],
)
def test_a_start_or_goal_the_map_does_not_know_is_an_error_at_its_line(
    tmp_path: Path, old: str, new: str, pixels: Pixels | None, line: int, point: str
) -> None:
    from pytest_lasertest.pairsfile import load_pairs_file

    with pytest.raises(SpecError) as raised:
        load_pairs_file(_doorway(tmp_path, old, new, pixels))
    assert raised.value.location.line == line
    assert f"{point} lies off the map or on a cell it leaves unknown" in raised.value.problem
    assert "give a map that covers the route" in raised.value.fix


# The world's size: each bound alone would let through a world that breaks another.


def test_a_map_wider_than_the_costmaps_cover_is_an_error_at_its_image_line(tmp_path: Path) -> None:
    # 250 cells of 1 m: few cells, but 250 m, 5000 cells a side of a 0.05 m costmap.
    text = MAP.replace("resolution: 0.05", "resolution: 1.0")
    with pytest.raises(SpecError) as raised:
        load(tmp_path, np.full((250, 250), WHITE), text)
    assert raised.value.location.line == 1
    assert "the map spans 250 x 250 m, wider than the 200 m a side" in raised.value.problem


def test_a_speckled_map_of_more_wall_boxes_than_the_simulator_steps_is_an_error(
    tmp_path: Path,
) -> None:
    speckle = np.where(np.random.default_rng(0).random((300, 300)) < 0.15, BLACK, WHITE)
    with pytest.raises(SpecError) as raised:
        load(tmp_path, speckle)
    assert "wall boxes, more than the 5,000 the simulator steps" in raised.value.problem
    assert "clean the map of its speckle" in raised.value.fix


FAR_WALL = "{x: 9000.0, y: -9000.0, length: 2.0, width: 0.2, height: 2.0}"
BESIDE = "    - {x: 6.0, y: 4.0, length: 2.0, width: 0.2, height: 2.0}\n"
# The wall beside the goal, and one 9 km off.
FAR = WALL_BESIDE_THE_GOAL.replace(BESIDE, f"{BESIDE}    - {FAR_WALL}\n")


@pytest.mark.parametrize(
    ("world", "line", "problem"),
    [
        (
            lambda tmp_path: write(tmp_path, FAR),
            7,
            "the walls and the route spread over 9003 x 9006.2 m, wider than the 200 m a side "
            "the gate draws into a map",
        ),
        # The doorway's map spans x 0 to 10 m, y 0 to 5 m.
        (
            lambda tmp_path: _doorway(
                tmp_path, "  time_limit", f"  walls: [{FAR_WALL}]\n  time_limit"
            ),
            12,
            "the map and its walls spread over 9001 x 9005.1 m, wider than the 200 m a side a "
            "map may span",
        ),
    ],
    ids=["listed-walls", "a-map-and-listed-walls"],
)
def test_walls_kilometres_apart_are_an_error_at_the_walls_line(
    tmp_path: Path, world: Callable[[Path], Path], line: int, problem: str
) -> None:
    from pytest_lasertest.pairsfile import load_pairs_file

    assert FAR_WALL in FAR
    with pytest.raises(SpecError) as raised:
        load_pairs_file(world(tmp_path))
    assert raised.value.location.line == line
    assert problem in raised.value.problem
    assert "keep the walls of the part the robot drives through" in raised.value.fix


TWO_WALLS = (
    "  walls:\n"
    "    - {x: 2.0, y: 4.0, length: 1.0, width: 0.2, height: 2.0}\n"
    "    - {x: 8.0, y: 1.0, length: 1.0, width: 0.2, height: 2.0}\n"
)
# An SDF world of three static crates, each a box.
CRATES = """\
<?xml version="1.0"?>
<sdf version="1.7">
  <world name="default">
    <model name="crates">
      <static>true</static>
      <link name="a"><pose>2 2.5 0.5 0 0 0</pose><collision name="collision">
        <geometry><box><size>0.4 0.4 1</size></box></geometry></collision></link>
      <link name="b"><pose>3 2.5 0.5 0 0 0</pose><collision name="collision">
        <geometry><box><size>0.4 0.4 1</size></box></geometry></collision></link>
      <link name="c"><pose>7 2.5 0.5 0 0 0</pose><collision name="collision">
        <geometry><box><size>0.4 0.4 1</size></box></geometry></collision></link>
    </model>
  </world>
</sdf>
"""


@pytest.mark.parametrize(
    ("lone_cells", "sdf", "line", "problem"),
    [
        (
            5_000,
            "",
            12,
            "the map's 5,000 wall boxes and the 2 listed walls make 5,002 wall boxes",
        ),
        (
            4_998,
            "  sdf: crates.world\n",
            15,
            "the map's 4,998 wall boxes, the 2 listed walls and the 3 static boxes of the SDF "
            "world make 5,003 wall boxes",
        ),
    ],
    ids=["listed-walls", "an-sdf-world-after-them"],
)
def test_walls_that_take_a_maps_boxes_past_what_the_simulator_steps_are_an_error_at_their_line(
    tmp_path: Path, lone_cells: int, sdf: str, line: int, problem: str
) -> None:
    # Each source alone is within its bound: the map's 5,000 boxes, 500 listed, 500 in SDF.
    from pytest_lasertest.pairsfile import load_pairs_file

    dots = np.full((100, 200), WHITE)
    dots[::2, ::2] = BLACK  # 5,000 lone occupied cells, each a box of its own
    dots[0, : 2 * (5_000 - lone_cells) : 2] = WHITE
    (tmp_path / "crates.world").write_text(CRATES)
    pairs = _doorway(tmp_path, "  time_limit", f"{TWO_WALLS}{sdf}  time_limit", dots)
    with pytest.raises(SpecError) as raised:
        load_pairs_file(pairs)
    assert raised.value.location.line == line
    assert problem in raised.value.problem
    assert "more than the 5,000 the simulator steps and casts every scan against" in (
        raised.value.problem
    )
    assert "clean the map of its speckle" in raised.value.fix


def test_five_hundred_walls_are_drawn_into_a_map_of_16_million_cells(
    tmp_path: Path,
) -> None:
    # Each wall is drawn over the cells round it, not tested against all 16 million.
    from pytest_lasertest.model.obstacles import Box
    from pytest_lasertest.model.occupancy import drawn

    grid = OccupancyGrid(0.05, (0.0, 0.0), np.zeros((4000, 4000), dtype=np.int8))
    walls = tuple(
        Box(2.0 * (i % 90) + 1, 2.0 * (i // 90) + 1, 0.3, 1.0, 0.2, 1.0) for i in range(500)
    )
    assert (drawn(grid, walls).data == 100).sum() > 500 * 80  # 1.0 x 0.2 m: 80 cells each


def test_the_map_drawn_of_listed_walls_covers_the_start_and_the_route(tmp_path: Path) -> None:
    from pytest_lasertest.model.occupancy import FREE
    from pytest_lasertest.pairsfile import load_pairs_file

    goal = "  goal: {x: 6.0, y: 0.0}\n"
    assert goal in WALL_BESIDE_THE_GOAL
    route = "  route:\n    - {x: 3.0, y: -2.0}\n    - {x: 6.0, y: 0.0}\n"
    beside = WALL_BESIDE_THE_GOAL.replace(goal, route)
    grid = load_pairs_file(write(tmp_path, beside)).world.walls.grid
    assert grid is not None
    driven = np.array([[0.0, 0.0], [3.0, -2.0], [6.0, 0.0], [-0.9, -2.9], [6.9, 0.9]])
    assert (grid.values_at(driven) == FREE).all()
