"""Reading a recording (`inputs/bags.py`) and the profile it shows (`inputs/inferred.py`): bags
written with rosbags's own writers in each format, from drivers that publish no-returns,
range_max, the turning direction and their stamps each their own way; and bags that give no
profile, each refused with the file, what is wrong and the fix."""

from __future__ import annotations

import math
import os
from dataclasses import replace
from pathlib import Path

import pytest

from pytest_lasertest.inputs.bags import BagError, read_recording
from pytest_lasertest.inputs.inferred import (
    LATENCY_NOTE,
    InferredProfile,
    profile_fields,
    profile_from_bag,
)
from pytest_lasertest.model.driver import DEFAULT_DRIVER
from tests.helpers.bags import (
    FORMATS,
    LASERSCAN,
    START,
    Format,
    laser_scans,
    with_ranges,
    write_bag,
)

SCAN_TIME = 1.0 / 40.0  # s, the scans' period


def inferred(tmp_path: Path, kind: Format = "mcap", **scans: object) -> InferredProfile:
    """The profile of a bag of `laser_scans(**scans)` in the format `kind`."""
    name = "scans.bag" if kind == "ros1" else "scans"
    bag = write_bag(tmp_path / name, laser_scans(**scans), kind=kind)  # type: ignore[arg-type]
    return profile_from_bag(bag, "/scan")


def refusal(path: Path, topic: str | None = "/scan") -> BagError:
    with pytest.raises(BagError) as caught:
        profile_from_bag(path, topic)
    return caught.value


def noted(found: InferredProfile, words: str) -> str:
    """The one note that says `words`."""
    (note,) = [note for note in found.notes if words in note]
    return note


# What bags of each format show.


@pytest.mark.parametrize("kind", FORMATS)
def test_a_rosbag2_mcap_a_rosbag2_sqlite3_and_a_ros1_bag_give_the_profile_their_scans_show(
    tmp_path: Path, kind: Format
) -> None:
    found = inferred(tmp_path, kind, no_return=math.nan)
    profile = found.profile
    assert (found.topic, found.messages) == ("/scan", 30)
    assert (profile.samples, profile.resolution) == (181, 1.0)
    assert (profile.min_angle, profile.max_angle) == pytest.approx((-2.0, 2.0), abs=1e-6)
    assert (profile.range_min, profile.range_max) == (0.05, 20.0)
    assert profile.update_rate == 40.0
    assert profile.driver.no_return == "nan"


def test_a_rosbag2_recording_is_read_from_its_directory_or_from_its_storage_file(
    tmp_path: Path,
) -> None:
    directory = write_bag(tmp_path / "scans", laser_scans(no_return=0.0), kind="sqlite3")
    from_file = profile_from_bag(directory / "scans.db3", "/scan")
    assert from_file.profile == profile_from_bag(directory, "/scan").profile
    assert from_file.profile.driver.no_return == "zero"


@pytest.mark.parametrize(
    ("published", "encoding"),
    [(math.inf, "inf"), (math.nan, "nan"), (0.0, "zero"), ("range_max", "range_max")],
    ids=["inf", "nan", "zero", "range_max"],
)
def test_a_bag_whose_no_returns_are_published_one_way_gives_that_no_return(
    tmp_path: Path, published: float | str, encoding: str
) -> None:
    found = inferred(tmp_path, no_return=published)
    assert found.profile.driver.no_return == encoding
    assert not [note for note in found.notes if "several ways" in note]


def test_a_bag_whose_no_returns_are_published_several_ways_gives_the_most_frequent_and_a_note(
    tmp_path: Path,
) -> None:
    scans = laser_scans(no_return=math.nan)
    # One scan of thirty publishes its no-returns as 0.0 (37 readings against 29 x 37 NaN).
    scans[3] = with_ranges(scans[3], [0.0 if math.isnan(r) else r for r in scans[3].ranges])
    found = profile_from_bag(write_bag(tmp_path / "scans", scans), "/scan")
    assert found.profile.driver.no_return == "nan"
    assert "(1073 NaN, 37 0.0): no_return is the most frequent, nan" in noted(found, "several")


def test_a_bag_in_which_every_beam_returned_leaves_no_return_at_inf_and_says_so(
    tmp_path: Path,
) -> None:
    scans = [with_ranges(scan, [1.0] * 181) for scan in laser_scans()]
    found = profile_from_bag(write_bag(tmp_path / "scans", scans), "/scan")
    assert found.profile.driver.no_return == "inf"
    assert "no_return is left at inf (REP 117)" in noted(found, "without a return")


def test_a_range_max_that_moves_per_scan_gives_range_max_per_scan_and_the_largest_seen(
    tmp_path: Path,
) -> None:
    found = inferred(tmp_path, per_scan=True)
    largest = max(scan.range_max for scan in laser_scans(per_scan=True))
    assert found.profile.driver.range_max == "per_scan"
    assert found.profile.range_max == pytest.approx(largest, abs=1e-6)
    assert found.profile.driver.no_return == "inf"  # the reading that set range_max is a return
    assert "range_max per_scan" in noted(found, "range_max moved between scans")


def test_a_per_scan_range_max_that_no_returns_are_published_as_gives_no_return_range_max(
    tmp_path: Path,
) -> None:
    found = inferred(tmp_path, per_scan=True, no_return="range_max")
    assert (found.profile.driver.range_max, found.profile.driver.no_return) == (
        "per_scan",
        "range_max",
    )


def test_a_scan_turning_clockwise_gives_ascending_angles_and_keeps_the_beam_order(
    tmp_path: Path,
) -> None:
    found = inferred(tmp_path, clockwise=True)
    (tmp_path / "counter").mkdir()
    counter = inferred(tmp_path / "counter")
    assert (found.profile.min_angle, found.profile.max_angle) == pytest.approx((-2.0, 2.0))
    # Its header says it turns clockwise, so consumers place its beams right: the same beams.
    assert found.profile.beam_angles() == pytest.approx(counter.profile.beam_angles(), abs=1e-6)
    assert found.profile.driver == counter.profile.driver
    assert found.profile.driver.beam_order == "counter-clockwise"
    assert "header says so" in noted(found, "turn clockwise")


def test_a_bag_whose_scans_arrive_at_their_stamp_gives_stamp_end(tmp_path: Path) -> None:
    found = inferred(tmp_path, arrival=0.0)
    assert found.profile.driver.stamp == "end"
    assert found.arrival_age == 0.0
    assert "arrived 0.0 ms after their stamps" in noted(found, "stamp end")


def test_a_bag_whose_scans_arrive_a_sweep_and_5_ms_after_their_stamp_gives_stamp_start(
    tmp_path: Path,
) -> None:
    found = inferred(tmp_path, arrival=SCAN_TIME + 0.005)
    assert found.profile.driver.stamp == "start"
    assert found.arrival_age == pytest.approx(0.030)
    assert "arrived 30.0 ms after their stamps" in noted(found, "stamp start")
    assert found.profile.driver == DEFAULT_DRIVER


def test_a_bag_logged_on_another_clock_than_the_stamps_leaves_stamp_start(
    tmp_path: Path,
) -> None:
    found = inferred(tmp_path, arrival=-3600.0)  # the bag's clock an hour behind the driver's
    assert found.profile.driver.stamp == "start"
    assert "the bag's clock is not the driver's" in noted(found, "after their stamps")


def test_stamps_that_do_not_advance_give_the_rate_from_scan_time_and_leave_stamp_start(
    tmp_path: Path,
) -> None:
    scans = [replace(scan, stamp=0) for scan in laser_scans(rate=12.5)]
    found = profile_from_bag(write_bag(tmp_path / "scans", scans), "/scan")
    assert found.profile.update_rate == 12.5
    assert (found.profile.driver.stamp, found.arrival_age) == ("start", None)
    assert "update_rate is 1 / scan_time" in noted(found, "do not advance: update_rate")


def test_latency_is_left_at_zero_and_the_notes_say_it_cannot_be_measured(tmp_path: Path) -> None:
    found = inferred(tmp_path, arrival=0.2)
    assert found.profile.driver.latency == 0.0
    assert LATENCY_NOTE in found.notes


def test_minus_inf_readings_are_noted_as_too_near_and_too_near_stays_minus_inf(
    tmp_path: Path,
) -> None:
    scans = laser_scans()
    scans[0] = with_ranges(scans[0], [-math.inf, *scans[0].ranges[1:]])
    found = profile_from_bag(write_bag(tmp_path / "scans", scans), "/scan")
    assert found.profile.driver.too_near == "-inf"
    assert noted(found, "-inf") == "1 readings were -inf, nearer than range_min (REP 117)"


def test_a_few_scans_with_another_beam_count_are_left_out_with_a_note(tmp_path: Path) -> None:
    scans = laser_scans()
    for index in (4, 9, 20):
        scans[index] = with_ranges(scans[index], scans[index].ranges[:180])
    found = profile_from_bag(write_bag(tmp_path / "scans", scans), "/scan")
    assert found.profile.samples == 181
    assert noted(found, "other beams") == (
        "3 of 30 scans had other beams (3 had 180 beams from -2 rad every 0.0222222 rad); "
        "the profile follows the other 27, with 181 beams from -2 rad every 0.0222222 rad"
    )


def test_the_only_laserscan_topic_is_read_when_none_is_named(tmp_path: Path) -> None:
    bag = write_bag(tmp_path / "scans", laser_scans(), topic="/front/scan", chatter=True)
    assert profile_from_bag(bag).topic == "/front/scan"


def test_the_pasteable_fields_hold_only_the_driver_traits_that_are_not_gazebo_s(
    tmp_path: Path,
) -> None:
    fields = profile_fields(inferred(tmp_path, no_return=math.nan).profile)
    assert list(fields) == [
        "samples",
        "min_angle",
        "max_angle",
        "range.min",
        "range.max",
        "update_rate",
        "driver.no_return",
        "driver.stamp",
    ]
    assert (fields["driver.no_return"], fields["driver.stamp"]) == ("nan", "end")


# Bags that give no profile.


def test_a_path_that_does_not_exist_is_refused(tmp_path: Path) -> None:
    error = refusal(tmp_path / "missing.mcap")
    assert error.problem == "does not exist"
    assert "check the path and its spelling" in error.fix
    assert str(error).startswith(f"{tmp_path / 'missing.mcap'}: does not exist\n  fix: ")


@pytest.mark.parametrize(
    ("name", "kind"),
    [
        ("junk.mcap", "an MCAP file"),
        ("junk.db3", "a rosbag2 SQLite file"),
        ("junk.bag", "a ROS 1 bag"),
    ],
)
def test_a_file_of_garbage_bytes_is_refused_as_no_bag_of_its_kind(
    tmp_path: Path, name: str, kind: str
) -> None:
    path = tmp_path / name
    path.write_bytes(bytes(range(256)) * 8)
    error = refusal(path)
    assert error.problem.startswith(f"is not {kind}: it does not start as one (rosbags: ")
    assert "give a rosbag2 directory" in error.fix


def test_an_mcap_cut_in_half_is_refused_as_damaged_with_how_to_mend_it(tmp_path: Path) -> None:
    whole = write_bag(tmp_path / "scans", laser_scans()) / "scans.mcap"
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(whole.read_bytes()[: whole.stat().st_size // 2])
    error = refusal(cut)
    assert error.problem.startswith("is damaged or cut short")
    assert "mcap recover" in error.fix


def test_a_ros1_bag_cut_in_half_is_refused_as_damaged_with_how_to_mend_it(tmp_path: Path) -> None:
    whole = write_bag(tmp_path / "scans.bag", laser_scans(), kind="ros1")
    cut = tmp_path / "cut.bag"
    cut.write_bytes(whole.read_bytes()[: whole.stat().st_size // 2])
    error = refusal(cut)
    assert error.problem.startswith("is damaged or cut short")
    assert "rosbag reindex" in error.fix


@pytest.mark.parametrize("name", ["notes.txt", "metadata.yaml", "folder"])
def test_a_path_that_is_no_bag_is_refused_before_rosbags_reads_it(
    tmp_path: Path, name: str
) -> None:
    path = tmp_path / name
    if name == "folder":
        path.mkdir()
    else:
        path.write_text("hello")
    problem = {
        "notes.txt": "is not a bag: rosbags reads .mcap, .db3, .bag files and rosbag2 directories",
        "metadata.yaml": "is a rosbag2 recording's metadata",
        "folder": "is a directory, not a rosbag2 recording: it holds no metadata.yaml",
    }[name]
    assert refusal(path).problem == problem


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs")
def test_a_fifo_named_as_a_bag_is_refused_without_waiting_for_a_writer(tmp_path: Path) -> None:
    path = tmp_path / "scans.mcap"
    os.mkfifo(path)
    assert refusal(path).problem == "is not a regular file (a pipe, socket or device)"


def test_a_topic_the_bag_lacks_is_refused_naming_its_laserscan_topics(tmp_path: Path) -> None:
    bag = write_bag(tmp_path / "scans", laser_scans(), more_scans=["/rear/scan"], chatter=True)
    error = refusal(bag, "/scna")
    assert error.problem == "has no topic /scna; its LaserScan topics: /rear/scan, /scan"
    assert error.fix == "did you mean /scan? name one of its LaserScan topics: /rear/scan, /scan"
    assert error.about == "topic"


def test_a_topic_of_another_message_type_is_refused_naming_its_type(tmp_path: Path) -> None:
    bag = write_bag(tmp_path / "scans", laser_scans(), chatter=True)
    error = refusal(bag, "/chatter")
    assert error.problem == (
        "the topic /chatter holds std_msgs/msg/String messages, not sensor_msgs/msg/LaserScan"
    )
    assert error.fix == "name one of its LaserScan topics: /scan"


def test_a_topic_without_messages_is_refused(tmp_path: Path) -> None:
    error = refusal(write_bag(tmp_path / "scans", []))
    assert error.problem == "the topic /scan holds no messages"
    assert "ros2 topic hz /scan" in error.fix


def test_a_bag_with_several_laserscan_topics_and_none_named_is_refused(tmp_path: Path) -> None:
    bag = write_bag(tmp_path / "scans", laser_scans(), more_scans=["/rear/scan"])
    error = refusal(bag, None)
    assert error.problem == "has several LaserScan topics (/rear/scan, /scan), and none was named"


def test_a_bag_without_laserscan_topics_is_refused_listing_its_topics(tmp_path: Path) -> None:
    bag = write_bag(tmp_path / "scans", [], topic=None, chatter=True)
    error = refusal(bag, None)
    assert error.problem == "has no LaserScan topic; its topics: /chatter (std_msgs/msg/String)"
    assert error.fix == "record the scanner's LaserScan topic (e.g. `ros2 bag record /scan`)"


def test_scans_that_share_no_beam_layout_by_half_are_refused(tmp_path: Path) -> None:
    scans = laser_scans()
    for index in range(10):
        scans[index] = with_ranges(scans[index], scans[index].ranges[:100])
        scans[index + 10] = with_ranges(scans[index + 10], scans[index + 10].ranges[:50])
    error = refusal(write_bag(tmp_path / "scans", scans))
    assert error.problem.startswith(
        "its scans disagree on their beams, no layout shared by half of them: "
        "10 with 100 beams from -2 rad every 0.0222222 rad; "
    )
    assert error.fix == "record one configuration of the scanner at a time, or cut the bag to one"


def test_a_bag_whose_own_laserscan_definition_lacks_ranges_is_refused_naming_the_field(
    tmp_path: Path,
) -> None:
    # A bag holds the definition each type was recorded with; this one's LaserScan has no
    # ranges, and reading its messages must say so, not raise.
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    jazzy = get_typestore(Stores.ROS2_JAZZY)
    store = get_typestore(Stores.EMPTY)
    store.register({name: d for name, d in jazzy.fielddefs.items() if name != LASERSCAN})
    store.register(get_types_from_msg("std_msgs/Header header\nfloat32 range_max\n", LASERSCAN))
    types = store.types
    time = types["builtin_interfaces/msg/Time"](sec=1, nanosec=0)
    message = types[LASERSCAN](
        header=types["std_msgs/msg/Header"](stamp=time, frame_id="laser"), range_max=10.0
    )
    path = tmp_path / "bag"
    with Writer(path, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        connection = writer.add_connection("/scan", LASERSCAN, typestore=store)
        writer.write(connection, START, store.serialize_cdr(message, LASERSCAN))
    with pytest.raises(BagError) as raised:
        read_recording(path)
    assert "is not a sensor_msgs/msg/LaserScan as ROS defines it" in raised.value.problem
    assert "ranges" in raised.value.problem


def test_scans_whose_beam_geometry_is_nan_are_refused_in_one_line(tmp_path: Path) -> None:
    # NaN equals nothing, not even itself: each scan would have been a layout of its own, and
    # the error listed every one of them.
    scans = [replace(scan, angle_increment=math.nan) for scan in laser_scans(200)]
    with pytest.raises(BagError) as raised:
        profile_from_bag(write_bag(tmp_path / "bag", scans))
    assert raised.value.problem == (
        "200 of its 200 scans give angle_increment as nan: no beam layout can be made of it"
    )


def test_scans_of_many_layouts_name_the_three_most_common(tmp_path: Path) -> None:
    scans = [with_ranges(scan, [1.0] * (20 + index)) for index, scan in enumerate(laser_scans(30))]
    with pytest.raises(BagError) as raised:
        profile_from_bag(write_bag(tmp_path / "bag", scans))
    assert raised.value.problem.count(" with ") == 3
    assert raised.value.problem.endswith("; and 27 layouts more")
