"""A failure's picture over the candidate's costmap: the costmap its controller published when
it failed, kept by driving it again; the paper's phantom arc, 5 m ahead of the 5 m scanner."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from matplotlib.image import imread

from pytest_lasertest.artifacts.evidence import drive_figure, driven_again
from pytest_lasertest.artifacts.picture import LETHAL_COLOUR, build_figure, draw_failure
from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.nav.move_base import MoveBase
from pytest_lasertest.nav.move_base.publisher import COST_TRANSLATION
from pytest_lasertest.nav.protocol import LaserScan, Odometry
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.search.drives import drive
from pytest_lasertest.sim.scenario import run_scenario
from tests.artifacts.test_picture import BOX, failure_figure
from tests.helpers import EXAMPLES

PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
DISTANCE = next(pair for pair in PAPER.pairs if pair.name == "distance")
MOVE_BASE = ControllerChoice("move_base", "the default", MoveBase)


def lethal_pixels(image: np.ndarray) -> np.ndarray:
    """Where the picture shows a lethal cell: rows and columns of pixels near its colour."""
    # Drawn 85 % opaque over the light grey ground.
    ground = np.array([0.949, 0.949, 0.949])
    alpha = LETHAL_COLOUR[3]
    colour = alpha * np.array(LETHAL_COLOUR[:3]) + (1.0 - alpha) * ground
    return np.argwhere(np.abs(image[:, :, :3] - colour).max(axis=2) < 0.05)


def test_a_published_costmap_s_lethal_cells_are_drawn_where_they_lie(tmp_path: Path) -> None:
    # One lethal cell, 10 cm across, at (3.0, -2.0) m.
    data = np.zeros((100, 100), dtype=np.int8)
    data[50, 80] = 100
    grid = OccupancyGrid(0.1, (-5.0, -7.0), data)
    figure = dataclasses.replace(failure_figure(BOX), costmap=grid)
    picture = build_figure(figure)
    picture.canvas.draw()
    x, y = picture.axes[0].transData.transform((3.05, -1.95))
    image = imread(draw_failure(figure, tmp_path / "item.png"))
    rows, columns = lethal_pixels(image).T
    # Inside the axes (the legend's patch is of the same colour). Display coordinates count up
    # from the bottom, image rows down from the top.
    box = picture.axes[0].get_window_extent()
    inside = (columns > box.x0) & (columns < box.x1) & (700 - rows > box.y0)
    assert np.count_nonzero(inside) > 4
    assert abs(np.median(columns[inside]) - x) < 3
    assert abs(np.median(700 - rows[inside]) - y) < 3
    labels = [text.get_text() for text in picture.legends[0].get_texts()]
    assert "candidate's costmap: lethal" in labels


def test_the_distance_pairs_candidate_is_stuck_before_its_phantom_arc_5_m_ahead() -> None:
    run = drive(PAPER, DISTANCE.candidate.profile, (), 1, MoveBase)
    runs, note = driven_again((None, run), MOVE_BASE)
    again = runs["candidate"]
    # The same run, now with the costmap move_base published when it was judged stuck.
    assert (again.digest(), note) == (run.digest(), "")
    assert not again.passed
    assert again.recording is not None
    grid = again.recording.last_costmap
    assert grid is not None
    lethal = np.argwhere(grid.data == 100)[:, ::-1] * grid.resolution + np.array(grid.origin)
    reach = np.hypot(*(lethal - PAPER.world.start.x).T)
    # The no-return readings of the 5 m scanner, marked 5 m from where it stood: an arc.
    arc = lethal[np.abs(reach - 5.0) < 0.5]
    assert len(arc) > 100
    assert np.ptp(arc[:, 1]) > 4.0  # m across the route
    figure = drive_figure("distance", PAPER, DISTANCE, (run, again), None)
    assert figure.costmap is grid


class Broken(MoveBase):
    """move_base whose published_costmap answers something that is not a costmap."""

    def published_costmap(self) -> OccupancyGrid | None:  # type: ignore[override]
        return "a costmap"  # type: ignore[return-value]


def test_a_controller_that_publishes_no_costmap_leaves_the_picture_without_one() -> None:
    run = drive(PAPER, DISTANCE.candidate.profile, (), 1, MoveBase)
    broken = ControllerChoice("broken", "a test", Broken)
    runs, note = driven_again((None, run), broken)
    assert runs == {"candidate": run}
    assert note == (
        " (not recorded: published_costmap returned 'a costmap', not an OccupancyGrid or None)"
    )


class Blind:
    """A controller without a published costmap: it stands still."""

    def observe(self, scan: LaserScan, odometry: Odometry, time: float) -> tuple[float, float]:
        return (0.0, 0.0)


def test_a_run_of_a_controller_without_a_costmap_keeps_none() -> None:
    run = drive(PAPER, DISTANCE.candidate.profile, (), 1, lambda robot, route: Blind())
    recording = dataclasses.replace(run.scenario, record=True)
    kept = run_scenario(recording, lambda robot, route: Blind()).recording
    assert kept is not None
    assert (kept.costmaps, kept.plans) == ((), ())
    # Its scans are kept all the same: a failure's rosbag2 holds them.
    assert len(kept.scans) == run.scans


@pytest.mark.parametrize("cost", [0, 1, 126, 252, 253, 254, 255])
def test_costs_are_published_as_costmap_2d_translates_them(cost: int) -> None:
    expected = {0: 0, 253: 99, 254: 100, 255: -1}.get(cost, 1 + (97 * (cost - 1)) // 251)
    assert COST_TRANSLATION[cost] == expected


class NotAPlan(MoveBase):
    """move_base whose published_plan answers points that are not finite."""

    def published_plan(self) -> FloatArray:
        return np.array([[0.0, float("nan")]])


class Raising(MoveBase):
    """move_base whose published_costmap raises."""

    def published_costmap(self) -> OccupancyGrid | None:
        raise KeyError("global_costmap")


@pytest.mark.parametrize(
    ("factory", "problem"),
    [
        (NotAPlan, "published_plan returned array([[ 0., nan]]), not finite points (N, 2) in m"),
        (Raising, "published_costmap raised KeyError: 'global_costmap'"),
    ],
    ids=["a plan of NaN", "a costmap that raises"],
)
def test_a_controller_that_breaks_on_being_recorded_is_named_and_its_runs_kept(
    factory: type[MoveBase], problem: str
) -> None:
    run = drive(PAPER, DISTANCE.candidate.profile, (), 1, MoveBase)
    runs, note = driven_again((None, run), ControllerChoice("broken", "a test", factory))
    assert runs == {"candidate": run}
    assert note.startswith(f" (not recorded: {problem}")
