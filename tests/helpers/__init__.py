"""What several test modules share, apart from fixtures (those are in the conftest.py files):
constants and plain functions, each in the module of its kind.

- `tests.helpers` (here): where the repository, its examples and the test data are;
- `tests.helpers.texts`: the pairs files, robot files and robot descriptions tests write;
- `tests.helpers.runs`: what a pytest run of a pairs file must show, and its JUnit XML;
- `tests.helpers.git`: git repositories made for a test;
- `tests.helpers.model`: scanner profiles and obstacles;
- `tests.helpers.paper`: the paper's pairs file as the solver and the verifier see it;
- `tests.helpers.costmap`: scans fed to a costmap, and the costs read back;
- `tests.helpers.sim`: what the simulator tests share;
- `tests.helpers.upstream`: the upstream tests tests/conformance ports, and their table;
- `tests.helpers.nav2_costmap`, `tests.helpers.ros1_costmap`, `tests.helpers.mppi`,
  `tests.helpers.dwb`, `tests.helpers.laser_filters`: the upstream test harnesses of Nav2's
  costmap, ROS 1's costmap_2d, MPPI, DWB and laser_filters, rebuilt on ours;
- `tests.helpers.nav2_params`: Nav2 params files as tests set them up, nav2_params.yaml with the
  nodes a test is about replaced.

No test module imports another test module or a conftest.py: what they share is here.
"""

from __future__ import annotations

from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"
DATA = REPO / "tests" / "data"
# The example worlds with walls (maps of a doorway and an aisle) that tests drive and plan in.
WORLDS = EXAMPLES / "worlds"
