"""The top-down PNG of a failing item: its size, colours, view and legend, written atomically."""

from __future__ import annotations

import dataclasses
import math
import os
import struct
from pathlib import Path

import numpy as np
import pytest
from matplotlib.collections import PolyCollection
from matplotlib.colors import to_rgb
from matplotlib.figure import Figure
from matplotlib.image import imread

from pytest_lasertest.artifacts.picture import (
    BASELINE_COLOUR,
    CANDIDATE_COLOUR,
    OBSTACLE_COLOUR,
    RING_COLOUR,
    WALL_COLOUR,
    WALL_REACH,
    BeamFan,
    FailureFigure,
    build_figure,
    draw_failure,
)
from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.obstacles import Box, Cylinder, Obstacle, ray_distances

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
HUSKY = np.array([[0.495, 0.335], [-0.495, 0.335], [-0.495, -0.335], [0.495, -0.335]])  # m
BOX = Box(x=6.2, y=0.0, yaw=0.5, length=1.0, width=0.8, height=0.5)
CYLINDER = Cylinder(x=6.2, y=0.0, radius=0.5, height=0.5)
# A corridor wall above the baseline's arc, one below the candidate, and a turned one past the
# goal: all within WALL_REACH of what the picture shows.
WALLS = (
    Box(x=6.0, y=3.0, yaw=0.0, length=16.0, width=0.2, height=2.0),
    Box(x=6.0, y=-1.5, yaw=0.0, length=16.0, width=0.2, height=2.0),
    Box(x=13.0, y=0.5, yaw=0.4, length=1.0, width=0.2, height=2.0),
)


def fan(label: str, pose: tuple[float, float, float], obstacle: Obstacle) -> BeamFan:
    """A 270 degree fan of 32 beams reaching 10 m from the robot's centre."""
    angles = pose[2] + np.linspace(-0.75 * math.pi, 0.75 * math.pi, 32)
    directions = np.column_stack([np.cos(angles), np.sin(angles)])
    origins = np.tile([pose[0], pose[1]], (32, 1)).astype(np.float64)
    distances = ray_distances(origins, directions, obstacle)
    hits = distances <= 10.0
    ends: FloatArray = origins + np.minimum(distances, 10.0)[:, None] * directions
    return BeamFan(label, origins, ends, hits)


def failure_figure(obstacle: Obstacle) -> FailureFigure:
    """The candidate drove straight into the obstacle; the baseline swerved round it."""
    t = np.linspace(0.0, 1.0, 100)
    candidate_pose = (5.0, 0.0, 0.0)
    baseline_pose = (5.0, 1.6, 0.2)
    return FailureFigure(
        title="gate.lasertest.yaml::to_lms111[collision]",
        obstacle=obstacle,
        baseline_path=np.column_stack([12.0 * t, 2.0 * np.sin(math.pi * t)]),
        candidate_path=np.column_stack([5.0 * t, 0.0 * t]),
        footprint=HUSKY,
        candidate_pose=candidate_pose,
        baseline_pose=baseline_pose,
        beams=(
            fan("baseline sick_lms111: 32 beams, 10 m", baseline_pose, obstacle),
            fan("candidate sick_lms111: 32 beams, 10 m", candidate_pose, obstacle),
        ),
        failure=(5.5, 0.0),
        failure_label="collided at t = 11.82 s",
        goal=(12.0, 0.0),
        start=(0.0, 0.0),
    )


def png_size(path: Path) -> tuple[int, int]:
    """Width and height from a PNG's IHDR chunk, which always comes first."""
    header = path.read_bytes()[:24]
    assert header[12:16] == b"IHDR"
    width, height = struct.unpack(">II", header[16:24])
    return width, height


def pixels_near(image: FloatArray, colour: str, tolerance: float = 0.04) -> int:
    """How many pixels of an RGB(A) image in [0, 1] are within tolerance of colour."""
    distance = np.abs(image[:, :, :3] - np.array(to_rgb(colour))).max(axis=2)
    return int(np.count_nonzero(distance <= tolerance))


def test_the_picture_is_a_1000_by_700_png_and_no_temporary_is_left(tmp_path: Path) -> None:
    path = tmp_path / "pictures" / "item.png"
    assert draw_failure(failure_figure(BOX), path) == path
    assert path.read_bytes().startswith(PNG_SIGNATURE)
    assert png_size(path) == (1000, 700)
    assert imread(path).shape[:2] == (700, 1000)
    assert list(path.parent.iterdir()) == [path]


def test_drawing_again_replaces_the_picture_and_leaves_one_file(tmp_path: Path) -> None:
    path = tmp_path / "item.png"
    path.write_bytes(b"an old picture")
    draw_failure(failure_figure(CYLINDER), path)
    assert path.read_bytes().startswith(PNG_SIGNATURE)
    assert list(tmp_path.iterdir()) == [path]


@pytest.mark.parametrize("obstacle", [BOX, CYLINDER], ids=["box", "cylinder"])
def test_the_obstacle_is_filled_where_it_stands(obstacle: Obstacle, tmp_path: Path) -> None:
    figure = failure_figure(obstacle)
    picture = build_figure(figure)
    picture.canvas.draw()
    x, y = picture.axes[0].transData.transform((obstacle.x, obstacle.y))
    image = imread(draw_failure(figure, tmp_path / "item.png"))
    # Display coordinates count up from the bottom, image rows down from the top.
    centre = image[round(700 - y), round(x), :3]
    assert np.abs(centre - np.array(to_rgb(OBSTACLE_COLOUR))).max() < 0.02


def test_the_candidate_and_the_baseline_appear_in_their_own_colours(tmp_path: Path) -> None:
    image = imread(draw_failure(failure_figure(BOX), tmp_path / "item.png"))
    # A 5 m path two pixels wide at some 60 pixels a metre covers hundreds of pixels.
    assert pixels_near(image, CANDIDATE_COLOUR) > 300
    assert pixels_near(image, BASELINE_COLOUR) > 300
    assert to_rgb(CANDIDATE_COLOUR) != to_rgb(BASELINE_COLOUR)


def test_the_view_is_the_padded_box_widened_to_an_equal_aspect() -> None:
    figure = failure_figure(BOX)
    picture = build_figure(figure)
    picture.canvas.draw()
    axes = picture.axes[0]
    (left, right), (bottom, top) = axes.get_xlim(), axes.get_ylim()
    # The paths run from x = 0 m to the goal at 12 m, the baseline arcs up and the turned box
    # reaches down; all padded by 1 m.
    assert (left, right) == (-1.0, 13.0)
    lowest = -(BOX.length / 2.0 * math.sin(BOX.yaw) + BOX.width / 2.0 * math.cos(BOX.yaw))
    highest = float(figure.baseline_path[:, 1].max())
    assert bottom < lowest - 1.0 < highest + 1.0 < top
    assert math.isclose((bottom + top) / 2.0, (lowest + highest) / 2.0)
    width, height = axes.get_window_extent().size
    assert math.isclose((right - left) / width, (top - bottom) / height)
    assert axes.get_xlabel() == "x (m)"
    assert axes.get_ylabel() == "y (m)"


def test_the_legend_names_both_scanners_with_their_hits_and_the_failure() -> None:
    figure = failure_figure(BOX)
    labels = [text.get_text() for text in build_figure(figure).legends[0].get_texts()]
    hits = [int(np.count_nonzero(beams.hits)) for beams in figure.beams]
    assert min(hits) > 0
    assert f"baseline sick_lms111: 32 beams, 10 m ({hits[0]} on the obstacle)" in labels
    assert f"candidate sick_lms111: 32 beams, 10 m ({hits[1]} on the obstacle)" in labels
    for label in ("obstacle", "baseline path", "candidate path", "start", "goal"):
        assert label in labels
    assert "collided at t = 11.82 s" in labels


def test_a_beam_fan_whose_arrays_disagree_in_length_is_refused() -> None:
    origins = np.zeros((3, 2))
    with pytest.raises(ValueError, match="beam fan"):
        BeamFan("short", origins, np.ones((3, 2)), np.array([True, False]))
    with pytest.raises(ValueError, match="beam fan"):
        BeamFan("flat", origins, np.ones(6), np.array([True, False, True]))


def test_a_picture_whose_directory_cannot_be_made_raises_and_leaves_nothing(
    tmp_path: Path,
) -> None:
    blocker = tmp_path / "blocker"
    blocker.write_text("a file where a directory should go")
    with pytest.raises(OSError):  # noqa: PT011  (FileExistsError or NotADirectoryError)
        draw_failure(failure_figure(BOX), blocker / "pictures" / "item.png")
    assert list(tmp_path.iterdir()) == [blocker]


def test_a_written_artifact_gets_the_mode_of_any_new_file(tmp_path: Path) -> None:
    previous = os.umask(0o027)
    try:
        path = draw_failure(failure_figure(BOX), tmp_path / "item.png")
    finally:
        os.umask(previous)
    assert path.stat().st_mode & 0o777 == 0o640


def test_every_label_title_and_legend_lies_inside_the_picture() -> None:
    picture = build_figure(failure_figure(CYLINDER))
    picture.canvas.draw()
    drawn = picture.get_tightbbox()  # inches
    assert drawn is not None
    assert drawn.x0 >= 0.0
    assert drawn.y0 >= 0.0
    assert drawn.x1 <= 10.0
    assert drawn.y1 <= 7.0


# Walls


def walls_drawn(picture: Figure) -> PolyCollection:
    """The one collection the picture fills with the walls."""
    (walls,) = [each for each in picture.axes[0].collections if each.get_label() == "walls"]
    assert isinstance(walls, PolyCollection)
    return walls


def outlines(walls: PolyCollection) -> list[FloatArray]:
    """The corners of each polygon drawn, shape (4, 2) m: a path repeats its first to close."""
    return [np.asarray(path.vertices, dtype=np.float64)[:4] for path in walls.get_paths()]


def test_the_walls_are_filled_dark_grey_where_they_stand() -> None:
    walls = walls_drawn(build_figure(dataclasses.replace(failure_figure(BOX), walls=WALLS)))
    drawn = outlines(walls)
    assert len(drawn) == len(WALLS)
    for outline, wall in zip(drawn, WALLS, strict=True):
        np.testing.assert_allclose(outline, np.array(wall.corners()))
    colours = np.asarray(walls.get_facecolor(), dtype=np.float64)[:, :3]
    np.testing.assert_allclose(colours, np.array([to_rgb(WALL_COLOUR)]))
    assert to_rgb(WALL_COLOUR) != to_rgb(OBSTACLE_COLOUR)


def test_the_walls_lie_beneath_the_beams_the_paths_the_robots_and_the_obstacle() -> None:
    picture = build_figure(dataclasses.replace(failure_figure(BOX), walls=WALLS))
    axes = picture.axes[0]
    walls = walls_drawn(picture)
    above = [*axes.lines, *axes.patches, *(c for c in axes.collections if c is not walls)]
    assert above
    assert all(walls.get_zorder() < artist.get_zorder() for artist in above)
    # Over the grid, which the axes draw below everything else.
    assert walls.get_zorder() > axes.xaxis.get_zorder()


def test_the_legend_names_the_walls_once_however_many_there_are() -> None:
    many = WALLS * 50
    picture = build_figure(dataclasses.replace(failure_figure(BOX), walls=many))
    labels = [text.get_text() for text in picture.legends[0].get_texts()]
    assert labels.count("walls") == 1
    assert len(walls_drawn(picture).get_paths()) == len(many)


def test_a_picture_without_walls_draws_and_names_none() -> None:
    picture = build_figure(failure_figure(BOX))
    labels = [text.get_text() for text in picture.legends[0].get_texts()]
    assert "walls" not in labels
    assert not [each for each in picture.axes[0].collections if each.get_label() == "walls"]


def test_a_wall_just_past_the_padding_widens_the_view_to_hold_it() -> None:
    # Past the goal (x = 12 m) and its 1 m of padding, within WALL_REACH.
    wall = Box(x=13.6, y=0.5, yaw=0.0, length=0.4, width=3.0, height=2.0)
    picture = build_figure(dataclasses.replace(failure_figure(BOX), walls=(wall,)))
    picture.canvas.draw()
    left, right = picture.axes[0].get_xlim()
    assert left == pytest.approx(-1.0)
    assert right == pytest.approx(13.8)


def test_a_building_s_walls_widen_the_view_no_further_than_the_wall_reach() -> None:
    building = (
        # A wall 100 m long beside the route, and one 50 m away.
        Box(x=6.0, y=3.0, yaw=0.0, length=100.0, width=0.2, height=2.0),
        Box(x=62.0, y=0.0, yaw=0.3, length=0.2, width=80.0, height=2.0),
    )
    picture = build_figure(dataclasses.replace(failure_figure(BOX), walls=building))
    picture.canvas.draw()
    axes = picture.axes[0]
    # The paths and the goal run from x = 0 m to 12 m: the long wall counts only that far and
    # WALL_REACH beyond; the axes cut off the rest of it, and all of the far one.
    assert axes.get_xlim() == pytest.approx((-WALL_REACH, 12.0 + WALL_REACH))
    bottom, top = axes.get_ylim()
    assert bottom < -1.0 < 3.1 < top < 20.0
    assert walls_drawn(picture).get_clip_on()


def test_a_picture_among_walls_keeps_every_label_inside_it() -> None:
    picture = build_figure(dataclasses.replace(failure_figure(CYLINDER), walls=WALLS))
    picture.canvas.draw()
    drawn = picture.get_tightbbox()  # inches
    assert drawn is not None
    assert drawn.x0 >= 0.0
    assert drawn.y0 >= 0.0
    assert drawn.x1 <= 10.0
    assert drawn.y1 <= 7.0


POLE = Cylinder(x=6.2, y=0.0, radius=0.025, height=0.5)  # the paper's thin pole, 5 cm


def test_a_thin_pole_is_ringed_so_that_it_stands_out_at_a_glance(tmp_path: Path) -> None:
    figure = failure_figure(POLE)
    picture = build_figure(figure)
    picture.canvas.draw()
    centre = picture.axes[0].transData.transform((POLE.x, POLE.y))
    image = imread(draw_failure(figure, tmp_path / "item.png"))
    rows, columns = np.nonzero(
        np.abs(image[:, :, :3] - np.array(to_rgb(RING_COLOUR))).max(axis=2) < 0.05
    )
    # Display coordinates count up from the bottom, image rows down from the top.
    reach = np.hypot(columns - centre[0], (700 - rows) - centre[1])
    ring = reach[reach < 40]
    # A ring of some 50 pixels across, about the pole, where the pole is three pixels wide.
    assert len(ring) > 100
    assert 15 < np.median(ring) < 35
    labels = [text.get_text() for text in picture.legends[0].get_texts()]
    assert "the obstacle, ringed: it is thin" in labels


def test_an_obstacle_wide_enough_to_see_is_not_ringed(tmp_path: Path) -> None:
    image = imread(draw_failure(failure_figure(BOX), tmp_path / "item.png"))
    assert pixels_near(image, RING_COLOUR, tolerance=0.05) == 0
