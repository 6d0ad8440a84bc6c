"""Behaviour of Nav2's DWB critics that no upstream unit test pins down, asserted as the upstream
code computes it (ros-navigation/navigation2 at humble 3c3db59d, nav2_dwb_controller/):

- dwb_critics/src/map_grid.cpp (with costmap_queue/src/costmap_queue.cpp and include/
  costmap_queue/map_based_queue.hpp), path_dist.cpp, goal_dist.cpp, path_align.cpp,
  goal_align.cpp, alignment_util.cpp: the Manhattan-distance grids, unreachable cells, what a
  trajectory's score is made of, on our `dwb_critics` functions (`path_dist`, `goal_dist`,
  `path_align`, `goal_align`, `Frame`) and `dwb.DwbController._scale` (getScale);
- dwb_critics/src/rotate_to_goal.cpp: the window, the slowing down, the rotation, on our
  `dwb_critics.RotateToGoal`;
- dwb_critics/src/oscillation.cpp: the sign flips it forbids and when it forgets them, on our
  `dwb_critics.Oscillation`.

The grids are 12 x 8 cells of 0.1 m from (0, 0), built directly: the critics read whatever grid
they are given. Each expected figure is worked out here from the upstream lines cited, by hand
or, for the distance grid, with a few lines that run the upstream queue; never by calling our
code. These tests port no upstream assertion: they carry no `upstream` mark and do not count in
the conformance table.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt
import pytest

from pytest_lasertest.nav.move_base.cost_values import LETHAL, UNKNOWN
from pytest_lasertest.nav.nav2.dwb import DwbController
from pytest_lasertest.nav.nav2.dwb_critics import (
    Frame,
    Oscillation,
    Pose,
    Rollouts,
    RotateToGoal,
    Scored,
    goal_align,
    goal_dist,
    path_align,
    path_dist,
)
from pytest_lasertest.nav.nav2.mppi import CostGrid

F64 = npt.NDArray[np.float64]
WIDTH, HEIGHT = 12, 8  # cells
RESOLUTION = 0.1  # m
# map_grid.cpp:103-104: obstacle_score_ is the cell count, unreachable_score_ one more.
UNREACHABLE = WIDTH * HEIGHT + 1
# nav2_params.yaml's PathAlign and GoalAlign forward_point_distance.
FORWARD = 0.1  # m


def at(column: float) -> float:
    """The centre (m) of cell `column` (or row) of the 0.1 m grid; halves work as fractions."""
    return (column + 0.5) * RESOLUTION


def grid(costs: dict[tuple[int, int], int] | None = None) -> CostGrid:
    """The free grid with `costs` at cells (column, row)."""
    made = CostGrid(np.zeros((HEIGHT, WIDTH), dtype=np.uint8), (0.0, 0.0), RESOLUTION, False)
    for (column, row), cost in (costs or {}).items():
        made.costs[row, column] = cost
    return made


def plan_through(cells: Sequence[tuple[float, float]]) -> F64:
    """A plan (P, 2) m through the centres of cells (column, row)."""
    return np.array([[at(column), at(row)] for column, row in cells], dtype=np.float64)


def frame(
    costs: CostGrid,
    plan: F64,
    trajectories: Sequence[Sequence[Pose]],
    *,
    pose: Pose = (0.05, 0.05, 0.0),
    goal: tuple[float, float] | None = None,
    vx: Sequence[float] | None = None,
    wz: Sequence[float] | None = None,
) -> Frame:
    """One cycle's frame: trajectories of equal length (poses m, m, rad), commands `vx`, `wz`
    (zeros unless given), the goal at the plan's end unless given."""
    x, y, yaw = (np.array([[p[i] for p in poses] for poses in trajectories]) for i in range(3))
    count = len(trajectories)
    rollouts = Rollouts(
        np.zeros(count) if vx is None else np.array(vx, dtype=np.float64),
        np.zeros(count) if wz is None else np.array(wz, dtype=np.float64),
        x,
        y,
        yaw,
    )
    end = (float(plan[-1, 0]), float(plan[-1, 1])) if goal is None else goal
    return Frame(pose, end, plan, costs, rollouts, (FORWARD, FORWARD))


def ending_at(*cells: tuple[float, float], yaw: float = 0.0) -> list[list[Pose]]:
    """One trajectory per cell (column, row): from the grid's centre to that cell's centre."""
    start: Pose = (at(5.5), at(3.5), yaw)
    return [[start, (at(column), at(row), yaw)] for column, row in cells]


ROW_0 = [(float(column), 0.0) for column in range(WIDTH)]  # the plan along the bottom row


def upstream_queue(sources: Sequence[tuple[int, int]]) -> F64:
    """MapGridCritic's grid (map_grid.cpp:99-115) from source cells (column, row) enqueued in
    order: CostmapQueue (costmap_queue.cpp:60-110, manhattan) pops the last cell of the
    lowest-priority bin (map_based_queue.hpp front/pop), enqueues its unseen neighbours (left,
    down, right, up) with the popped cell's source and their Manhattan distance from it, and the
    popped cell's value is its own distance from its source."""
    values = np.full((HEIGHT, WIDTH), float(UNREACHABLE))
    seen = np.zeros((HEIGHT, WIDTH), dtype=bool)
    bins: dict[int, list[tuple[int, int, int, int]]] = {}

    def enqueue(x: int, y: int, source_x: int, source_y: int) -> None:
        if not seen[y, x]:
            seen[y, x] = True
            distance = abs(x - source_x) + abs(y - source_y)
            bins.setdefault(distance, []).append((x, y, source_x, source_y))

    for x, y in sources:
        values[y, x] = 0.0
        enqueue(x, y, x, y)
    while any(bins.values()):
        x, y, source_x, source_y = bins[min(k for k, cells in bins.items() if cells)].pop()
        for next_x, next_y in ((x - 1, y), (x, y - 1), (x + 1, y), (x, y + 1)):
            if 0 <= next_x < WIDTH and 0 <= next_y < HEIGHT:
                enqueue(next_x, next_y, source_x, source_y)
        values[y, x] = abs(source_x - x) + abs(source_y - y)
    return values


def test_path_dist_counts_manhattan_cells_not_metres_or_euclidean_cells() -> None:
    # map_grid.cpp:108-115 with the Manhattan cache (costmap_queue.cpp:129-130): from a plan of
    # one point at cell (1, 1), cell (4, 5) is 3 + 4 = 7 (Euclidean 5), its own cell 0.
    seen = frame(grid(), plan_through([(1, 1)]), ending_at((4, 5), (1, 1), (11, 7)))
    for scored in (path_dist(seen), goal_dist(seen)):
        assert scored.raw.tolist() == [7.0, 0.0, 16.0]
        assert scored.legal.all()


def test_the_distance_grid_is_what_the_upstream_queue_makes_from_a_zigzag_plan() -> None:
    # Diagonal steps (0.14 m) are below adjustPlanResolution's two cells: no point is added.
    zigzag = [(1, 6), (2, 5), (3, 4), (4, 3), (5, 2), (6, 2), (7, 3), (8, 4), (9, 5), (10, 6)]
    seen = frame(grid(), plan_through(zigzag), ending_at((0, 0)))
    assert np.array_equal(seen.path_distances, upstream_queue(zigzag))


def test_the_last_pose_is_the_score_but_every_pose_must_be_on_the_grid() -> None:
    # map_grid.cpp:128-143 (stop_on_failure, aggregation "last"): every pose is read, the last
    # one's value is the score; scorePose throws for a pose off the grid (:162-165).
    through_top = [(at(5), at(7), 0.0), (at(5), at(2), 0.0)]
    from_below = [(at(5), -0.05, 0.0), (at(5), at(2), 0.0)]
    to_above = [(at(5), at(2), 0.0), (at(5), 0.85, 0.0)]
    seen = frame(grid(), plan_through(ROW_0), [through_top, from_below, to_above])
    scored = path_dist(seen)
    assert scored.legal.tolist() == [True, False, False]
    assert scored.raw[0] == 2.0


def test_the_distances_run_through_lethal_and_unknown_cells() -> None:
    # MapGridQueue::validCellToQueue accepts every cell (map_grid.cpp:53-56) and no critic here
    # calls setAsObstacle: a lethal row and an unknown cell between the plan and the pose
    # lengthen nothing, and a trajectory across them is not PathDist's to forbid.
    walls = {(column, 3): LETHAL for column in range(WIDTH)} | {(5, 4): UNKNOWN}
    across = [(at(5), at(1), 0.0), (at(5), at(3), 0.0), (at(5), at(6), 0.0)]
    scored = path_dist(frame(grid(walls), plan_through(ROW_0), [across]))
    assert scored.legal.tolist() == [True]
    assert scored.raw[0] == 6.0


def test_only_the_first_run_of_known_plan_cells_is_the_source() -> None:
    # path_dist.cpp:63-78: points off the grid or on NO_INFORMATION are skipped until the path
    # starts, and end it; goal_dist.cpp:75-90: the local goal is that run's last point. Cell
    # (6, 0) unknown: the sources are cells 0 to 5 of row 0, the local goal (5, 0).
    plan = plan_through([(-2.5, 0.0), (-1.5, 0.0), *ROW_0])  # x = -0.2 and -0.1 m: off
    seen = frame(grid({(6, 0): UNKNOWN}), plan, ending_at((9, 0), (0, 0), (3, 2)))
    assert path_dist(seen).raw.tolist() == [4.0, 0.0, 2.0]
    assert goal_dist(seen).raw.tolist() == [4.0, 5.0, 4.0]


def test_the_local_goal_is_the_last_plan_point_before_the_plan_leaves_the_grid() -> None:
    # goal_dist.cpp:87-89: once the plan has been on the grid, the first point off it ends the
    # search, whatever comes back on after: along row 0, off past column 11, back at (11, 1).
    plan = plan_through([*ROW_0, (12.0, 0.0), (11.0, 1.0)])
    seen = frame(grid(), plan, ending_at((11, 3), (10, 1)))
    assert goal_dist(seen).raw.tolist() == [3.0, 2.0]  # from (11, 0)
    assert path_dist(seen).raw.tolist() == [3.0, 1.0]  # row 0 only, not (11, 1)


def test_with_no_plan_point_on_the_grid_every_cell_is_unreachable() -> None:
    # reset() fills unreachable_score_ (map_grid.cpp:99-106) and prepare fails without a source
    # (path_dist.cpp:79-86, goal_dist.cpp:94-101). PathDist and GoalDist throw on it
    # (stop_on_failure, :134-136); PathAlign and GoalAlign (stop_on_failure false) score it.
    plan = np.array([[-0.5, 0.05], [-0.3, 0.05], [-0.1, 0.05]])
    seen = frame(grid(), plan, ending_at((2, 2), (7, 5)), goal=(3.0, 3.0))
    for forbidding in (path_dist, goal_dist):
        assert not forbidding(seen).legal.any()
    for scoring in (path_align, goal_align):
        scored = scoring(seen)
        assert scored.legal.all()
        assert scored.raw.tolist() == [UNREACHABLE, UNREACHABLE]


def test_path_align_reads_only_the_point_ahead_of_the_last_pose() -> None:
    # path_align.cpp:88-91 scores getForwardPose (alignment_util.cpp: forward_point_distance
    # along the pose's yaw), and with stop_on_failure false and aggregation "last" only the last
    # pose is read (map_grid.cpp:123-125): a first pose off the grid is no matter; a forward
    # point off the grid is (scorePose throws, :162-165).
    down = [(at(3), -0.05, 0.0), (at(3), 0.48, -math.pi / 2)]  # ahead: (0.35, 0.38), cell (3, 3)
    up = [(at(3), at(3), 0.0), (at(3), 0.75, math.pi / 2)]  # ahead: (0.35, 0.85), off the grid
    seen = frame(grid(), plan_through(ROW_0), [down, up], goal=(3.0, 3.0))
    aligned = path_align(seen)
    assert aligned.legal.tolist() == [True, False]
    assert aligned.raw[0] == 3.0
    # PathDist on the same trajectories: the first is off the grid, the second's last pose is
    # at cell (3, 7).
    distance = path_dist(seen)
    assert distance.legal.tolist() == [False, True]
    assert distance.raw[1] == 7.0


def test_goal_align_moves_the_local_goal_along_the_bearing_from_the_robot_to_the_goal() -> None:
    # goal_align.cpp:70-76: the plan's last point moves forward_point_distance along
    # atan2(goal - robot), here (0.4, -0.3) m, so by (0.08, -0.06) m: from (0.55, 0.25) to
    # (0.63, 0.19), cell (6, 1); not down the path's last leg, which would give cell (5, 1).
    plan = plan_through([(1, 5), (2, 5), (3, 5), (4, 5), (5, 5), (5, 4), (5, 3), (5, 2)])
    seen = frame(
        grid(),
        plan,
        [[(0.63, 0.09, math.pi / 2)] * 2, [(at(5), at(0), math.pi / 2)] * 2],
        pose=(at(1), at(5), 0.0),
        goal=(at(5), at(2)),
    )
    assert goal_align(seen).raw.tolist() == [0.0, 1.0]  # ahead: cells (6, 1) and (5, 1)
    assert goal_dist(seen).raw.tolist() == [3.0, 2.0]  # last poses (6, 0) and (5, 0) to (5, 2)


def test_a_moved_local_goal_off_the_grid_falls_back_to_the_plan_point_before_it() -> None:
    # goal_align.cpp:70-76 then goal_dist.cpp:75-90: the robot straight above the goal at
    # (0.55, 0.05) moves it 0.1 m down to y = -0.05, off the grid; the local goal is then the
    # point before, cell (4, 0).
    plan = plan_through([(column, 0) for column in range(6)])
    seen = frame(
        grid(), plan, [[(at(4), 0.12, math.pi / 2)] * 2], pose=(at(5), at(5), 0.0), goal=None
    )
    assert goal_align(seen).raw.tolist() == [2.0]  # ahead: (0.45, 0.22), cell (4, 2)


def scale_of(critic: str, pose: Pose, goal: tuple[float, float]) -> float:
    seen = frame(grid(), plan_through(ROW_0), ending_at((0, 0)), pose=pose, goal=goal)
    return DwbController()._scale(critic, seen)


def test_the_map_grid_scales_are_half_a_cell_times_the_scale() -> None:
    # map_grid.hpp:69: resolution x 0.5 x scale (nav2_params.yaml: PathDist 32, GoalDist 24,
    # GoalAlign 24); BaseObstacle's is its own 0.02.
    far: tuple[Pose, tuple[float, float]] = ((0.0, 0.0, 0.0), (1.0, 0.0))
    assert scale_of("PathDist", *far) == pytest.approx(0.1 * 0.5 * 32.0, rel=1e-12)
    assert scale_of("GoalDist", *far) == pytest.approx(0.1 * 0.5 * 24.0, rel=1e-12)
    assert scale_of("GoalAlign", *far) == pytest.approx(0.1 * 0.5 * 24.0, rel=1e-12)
    assert scale_of("BaseObstacle", *far) == pytest.approx(0.02, rel=1e-12)


def test_path_align_has_no_weight_within_its_forward_point_distance_of_the_goal() -> None:
    # path_align.cpp:65-74 and 79-86: sq_dist > forward_point_distance^2 keeps the scale; at
    # 0.1 m from the goal (0.1 x 0.1 either side) it is zero.
    assert scale_of("PathAlign", (0.0, 0.0, 0.0), (0.1, 0.0)) == 0.0
    assert scale_of("PathAlign", (0.0, 0.0, 0.0), (0.11, 0.0)) == pytest.approx(1.6, rel=1e-12)
    # GoalAlign has no such rule.
    assert scale_of("GoalAlign", (0.0, 0.0, 0.0), (0.1, 0.0)) == pytest.approx(1.2, rel=1e-12)


# RotateToGoal: nav2_params.yaml's xy_goal_tolerance and trans_stopped_velocity 0.25 and
# slowing_factor 5.0. The goal's heading is taken to be the robot's (ours has no goal
# heading; see dwb_critics.RotateToGoal), so every case here has a goal facing as the robot does.


def rotate_to_goal(slowing_factor: float = 5.0) -> RotateToGoal:
    return RotateToGoal(
        xy_goal_tolerance=0.25, trans_stopped_velocity=0.25, slowing_factor=slowing_factor
    )


def commands(vx: Sequence[float], end_yaws: Sequence[float]) -> Frame:
    """Trajectories of commands `vx` whose last poses face `end_yaws`."""
    trajectories = [[(0.0, 0.0, 0.0), (0.0, 0.0, yaw)] for yaw in end_yaws]
    return frame(grid(), plan_through(ROW_0), trajectories, vx=vx)


def legal_raw(scored: Scored) -> list[float | None]:
    """The raw score of each legal trajectory, None for each illegal one (upstream throws
    instead of scoring)."""
    return [
        float(raw) if legal else None for raw, legal in zip(scored.raw, scored.legal, strict=True)
    ]


def test_rotate_to_goal_scores_nothing_outside_the_goal_window() -> None:
    # rotate_to_goal.cpp:89-90, 100-101: 0.26 m from the goal is outside 0.25 m.
    critic = rotate_to_goal()
    critic.prepare((0.0, 0.0, 0.5), (0.3, 0.0), (0.26, 0.0))
    scored = critic.score(commands([0.3, 0.0, -0.2], [0.5, 2.0, -1.0]))
    assert legal_raw(scored) == [0.0, 0.0, 0.0]


def test_in_the_window_while_moving_only_slower_commands_are_legal() -> None:
    # rotate_to_goal.cpp:90 (<=: exactly 0.25 m is in), 102-107: while faster than
    # trans_stopped_velocity, speed^2 >= the robot's (0.3 m/s) throws; the rest score
    # slowing_factor speed^2 + |shortest_angular_distance(end yaw, goal yaw)|.
    critic = rotate_to_goal()
    critic.prepare((0.0, 0.0, 0.5), (0.3, 0.0), (0.25, 0.0))
    scored = critic.score(commands([0.3, 0.2, 0.0, -0.35, -0.2], [0.5, 0.8, 0.2, 0.5, 0.5]))
    expected = [None, 5.0 * 0.04 + 0.3, 0.3, None, 5.0 * 0.04]
    assert legal_raw(scored) == pytest.approx(expected, abs=1e-12)


def test_the_slowing_factor_weighs_the_squared_speed() -> None:
    # rotate_to_goal.cpp:69-71, 107: RotateToGoal.slowing_factor 2.0 in place of 5.0.
    critic = rotate_to_goal(slowing_factor=2.0)
    critic.prepare((0.0, 0.0, 0.0), (0.3, 0.0), (0.1, 0.0))
    scored = critic.score(commands([0.2, 0.1], [0.25, 0.0]))
    assert legal_raw(scored) == pytest.approx([2.0 * 0.04 + 0.25, 2.0 * 0.01], abs=1e-12)


def test_once_stopped_in_the_window_only_rotations_are_legal_scored_by_the_shortest_turn() -> None:
    # rotate_to_goal.cpp:92 (<=: exactly 0.25 m/s counts as stopped), 110-116, 132: any
    # translation throws, either way; a rotation scores |shortest_angular_distance|, across
    # +-pi: from 3.0 to -3.0 rad is 2 pi - 6 = 0.283 rad.
    critic = rotate_to_goal()
    critic.prepare((0.0, 0.0, -3.0), (0.25, 0.0), (0.1, 0.0))
    scored = critic.score(commands([0.0, 0.1, -0.1, 0.0], [3.0, -3.0, -3.0, -2.9]))
    expected = [2.0 * math.pi - 6.0, None, None, 0.1]
    assert legal_raw(scored) == pytest.approx(expected, abs=1e-12)


def test_the_goal_window_and_the_rotating_phase_last_until_reset() -> None:
    # rotate_to_goal.cpp:90, 92 latch in_window_ and rotating_; reset() (:78-82, at setPlan)
    # clears them.
    window = rotate_to_goal()
    window.prepare((0.0, 0.0, 0.0), (0.4, 0.0), (0.2, 0.0))  # in the window, still moving
    window.prepare((0.0, 0.0, 0.0), (0.4, 0.0), (1.0, 0.0))  # out again: still in it
    assert legal_raw(window.score(commands([0.4, 0.3], [0.0, 0.0]))) == [None, 5.0 * 0.09]
    rotating = rotate_to_goal()
    rotating.prepare((0.0, 0.0, 0.0), (0.1, 0.0), (0.2, 0.0))  # in the window and stopped
    rotating.prepare((0.0, 0.0, 0.0), (0.5, 0.0), (1.0, 0.0))  # away and fast: still rotating
    assert legal_raw(rotating.score(commands([0.3, 0.0], [0.0, 0.0]))) == [None, 0.0]
    rotating.reset()
    rotating.prepare((0.0, 0.0, 0.0), (0.5, 0.0), (1.0, 0.0))
    assert legal_raw(rotating.score(commands([0.3, 0.0], [0.0, 0.0]))) == [0.0, 0.0]


# Oscillation: the source defaults (oscillation.cpp:101-115) oscillation_reset_dist 0.05 m,
# oscillation_reset_angle 0.2 rad, x_only_threshold 0.05 m/s; oscillation_reset_time -1 (off).


def oscillation() -> Oscillation:
    return Oscillation(reset_distance=0.05, reset_angle=0.2, x_only_threshold=0.05)


def drive(critic: Oscillation, *cycles: tuple[Pose, tuple[float, float]]) -> None:
    """Cycles of prepare at a pose and debrief with the command chosen there."""
    for pose, command in cycles:
        critic.prepare(pose)
        critic.debrief(command)


def legal(critic: Oscillation, vx: Sequence[float], wz: Sequence[float]) -> list[bool]:
    """Which commands (vx, wz) the critic leaves legal; it scores each legal one 0."""
    trajectories = [[(0.0, 0.0, 0.0)] * 2 for _ in vx]
    scored = critic.score(frame(grid(), plan_through(ROW_0), trajectories, vx=vx, wz=wz))
    assert (scored.raw == 0.0).all()  # oscillation.cpp:231
    return [bool(flag) for flag in scored.legal]


HERE: Pose = (0.0, 0.0, 0.0)


def test_a_flip_from_forward_to_reverse_forbids_forward_and_a_stop_does_not_flip() -> None:
    # oscillation.cpp:63-80: the sign changes only on a nonzero command, and a change from
    # positive to negative sets negative_only_; isOscillating (:82-85) forbids positive x.
    critic = oscillation()
    assert legal(critic, [0.2, 0.0, -0.2], [0.0] * 3) == [True, True, True]
    drive(critic, (HERE, (0.2, 0.0)), (HERE, (0.0, 0.0)))
    assert legal(critic, [0.2, 0.0, -0.2], [0.0] * 3) == [True, True, True]
    drive(critic, (HERE, (-0.2, 0.0)))
    assert legal(critic, [0.2, 0.0, -0.2], [0.0] * 3) == [False, True, True]


def test_a_second_flip_forbids_both_directions() -> None:
    # oscillation.cpp:66-77: positive_only_ and negative_only_ both set: only x = 0 is legal.
    critic = oscillation()
    drive(critic, (HERE, (0.2, 0.0)), (HERE, (-0.2, 0.0)), (HERE, (0.2, 0.0)))
    assert legal(critic, [0.2, 0.0, -0.2], [0.0] * 3) == [False, True, False]


def test_turn_flips_count_only_while_x_is_within_x_only_threshold() -> None:
    # oscillation.cpp:215-218: the theta trend is updated only if |x| <= x_only_threshold.
    fast = oscillation()
    drive(fast, (HERE, (0.1, 0.5)), (HERE, (0.1, -0.5)))
    assert legal(fast, [0.0, 0.0], [0.5, -0.5]) == [True, True]
    slow = oscillation()
    drive(slow, (HERE, (0.05, 0.5)), (HERE, (0.05, -0.5)))
    assert legal(slow, [0.0, 0.0], [0.5, -0.5]) == [False, True]


def test_the_flags_are_lifted_after_the_cycle_the_robot_has_moved_past_the_reset_distance() -> None:
    # oscillation.cpp:160-173, 178-185: at each debrief, sq_dist from the pose of the last flip
    # > oscillation_reset_dist^2 resets; 0.05 m is not past 0.05 m. The check is in debrief,
    # after the cycle's scoring: the cycle at 0.06 m still forbids, the next does not.
    critic = oscillation()
    drive(critic, (HERE, (0.2, 0.0)), (HERE, (-0.2, 0.0)), ((0.05, 0.0, 0.0), (-0.2, 0.0)))
    assert legal(critic, [0.2], [0.0]) == [False]
    critic.prepare((0.06, 0.0, 0.0))
    assert legal(critic, [0.2], [0.0]) == [False]
    critic.debrief((-0.2, 0.0))
    assert legal(critic, [0.2], [0.0]) == [True]


def test_the_reset_angle_is_the_raw_difference_of_the_yaws() -> None:
    # oscillation.cpp:186-190: fabs(theta - theta at the flip) > oscillation_reset_angle, not
    # normalised: from 3.1 to -3.1 rad (a turn of 0.08 rad) is 6.2 and resets; a real turn of
    # 0.15 rad does not.
    across = oscillation()
    drive(across, ((0.0, 0.0, 3.1), (0.2, 0.0)), ((0.0, 0.0, 3.1), (-0.2, 0.0)))
    drive(across, ((0.0, 0.0, -3.1), (-0.2, 0.0)))
    assert legal(across, [0.2], [0.0]) == [True]
    turned = oscillation()
    drive(turned, (HERE, (0.2, 0.0)), (HERE, (-0.2, 0.0)), ((0.0, 0.0, 0.15), (-0.2, 0.0)))
    assert legal(turned, [0.2], [0.0]) == [False]
    drive(turned, ((0.0, 0.0, 0.21), (-0.2, 0.0)))
    assert legal(turned, [0.2], [0.0]) == [True]


def test_a_flip_far_from_the_last_one_moves_the_reset_point_before_the_reset_check() -> None:
    # oscillation.cpp:162-173: setOscillationFlags' flip stores the pose first, then
    # resetAvailable compares the pose with itself: a flip 1 m from the first keeps both flags.
    critic = oscillation()
    drive(critic, (HERE, (0.2, 0.0)), (HERE, (-0.2, 0.0)), ((1.0, 0.0, 0.0), (0.2, 0.0)))
    assert legal(critic, [0.2, 0.0, -0.2], [0.0] * 3) == [False, True, False]
