"""The top-down picture of a failing item, drawn like the paper's RViz figures.

Only matplotlib's object API on an Agg canvas: no pyplot, so no global figure state, and no
display is needed. This module is imported only when a failure is written.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Any, TypeAlias

import numpy as np
import numpy.typing as npt
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.colors import to_rgba
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.offsetbox import AnchoredOffsetbox, AuxTransformBox, TextArea, VPacker
from matplotlib.patches import Circle, Patch, Polygon, Rectangle
from matplotlib.ticker import MultipleLocator

from pytest_lasertest.artifacts.files import write_atomically
from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.obstacles import Box, Obstacle
from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.model.route import place

BoolArray = npt.NDArray[np.bool_]
Pose: TypeAlias = tuple[float, float, float]  # m, m, rad

BASELINE_COLOUR = "#1f77b4"  # blue
CANDIDATE_COLOUR = "#d62728"  # red
OBSTACLE_COLOUR = "#4d4d4d"  # dark grey
WALL_COLOUR = "#7a7a7a"  # dark grey, lighter than the obstacle's, so one by a wall stands out
GOAL_COLOUR = "#2ca02c"  # green
GROUND_COLOUR = "#f2f2f2"  # light grey
RING_COLOUR = "#ff7f0e"  # orange: neither robot's colour, nor a wall's grey
# RViz's costmap colour scheme: lethal cells purple, inscribed cells cyan.
LETHAL_COLOUR = (0.58, 0.0, 0.83, 0.85)  # RGBA
INSCRIBED_COLOUR = (0.0, 0.74, 0.83, 0.45)  # RGBA
LETHAL_VALUE, INSCRIBED_VALUE = 100, 99  # as costmap_2d publishes them
# An obstacle thinner than this is ringed: at some 60 pixels a metre, a 5 cm pole is three
# pixels across, under the beams and a footprint's edge.
RING_BELOW = 0.3  # m, the obstacle's bounding radius
RING_SIZE = 36.0  # points across, whatever the view's scale: half an inch at the picture's size
SIZE = (10.0, 7.0)  # inches; 1000 x 700 pixels at DPI
DPI = 100  # pixels per inch
PADDING = 1.0  # m, around everything the view must hold
# Walls within this of the paths, the obstacle and the markers widen the view as far as they
# reach into it; the rest of a building is cut off at the view's edge.
WALL_REACH = 2.0  # m


@dataclass(frozen=True)
class BeamFan:
    """One scanner's beams at one instant: where each starts and ends, which read the obstacle."""

    label: str  # e.g. "baseline sick_lms111: 32 beams, 10 m"
    origins: FloatArray  # (N, 2) m, world frame
    ends: FloatArray  # (N, 2) m, where each beam stops: its hit on the obstacle, or range_max
    hits: BoolArray  # (N,) whether the beam reads the obstacle

    def __post_init__(self) -> None:
        shapes = (np.shape(self.origins), np.shape(self.ends), np.shape(self.hits))
        count = shapes[2][0] if len(shapes[2]) == 1 else -1
        if shapes != ((count, 2), (count, 2), (count,)):
            raise ValueError(
                f"a beam fan needs origins (N, 2), ends (N, 2) and hits (N,), not {shapes}"
            )


@dataclass(frozen=True)
class FailureFigure:
    """Everything the picture of one failure shows, in the world frame."""

    title: str  # one line, e.g. the item id and the oracle
    obstacle: Obstacle | None  # None for a failure in the empty world
    baseline_path: FloatArray  # (T, 2) m
    candidate_path: FloatArray  # (T, 2) m
    footprint: FloatArray  # (V, 2) m, robot footprint polygon in the base frame
    candidate_pose: Pose  # m, m, rad: the candidate at its failure
    baseline_pose: Pose  # m, m, rad: the baseline at the same instant
    beams: tuple[BeamFan, BeamFan]  # baseline's, candidate's, both at that instant
    failure: tuple[float, float]  # m: the collision point or where it got stuck
    failure_label: str  # e.g. "collided at t = 11.82 s" / "stuck at t = 21.22 s"
    goal: tuple[float, float]  # m
    start: tuple[float, float]  # m
    walls: tuple[Box, ...] = ()  # the world's; none in an empty world
    # The costmap the candidate's controller published when it failed, if it publishes one.
    costmap: OccupancyGrid | None = None


def draw_failure(figure: FailureFigure, path: Path) -> Path:
    """Write the figure as a PNG at `path`, atomically; returns `path`."""
    picture = build_figure(figure)

    def write(handle: IO[bytes]) -> None:
        picture.savefig(handle, format="png", dpi=DPI)

    return write_atomically(path, write)


def build_figure(figure: FailureFigure) -> Figure:
    """The picture as a matplotlib Figure on its own Agg canvas, not yet written anywhere."""
    picture = Figure(figsize=SIZE, dpi=DPI, layout="constrained")
    # The canvas attaches itself: the figure renders with Agg whatever backend pyplot may use.
    FigureCanvasAgg(picture)
    axes = picture.add_subplot()
    low, high, step = _frame(axes, figure)
    walls = [_draw_walls(axes, figure.walls)] if figure.walls else []
    costmap = [] if figure.costmap is None else _draw_costmap(axes, figure.costmap, low, high)
    obstacles = [] if figure.obstacle is None else _draw_obstacle(axes, figure.obstacle)
    beams, paths, footprints = [], [], []
    for (name, colour, path, pose), fan in zip(_robots(figure), figure.beams, strict=True):
        beams.append(_draw_beams(axes, fan, colour))
        paths.extend(
            axes.plot(path[:, 0], path[:, 1], color=colour, lw=2.0, label=f"{name} path", zorder=4)
        )
        footprints.append(_draw_robot(axes, figure.footprint, pose, colour, f"{name} footprint"))
    start, goal, failure = _draw_markers(axes, figure)
    _add_scale_bar(axes, step)
    # Filled column by column: the two long beam labels share the first, so three columns fit.
    handles: list[Artist] = [
        *beams,
        *obstacles,
        *walls,
        start,
        *paths,
        *footprints,
        goal,
        failure,
        *costmap,
    ]
    # Below the axes, so it never hides the obstacle or a path and leaves the view its width.
    picture.legend(handles=handles, loc="outside lower center", ncols=3, fontsize=8)
    picture.suptitle(_literal(figure.title), fontsize=10)
    _fit_view(picture, axes, low, high)
    return picture


def _literal(text: str) -> str:
    """`text` (holding names a user wrote) shown as written: matplotlib reads `$...$` as
    mathematics, and a name such as `$\\frac$` would stop the picture being drawn at all."""
    return text.replace("$", r"\$")


def _robots(figure: FailureFigure) -> tuple[tuple[str, str, FloatArray, Pose], ...]:
    """Name, colour, path and pose at the failure of the baseline and the candidate."""
    return (
        ("baseline", BASELINE_COLOUR, figure.baseline_path, figure.baseline_pose),
        ("candidate", CANDIDATE_COLOUR, figure.candidate_path, figure.candidate_pose),
    )


def _frame(axes: Axes, figure: FailureFigure) -> tuple[FloatArray, FloatArray, float]:
    """Set the ground, the grid and a first view; returns the view's lower left and upper right
    corners (m), the box round the paths, the obstacle and the markers, padded, and widened to
    the walls within WALL_REACH of them, and the grid step (m)."""
    points = np.vstack(
        [
            figure.baseline_path,
            figure.candidate_path,
            *([] if figure.obstacle is None else [_outline(figure.obstacle)]),
            [figure.goal, figure.start, figure.failure],
        ]
    )
    action_low, action_high = points.min(axis=0), points.max(axis=0)
    low, high = action_low - PADDING, action_high + PADDING
    near = _walls_within(figure.walls, action_low - WALL_REACH, action_high + WALL_REACH)
    if len(near):
        low, high = np.minimum(low, near.min(axis=0)), np.maximum(high, near.max(axis=0))
    axes.set_xlim(low[0], high[0])
    axes.set_ylim(low[1], high[1])
    step = _nice_length(float(max(high - low)))
    for axis in (axes.xaxis, axes.yaxis):
        axis.set_major_locator(MultipleLocator(step))
    axes.set_facecolor(GROUND_COLOUR)
    axes.set_axisbelow(True)
    axes.grid(True, color="#c8c8c8", linewidth=0.6)
    axes.set_xlabel("x (m)")
    axes.set_ylabel("y (m)")
    return low, high, step


def _fit_view(picture: Figure, axes: Axes, low: FloatArray, high: FloatArray) -> None:
    """Lay the figure out and freeze it, with the view widened about its centre to the shape of
    the axes, so that a metre is as long across as up."""
    # Matplotlib's own equal aspect either shrinks the axes or, re-applied on every layout
    # pass, widens the view more than it needs; fixed limits fitted to the laid out axes do
    # neither. Twice, as the first fit's tick labels can be wider than the first layout's.
    engine = picture.get_layout_engine()
    for _ in range(2):
        if engine is not None:
            engine.execute(picture)
        width, height = axes.get_window_extent().size  # pixels
        centre, half = (low + high) / 2.0, (high - low) / 2.0
        per_pixel = max(half[0] / width, half[1] / height)  # m
        axes.set_xlim(centre[0] - per_pixel * width, centre[0] + per_pixel * width)
        axes.set_ylim(centre[1] - per_pixel * height, centre[1] + per_pixel * height)
    picture.set_layout_engine("none")


def _nice_length(span: float) -> float:
    """The longest of 1, 2 or 5 times a power of ten that fits at least five times into span."""
    target = span / 5.0
    power = 10.0 ** math.floor(math.log10(target))
    return max(factor * power for factor in (1.0, 2.0, 5.0) if factor * power <= target)


def _outline(obstacle: Obstacle) -> FloatArray:
    """Points whose bounding box is the obstacle's footprint's, shape (4, 2) m."""
    if isinstance(obstacle, Box):
        return np.array(obstacle.corners())
    offsets = obstacle.radius * np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]])
    outline: FloatArray = offsets + np.array([obstacle.x, obstacle.y])
    return outline


def _walls_within(walls: Sequence[Box], low: FloatArray, high: FloatArray) -> FloatArray:
    """The corners of the walls' footprints cut to the box from `low` to `high` (m), shape
    (P, 2) m: what of them lies inside it."""
    cut: list[tuple[float, float]] = []
    for wall in walls:
        reach = wall.bounding_radius
        if np.all(low - reach <= (wall.x, wall.y)) and np.all((wall.x, wall.y) <= high + reach):
            cut.extend(_clipped(list(wall.corners()), low, high))
    return np.array(cut, dtype=np.float64).reshape(-1, 2)


def _clipped(
    polygon: list[tuple[float, float]], low: FloatArray, high: FloatArray
) -> list[tuple[float, float]]:
    """The part of a convex polygon inside the box from `low` to `high` (m), its corners in
    order; none when it lies outside (Sutherland and Hodgman's clipping, one side at a time)."""
    for axis in (0, 1):
        for bound, sign in ((float(low[axis]), -1.0), (float(high[axis]), 1.0)):
            kept: list[tuple[float, float]] = []
            for index, point in enumerate(polygon):
                previous = polygon[index - 1]
                inside = sign * (point[axis] - bound) <= 0.0
                was_inside = sign * (previous[axis] - bound) <= 0.0
                if inside != was_inside:
                    fraction = (bound - previous[axis]) / (point[axis] - previous[axis])
                    kept.append(
                        (
                            previous[0] + fraction * (point[0] - previous[0]),
                            previous[1] + fraction * (point[1] - previous[1]),
                        )
                    )
                if inside:
                    kept.append(point)
            polygon = kept
    return polygon


def _draw_walls(axes: Axes, walls: Sequence[Box]) -> PolyCollection:
    """The walls' footprints, filled, beneath everything else; the view cuts off what lies
    outside it."""
    # One collection: a map's walls are hundreds of boxes, and the legend names them once.
    collection = PolyCollection(
        [wall.corners() for wall in walls],
        facecolors=WALL_COLOUR,
        edgecolors="none",
        label="walls",
        zorder=2,
    )
    # A building must not widen the view: `_frame` takes in only the walls near the action.
    axes.add_collection(collection, autolim=False)
    return collection


def _draw_costmap(
    axes: Axes, grid: OccupancyGrid, low: FloatArray, high: FloatArray
) -> list[Artist]:
    """The costmap's lethal and inscribed cells under everything else, over the view and as
    far again each way (the view widens to the axes' shape); returns the legend's patches."""
    span = high - low
    first = np.floor((low - span - np.array(grid.origin)) / grid.resolution).astype(int)
    last = np.ceil((high + span - np.array(grid.origin)) / grid.resolution).astype(int)
    first = np.clip(first, 0, [grid.width, grid.height])
    last = np.clip(last, first, [grid.width, grid.height])
    cells = grid.data[first[1] : last[1], first[0] : last[0]]
    image = np.zeros((*cells.shape, 4))
    image[cells == INSCRIBED_VALUE] = INSCRIBED_COLOUR
    image[cells == LETHAL_VALUE] = LETHAL_COLOUR
    corner = np.array(grid.origin) + first * grid.resolution
    far = np.array(grid.origin) + last * grid.resolution
    extent = (corner[0], far[0], corner[1], far[1])
    # Row 0 is the grid's bottom row; "auto" leaves the view's own fitting alone.
    axes.imshow(image, origin="lower", extent=extent, interpolation="nearest", aspect="auto")
    return [
        Patch(facecolor=LETHAL_COLOUR, label="candidate's costmap: lethal"),
        Patch(facecolor=INSCRIBED_COLOUR, label="candidate's costmap: inscribed"),
    ]


def _draw_obstacle(axes: Axes, obstacle: Obstacle) -> list[Artist]:
    """The obstacle's footprint, filled: a box turned by its yaw or a circle; a thin one ringed,
    so that it stands out at a glance. Returns what the legend names."""
    # Above the footprints: a 5 cm pole would hide under the robot that touches it.
    style = {"facecolor": OBSTACLE_COLOUR, "edgecolor": "black", "label": "obstacle", "zorder": 5.5}
    if isinstance(obstacle, Box):
        shape: Patch = Polygon(_outline(obstacle), closed=True, **style)
    else:
        shape = Circle((obstacle.x, obstacle.y), obstacle.radius, **style)
    drawn: list[Artist] = [axes.add_patch(shape)]
    if obstacle.bounding_radius < RING_BELOW:
        ring: dict[str, Any] = {"marker": "o", "fillstyle": "none", "color": RING_COLOUR}
        ring |= {"markeredgewidth": 2.5, "linestyle": "none"}
        # A marker keeps its size in points however far the view reaches.
        axes.plot([obstacle.x], [obstacle.y], markersize=RING_SIZE, zorder=6, **ring)
        # The legend shows a ring of a legend entry's size.
        label = "the obstacle, ringed: it is thin"
        drawn.append(Line2D([], [], markersize=10.0, label=label, **ring))
    return drawn


def _draw_beams(axes: Axes, fan: BeamFan, colour: str) -> LineCollection:
    """Each beam as a line from its origin to its end, bold if it reads the obstacle; returns the
    bold ones."""
    segments = np.stack([fan.origins, fan.ends], axis=1)
    misses = LineCollection(list(segments[~fan.hits]), colors=colour, linewidths=0.5, alpha=0.3)
    hits = LineCollection(list(segments[fan.hits]), colors=colour, linewidths=1.4, alpha=0.9)
    hits.set_label(f"{_literal(fan.label)} ({int(np.count_nonzero(fan.hits))} on the obstacle)")
    for beams in (misses, hits):
        beams.set_zorder(3)
        # Beams run to range_max: they must not widen the view.
        axes.add_collection(beams, autolim=False)
    return hits


def _draw_robot(axes: Axes, footprint: FloatArray, pose: Pose, colour: str, label: str) -> Patch:
    """A robot's footprint at `pose`, with a line from its centre showing which way it faces."""
    outline = place(footprint, np.array(pose))
    patch = axes.add_patch(
        Polygon(outline, facecolor=to_rgba(colour, 0.35), edgecolor=colour, label=label, zorder=5)
    )
    x, y, yaw = pose
    reach = float(np.max(np.hypot(footprint[:, 0], footprint[:, 1])))
    axes.plot(
        [x, x + reach * math.cos(yaw)], [y, y + reach * math.sin(yaw)], color=colour, zorder=5
    )
    return patch


def _draw_markers(axes: Axes, figure: FailureFigure) -> list[Line2D]:
    """Start, goal, and the failure point with its label; returns their markers in that order."""
    marks = (
        (figure.start, "o", "white", "start"),
        (figure.goal, "*", GOAL_COLOUR, "goal"),
        (figure.failure, "X", "black", figure.failure_label),
    )
    style: dict[str, Any] = {"markersize": 12, "markeredgecolor": "black", "linestyle": "none"}
    markers = [
        axes.plot([x], [y], marker=marker, mfc=colour, label=label, zorder=6, **style)[0]
        for (x, y), marker, colour, label in marks
    ]
    axes.annotate(
        figure.failure_label,
        figure.failure,
        xytext=(10, 10),
        textcoords="offset points",
        fontsize=9,
        bbox={"boxstyle": "round", "facecolor": "white", "alpha": 0.9},
        zorder=7,
    )
    return markers


def _add_scale_bar(axes: Axes, length: float) -> None:
    """A bar `length` metres long in the lower right corner, labelled."""
    # The box scales its child by the data transform, so the bar stays true as the view changes.
    bar = AuxTransformBox(axes.transData)
    bar.add_artist(Rectangle((0.0, 0.0), length, 0.0, edgecolor="black", linewidth=2.0))
    label = TextArea(f"{length:g} m", textprops={"fontsize": 9})
    packed = VPacker(children=[bar, label], align="center", pad=0.0, sep=4.0)
    axes.add_artist(AnchoredOffsetbox(loc="lower right", child=packed, pad=0.4, borderpad=0.6))
