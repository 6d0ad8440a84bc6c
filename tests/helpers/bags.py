"""Bags written for a test with rosbags's own writers (rosbag2 MCAP, rosbag2 SQLite, ROS 1), holding
LaserScan messages as a real scanner's driver publishes them: its no-return encoding, a fixed or
per-scan range_max, either turning direction, and stamps at the sweep's start or at arrival."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Literal

import numpy as np

from pytest_lasertest.model.geometry import FloatArray

if TYPE_CHECKING:
    from rosbags.typesys.store import Typestore

Format = Literal["mcap", "sqlite3", "ros1"]
FORMATS: tuple[Format, ...] = ("mcap", "sqlite3", "ros1")
LASERSCAN = "sensor_msgs/msg/LaserScan"
START = 1_700_000_000_000_000_000  # ns, the first scan's stamp
FOV = 4.0  # rad, from -2 to 2
NO_RETURN_EVERY = 5  # every fifth beam of a scan met nothing


@dataclass(frozen=True)
class RecordedScan:
    """One LaserScan message and when the bag logged it."""

    stamp: int  # ns
    log_time: int  # ns
    angle_min: float  # rad
    angle_increment: float  # rad
    range_min: float  # m
    range_max: float  # m
    scan_time: float  # s
    ranges: FloatArray  # m, float32

    @property
    def angle_max(self) -> float:
        return self.angle_min + (len(self.ranges) - 1) * self.angle_increment


def laser_scans(
    count: int = 30,
    *,
    beams: int = 181,
    rate: float = 40.0,  # Hz
    no_return: float | Literal["range_max"] = math.inf,
    range_max: float = 20.0,  # m
    per_scan: bool = False,
    clockwise: bool = False,
    arrival: float = 0.0,  # s from the stamp to when the bag logged the scan
) -> list[RecordedScan]:
    """`count` scans of a scanner sweeping FOV over `beams` beams, every NO_RETURN_EVERY-th
    beam without a return, published as `no_return`. With `per_scan`, each scan's range_max
    is its largest reading (sick_scan_xd); with `clockwise`, angle_min is the left end and
    angle_increment negative."""
    period = round(1e9 / rate)  # ns
    step = FOV / (beams - 1)
    scans = []
    for index in range(count):
        # m, 1 to 10.8; the beams' own 0.1 mm each keeps one reading the largest.
        measured = 1.0 + np.arange(beams) % 40 * 0.25 + np.arange(beams) * 1e-4 + index * 0.01
        scan_max = float(np.float32(measured.max())) if per_scan else range_max
        lost = np.arange(beams) % NO_RETURN_EVERY == 0
        encoded = scan_max if no_return == "range_max" else no_return
        ranges = np.where(lost, encoded, measured).astype(np.float32)
        stamp = START + index * period
        scans.append(
            RecordedScan(
                stamp=stamp,
                log_time=stamp + round(arrival * 1e9),
                angle_min=FOV / 2 if clockwise else -FOV / 2,
                angle_increment=-step if clockwise else step,
                range_min=0.05,
                range_max=scan_max,
                scan_time=1.0 / rate,
                ranges=ranges,
            )
        )
    return scans


def with_ranges(scan: RecordedScan, ranges: Sequence[float]) -> RecordedScan:
    """The scan with other ranges (and so another beam count)."""
    return replace(scan, ranges=np.asarray(ranges, dtype=np.float32))


def write_bag(
    path: Path,
    scans: Sequence[RecordedScan],
    *,
    kind: Format = "mcap",
    topic: str | None = "/scan",
    chatter: bool = False,
    more_scans: Sequence[str] = (),
) -> Path:
    """A bag at `path` (a rosbag2 directory, or a ROS 1 .bag file) with `scans` on `topic`
    (None: no such topic); with `chatter`, a std_msgs/String on /chatter too; `more_scans` are
    LaserScan topics with the same scans."""
    from rosbags.rosbag1 import Writer as Ros1Writer
    from rosbags.rosbag2 import StoragePlugin
    from rosbags.rosbag2 import Writer as Ros2Writer
    from rosbags.typesys import Stores, get_typestore

    ros1 = kind == "ros1"
    store = get_typestore(Stores.ROS1_NOETIC if ros1 else Stores.ROS2_JAZZY)
    serialize = store.serialize_ros1 if ros1 else store.serialize_cdr
    storage = StoragePlugin.SQLITE3 if kind == "sqlite3" else StoragePlugin.MCAP
    writer = Ros1Writer(path) if ros1 else Ros2Writer(path, version=9, storage_plugin=storage)
    with writer:
        for name in [*([topic] if topic else []), *more_scans]:
            connection = writer.add_connection(name, LASERSCAN, typestore=store)
            for scan in scans:
                message = _message(store, scan, ros1=ros1)
                writer.write(connection, scan.log_time, serialize(message, LASERSCAN))
        if chatter:
            string = "std_msgs/msg/String"
            connection = writer.add_connection("/chatter", string, typestore=store)
            text = store.types[string](data="hello")
            writer.write(connection, START, serialize(text, string))
    return path


def _message(store: Typestore, scan: RecordedScan, *, ros1: bool) -> object:
    types = store.types
    seconds, nanoseconds = divmod(scan.stamp, 1_000_000_000)
    stamp = types["builtin_interfaces/msg/Time"](sec=seconds, nanosec=nanoseconds)
    header = types["std_msgs/msg/Header"](
        **({"seq": 0} if ros1 else {}), stamp=stamp, frame_id="laser"
    )
    return types[LASERSCAN](
        header=header,
        angle_min=scan.angle_min,
        angle_max=scan.angle_max,
        angle_increment=scan.angle_increment,
        time_increment=0.0,
        scan_time=scan.scan_time,
        range_min=scan.range_min,
        range_max=scan.range_max,
        ranges=scan.ranges,
        intensities=np.zeros(0, dtype=np.float32),
    )


# A pairs file whose candidate is left to the test: what follows `candidate:` (line 6).
RECORDED_PAIR = """\
robot: husky
world: {start: {x: 0, y: 0}, goal: {x: 5, y: 0}, time_limit: 30}
pairs:
  recorded:
    baseline: {model: hokuyo_ust_10lx}
    candidate:
"""
