"""The pairs files, robot files and robot descriptions tests write, and writing them."""

from __future__ import annotations

from pathlib import Path

# The paper's size pair on a 6 m run, one witness per direction: cheap to plan.
SIZE_PAIR = """\
robot: husky
world:
  start: {x: 0.0, y: 0.0, yaw: 0.0}
  goal: {x: 6.0, y: 0.0}
  time_limit: 60.0
settings:
  min_obstacle_size: 0.0507
  witnesses: 1
pairs:
  size:
    baseline: {model: clearpath_lms1xx_gazebo, samples: 32, range: {max: 10.0}}
    candidate: {model: clearpath_lms1xx_gazebo, samples: 16, range: {max: 10.0}}
"""

# Line numbers matter: tests that break a field assert the line it is on.
VALID_PAIRS = """\
robot: husky
world:
  start: {x: 0.0, y: 0.0, yaw: 0.0}
  goal: {x: 9.0, y: 0.0}
  time_limit: 60.0
settings:
  min_obstacle_size: 0.05
constraints:
  - "x > 1"
pairs:
  to_lms111:
    baseline:
      samples: 720
      min_angle: -1.57
      max_angle: 1.57
      range: {min: 0.1, max: 10.0}
      update_rate: 50
    candidate:
      model: sick_lms111
  same:
    baseline: {model: hokuyo_ust_10lx}
    candidate: {model: hokuyo_ust_10lx, noise: {stddev: 0.01}}
"""

# One 2 m wall 4 m beside a goal 6 m ahead, the Jackal under its bundled Nav2 parameters (issue
# 46): drawn round the wall alone, the map left the start and the goal off it, unknown space to
# the stacks, and the Jackal circled its goal.
WALL_BESIDE_THE_GOAL = """\
robot: jackal
controller: nav2
world:
  start: {x: 0.0, y: 0.0, yaw: 0.0}
  goal: {x: 6.0, y: 0.0}
  time_limit: 60.0
  walls:
    - {x: 6.0, y: 4.0, length: 2.0, width: 0.2, height: 2.0}
pairs:
  longer: {baseline: {model: hokuyo_ust_10lx}, candidate: {model: hokuyo_ust_20lx}}
"""

# One valid pair; tests append a line to it (`controller:` goes on line 5).
GOOD_PAIRS = """\
robot: husky
world: {start: {x: 0, y: 0}, goal: {x: 5, y: 0}, time_limit: 30}
pairs:
  longer: {baseline: {model: hokuyo_ust_10lx}, candidate: {model: hokuyo_ust_20lx}}
"""


# A pair that differs only in samples, and one that does not differ at all; one witness each.
PLACEMENT_PAIRS = (
    SIZE_PAIR
    + """\
  same:
    baseline: {model: clearpath_lms1xx_gazebo, samples: 32}
    candidate: {model: clearpath_lms1xx_gazebo, samples: 32, noise: {stddev: 0.02}}
"""
)

# A robot file of the user's own, as robots/mybot/robot.yaml next to a pairs file.
MY_ROBOT = """\
name: My bot
laser_mount: {xyz: [0.2, 0, 0.3], rpy: [0, 0, 0]}
footprint: [[-0.3, -0.2], [0.3, -0.2], [0.3, 0.2], [-0.3, 0.2]]
max_linear_velocity: 0.8
max_linear_acceleration: 1.5
max_angular_velocity: 1.2
max_angular_acceleration: 3.0
body: {height: 0.3}
"""


# A robot description with one laser, and a pairs file that reads it at HEAD and in the
# working tree.
ROBOT = """\
<?xml version="1.0"?>
<robot name="r">
  <link name="base_footprint"/>
  <link name="base_link"/>
  <joint name="base_joint" type="fixed">
    <parent link="base_footprint"/>
    <child link="base_link"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/>
  </joint>
  <link name="laser"/>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/>
    <child link="laser"/>
    <origin xyz="0.3 0 0.2" rpy="0 0 0"/>
  </joint>
  <gazebo reference="laser">
    <sensor type="ray" name="front">
      <update_rate>20</update_rate>
      <ray>
        <scan><horizontal>
          <samples>32</samples>
          <min_angle>-1.57</min_angle>
          <max_angle>1.57</max_angle>
        </horizontal></scan>
        <range><min>0.1</min><max>10.0</max></range>
      </ray>
    </sensor>
  </gazebo>
</robot>
"""

PAIRS = """\
robot: husky
world: {start: {x: 0, y: 0}, goal: {x: 6, y: 0}, time_limit: 30}
pairs:
  swap:
    baseline: {urdf: robot.urdf, ref: HEAD}
    candidate: {urdf: robot.urdf}
"""


# robot.urdf.xacro, whose laser macro lives in package `lidars` (front.xacro).
XACRO_ROBOT = """\
<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="laser_enabled" default="0"/>
  <xacro:include filename="$(find lidars)/front.xacro"/>
  <link name="base_footprint"/>
  <xacro:if value="$(arg laser_enabled)">
    <xacro:front_laser parent="base_footprint"/>
  </xacro:if>
</robot>
"""

XACRO_LIDAR = """\
<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="front_laser" params="parent samples:=64">
    <link name="laser"/>
    <joint name="laser_joint" type="fixed">
      <parent link="${parent}"/><child link="laser"/>
      <origin xyz="0.2 0 0.4" rpy="${pi} 0 0"/>
    </joint>
    <gazebo reference="laser">
      <sensor type="gpu_ray" name="front">
        <update_rate>10</update_rate>
        <ray>
          <scan><horizontal>
            <samples>${samples}</samples><min_angle>-2</min_angle><max_angle>2</max_angle>
          </horizontal></scan>
          <range><min>0.2</min><max>12</max></range>
        </ray>
      </sensor>
    </gazebo>
  </xacro:macro>
</robot>
"""


def write(directory: Path, text: str, name: str = "gate.lasertest.yaml") -> Path:
    """`text` written as `name` in `directory`, which is made if need be."""
    directory.mkdir(parents=True, exist_ok=True)
    path = directory / name
    path.write_text(text)
    return path
