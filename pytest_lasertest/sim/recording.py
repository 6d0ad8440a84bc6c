"""What a recorded run's robot published besides its trajectory: every scan as its driver
published it, and once a simulated second the costmap and the global plan its controller
publishes (if it publishes them), the last at the moment the run was decided. A failure's
artifacts write it out as a rosbag2 (`artifacts/bag.py`) and draw the last costmap."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.model.occupancy import OccupancyGrid
from pytest_lasertest.nav.protocol import LaserScan
from pytest_lasertest.sim.faults import ControllerFault, Faulted, shown
from pytest_lasertest.sim.guard import Guard

# How often the controller's costmap and plan are taken. Often enough to watch a costmap grow in
# RViz or Foxglove; a costmap of the paper's 44 m window is 0.8 MB a message.
SNAPSHOT_PERIOD = 1.0  # s


@dataclass(frozen=True, eq=False)
class Recording:
    """One robot's published messages over a run, in simulated time."""

    scans: tuple[LaserScan, ...]  # as delivered to the controller, stamped
    costmaps: tuple[tuple[float, OccupancyGrid], ...]  # (s, the costmap published then)
    plans: tuple[tuple[float, FloatArray], ...]  # (s, the global plan (N, 2) m, odom frame)

    @property
    def last_costmap(self) -> OccupancyGrid | None:
        """The costmap published when the run was decided, if the controller publishes one."""
        return self.costmaps[-1][1] if self.costmaps else None


@dataclass
class Recorder:
    """Collects a run's messages as it goes: the runner hands it each scan it delivers and asks
    it at each step whether a snapshot is due."""

    guard: Guard
    scans: list[LaserScan] = field(default_factory=list)
    costmaps: list[tuple[float, OccupancyGrid]] = field(default_factory=list)
    plans: list[tuple[float, FloatArray]] = field(default_factory=list)
    _next: float = 0.0  # s, when the next snapshot is due

    def step(self, time: float, delivered: list[LaserScan]) -> None:
        """Keep the scans delivered at `time` s; take the controller's costmap and plan if a
        snapshot is due."""
        self.scans.extend(delivered)
        if time + 1e-9 >= self._next:
            self.snapshot(time)
            self._next += SNAPSHOT_PERIOD

    def snapshot(self, time: float) -> None:
        """The controller's costmap and plan at `time` s, whatever it has of them."""
        costmap = published_costmap(self.guard, time)
        if costmap is not None:
            self.costmaps.append((time, costmap))
        plan = published_plan(self.guard, time)
        if plan is not None:
            self.plans.append((time, plan))

    def finish(self, time: float) -> Recording:
        """The recording, with a last snapshot at `time` s, when the run was decided."""
        self.snapshot(time)
        return Recording(tuple(self.scans), tuple(self.costmaps), tuple(self.plans))


def published_costmap(guard: Guard, time: float) -> OccupancyGrid | None:
    """The costmap the controller publishes, if it has a `published_costmap`: an
    OccupancyGrid, or None while it has none; anything else fails the drive, named."""
    grid = guard.ask("published_costmap", time)
    if grid is None or isinstance(grid, OccupancyGrid):
        return grid
    problem = f"returned {shown(grid)}, not an OccupancyGrid or None"
    fix = "return nav_msgs/OccupancyGrid (nav.protocol.OccupancyGrid), or None before a scan"
    raise Faulted(ControllerFault("published_costmap", time, problem, fix))


def published_plan(guard: Guard, time: float) -> FloatArray | None:
    """The global plan the controller publishes, if it has a `published_plan`: points (N, 2)
    m in the odom frame, or None while it has none; anything else fails the drive, named."""
    plan = guard.ask("published_plan", time)
    if plan is None:
        return None
    try:
        points: FloatArray | None = np.asarray(plan, dtype=float)
    except (TypeError, ValueError):
        points = None
    shaped = points is not None and points.ndim == 2 and points.shape[1] == 2
    if points is not None and shaped and np.isfinite(points).all():
        return points
    problem = f"returned {shown(plan)}, not finite points (N, 2) in m, or None"
    raise Faulted(ControllerFault("published_plan", time, problem, "return an (N, 2) array"))
