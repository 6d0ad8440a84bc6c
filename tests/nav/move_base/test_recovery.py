"""move_base's recovery behaviours: rotate_recovery, our back-up, and clear_costmap_recovery."""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
import pytest

from pytest_lasertest.model.geometry import FloatArray
from pytest_lasertest.nav.move_base.cost_values import FREE, LETHAL, UNKNOWN
from pytest_lasertest.nav.move_base.costmap import Costmap, CostmapSettings
from pytest_lasertest.nav.move_base.recovery import (
    BackUp,
    ClearCostmap,
    Pose,
    RotateInPlace,
    RotateSettings,
)

Mask = npt.NDArray[np.bool_]
Command = tuple[float, float]
RATE = 50.0  # Hz, how often the simulated robot asks for a command
DT = 1.0 / RATE  # s


def always_clear(poses: FloatArray) -> bool:
    return True


def wrapped(angle: float) -> float:
    """An angle as odometry reports it, in [-pi, pi]."""
    return math.atan2(math.sin(angle), math.cos(angle))


def spin(rotate: RotateInPlace, start: Pose, limit: float = 30.0) -> tuple[float, list[Command]]:
    """Drive `rotate` to its end, integrating the commanded turn rate at 50 Hz; the yaw (rad)
    turned in all, unwrapped, and every command it gave."""
    turned, time = 0.0, 0.0
    commands: list[Command] = []
    while time < limit:
        pose = (start[0], start[1], wrapped(start[2] + turned))
        command = rotate.step(pose, time)
        if command is None:
            return turned, commands
        commands.append(command)
        turned += command[1] * DT
        time += DT
    raise AssertionError(f"still turning after {limit} s, {turned} rad")


# --- RotateInPlace: rotate_recovery ---


@pytest.mark.parametrize("start_yaw", [0.3, 3.0, -2.0], ids=["0.3", "3.0", "-2.0"])
def test_rotate_in_place_turns_counter_clockwise_once_round_and_then_ends(
    start_yaw: float,
) -> None:
    settings = RotateSettings()
    turned, commands = spin(RotateInPlace(always_clear), (1.0, 2.0, start_yaw))
    # It stops once back within tolerance (0.1 rad) of where it began: not before, not past.
    assert 2.0 * math.pi - settings.tolerance <= turned <= 2.0 * math.pi
    assert all(linear == 0.0 and angular > 0.0 for linear, angular in commands)
    # At 1 rad/s most of the way, slowing down only for the last few tenths of a radian.
    duration = len(commands) * DT
    assert (2.0 * math.pi - settings.tolerance) / settings.max_rotational_vel <= duration < 7.0


def test_rotate_in_place_ends_at_once_when_the_rest_of_the_turn_would_collide() -> None:
    seen: list[FloatArray] = []

    def blocked(poses: FloatArray) -> bool:
        seen.append(poses.copy())
        return False

    assert RotateInPlace(blocked).step((1.0, 2.0, 0.3), 0.0) is None
    assert len(seen) == 1


def test_rotate_in_place_checks_the_footprint_along_all_the_rest_of_its_turn() -> None:
    seen: list[FloatArray] = []

    def record(poses: FloatArray) -> bool:
        seen.append(poses.copy())
        return True

    rotate = RotateInPlace(record)
    assert rotate.step((1.0, 2.0, 0.3), 0.0) is not None
    poses = seen[0]
    # At the robot's position, from its yaw round a full turn, every sim_granularity rad.
    np.testing.assert_allclose(poses[:, :2], np.tile([1.0, 2.0], (len(poses), 1)))
    steps = np.diff(poses[:, 2])
    np.testing.assert_allclose(steps, RotateSettings().sim_granularity)
    assert poses[0, 2] == pytest.approx(0.3)
    assert 0.3 + 2.0 * math.pi - poses[-1, 2] <= RotateSettings().sim_granularity


def test_rotate_in_place_gives_up_for_a_collision_only_near_the_end_of_its_turn() -> None:
    """rotate_recovery checks the whole turn left before each command, so an obstacle the
    footprint would sweep three quarters of the way round stops it before it starts."""

    def clear_until_three_quarters(poses: FloatArray) -> bool:
        turned = np.mod(poses[:, 2] - 0.3, 2.0 * math.pi)
        return not bool(((turned > 4.6) & (turned < 4.8)).any())

    assert RotateInPlace(clear_until_three_quarters).step((0.0, 0.0, 0.3), 0.0) is None


def test_rotate_in_place_stops_at_its_next_decision_once_the_turn_left_is_blocked() -> None:
    blocked = False

    def clear(poses: FloatArray) -> bool:
        return not blocked

    rotate, turned, time = RotateInPlace(clear), 0.0, 0.0
    while turned < 2.0:
        command = rotate.step((0.0, 0.0, wrapped(0.3 + turned)), time)
        assert command is not None
        turned, time = turned + command[1] * DT, time + DT
    blocked = True  # say something moved into the way of the rest of the turn
    answers: list[Command | None] = []
    for _ in range(6):
        answers.append(rotate.step((0.0, 0.0, wrapped(0.3 + turned)), time))
        time += DT
    # Its next decision, at most 1 / 20 Hz later (the third call at 50 Hz), is to stop; and
    # it stays stopped.
    first = answers.index(None)
    assert first <= 2
    assert all(answer is None for answer in answers[first:])
    assert turned < math.pi


def _speed(settings: RotateSettings, left: float) -> float:
    speed = math.sqrt(2.0 * settings.acc_lim_th * left)
    return min(max(speed, settings.min_in_place_rotational_vel), settings.max_rotational_vel)


# A robot that turns on the spot at 0.05 rad/s^2 and up to 10 rad/s: the square root unclamped.
GENTLE = RotateSettings(acc_lim_th=0.05, max_rotational_vel=10.0, min_in_place_rotational_vel=0.01)


@pytest.mark.parametrize(
    ("settings", "turned", "left"),
    [
        (GENTLE, [0.0], 2.0 * math.pi),
        (GENTLE, [0.0, 1.0], 2.0 * math.pi - 1.0),
        (GENTLE, [0.0, math.pi], math.pi),  # half way round
        (GENTLE, [0.0, math.pi, 2.0 * math.pi - 0.5], 0.5),
        (RotateSettings(), [0.0], 2.0 * math.pi),  # clamped to max_rotational_vel 1 rad/s
        (RotateSettings(), [0.0, math.pi, 2.0 * math.pi - 0.12], 0.12),  # 0.88 rad/s
        (RotateSettings(acc_lim_th=0.5), [0.0, math.pi, 2.0 * math.pi - 0.12], 0.12),  # 0.4
    ],
)
def test_rotate_in_place_turns_at_the_speed_that_stops_it_where_it_began(
    settings: RotateSettings, turned: list[float], left: float
) -> None:
    rotate = RotateInPlace(always_clear, settings)
    command: tuple[float, float] | None = None
    for call, angle in enumerate(turned):
        # A second apart: each call is a new decision at its 20 Hz.
        command = rotate.step((0.0, 0.0, wrapped(0.7 + angle)), float(call))
    assert command is not None
    assert command[0] == 0.0
    assert command[1] == pytest.approx(_speed(settings, left))


def test_rotate_in_place_holds_its_command_between_its_20_hz_decisions() -> None:
    rotate = RotateInPlace(always_clear, GENTLE)
    first = rotate.step((0.0, 0.0, 0.0), 0.0)
    assert rotate.step((0.0, 0.0, 1.0), 0.04) == first  # before 1 / 20 Hz: no new decision
    later = rotate.step((0.0, 0.0, 1.0), 0.05)
    assert later is not None
    assert first is not None
    assert later[1] < first[1]


# --- BackUp ---


def back_up(behaviour: BackUp, start: Pose, limit: float = 30.0) -> tuple[Pose, list[Command]]:
    """Drive `behaviour` to its end at 50 Hz; where it ended and every command it gave."""
    x, y, yaw = start
    time = 0.0
    commands: list[Command] = []
    while time < limit:
        command = behaviour.step((x, y, yaw), time)
        if command is None:
            return (x, y, yaw), commands
        commands.append(command)
        x += command[0] * math.cos(yaw) * DT
        y += command[0] * math.sin(yaw) * DT
        yaw += command[1] * DT
        time += DT
    raise AssertionError(f"still backing up after {limit} s")


def test_back_up_reverses_at_its_speed_until_it_has_covered_its_distance() -> None:
    start = (1.0, 2.0, 0.5)
    end, commands = back_up(BackUp(always_clear, distance=0.5, speed=0.1), start)
    assert commands
    assert all(command == (-0.1, 0.0) for command in commands)
    covered = math.dist(start[:2], end[:2])
    assert 0.5 <= covered <= 0.5 + 0.1 * DT + 1e-9
    # Straight back: against its heading.
    heading = (math.cos(0.5), math.sin(0.5))
    backwards = ((end[0] - start[0]) * heading[0] + (end[1] - start[1]) * heading[1]) / covered
    assert backwards == pytest.approx(-1.0)
    assert len(commands) * DT == pytest.approx(5.0, abs=2 * DT)


def test_back_up_stops_at_once_when_the_way_back_is_not_clear() -> None:
    start = (1.0, 2.0, 0.5)
    # An obstacle 0.3 m straight behind.
    behind = (start[0] - 0.3 * math.cos(0.5), start[1] - 0.3 * math.sin(0.5))

    def clear_of_behind(poses: FloatArray) -> bool:
        return bool((np.hypot(poses[:, 0] - behind[0], poses[:, 1] - behind[1]) > 0.05).all())

    assert BackUp(clear_of_behind, distance=0.5, speed=0.1).step(start, 0.0) is None
    # Backing up only 0.2 m, the way back stops short of it.
    end, _ = back_up(BackUp(clear_of_behind, distance=0.2, speed=0.1), start)
    assert math.dist(start[:2], end[:2]) >= 0.2


def test_back_up_checks_the_way_straight_back_as_far_as_is_left_to_go() -> None:
    seen: list[FloatArray] = []

    def record(poses: FloatArray) -> bool:
        seen.append(poses.copy())
        return True

    behaviour = BackUp(record, distance=0.5, speed=0.1)
    heading = (math.cos(0.5), math.sin(0.5))
    start, later = (1.0, 2.0), (1.0 - 0.2 * heading[0], 2.0 - 0.2 * heading[1])
    behaviour.step((*start, 0.5), 0.0)
    behaviour.step((*later, 0.5), 0.1)
    for poses, (x, y), left in zip(seen, [start, later], [0.5, 0.3], strict=True):
        back = -((poses[:, 0] - x) * heading[0] + (poses[:, 1] - y) * heading[1])
        across = (poses[:, 1] - y) * heading[0] - (poses[:, 0] - x) * heading[1]
        np.testing.assert_allclose(across, 0.0, atol=1e-12)
        np.testing.assert_allclose(poses[:, 2], 0.5)
        assert back[0] == pytest.approx(0.0)
        assert left <= back.max() <= left + 0.05
        assert np.diff(back).max() <= 0.025 + 1e-12  # no gap wider than half a cell


# --- ClearCostmap ---


def random_costmap(track_unknown_space: bool, seed: int) -> Costmap:
    settings = CostmapSettings(size=6.0, resolution=0.05, track_unknown_space=track_unknown_space)
    footprint = np.array([[-0.5, -0.3], [0.5, -0.3], [0.5, 0.3], [-0.5, 0.3]])
    costmap = Costmap(settings, footprint)
    rng = np.random.default_rng(seed)
    costmap.grid[:] = rng.choice(
        np.array([FREE, LETHAL, UNKNOWN], dtype=np.uint8), costmap.grid.shape
    )
    return costmap


def inside_square(costmap: Costmap, x: float, y: float, size: float) -> Mask:
    """Which cells [y, x] lie wholly inside the square `size` m wide around (x, y)."""
    resolution = costmap.settings.resolution
    low = costmap.origin[0] + resolution * np.arange(costmap.settings.cells)
    columns = (low > x - size / 2.0) & (low + resolution < x + size / 2.0)
    low = costmap.origin[1] + resolution * np.arange(costmap.settings.cells)
    rows = (low > y - size / 2.0) & (low + resolution < y + size / 2.0)
    inside: Mask = rows[:, np.newaxis] & columns[np.newaxis, :]
    return inside


@pytest.mark.parametrize("track_unknown_space", [True, False], ids=["unknown", "free"])
def test_clear_costmap_forgets_every_cell_outside_the_square_and_keeps_those_inside(
    track_unknown_space: bool,
) -> None:
    costmap = random_costmap(track_unknown_space, seed=3)
    before = costmap.grid.copy()
    pose = (3.013, 2.487, 1.0)
    assert ClearCostmap("conservative_reset", costmap, 3.0).step(pose, 0.0) is None
    inside = inside_square(costmap, pose[0], pose[1], 3.0)
    assert inside.sum() == 59 * 59  # 3 m less the two cells its edges cut
    np.testing.assert_array_equal(costmap.grid[inside], before[inside])
    unseen = UNKNOWN if track_unknown_space else FREE
    assert (costmap.grid[~inside] == unseen).all()
    assert (before[~inside] != unseen).any()
