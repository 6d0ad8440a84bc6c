"""A failure's rosbag2: both robots as their stacks would publish them, in simulated time,
read back with rosbags as Foxglove and `ros2 bag play` would read it."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from rosbags.highlevel import AnyReader

from pytest_lasertest.artifacts.bag import write_bag
from pytest_lasertest.artifacts.evidence import driven_again
from pytest_lasertest.model.obstacles import Cylinder
from pytest_lasertest.nav.move_base import MoveBase
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.pairsfile.controller import ControllerChoice
from pytest_lasertest.search.drives import drive
from pytest_lasertest.sim.scenario import Run
from tests.helpers import EXAMPLES

PAPER = load_pairs_file(EXAMPLES / "paper.lasertest.yaml")
DISTANCE = next(pair for pair in PAPER.pairs if pair.name == "distance")
POLE = Cylinder(x=3.0, y=1.5, radius=0.05, height=1.0)
TOPICS = {
    "/tf": "tf2_msgs/msg/TFMessage",
    "/tf_static": "tf2_msgs/msg/TFMessage",
    "/markers": "visualization_msgs/msg/MarkerArray",
    "/baseline/odom": "nav_msgs/msg/Odometry",
    "/baseline/scan": "sensor_msgs/msg/LaserScan",
    "/candidate/odom": "nav_msgs/msg/Odometry",
    "/candidate/scan": "sensor_msgs/msg/LaserScan",
    "/candidate/global_costmap/costmap": "nav_msgs/msg/OccupancyGrid",
    "/candidate/plan": "nav_msgs/msg/Path",
}


@pytest.fixture(scope="module")
def runs() -> dict[str, Run]:
    """The distance pair's two robots in the empty world, past a pole, driven again recorded."""
    driven = tuple(
        drive(PAPER, scanner.profile, (POLE,), 1, MoveBase)
        for scanner in (DISTANCE.baseline, DISTANCE.candidate)
    )
    again, note = driven_again(driven, ControllerChoice("move_base", "the default", MoveBase))
    assert note == ""
    return again


@pytest.fixture(scope="module")
def bag(runs: dict[str, Run], tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("artifacts") / "distance_no-obstacle"
    footprint = PAPER.robot.footprint_array()
    assert write_bag(path, runs, footprint, (POLE,)) == path
    return path


def read(bag: Path, topic: str) -> list[tuple[int, object]]:
    """Every message on `topic`: (log time in ns, message)."""
    with AnyReader([bag]) as reader:
        chosen = [c for c in reader.connections if c.topic == topic]
        return [
            (stamp, reader.deserialize(data, connection.msgtype))
            for connection, stamp, data in reader.messages(connections=chosen)
        ]


def test_the_bag_is_one_mcap_file_and_its_metadata(bag: Path) -> None:
    assert sorted(path.name for path in bag.iterdir()) == [
        "distance_no-obstacle.mcap",
        "metadata.yaml",
    ]
    # Nothing half-written is left beside it.
    assert [path.name for path in bag.parent.iterdir()] == ["distance_no-obstacle"]


def test_it_holds_each_robot_s_topics_of_their_ros_types(bag: Path) -> None:
    with AnyReader([bag]) as reader:
        found = {connection.topic: connection.msgtype for connection in reader.connections}
    assert found == TOPICS


def test_each_scan_is_there_as_its_driver_published_it_stamped_in_sim_time(
    bag: Path, runs: dict[str, Run]
) -> None:
    for role, run in runs.items():
        assert run.recording is not None
        scans = read(bag, f"/{role}/scan")
        assert len(scans) == run.scans == len(run.recording.scans)
        for (logged, message), scan in zip(scans, run.recording.scans, strict=True):
            stamp = message.header.stamp  # type: ignore[attr-defined]
            assert stamp.sec * 10**9 + stamp.nanosec == logged == round(scan.stamp * 1e9)
            assert message.header.frame_id == f"{role}/laser"  # type: ignore[attr-defined]
            np.testing.assert_array_equal(
                message.ranges,  # type: ignore[attr-defined]
                scan.ranges.astype(np.float32),
            )


def test_odometry_and_tf_follow_each_robot_at_every_physics_step(
    bag: Path, runs: dict[str, Run]
) -> None:
    transforms = [message.transforms[0] for _, message in read(bag, "/tf")]  # type: ignore[attr-defined]
    for role, run in runs.items():
        odometry = read(bag, f"/{role}/odom")
        assert len(odometry) == len(run.times)
        ours = [t for t in transforms if t.child_frame_id == f"{role}/base_footprint"]
        assert len(ours) == len(run.times)
        last = ours[-1].transform.translation
        assert (last.x, last.y) == pytest.approx(tuple(run.poses[-1, :2]))
        assert {t.header.frame_id for t in ours} == {"odom"}


def test_both_mounts_are_one_static_message_offered_as_tf2_s_static_broadcaster_does(
    bag: Path,
) -> None:
    # One message, kept for a late subscriber: RViz started after `ros2 bag play` gets both.
    ((_, message),) = read(bag, "/tf_static")
    mounts = {t.child_frame_id: t for t in message.transforms}  # type: ignore[attr-defined]
    assert set(mounts) == {"baseline/laser", "candidate/laser"}
    height = DISTANCE.candidate.profile.pose.xyz[2]
    assert mounts["candidate/laser"].transform.translation.z == pytest.approx(height)
    with AnyReader([bag]) as reader:
        (static,) = [c for c in reader.connections if c.topic == "/tf_static"]
        (qos,) = static.ext.offered_qos_profiles  # type: ignore[union-attr]
    assert (qos.depth, qos.durability.name, qos.reliability.name) == (
        1,
        "TRANSIENT_LOCAL",
        "RELIABLE",
    )


def test_the_candidate_s_costmap_and_plan_come_once_a_simulated_second(
    bag: Path, runs: dict[str, Run]
) -> None:
    recording = runs["candidate"].recording
    assert recording is not None
    costmaps = read(bag, "/candidate/global_costmap/costmap")
    assert len(costmaps) == len(recording.costmaps) > 5
    times = np.array([logged for logged, _ in costmaps]) / 1e9
    # A second apart, and a last one when the drive was decided.
    assert np.diff(times[:-1]) == pytest.approx(1.0, abs=0.03)
    _, last = costmaps[-1]
    grid = recording.costmaps[-1][1]
    assert (last.info.width, last.info.height) == (grid.width, grid.height)  # type: ignore[attr-defined]
    np.testing.assert_array_equal(last.data, grid.data.ravel())  # type: ignore[attr-defined]
    plans = read(bag, "/candidate/plan")
    assert len(plans) == len(recording.plans)


def test_the_markers_show_the_obstacle_and_both_footprints(bag: Path) -> None:
    ((_, array),) = read(bag, "/markers")
    markers = array.markers  # type: ignore[attr-defined]
    pole, *footprints = markers
    assert (pole.pose.position.x, pole.pose.position.y) == (POLE.x, POLE.y)
    assert pole.scale.x == pytest.approx(2 * POLE.radius)
    assert [m.header.frame_id for m in footprints] == [
        "baseline/base_footprint",
        "candidate/base_footprint",
    ]
    # A closed outline: the footprint's corners and the first again.
    assert len(footprints[0].points) == len(PAPER.robot.footprint_array()) + 1
