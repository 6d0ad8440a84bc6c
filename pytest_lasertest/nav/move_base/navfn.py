"""The global planner: a grid planner with the semantics of ROS navfn (NavfnROS).

The costmap's costs become navfn's: a cell costing c < 253 costs neutral_cost + cost_factor c
to enter (truncated to an integer and capped at 253, as navfn stores it in a byte), an unknown
cell (255) costs 253 with `allow_unknown`, and inscribed (253), lethal (254) and, without
`allow_unknown`, unknown cells cannot be entered. As NavfnROS does, the potential spreads from
the robot's cell (whatever it costs: NavfnROS clears the robot's cell first), the plan runs
back down it from the goal, and a goal no path reaches is
replaced by the reached cell nearest it within `default_tolerance`.

Deviations from navfn, all deliberate:

- navfn interpolates each cell's potential from its 4 neighbours (an approximation of the
  eikonal equation) and follows the potential's gradient to a smooth path. Here the potential is
  the exact 8-connected cheapest-path cost, entering a cell costing its navfn cost times the
  step's length (1, or sqrt(2) diagonally), so the plan is an optimal chain of cells in
  0, 45 and 90 degree segments over the same costs.
- A diagonal step may not cut the corner of a cell that cannot be entered: the plan never
  touches an obstacle, and the cells reached are those navfn's 4-neighbour spreading reaches.
- navfn blocks the map's outermost ring of cells and stops spreading once the goal is reached;
  here every cell of the grid counts, and the potential covers the whole grid.
- The tolerance window is exactly +-floor(default_tolerance / resolution) cells about the goal
  along each axis; NavfnROS steps through it in floating point and may miss its last row or
  column. As in NavfnROS, the nearest reached cell wins, the first in [y, x] order among equals.

The potential is computed in integers (navfn costs times SCALE, diagonal steps rounded), so it is
exact and deterministic: each cell's cheapest-path cost, found by Dijkstra's algorithm, compiled
in kernels.py. The grid is stored flat, each row followed by blocked cells and the grid framed by
blocked rows, so that every step off the grid enters a cell that cannot be entered.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TypeVar

import numpy as np
import numpy.typing as npt

from pytest_lasertest.model.geometry import FloatArray, IntArray
from pytest_lasertest.nav.move_base.cost_values import INSCRIBED, UNKNOWN
from pytest_lasertest.nav.move_base.costmap import Costmap
from pytest_lasertest.nav.move_base.kernels import cheapest_costs, descend

SCALE = 1000  # potential units per navfn cost unit and cell stepped
UNREACHABLE = int(np.iinfo(np.intp).max)  # the potential of a cell no path reaches
_Bytes = npt.NDArray[np.uint8]
_Cell = TypeVar("_Cell", bound=np.generic)


@dataclass(frozen=True)
class NavfnSettings:
    """NavfnROS's parameters, with its names; defaults as the Husky's planner.yaml sets them."""

    allow_unknown: bool = True  # husky_navigation planner.yaml
    default_tolerance: float = 0.1  # m, husky_navigation planner.yaml
    neutral_cost: int = 50  # navfn's COST_NEUTRAL
    cost_factor: float = 0.8  # navfn's COST_FACTOR

    def __post_init__(self) -> None:
        # A free step must cost something, or the potential would not fall along the plan.
        if self.neutral_cost < 1 or self.cost_factor < 0.0 or self.default_tolerance < 0.0:
            raise ValueError(f"NavfnSettings need neutral_cost >= 1 and no negative value: {self}")


def _navfn_costs(costs: npt.ArrayLike, settings: NavfnSettings) -> _Bytes:
    """navfn's cost (R, C) of entering each cell of the costmap `costs` (R, C); 0: never."""
    codes = np.asarray(costs)
    if codes.ndim != 2 or codes.size == 0:
        raise ValueError(f"the costmap must be a non-empty 2-D grid, not of shape {codes.shape}")
    if codes.dtype != np.uint8:
        raise ValueError(f"the costmap must hold costmap_2d's uint8 costs, not {codes.dtype}")
    every = np.arange(UNKNOWN + 1)
    navfn = np.minimum(np.floor(settings.neutral_cost + settings.cost_factor * every), INSCRIBED)
    navfn[INSCRIBED:] = 0
    if settings.allow_unknown:
        navfn[UNKNOWN] = INSCRIBED
    entered: _Bytes = navfn.astype(np.uint8)[codes]
    return entered


@dataclass(frozen=True)
class _Layout:
    """The grid stored flat: each row followed by blocked cells, framed by blocked rows."""

    rows: int
    cols: int
    width: int  # cells per stored row, the row's and then blocked ones
    costs: _Bytes  # (B,) navfn costs in the flat layout, 0 where no path may enter

    @classmethod
    def of(cls, costs: npt.ArrayLike, settings: NavfnSettings) -> _Layout:
        """The layout of navfn's costs for the costmap `costs` (R, C)."""
        navfn = _navfn_costs(costs, settings)
        rows, cols = navfn.shape
        # At least 3 cells a row, so that the steps 1, width - 1, width and width + 1 differ.
        width = max(cols + 1, 3)
        layout = cls(rows, cols, width, np.zeros((rows + 2) * width, dtype=np.uint8))
        layout.grid(layout.costs)[:] = navfn
        return layout

    def index(self, cell: tuple[int, int]) -> int:
        """The flat index of cell [x, y]."""
        return (cell[1] + 1) * self.width + cell[0]

    def grid(self, buffer: npt.NDArray[_Cell]) -> npt.NDArray[_Cell]:
        """A view of the grid's cells (R, C) in the flat `buffer` (B,)."""
        inner = buffer[self.width : self.width * (self.rows + 1)]
        return inner.reshape(self.rows, self.width)[:, : self.cols]

    def check(self, cell: tuple[int, int], name: str) -> None:
        x, y = cell
        if not (0 <= x < self.cols and 0 <= y < self.rows):
            raise ValueError(
                f"the {name} cell [x, y] = {list(cell)} lies outside the costmap of "
                f"{self.cols} x {self.rows} cells"
            )


def _step_costs(layout: _Layout) -> tuple[IntArray, IntArray, int]:
    """The cost (256,) of entering a cell of each navfn cost along an axis and diagonally, and
    the blocked cost: it exceeds every real path's, so any sum holding it marks no path."""
    every = np.arange(INSCRIBED + 1)  # lookup tables keep big temporaries few
    diagonal_of = np.rint(every * SCALE * math.sqrt(2.0)).astype(np.intp)
    blocked = (int(np.count_nonzero(layout.costs)) + 1) * int(diagonal_of[-1]) + 1
    axis_of = every * SCALE
    axis_of[0] = diagonal_of[0] = blocked
    if (layout.costs.size + 2) * blocked >= np.iinfo(np.intp).max:
        raise ValueError(f"a costmap of {layout.cols} x {layout.rows} cells is too large to plan")
    return axis_of, diagonal_of, blocked


def _flat_potential(
    layout: _Layout, steps: tuple[IntArray, IntArray, int], start: int, goal: int = -1
) -> IntArray:
    """The potential (B,) from flat cell `start`, by the compiled Dijkstra over the step costs
    `_step_costs` gives: exact for every cell if `goal` is -1, else for the cells no dearer
    than flat cell `goal` (the others no cheaper than it)."""
    axis_of, diagonal_of, blocked = steps
    potential = np.empty(layout.costs.size, dtype=np.intp)
    cheapest_costs(
        layout.costs, layout.width, axis_of, diagonal_of, blocked, start, goal, potential
    )
    return potential


def potential(costs: npt.ArrayLike, start: tuple[int, int], settings: NavfnSettings) -> IntArray:
    """The cost (R, C) of the cheapest path from cell `start` [x, y] to each cell of `costs` (R, C).

    In navfn cost units per cell stepped, times SCALE; UNREACHABLE where no path leads. The
    start's own cost is never paid.
    """
    layout = _Layout.of(costs, settings)
    layout.check(start, "start")
    steps = _step_costs(layout)
    flat, blocked = _flat_potential(layout, steps, layout.index(start)), steps[2]
    grid = layout.grid(flat)
    result: IntArray = np.where(grid < blocked, grid, UNREACHABLE)
    return result


def _nearest_reached(
    potential: IntArray, blocked: int, goal: tuple[int, int], reach: int
) -> tuple[int, int] | None:
    """The cell [x, y] nearest `goal` whose potential (R, C) is real, at most `reach` cells off
    along each axis, as NavfnROS's tolerance search picks it; None if there is none."""
    x0, y0 = max(goal[0] - reach, 0), max(goal[1] - reach, 0)
    window = potential[y0 : goal[1] + reach + 1, x0 : goal[0] + reach + 1]
    ys, xs = np.indices(window.shape)
    offsets = (xs + x0 - goal[0]) ** 2 + (ys + y0 - goal[1]) ** 2
    squared = np.where(window < blocked, offsets, UNREACHABLE)
    best = int(np.argmin(squared))  # the first in [y, x] order among equals
    if squared.flat[best] == UNREACHABLE:
        return None
    y, x = divmod(best, window.shape[1])
    return x + x0, y + y0


def _descend(
    layout: _Layout, steps: tuple[IntArray, IntArray, int], potential: IntArray, end: int
) -> IntArray:
    """The cells (K, 2) [x, y] of a cheapest path from the potential's zero to flat cell `end`
    (compiled: kernels.descend). Off the grid lie the frame's blocked cells (before the first
    cell, the frame's last cell by negative index): valid to read, and never the cheapest."""
    axis_of, diagonal_of, _ = steps
    flat = descend(layout.costs, layout.width, axis_of, diagonal_of, potential, end)
    return np.column_stack((flat % layout.width, flat // layout.width - 1))


def plan_path(
    costs: npt.ArrayLike,
    start: tuple[int, int],
    goal: tuple[int, int],
    settings: NavfnSettings,
    resolution: float,
) -> IntArray | None:
    """The cells (K, 2) [x, y] of a cheapest path over `costs` (R, C) from `start` to `goal`.

    If no path reaches the goal, the path ends at the reached cell nearest it within
    `default_tolerance`; None if there is none.
    `resolution` is in m per cell.
    """
    layout = _Layout.of(costs, settings)
    layout.check(start, "start")
    layout.check(goal, "goal")
    if not resolution > 0.0:
        raise ValueError(f"the resolution must be positive, not {resolution} m per cell")
    # Where the goal is reached, the search stops there: it is the nearest reached cell, and
    # its descent reads only cells cheaper than it. Where not, the search covers every cell.
    steps = _step_costs(layout)
    flat = _flat_potential(layout, steps, layout.index(start), layout.index(goal))
    blocked = steps[2]
    reach = math.floor(settings.default_tolerance / resolution + 1e-9)
    end = _nearest_reached(layout.grid(flat), blocked, goal, reach)
    if end is None:
        return None
    return _descend(layout, steps, flat, layout.index(end))


def windowed_plan(
    costmap: Costmap,
    start: tuple[float, float],
    goal: tuple[float, float],
    settings: NavfnSettings,
    margin: float,
) -> FloatArray | None:
    """navfn's plan (K, 2) m from `start` to `goal` (m) on `costmap`, searched in the rectangle
    spanning both widened by `margin` m, the goal appended; None if there is none, or if
    either end lies off the costmap."""
    corners = np.array([start, goal])
    low_x, low_y, _ = costmap.cell_of(corners.min(axis=0)[np.newaxis] - margin)
    high_x, high_y, _ = costmap.cell_of(corners.max(axis=0)[np.newaxis] + margin)
    cells = costmap.settings.cells
    columns = slice(max(int(low_x[0]), 0), min(int(high_x[0]) + 1, cells))
    rows = slice(max(int(low_y[0]), 0), min(int(high_y[0]) + 1, cells))
    ends_x, ends_y, inside = costmap.cell_of(corners)
    if not inside.all():
        return None
    first = (int(ends_x[0]) - columns.start, int(ends_y[0]) - rows.start)
    last = (int(ends_x[1]) - columns.start, int(ends_y[1]) - rows.start)
    resolution = costmap.settings.resolution
    path = plan_path(costmap.costs(columns, rows), first, last, settings, resolution)
    if path is None:
        return None
    points = costmap.centres(path[:, 0] + columns.start, path[:, 1] + rows.start)
    return np.vstack([points, [goal]])
