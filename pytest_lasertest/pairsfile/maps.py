"""The `map:` of a pairs file's world: a map_server map, its YAML file and its image, read into
the OccupancyGrid map_server publishes on /map.

    world: {map: maps/doorway.yaml, ...}

with maps/doorway.yaml as map_saver writes it:

    image: doorway.pgm
    mode: trinary
    resolution: 0.05
    origin: [-10.0, -10.0, 0.0]
    negate: 0
    occupied_thresh: 0.65
    free_thresh: 0.25

It is read as Nav2's map_server reads it: loadMapYaml and loadMapFromFile in
nav2_map_server/src/map_io.cpp at a3a97043ee93d92fe8d70ec56d183933169beb1c. Where map_server
would load a map the gate cannot use as it means (a rotated origin, thresholds out of order, a
map too large or too fine to plan over), the gate refuses it and says why.

Pillow reads the image; it is imported inside the function that does, so that importing the
plugin stays cheap.
"""

from __future__ import annotations

import difflib
import io
import math
import struct
import warnings
import zlib
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from pytest_lasertest.inputs.errors import display_path
from pytest_lasertest.inputs.files import FileKind, UnreadableFile, read_regular_file
from pytest_lasertest.inputs.node import Bounds, SpecNode, describe, read_root
from pytest_lasertest.model.occupancy import FREE, OCCUPIED, UNKNOWN, Cells, OccupancyGrid
from pytest_lasertest.model.walls import MAP_RESOLUTION
from pytest_lasertest.nav.move_base.settings import MAX_CELLS

if TYPE_CHECKING:
    from PIL.Image import Image

REQUIRED_MAP_KEYS = ("image", "resolution", "origin", "occupied_thresh", "free_thresh")
MAP_KEYS = (*REQUIRED_MAP_KEYS, "negate", "mode")
MODES = ("trinary", "scale", "raw")  # map_server's MapMode; trinary when `mode` is not given
# A map's cell is the costmap's: Nav2's static layer sizes the global costmap to the map.
RESOLUTION = Bounds(
    0.005,
    1.0,
    "m",
    "no laser scanner resolves 5 mm, and at that a 20 m room is 4000 cells a side",
    "a cell wider than a doorway closes the gaps the robot drives through",
)
# Far from the origin a float holds positions to less than the millimetres the verifier needs.
ORIGIN = Bounds(
    -10_000.0,
    10_000.0,
    "m",
    "positions that far out lose the millimetres the verifier judges by",
    "positions that far out lose the millimetres the verifier judges by",
)
THRESHOLD = Bounds(
    0.0,
    1.0,
    "",
    "a threshold is a probability of occupancy, from 0 to 1",
    "a threshold is a probability of occupancy, from 0 to 1",
)
# The same bound as a costmap's side (16 million cells): the global costmap takes the map's size.
MAX_MAP_SIDE = MAX_CELLS  # cells
# And in metres: a costmap of the common 0.05 m cells over a map this wide has MAX_CELLS a side.
MAX_MAP_EXTENT = MAX_CELLS * MAP_RESOLUTION  # m
# Each occupied run of a map is a box the simulator steps and casts every scan against; a
# speckled map of 800 x 800 cells makes 74,000 of them.
MAX_MAP_WALLS = 5_000
# An uncompressed 4000 x 4000 RGBA image is 64 MB, and so is an ASCII PGM of 4000 x 4000.
MAX_IMAGE_BYTES = 80 * 1024 * 1024  # bytes
IMAGE_FILE = FileKind(
    "a map image",
    MAX_IMAGE_BYTES,
    "point the map file's `image:` at the map's image file itself",
    "save the map as PNG or as a binary PGM (P5), as map_saver writes it, at most "
    f"{MAX_MAP_SIDE} x {MAX_MAP_SIDE} pixels",
)
MAP_FIX = (
    "write it as map_saver does: `image: map.pgm`, `resolution: 0.05`, `origin: [x, y, 0.0]`, "
    "`occupied_thresh: 0.65`, `free_thresh: 0.25`"
)
# What Pillow raises for a file it cannot decode: no format it knows (an OSError), a file cut
# short, a broken chunk, a pixel format it cannot convert; its format plugins raise the rest on
# corrupt headers (found by feeding it 60,000 truncated and altered PNG, PGM, TIFF, BMP, GIF,
# JPEG and WebP files).
_UNDECODABLE = (
    OSError,
    ValueError,
    TypeError,
    IndexError,
    KeyError,
    SyntaxError,
    EOFError,
    struct.error,
    zlib.error,
)

Bytes = npt.NDArray[np.uint8]


@dataclass(frozen=True)
class _MapFile:
    """A map YAML file's fields, as map_server's LoadParameters holds them."""

    image: Path
    image_node: SpecNode  # where `image:` is written, for the image's errors
    resolution: float  # m per cell
    origin: tuple[float, float]  # m, the lower left corner of the image's bottom left pixel
    occupied_thresh: float
    free_thresh: float
    mode: str  # one of MODES
    negate: bool


def read_map(node: SpecNode) -> OccupancyGrid:
    """The OccupancyGrid Nav2's map_server publishes for the map YAML file `node` names, relative
    to the file `node` is written in, and the image that map file names, relative to the map file.

    A problem with the path is a SpecError at `node`; a problem in the map file or its image, one
    at the map file's line and field."""
    path = node.location.path.parent / node.text(
        what="a path to a map_server map YAML file",
        fix="write the path of the map's YAML file relative to this file, e.g. maps/doorway.yaml",
    )
    if not path.exists():
        raise node.error(
            f"the map file {display_path(path)} does not exist",
            "give the path of a map_server map YAML file (as map_saver writes it, next to its "
            "image) relative to this file",
        )
    if path.is_dir():
        raise node.error(
            f"{display_path(path)} is a directory, not a map YAML file",
            "name the map's YAML file in it, e.g. maps/doorway.yaml",
        )
    fields = _read_map_file(path)
    grey, alpha = _read_image(fields.image, fields.image_node)
    cells = _occupancy(grey, alpha, fields)
    # map_server flips the image (its first row is the map's top) so that row 0 is the bottom.
    grid = OccupancyGrid(fields.resolution, fields.origin, cells[::-1])
    _check_extent(grid, fields.image_node)
    return grid


def _check_extent(grid: OccupancyGrid, node: SpecNode) -> None:
    """Refuse a map wider than the stacks' costmaps cover, or one that makes more wall boxes
    than the simulator steps: each bound alone lets through a map that breaks the other."""
    width, height = grid.width * grid.resolution, grid.height * grid.resolution  # m
    if max(width, height) > MAX_MAP_EXTENT:
        raise node.error(
            f"the map spans {width:g} x {height:g} m, wider than the {MAX_MAP_EXTENT:g} m a side "
            f"the gate accepts: the global costmap takes the map's size, and at the common 0.05 "
            f"m cells that is {MAX_CELLS} cells a side",
            "crop the map to the part the robot drives through",
        )
    boxes = grid.wall_box_count
    if boxes > MAX_MAP_WALLS:
        raise node.error(
            f"the map's occupied cells make {boxes:,} wall boxes, more than the "
            f"{MAX_MAP_WALLS:,} the simulator steps and casts every scan against",
            "clean the map of its speckle (isolated occupied cells), or coarsen it",
        )


def _read_map_file(path: Path) -> _MapFile:
    """The fields of a map YAML file, checked as loadMapYaml reads them and beyond."""
    root = read_root(path, what="map file", needs=", ".join(REQUIRED_MAP_KEYS))
    fields = root.entries(what="map fields (image, resolution, origin, ...)")
    for key, child in fields.items():
        # map_server reads its keys and ignores the rest; a near miss of one is a typo that
        # would silently take a default.
        close = difflib.get_close_matches(key, MAP_KEYS, n=1, cutoff=0.75)
        if key not in MAP_KEYS and close:
            raise child.error(
                f"unknown key '{key}'",
                f"did you mean '{close[0]}'? map_server reads {', '.join(MAP_KEYS)}",
            )
    for key in REQUIRED_MAP_KEYS:
        if key not in fields:
            raise root.missing(key, f"map_server needs it: {MAP_FIX}")
    image_node = fields["image"]
    image = image_node.text(
        what="the path of the map's image",
        fix="write the image's file name, relative to this map file, e.g. `image: map.pgm`",
    )
    resolution = fields["resolution"].number_in(RESOLUTION)
    origin = _origin(fields["origin"])
    free, occupied = fields["free_thresh"], fields["occupied_thresh"]
    free_thresh, occupied_thresh = _threshold(free), _threshold(occupied)
    if free_thresh >= occupied_thresh:
        raise free.error(
            f"free_thresh {free_thresh:g} is not below occupied_thresh {occupied_thresh:g}: a "
            "cell would be free and occupied at once",
            "write a free_thresh below occupied_thresh; map_saver writes 0.25 and 0.65",
        )
    return _MapFile(
        # Absolute as written, else relative to the map file's folder, as loadMapYaml joins it.
        image=path.parent / image,
        image_node=image_node,
        resolution=resolution,
        origin=origin,
        occupied_thresh=occupied_thresh,
        free_thresh=free_thresh,
        mode=_mode(fields["mode"]) if "mode" in fields else "trinary",
        negate=_negate(fields["negate"]) if "negate" in fields else False,
    )


def _origin(node: SpecNode) -> tuple[float, float]:
    """[x, y, yaw]: the pose of the image's bottom left corner in the map frame, with no yaw."""
    items = node.items(what="3 numbers [x, y, yaw] (m, m, rad)")
    if len(items) != 3:
        raise node.error(
            f"expected 3 numbers [x, y, yaw] (m, m, rad), got {len(items)}",
            "write the map's lower left corner and yaw, e.g. `origin: [-10.0, -10.0, 0.0]`",
        )
    x, y = items[0].number_in(ORIGIN), items[1].number_in(ORIGIN)
    yaw = items[2].number("rad")
    if yaw != 0.0:
        # Nav2's static layer reads only origin.position, never its orientation
        # (nav2_costmap_2d/plugins/static_layer.cpp, StaticLayer::processMap, at a3a97043): the
        # costmap would hold the map unrotated while rviz and amcl turn it.
        raise items[2].error(
            f"the map's yaw is {yaw:g} rad: the gate's world frame is the map frame, and Nav2's "
            "static layer ignores a map's yaw, so its costmap would not be the map you drew",
            "rotate the image itself and write a yaw of 0.0",
        )
    return x, y


def _threshold(node: SpecNode) -> float:
    """A probability of occupancy, from 0 to 1."""
    value = node.value
    if (
        isinstance(value, bool)
        or not isinstance(value, int | float)
        or (isinstance(value, float) and not math.isfinite(value))
    ):
        raise node.error(
            f"expected a probability of occupancy from 0 to 1, got {describe(value)}",
            "write a number from 0 to 1; map_saver writes occupied_thresh: 0.65 and "
            "free_thresh: 0.25",
        )
    return float(THRESHOLD.check(node, value))


def _negate(node: SpecNode) -> bool:
    """0 or 1, or false or true, as loadMapYaml reads an int, else a bool."""
    value = node.value
    if isinstance(value, bool):
        return value
    if isinstance(value, int) and value in (0, 1):
        return value == 1
    raise node.error(
        f"negate is 0 or 1 (or false or true), not {describe(value)}",
        "write 0 (black is occupied, as map_saver writes it) or 1 (white is occupied)",
    )


def _mode(node: SpecNode) -> str:
    """trinary, scale or raw, in any case, as map_mode_from_string (map_mode.cpp) reads it."""
    mode = node.text(what="a map mode", fix=f"write {', '.join(MODES)}")
    if mode.lower() not in MODES:
        raise node.error(
            f"{mode!r} is not a map mode map_server knows",
            "write trinary (the default: occupied, free or unknown), scale (grey levels between "
            "the thresholds scaled from 0 to 100) or raw (each pixel's value is the cell's)",
        )
    return mode.lower()


def _read_image(path: Path, node: SpecNode) -> tuple[Bytes, Bytes | None]:
    """The image's grey level (0 black to 255 white) and, if it has one, its alpha, each
    (height, width) with the image's top row first; errors at `node`, the map file's `image:`."""
    from PIL import Image

    shown = display_path(path)
    try:
        data = read_regular_file(path, IMAGE_FILE)
    except FileNotFoundError:
        raise node.error(
            f"the map's image {shown} does not exist",
            f"write its path relative to this map file's folder ({display_path(path.parent)}), "
            "or an absolute path",
        ) from None
    except UnreadableFile as error:
        raise node.error(error.problem, error.fix) from None
    except OSError as error:  # failing while reading, past the checks
        raise node.error(
            f"the map's image {shown} cannot be read: {error.strerror}", "check the path"
        ) from None
    not_an_image = node.error(
        f"the map's image {shown} is not an image Pillow can read",
        "save the map as PNG or PGM, as map_saver writes it",
    )
    try:
        with warnings.catch_warnings():
            # Pillow warns of an image of more than 89 million pixels as it opens it.
            warnings.simplefilter("error", Image.DecompressionBombWarning)
            with Image.open(io.BytesIO(data)) as image:
                _check_size(image.size, node, shown)
                image.load()
                return _grey_and_alpha(image)
    except (Image.DecompressionBombError, Image.DecompressionBombWarning):
        raise node.error(
            f"the map's image {shown} has more pixels than the gate reads",
            f"crop or coarsen the map to at most {MAX_MAP_SIDE} x {MAX_MAP_SIDE} pixels",
        ) from None
    except _UNDECODABLE:
        raise not_an_image from None


def _check_size(size: tuple[int, int], node: SpecNode, shown: str) -> None:
    width, height = size
    if width < 1 or height < 1:
        raise node.error(
            f"the map's image {shown} is {width} x {height} pixels: it holds no cell",
            "save the map's image with its pixels",
        )
    if max(width, height) > MAX_MAP_SIDE:
        raise node.error(
            f"the map's image {shown} is {width} x {height} pixels, more than the "
            f"{MAX_MAP_SIDE} a side the gate accepts: the global costmap takes the map's size, "
            "and every cell of it is marked, inflated and planned through",
            f"crop the map to the part the robot drives through, or coarsen it, to at most "
            f"{MAX_MAP_SIDE} x {MAX_MAP_SIDE} pixels (and raise resolution to match)",
        )


def _grey_and_alpha(image: Image) -> tuple[Bytes, Bytes | None]:
    """The grey levels loadMapFromFile reads and, when the image has an alpha channel (or a
    transparent colour), its alpha."""
    has_alpha = any(band in ("A", "a") for band in image.getbands()) or (
        "transparency" in image.info
    )
    if image.mode == "I" or image.mode.startswith("I;16"):
        # A 16-bit grey image: map_server exports 8-bit levels (Magick::CharPixel), a 16-bit
        # level v as the nearest, v / 257 rounded.
        levels = np.clip(np.asarray(image).astype(np.int64), 0, 65535)
        grey = ((levels + 128) // 257).astype(np.uint8)
        key = image.info.get("transparency")
        alpha = np.where(levels == key, 0, 255).astype(np.uint8) if isinstance(key, int) else None
        return grey, alpha
    rgba = np.asarray(image.convert("RGBA"))
    # loadMapFromFile makes the image grey with `type(GrayscaleType)` of GraphicsMagick (Nav2's
    # package.xml depends on graphicsmagick), whose GRAYColorspace is Rec. 601 luma,
    # 0.299 R + 0.587 G + 0.114 B rounded to the nearest level (magick/colorspace.c,
    # RGBTransformImage). Pillow's convert("L") has the same weights in fixed point; this says
    # them. A grey image's levels are their own.
    red, green, blue = (rgba[..., band].astype(np.float64) for band in range(3))
    grey = np.floor(0.299 * red + 0.587 * green + 0.114 * blue + 0.5)
    return np.clip(grey, 0, 255).astype(np.uint8), rgba[..., 3].copy() if has_alpha else None


def _occupancy(grey: Bytes, alpha: Bytes | None, fields: _MapFile) -> Cells:
    """The cells of the image's pixels, image rows first, as loadMapFromFile computes them."""
    if fields.mode == "raw":
        # Each grey level is the cell's value; what is not 0 to 100 is unknown. Neither negate
        # nor alpha applies.
        return np.where(grey <= OCCUPIED, grey, UNKNOWN).astype(np.int8)
    # map_server computes in float (Eigen float matrices): the doubles it reads for the
    # thresholds become floats where they meet the pixels.
    lightness = grey.astype(np.float32) / np.float32(255.0)
    # Without negate a dark pixel is likely occupied: the occupancy is 1 - lightness.
    occupancy = lightness if fields.negate else np.float32(1.0) - lightness
    occupied_at, free_at = np.float32(fields.occupied_thresh), np.float32(fields.free_thresh)
    cells = np.full(grey.shape, UNKNOWN, dtype=np.int8)
    cells[occupancy >= occupied_at] = OCCUPIED
    cells[occupancy <= free_at] = FREE
    if fields.mode == "scale":
        # Between the thresholds, the occupancy scaled from 0 at free_thresh to 100 at
        # occupied_thresh, rounded half away from zero (Eigen's round, std::round).
        between = (occupancy > free_at) & (occupancy < occupied_at)
        span = np.float32(fields.occupied_thresh - fields.free_thresh)
        scaled = (occupancy[between] - free_at) / span * np.float32(100.0)
        cells[between] = np.floor(scaled.astype(np.float64) + 0.5).astype(np.int8)
    if alpha is not None:
        # A pixel less than opaque is unknown, in trinary and scale modes alike.
        cells[alpha < 255] = UNKNOWN
    return cells
