"""The LaserScan messages of one topic of a bag (a rosbag2 directory, an .mcap or .db3 file, or
a ROS 1 .bag), read with rosbags, which needs no ROS install: each message's header stamp, the
time the bag logged it and its LaserScan fields, its ranges counted by the values a driver
publishes for 'no reading' (a recording of an hour holds too many ranges to keep).

A bag that cannot be read is a BagError naming the file, what is wrong and the fix: no such
path, no bag (a FIFO, another kind of file, bytes that do not start as the format's), a damaged
or cut short one (rosbags's parsers raise anything on damaged bytes: every error is caught
where rosbags is called), a topic it lacks or of another type, a topic without messages.

rosbags is imported inside the functions that read a bag: importing the plugin stays cheap.
"""

from __future__ import annotations

import stat
from collections.abc import Iterator
from dataclasses import dataclass
from difflib import get_close_matches
from itertools import islice
from pathlib import Path
from typing import TYPE_CHECKING, Literal, Protocol, cast

import numpy as np

from pytest_lasertest.inputs.errors import display_path
from pytest_lasertest.model.geometry import FloatArray

if TYPE_CHECKING:
    from rosbags.highlevel import AnyReader
    from rosbags.interfaces import Connection

LASERSCAN = "sensor_msgs/msg/LaserScan"  # rosbags names ROS 1 types this way too
# A recording longer than this is read only so far: 40 minutes at 40 Hz tells the driver's
# ways as well as a day, and each scan read is kept (without its ranges).
MAX_MESSAGES = 100_000
_SUFFIXES = {".mcap": "an MCAP file", ".db3": "a rosbag2 SQLite file", ".bag": "a ROS 1 bag"}
_MAGIC = {
    ".mcap": b"\x89MCAP0\r\n",
    ".db3": b"SQLite format 3\x00",
    ".bag": b"#ROSBAG V2.0\n",
}
# How a recording cut short (a recorder killed before it closed the file) is mended.
_MEND = {
    ".mcap": "`mcap recover FILE -o FIXED.mcap` (the mcap CLI) copies out what can be read",
    ".db3": "`ros2 bag reindex DIR` rebuilds a rosbag2 directory's metadata; a malformed "
    "database needs `sqlite3 FILE .recover`",
    ".bag": "`rosbag reindex FILE` rebuilds the index of a ROS 1 bag cut short",
}
GIVE_A_BAG = (
    "give a rosbag2 directory (the one `ros2 bag record` wrote, with metadata.yaml), one of its "
    ".mcap or .db3 files, or a ROS 1 .bag file"
)


class BagError(Exception):
    """A bag that gives no profile: which file, what is wrong, and how to fix it. `about` says
    whether the bag's path or the topic asked of it is at fault."""

    def __init__(
        self, path: Path, problem: str, fix: str, *, about: Literal["path", "topic"] = "path"
    ) -> None:
        super().__init__(path, problem, fix)
        self.path = path
        self.problem = problem
        self.fix = fix
        self.about = about

    def __str__(self) -> str:
        return f"{display_path(self.path)}: {self.problem}\n  fix: {self.fix}"


@dataclass(frozen=True)
class Readings:
    """How many readings of one scan held each value a driver may publish for 'no reading'."""

    nan: int
    inf: int
    neg_inf: int
    zero: int
    at_range_max: int  # exactly the scan's own range_max


@dataclass(frozen=True)
class Scan:
    """One LaserScan message as recorded; its ranges are kept only as counts (Readings)."""

    stamp: int  # ns, the header stamp
    log_time: int  # ns, when the bag logged it
    beams: int  # len(ranges)
    angle_min: float  # rad
    angle_max: float  # rad
    angle_increment: float  # rad
    scan_time: float  # s
    range_min: float  # m
    range_max: float  # m
    readings: Readings


@dataclass(frozen=True)
class Recording:
    """The scans of one LaserScan topic of a bag, in the order the bag logged them."""

    path: Path
    topic: str
    scans: tuple[Scan, ...]
    total: int  # messages on the topic; more than len(scans) when it held over MAX_MESSAGES


class _Time(Protocol):
    sec: int
    nanosec: int


class _Header(Protocol):
    stamp: _Time


class _LaserScan(Protocol):
    """The fields of a sensor_msgs/LaserScan message read here, as rosbags gives them."""

    header: _Header
    angle_min: float
    angle_max: float
    angle_increment: float
    scan_time: float
    range_min: float
    range_max: float
    ranges: FloatArray


def read_recording(path: Path, topic: str | None = None) -> Recording:
    """The LaserScan messages on `topic` of the bag at `path`, at most MAX_MESSAGES."""
    _check_path(path)
    reader = _open(path)
    try:
        name, total = _choose_topic(reader, path, topic)
        connections = [item for item in reader.connections if item.topic == name]
        decoded = islice(_decoded(reader, connections, path), MAX_MESSAGES)
        scans = tuple(_laser_scan(path, name, message, log_time) for log_time, message in decoded)
    finally:
        reader.close()
    if not scans:
        raise BagError(
            path,
            f"the topic {name} holds no messages",
            f"record while the scanner's driver publishes (`ros2 topic hz {name}` shows it)",
            about="topic",
        )
    return Recording(path, name, scans, max(total, len(scans)))


def _check_path(path: Path) -> None:
    """Refuse what is no bag before rosbags opens it: a FIFO would block it for ever."""
    try:
        mode = path.stat().st_mode
    except FileNotFoundError:
        fix = f"check the path and its spelling; {GIVE_A_BAG}"
        raise BagError(path, "does not exist", fix) from None
    except OSError as error:
        raise BagError(path, f"cannot be read: {error.strerror}", GIVE_A_BAG) from None
    except ValueError:  # a NUL character in the name
        raise BagError(path, "names no file: its name holds a NUL character", GIVE_A_BAG) from None
    if stat.S_ISDIR(mode):
        if not (path / "metadata.yaml").is_file():
            problem = "is a directory, not a rosbag2 recording: it holds no metadata.yaml"
            raise BagError(path, problem, GIVE_A_BAG)
        return
    if not stat.S_ISREG(mode):
        raise BagError(path, "is not a regular file (a pipe, socket or device)", GIVE_A_BAG)
    if path.name == "metadata.yaml":
        raise BagError(path, "is a rosbag2 recording's metadata", "give its directory instead")
    if path.suffix not in _SUFFIXES:
        problem = (
            f"is not a bag: rosbags reads {', '.join(_SUFFIXES)} files and rosbag2 directories"
        )
        raise BagError(path, problem, GIVE_A_BAG)


def _open(path: Path) -> AnyReader:
    """An open reader of the bag; BagError when rosbags cannot open it."""
    from rosbags.highlevel import AnyReader
    from rosbags.typesys import Stores, get_typestore

    # A .db3 written before ROS 2 Iron holds no message definitions: rosbags then needs the
    # types, and LaserScan is the same in every ROS 2 release.
    try:
        reader = AnyReader([path], default_typestore=get_typestore(Stores.ROS2_JAZZY))
        reader.open()
    except Exception as error:  # noqa: BLE001  (rosbags's parsers raise anything on damaged bytes)
        raise _unreadable(path, error) from None
    return reader


def _decoded(
    reader: AnyReader, connections: list[Connection], path: Path
) -> Iterator[tuple[int, _LaserScan]]:
    """Each message on `connections` with its log time (ns), as the bag logged them."""
    messages = reader.messages(connections)
    while True:
        try:
            item = next(messages, None)
            if item is None:
                return
            connection, log_time, raw = item
            message = reader.deserialize(raw, connection.msgtype)
        except Exception as error:  # noqa: BLE001  (a damaged chunk surfaces only here)
            raise _unreadable(path, error) from None
        yield log_time, cast(_LaserScan, message)


def _unreadable(path: Path, error: Exception) -> BagError:
    """Why rosbags could not read the bag: it is no bag of its kind, or it is damaged."""
    said = f"(rosbags: {str(error) or type(error).__name__})"
    if isinstance(error, PermissionError):
        return BagError(path, "cannot be read: permission denied", "let this user read it")
    files = sorted(path.glob("*")) if path.is_dir() else [path]
    stored = [item for item in files if item.suffix in _MAGIC]
    strangers = [item for item in stored if not _starts_as_its_kind(item)]
    if strangers or not stored:
        kind = _SUFFIXES.get(strangers[0].suffix, "a bag") if strangers else "a bag"
        named = f" ({strangers[0].name})" if strangers and strangers[0] != path else ""
        return BagError(path, f"is not {kind}{named}: it does not start as one {said}", GIVE_A_BAG)
    return BagError(
        path,
        f"is damaged or cut short (a recording stopped before it was closed?) {said}",
        _MEND[stored[0].suffix],
    )


def _starts_as_its_kind(path: Path) -> bool:
    magic = _MAGIC[path.suffix]
    try:
        with path.open("rb") as file:
            return file.read(len(magic)) == magic
    except OSError:
        return False


def _choose_topic(reader: AnyReader, path: Path, topic: str | None) -> tuple[str, int]:
    """The topic to read and how many messages it holds."""
    types = {name: info.msgtype for name, info in reader.topics.items()}
    scans = sorted(name for name, kind in types.items() if kind == LASERSCAN)
    if topic is None:
        if len(scans) == 1:
            return scans[0], reader.topics[scans[0]].msgcount
        raise _no_single_topic(path, scans, types)
    if topic not in types:
        close = get_close_matches(topic, scans, n=1, cutoff=0.5)
        hint = f"did you mean {close[0]}? " if close else ""
        problem = f"has no topic {topic}; {_scan_topics(scans)}"
        raise BagError(path, problem, hint + _name_one(scans), about="topic")
    if types[topic] != LASERSCAN:
        kind = types[topic] or "several types of"  # rosbags's None: connections disagree
        problem = f"the topic {topic} holds {kind} messages, not {LASERSCAN}"
        raise BagError(path, problem, _name_one(scans), about="topic")
    return topic, reader.topics[topic].msgcount


def _no_single_topic(path: Path, scans: list[str], types: dict[str, str | None]) -> BagError:
    if scans:
        problem = f"has several LaserScan topics ({', '.join(scans)}), and none was named"
        return BagError(path, problem, "name the topic to read", about="topic")
    listed = ", ".join(f"{name} ({kind})" for name, kind in sorted(types.items())) or "none"
    return BagError(path, f"has no LaserScan topic; its topics: {listed}", RECORD_ONE)


def _scan_topics(scans: list[str]) -> str:
    return f"its LaserScan topics: {', '.join(scans)}" if scans else "it has no LaserScan topic"


RECORD_ONE = "record the scanner's LaserScan topic (e.g. `ros2 bag record /scan`)"


def _name_one(scans: list[str]) -> str:
    return f"name one of its LaserScan topics: {', '.join(scans)}" if scans else RECORD_ONE


def _laser_scan(path: Path, topic: str, message: _LaserScan, log_time: int) -> Scan:
    """`_scan`, or a BagError where the message is no LaserScan as ROS defines one: a bag
    holds the definition each type was recorded with, and its own may lack a field."""
    try:
        return _scan(message, log_time)
    except (AttributeError, TypeError, ValueError) as error:
        raise BagError(
            path,
            f"a message on {topic} is not a sensor_msgs/msg/LaserScan as ROS defines it, by the "
            f"definition the bag holds ({error})",
            "record the scanner's driver with ROS's own sensor_msgs/msg/LaserScan",
            about="topic",
        ) from None


def _scan(message: _LaserScan, log_time: int) -> Scan:
    """One message, its ranges counted by the values a driver publishes for 'no reading'."""
    ranges = np.asarray(message.ranges, dtype=np.float32)
    at_max = ranges == np.float32(message.range_max)
    stamp = message.header.stamp
    return Scan(
        stamp=int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec),
        log_time=int(log_time),
        beams=len(ranges),
        angle_min=_single(message.angle_min),
        angle_max=_single(message.angle_max),
        angle_increment=_single(message.angle_increment),
        scan_time=_single(message.scan_time),
        range_min=_single(message.range_min),
        range_max=_single(message.range_max),
        readings=Readings(
            nan=int(np.isnan(ranges).sum()),
            inf=int(np.isposinf(ranges).sum()),
            neg_inf=int(np.isneginf(ranges).sum()),
            zero=int((ranges == 0.0).sum()),
            at_range_max=int(at_max.sum()),
        ),
    )


def _single(value: float) -> float:
    """A float32 field as the shortest decimal that is the same float32: -2.3561945, not
    -2.356194496154785, which is what it is as a double."""
    return float(str(np.float32(value)))
