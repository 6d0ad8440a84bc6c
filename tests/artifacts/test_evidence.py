"""What a failure's artifacts show of its world: the walls in the picture and in the Gazebo world,
the beams stopped at them, and the wall the robot ran into."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from matplotlib.collections import PolyCollection

from pytest_lasertest.artifacts.evidence import beam_fan, drive_figure, write_control_evidence
from pytest_lasertest.artifacts.picture import build_figure
from pytest_lasertest.model.obstacles import Box
from pytest_lasertest.nav.reactive import ReactiveController
from pytest_lasertest.pairsfile import Pair, PairsFile, load_pairs_file
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.search.drives import PairDrive
from pytest_lasertest.sim.oracles import Collision, Goal, Stuck, Verdicts
from pytest_lasertest.sim.scenario import Run, Scenario
from tests.helpers.texts import VALID_PAIRS, write

# A corridor along x, its walls 4 m apart: one listed as a box, one as a segment.
WALLED_PAIRS = VALID_PAIRS.replace(
    "  goal: {x: 9.0, y: 0.0}\n",
    "  route: [{x: 9.0, y: 0.0}]\n"
    "  walls:\n"
    "    - {x: 5.0, y: 2.0, length: 14.0, width: 0.2}\n"
    "    - {from: {x: -2.0, y: -2.0}, to: {x: 12.0, y: -2.0}, thickness: 0.2}\n",
)
NODEID = "gate.lasertest.yaml::same"
REACTIVE = ControllerChoice("reactive", "the default", ReactiveController)


@pytest.fixture
def spec(tmp_path: Path) -> PairsFile:
    return load_pairs_file(write(tmp_path / "project", WALLED_PAIRS))


def same(spec: PairsFile) -> Pair:
    return next(pair for pair in spec.pairs if pair.name == "same")


def run(spec: PairsFile, end: tuple[float, float], collided: bool) -> Run:
    """A run driving straight from the start to `end` in 5 s, colliding there or arriving."""
    world, pair = spec.world, same(spec)
    scenario = Scenario(
        spec.robot,
        pair.candidate.profile,
        (),
        world.start,
        world.route,
        world.time_limit,
        0,
        walls=world.walls,
    )
    times = np.linspace(0.02, 5.0, 250)
    fraction = times / times[-1]
    heading = float(np.arctan2(end[1], end[0]))
    poses = np.column_stack([end[0] * fraction, end[1] * fraction, np.full(250, heading)])
    verdicts = Verdicts(
        Collision(5.0 if collided else None, 0.0 if collided else 0.4),
        Stuck(None, np.inf, 0.1, 10.0),
        Goal(None if collided else 5.0, 1.0 if collided else 0.0, 0.2),
    )
    return Run(scenario, times, poses, np.zeros((250, 2)), np.zeros((250, 2)), 1, verdicts)


def drives(spec: PairsFile) -> PairDrive:
    """The baseline drove to the goal; the candidate veered into the wall at y = 1.9 m."""
    return PairDrive(run(spec, (10.0, 0.0), False), run(spec, (4.0, 1.6), True))


def test_the_picture_of_a_failure_among_walls_draws_the_world_s_walls(spec: PairsFile) -> None:
    runs = drives(spec)
    figure = drive_figure(
        f"{NODEID}: no obstacle", spec, same(spec), (runs.baseline, runs.candidate), None
    )
    assert figure.walls == spec.world.walls.boxes
    picture = build_figure(figure)
    (walls,) = [each for each in picture.axes[0].collections if each.get_label() == "walls"]
    assert isinstance(walls, PolyCollection)
    for path, wall in zip(walls.get_paths(), spec.world.walls.boxes, strict=True):
        corners = np.asarray(path.vertices, dtype=np.float64)[:4]
        np.testing.assert_allclose(corners, np.array(wall.corners()))


def test_a_collision_with_a_wall_is_marked_where_the_wall_was_touched(spec: PairsFile) -> None:
    runs = drives(spec)
    figure = drive_figure(NODEID, spec, same(spec), (runs.baseline, runs.candidate), None)
    # The point of the nearest wall nearest the candidate, at (4.0, 1.6).
    assert figure.failure == pytest.approx((4.0, 1.9))
    assert figure.failure_label == "collided at t = 5.00 s"


def test_beams_stop_at_the_walls_and_read_no_obstacle_behind_one(spec: PairsFile) -> None:
    profile = same(spec).candidate.profile
    pose = np.array([5.0, 0.0, 0.0])
    # Behind the wall at y = 2 m, where the scanner looks straight at it (+90 degrees).
    hidden = Box(x=5.0, y=3.0, yaw=0.0, length=1.0, width=0.5, height=1.0)
    seen = beam_fan("candidate", profile, pose, hidden)
    assert np.count_nonzero(seen.hits) > 0
    fan = beam_fan("candidate", profile, pose, hidden, spec.world.walls)
    assert not np.any(fan.hits)
    # No beam passes through a wall: between their ends (x from -2 m to 12 m), every beam stops
    # at the corridor's sides.
    along = (fan.ends[:, 0] > -2.0) & (fan.ends[:, 0] < 12.0)
    assert np.count_nonzero(along) > len(along) / 2
    assert np.all(np.abs(fan.ends[along, 1]) <= 1.9 + 1e-9)
    lengths = np.hypot(*(fan.ends - fan.origins).T)
    assert np.all(lengths <= profile.range_max + 1e-9)


def test_beams_in_a_world_without_walls_run_to_range_max_as_before(spec: PairsFile) -> None:
    profile = same(spec).candidate.profile
    fan = beam_fan("candidate", profile, np.array([5.0, 0.0, 0.0]), None)
    lengths = np.hypot(*(fan.ends - fan.origins).T)
    np.testing.assert_allclose(lengths, profile.range_max)


def test_the_gazebo_world_of_a_failure_without_an_obstacle_holds_the_walls(
    spec: PairsFile, tmp_path: Path
) -> None:
    artifacts = write_control_evidence(
        tmp_path / "out", NODEID, spec, same(spec), drives(spec), {"seed": 0}, REACTIVE
    )
    assert not artifacts.unwritten
    (world_file,) = [path for path in artifacts.written if path.suffix == ".world"]
    world = ET.parse(world_file).getroot()[0]
    found = {model.attrib["name"]: model for model in world.iter("model")}
    assert list(found) == ["ground_plane", "wall_0", "wall_1"]
    for index, wall in enumerate(spec.world.walls.boxes):
        size = found[f"wall_{index}"].findtext("link/collision/geometry/box/size")
        assert size is not None
        assert [float(word) for word in size.split()] == [wall.length, wall.width, wall.height]
