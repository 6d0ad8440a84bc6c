"""A failure as a rosbag2 in MCAP, to open in Foxglove (the .mcap) or replay into RViz
(`ros2 bag play` on its directory): both robots as their stacks would publish them, in simulated
time.

Written with rosbags, the library the gate already reads recordings with: pure Python, with ROS
2's message definitions built in (Jazzy's), so neither a ROS install nor a second library for
the same format. Topics, each robot's under its role (`baseline`, `candidate`):

- `/tf_static`: base_footprint to the laser frame, both robots' mounts in one message, offered
  with tf2_ros's StaticBroadcasterQoS (transient local, the last message kept), so that RViz
  subscribing after `ros2 bag play` starts still gets both;
- `/tf`: odom to base_footprint, at every physics step (both robots share the world's frame,
  `odom`, as they drove the same world);
- `/<role>/odom` (nav_msgs/Odometry, at every physics step) and `/<role>/scan`
  (sensor_msgs/LaserScan, each scan as its driver published it, stamped as it was);
- `/candidate/global_costmap/costmap` (nav_msgs/OccupancyGrid) and `/candidate/plan`
  (nav_msgs/Path), once a simulated second and when the drive was decided, where its controller
  publishes them (`nav/protocol.py`);
- `/markers` (visualization_msgs/MarkerArray): the obstacle, the walls and both footprints.
"""

from __future__ import annotations

import math
import os
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np

from pytest_lasertest.model.geometry import FloatArray, Pose3D
from pytest_lasertest.model.obstacles import Box, Obstacle
from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.nav.protocol import LaserScan
from pytest_lasertest.sim.scenario import Run

WORLD_FRAME = "odom"
# (s, topic, message type, message): one message of the bag.
Message = tuple[float, str, str, Any]
# RViz's default colours for what stands in the world, and each robot's, as the picture's.
OBSTACLE_RGBA = (0.3, 0.3, 0.3, 1.0)
WALL_RGBA = (0.48, 0.48, 0.48, 1.0)
ROLE_RGBA = {"baseline": (0.12, 0.47, 0.71, 1.0), "candidate": (0.84, 0.15, 0.16, 1.0)}


def write_bag(
    path: Path, runs: dict[str, Run], footprint: FloatArray, solids: tuple[Obstacle, ...]
) -> Path:
    """The recorded runs (by role) as a rosbag2 directory at `path`, its MCAP file named after
    it, with the footprint (V, 2) m and what stands in the world (obstacles, then walls);
    written beside `path` first and renamed, so that no half bag is ever left there."""
    from rosbags.typesys import Stores, get_typestore

    build = _Builder(get_typestore(Stores.ROS2_JAZZY))
    messages = [*build.markers(footprint, solids, tuple(runs)), build.mounts(runs)]
    for role, run in runs.items():
        messages += build.robot(role, run)
    messages.sort(key=lambda message: message[0])
    path.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(dir=path.parent, prefix=f".{path.name}."))
    try:
        _write(staging / path.name, messages, build.typestore)
        if path.exists():
            shutil.rmtree(path)
        os.replace(staging / path.name, path)
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return path


def _write(path: Path, messages: list[Message], typestore: Any) -> None:
    from rosbags.rosbag2 import StoragePlugin, Writer

    writer = Writer(path, version=9, storage_plugin=StoragePlugin.MCAP)
    writer.open()
    try:
        connections: dict[str, Any] = {}
        for time, topic, msgtype, message in messages:
            if topic not in connections:
                connections[topic] = writer.add_connection(
                    topic, msgtype, typestore=typestore, offered_qos_profiles=_offered(topic)
                )
            data = typestore.serialize_cdr(message, msgtype)
            writer.write(connections[topic], round(time * 1e9), data)
    finally:
        writer.close()


def _offered(topic: str) -> tuple[Any, ...]:
    """The QoS a topic's publisher offers, as rosbag2 records it for `ros2 bag play`: for
    /tf_static tf2_ros's StaticBroadcasterQoS (ros2/geometry2 02849c04,
    tf2_ros/include/tf2_ros/qos.hpp: depth 1, transient local, reliable), else none recorded,
    which plays with the player's defaults."""
    if topic != "/tf_static":
        return ()
    from rosbags.interfaces import (
        Qos,
        QosDurability,
        QosHistory,
        QosLiveliness,
        QosReliability,
        QosTime,
    )

    infinite = QosTime(2147483647, 4294967295)  # rosbag2's "infinite" duration
    return (
        Qos(
            QosHistory.KEEP_LAST,
            1,
            QosReliability.RELIABLE,
            QosDurability.TRANSIENT_LOCAL,
            infinite,
            infinite,
            QosLiveliness.AUTOMATIC,
            infinite,
            avoid_ros_namespace_conventions=False,
        ),
    )


class _Builder:
    """ROS 2 messages from the gate's values, in one typestore."""

    def __init__(self, typestore: Any) -> None:
        self.typestore = typestore
        self.types = typestore.types

    def robot(self, role: str, run: Run) -> list[Message]:
        """Everything one robot published over its run."""
        messages = list(self.motion(role, run))
        recording = run.recording
        if recording is None:
            return messages
        messages += [self.scan(role, scan) for scan in recording.scans]
        if role == "candidate":
            messages += [self.costmap(time, grid) for time, grid in recording.costmaps]
            messages += [self.plan(time, points) for time, points in recording.plans]
        return messages

    def mounts(self, runs: dict[str, Run]) -> Message:
        """/tf_static: each robot's base_footprint to its laser frame, in one message, as
        robot_state_publisher sends all of a robot's fixed joints."""
        transforms = [
            self.transform(
                0.0, f"{role}/base_footprint", f"{role}/laser", run.scenario.profile.pose
            )
            for role, run in runs.items()
        ]
        return 0.0, "/tf_static", "tf2_msgs/msg/TFMessage", self._tf(transforms)

    def motion(self, role: str, run: Run) -> Iterator[Message]:
        """/tf and /<role>/odom at every physics step."""
        times, poses = run.times, run.poses
        steps = np.diff(np.r_[0.0, times])
        previous = np.vstack([poses[:1], poses[:-1]])
        moved = poses[:, :2] - previous[:, :2]
        forward = moved[:, 0] * np.cos(poses[:, 2]) + moved[:, 1] * np.sin(poses[:, 2])
        turned = np.angle(np.exp(1j * (poses[:, 2] - previous[:, 2])))
        for time, (x, y, yaw), v, w in zip(
            times, poses, forward / steps, turned / steps, strict=True
        ):
            pose = Pose3D((float(x), float(y), 0.0), (0.0, 0.0, float(yaw)))
            base = f"{role}/base_footprint"
            transform = self.transform(float(time), WORLD_FRAME, base, pose)
            yield float(time), "/tf", "tf2_msgs/msg/TFMessage", self._tf([transform])
            odometry = self.odometry(float(time), base, pose, (float(v), float(w)))
            yield float(time), f"/{role}/odom", "nav_msgs/msg/Odometry", odometry

    def scan(self, role: str, scan: LaserScan) -> Message:
        """/<role>/scan: one scan as its driver published it."""
        meta = scan.meta
        message = self.types["sensor_msgs/msg/LaserScan"](
            header=self.header(scan.stamp, f"{role}/laser"),
            angle_min=meta.angle_min,
            angle_max=meta.angle_max,
            angle_increment=meta.angle_increment,
            time_increment=meta.time_increment,
            scan_time=meta.scan_time,
            range_min=meta.range_min,
            range_max=meta.range_max,
            ranges=np.asarray(scan.ranges, dtype=np.float32),
            intensities=np.zeros(0, dtype=np.float32),
        )
        return scan.stamp, f"/{role}/scan", "sensor_msgs/msg/LaserScan", message

    def costmap(self, time: float, grid: OccupancyGrid) -> Message:
        """/candidate/global_costmap/costmap, as costmap_2d publishes it."""
        types = self.types
        info = types["nav_msgs/msg/MapMetaData"](
            map_load_time=self.stamp(time),
            resolution=grid.resolution,
            width=grid.width,
            height=grid.height,
            origin=self.pose(Pose3D((*grid.origin, 0.0), (0.0, 0.0, 0.0))),
        )
        message = types["nav_msgs/msg/OccupancyGrid"](
            header=self.header(time, WORLD_FRAME), info=info, data=grid.data.ravel()
        )
        topic = "/candidate/global_costmap/costmap"
        return time, topic, "nav_msgs/msg/OccupancyGrid", message

    def plan(self, time: float, points: FloatArray) -> Message:
        """/candidate/plan: the global plan's points."""
        stamped = self.types["geometry_msgs/msg/PoseStamped"]
        poses = [
            stamped(
                header=self.header(time, WORLD_FRAME),
                pose=self.pose(Pose3D((float(x), float(y), 0.0), (0.0, 0.0, 0.0))),
            )
            for x, y in points
        ]
        message = self.types["nav_msgs/msg/Path"](
            header=self.header(time, WORLD_FRAME), poses=poses
        )
        return time, "/candidate/plan", "nav_msgs/msg/Path", message

    def markers(
        self, footprint: FloatArray, solids: tuple[Obstacle, ...], roles: tuple[str, ...]
    ) -> Iterator[Message]:
        """/markers at the start: what stands in the world, and each robot's footprint."""
        markers = [self.solid(index, solid) for index, solid in enumerate(solids)]
        markers += [self.footprint(role, footprint) for role in roles]
        array = self.types["visualization_msgs/msg/MarkerArray"](markers=markers)
        yield 0.0, "/markers", "visualization_msgs/msg/MarkerArray", array

    def solid(self, index: int, solid: Obstacle) -> Any:
        """A box as a CUBE, a cylinder as a CYLINDER, standing on the ground."""
        marker_type = self.types["visualization_msgs/msg/Marker"]
        if isinstance(solid, Box):
            kind, size = marker_type.CUBE, (solid.length, solid.width, solid.height)
        else:
            kind, size = marker_type.CYLINDER, (2 * solid.radius, 2 * solid.radius, solid.height)
        pose = Pose3D((solid.x, solid.y, solid.height / 2.0), (0.0, 0.0, solid.yaw))
        return self.marker(WORLD_FRAME, "world", index, kind, pose, size, OBSTACLE_RGBA, [])

    def footprint(self, role: str, footprint: FloatArray) -> Any:
        """The robot's footprint, a closed line in its base_footprint, moving with it."""
        point = self.types["geometry_msgs/msg/Point"]
        corners = [point(x=float(x), y=float(y), z=0.0) for x, y in footprint]
        kind = self.types["visualization_msgs/msg/Marker"].LINE_STRIP
        frame, origin = f"{role}/base_footprint", Pose3D((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
        width = (0.02, 0.0, 0.0)  # m, a line strip's thickness is its scale's x
        closed = corners + corners[:1]
        return self.marker(frame, "footprint", 0, kind, origin, width, ROLE_RGBA[role], closed)

    def marker(
        self,
        frame: str,
        namespace: str,
        index: int,
        kind: int,
        pose: Pose3D,
        scale: tuple[float, float, float],
        rgba: tuple[float, float, float, float],
        points: list[Any],
    ) -> Any:
        types = self.types
        marker_type = types["visualization_msgs/msg/Marker"]
        return marker_type(
            header=self.header(0.0, frame),
            ns=namespace,
            id=index,
            type=kind,
            action=marker_type.ADD,
            pose=self.pose(pose),
            scale=types["geometry_msgs/msg/Vector3"](x=scale[0], y=scale[1], z=scale[2]),
            color=types["std_msgs/msg/ColorRGBA"](r=rgba[0], g=rgba[1], b=rgba[2], a=rgba[3]),
            lifetime=types["builtin_interfaces/msg/Duration"](sec=0, nanosec=0),
            frame_locked=True,
            points=points,
            colors=[],
            texture_resource="",
            texture=types["sensor_msgs/msg/CompressedImage"](
                header=self.header(0.0, ""), format="", data=np.zeros(0, dtype=np.uint8)
            ),
            uv_coordinates=[],
            text="",
            mesh_resource="",
            mesh_file=types["visualization_msgs/msg/MeshFile"](
                filename="", data=np.zeros(0, dtype=np.uint8)
            ),
            mesh_use_embedded_materials=False,
        )

    def odometry(self, time: float, base: str, pose: Pose3D, twist: tuple[float, float]) -> Any:
        types = self.types
        vector = types["geometry_msgs/msg/Vector3"]
        return types["nav_msgs/msg/Odometry"](
            header=self.header(time, WORLD_FRAME),
            child_frame_id=base,
            pose=types["geometry_msgs/msg/PoseWithCovariance"](
                pose=self.pose(pose), covariance=np.zeros(36)
            ),
            twist=types["geometry_msgs/msg/TwistWithCovariance"](
                twist=types["geometry_msgs/msg/Twist"](
                    linear=vector(x=twist[0], y=0.0, z=0.0),
                    angular=vector(x=0.0, y=0.0, z=twist[1]),
                ),
                covariance=np.zeros(36),
            ),
        )

    def transform(self, time: float, parent: str, child: str, pose: Pose3D) -> Any:
        types = self.types
        x, y, z, w = _quaternion(pose.rpy)
        return types["geometry_msgs/msg/TransformStamped"](
            header=self.header(time, parent),
            child_frame_id=child,
            transform=types["geometry_msgs/msg/Transform"](
                translation=types["geometry_msgs/msg/Vector3"](
                    x=pose.xyz[0], y=pose.xyz[1], z=pose.xyz[2]
                ),
                rotation=types["geometry_msgs/msg/Quaternion"](x=x, y=y, z=z, w=w),
            ),
        )

    def pose(self, pose: Pose3D) -> Any:
        types = self.types
        x, y, z, w = _quaternion(pose.rpy)
        return types["geometry_msgs/msg/Pose"](
            position=types["geometry_msgs/msg/Point"](x=pose.xyz[0], y=pose.xyz[1], z=pose.xyz[2]),
            orientation=types["geometry_msgs/msg/Quaternion"](x=x, y=y, z=z, w=w),
        )

    def header(self, time: float, frame: str) -> Any:
        return self.types["std_msgs/msg/Header"](stamp=self.stamp(time), frame_id=frame)

    def stamp(self, time: float) -> Any:
        nanoseconds = round(time * 1e9)
        return self.types["builtin_interfaces/msg/Time"](
            sec=nanoseconds // 10**9, nanosec=nanoseconds % 10**9
        )

    def _tf(self, transforms: list[Any]) -> Any:
        return self.types["tf2_msgs/msg/TFMessage"](transforms=transforms)


def _quaternion(rpy: tuple[float, float, float]) -> tuple[float, float, float, float]:
    """The quaternion (x, y, z, w) of roll, pitch and yaw (rad), as tf2's setRPY makes it."""
    roll, pitch, yaw = (angle / 2.0 for angle in rpy)
    cr, sr, cp, sp, cy, sy = (
        math.cos(roll),
        math.sin(roll),
        math.cos(pitch),
        math.sin(pitch),
        math.cos(yaw),
        math.sin(yaw),
    )
    return (
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy,
        cr * cp * cy + sr * sp * sy,
    )
