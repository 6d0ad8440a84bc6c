"""The benchmark scripts stay runnable and keep the last line CI and readers track."""

from __future__ import annotations

import importlib
import re
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest

from tests.helpers import REPO

SOLVER_LINE = re.compile(
    r"ms per witness at 720 beams: [\d.]+; at 2880 beams: [\d.]+; "
    r"speed-up over rejection sampling: \d+"
)
MATRIX_LINE = re.compile(
    r"undecided: (\d+) of (\d+) directions; median plan: \d+ ms; p95 plan: \d+ ms"
)


def printed(*arguments: str) -> list[str]:
    """The lines a benchmark script prints, run with `arguments` from the repository."""
    result = subprocess.run(
        [sys.executable, *arguments], cwd=REPO, capture_output=True, text=True, check=True
    )
    return result.stdout.strip().splitlines()


def test_the_solver_benchmark_runs_and_ends_with_its_figures() -> None:
    lines = printed(
        "benchmarks/solver.py",
        *("--catalogue-pairs", "1", "--budget", "0.2", "--matrix-models", "2"),
    )
    assert SOLVER_LINE.fullmatch(lines[-1])
    # Two models: two ordered pairs, on two routes, in two directions each.
    matrix = MATRIX_LINE.fullmatch(lines[-2])
    assert matrix is not None
    undecided, directions = map(int, matrix.groups())
    assert directions == 8
    assert sum(line.startswith("undecided, ") for line in lines) == undecided
    checked = next(line for line in lines if line.startswith("verified again by ray casting"))
    verified, total = map(int, re.findall(r"\d+", checked))
    assert verified == total > 0


SIM_LINE = re.compile(r"real-time factor: \d+; ratio to bare physics: [\d.]+")


MAP_LINE = re.compile(
    r"map: real-time factor \d+ in the aisle, \d+ on its route without walls; "
    r"a simulated second costs [\d.]+ times as much with the map"
)


def test_the_simulator_benchmark_runs_and_ends_with_its_figures() -> None:
    # Five runs: one in each world, the aisle and its route without walls among them.
    lines = printed("benchmarks/sim.py", "--runs", "5", "--memory-runs", "5")
    assert SIM_LINE.fullmatch(lines[-1])
    assert MAP_LINE.fullmatch(lines[-2])
    assert "0 physics clients left connected" in lines[-3]
    aisle = next(line for line in lines if line.startswith("aisle: "))
    assert aisle.endswith("passed")  # down the aisle to its far end, clear of the racks


NAV_LINE = re.compile(
    r"planning cycle: [\d.]+ ms; ratio to the physics of one control period: [\d.]+"
)


def test_the_navigation_benchmark_runs_and_ends_with_its_figures() -> None:
    lines = printed("benchmarks/nav.py", "--runs", "1")
    assert NAV_LINE.fullmatch(lines[-1])
    assert re.match(r"\d+ costmap updates: [\d.]+ ms; \d+ DWA commands: ", lines[0])


def test_both_benchmarks_time_nav2_with_mppi_and_the_robot_drives() -> None:
    lines = printed("benchmarks/nav.py", "--runs", "1", "--controller", "nav2")
    assert NAV_LINE.fullmatch(lines[-1])
    # MPPI at 20 Hz for the whole 30 s run; the local costmap at 5 Hz.
    assert re.match(r"1[45]\d costmap updates: [\d.]+ ms; 500 MPPI commands: ", lines[0])
    lines = printed(
        "benchmarks/sim.py", "--runs", "1", "--memory-runs", "1", "--controller", "nav2"
    )
    assert SIM_LINE.fullmatch(lines[-1])
    assert "goal not reached: 15." in lines[0]  # 15 m along in 30 s, at MPPI's 0.5 m/s


FAULT_LINE = re.compile(
    r"mutants killed: gate \d+ of \d+, random \d+ of \d+; "
    r"killed cells per 1000 simulations: gate [\d.]+, random [\d.]+"
)


@pytest.mark.parametrize("method", ["random corridor", "random world"])
def test_the_fault_finding_benchmark_runs_and_never_kills_the_equivalent_mutant(
    method: str,
) -> None:
    lines = printed(
        "benchmarks/fault_finding.py",
        *("--seeds", "1", "--jobs", "1", "--mutants", "nan_guard", "--pairs", "slower"),
        *("--random", method),
    )
    assert FAULT_LINE.fullmatch(lines[-1])
    # The equivalent mutant alone: nothing to kill, and no method kills it.
    assert lines[-1].startswith("mutants killed: gate 0 of 0, random 0 of 0")
    rows = [line.split() for line in lines if line.startswith("nan_guard")]
    assert [" ".join(row[1:-3]) for row in rows] == ["gate", method]
    assert all(row[-1] == "-" and row[-3].startswith("0/1") for row in rows)


def test_the_gate_is_charged_the_runs_up_to_its_killing_trial_not_the_shrinking_after(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.syspath_prepend(str(REPO / "benchmarks"))
    fault_finding = importlib.import_module("fault_finding")
    counter = fault_finding.Counter()
    runs = [object() for _ in range(6)]
    counter.made = {id(run): index + 1 for index, run in enumerate(runs)}
    counter.simulations = len(runs)  # the item went on to shrink with runs 5 and 6
    killing = SimpleNamespace(candidate=runs[2], baseline=runs[3])
    assert fault_finding._tried_by(counter, killing, 1) == 4
    # A trial whose runs an earlier item simulated happens within this one, not before it.
    cached = SimpleNamespace(candidate=runs[0], baseline=None)
    assert fault_finding._tried_by(counter, cached, 3) == 3


def test_a_kill_counts_only_if_a_second_draw_of_the_scan_noise_repeats_it(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.syspath_prepend(str(REPO / "benchmarks"))
    fault_finding = importlib.import_module("fault_finding")
    cell = fault_finding.Cell("speckle", "fewer_beams", 1)
    pair = SimpleNamespace(
        candidate=SimpleNamespace(profile="new"), baseline=SimpleNamespace(profile="old")
    )
    drives: list[tuple[str, str, int | None]] = []

    def search(candidate_fails_again: bool) -> SimpleNamespace:
        def drive(profile: str, obstacles: object, controller: str, seed: int | None = None):
            drives.append((profile, controller, seed))
            fails = profile == "new" and controller == "fault"
            again = seed is not None and not candidate_fails_again
            return SimpleNamespace(passed=not fails or again)

        fake = SimpleNamespace(cell=cell, pair=pair, fault="fault", clean="clean", drive=drive)
        fake.kills_again = lambda obstacles: fault_finding.Search.kills_again(fake, obstacles)
        return fake

    failed, passed = SimpleNamespace(passed=False), SimpleNamespace(passed=True)
    assert fault_finding.Search.kills(search(True), (), failed, passed)
    seeds = {seed for _, _, seed in drives if seed is not None}
    assert len(seeds) == 1  # one other draw, for all three checks
    assert cell.seed not in seeds
    assert len(drives) == 4  # the check without the fault, then the three again
    assert not fault_finding.Search.kills(search(False), (), failed, passed)


def test_the_verdicts_benchmark_compares_each_item_across_seeds() -> None:
    harmless = "tests/data/harmless/move_base.lasertest.yaml"
    lines = printed(
        "benchmarks/verdicts.py", harmless, "--seeds", "0,1", "--workers", "1", "-k", "coverage"
    )
    # The harmless changes' coverage items: none loses coverage, under either seed.
    assert lines == [
        f"{harmless}: 3 items; 0 change with the seed; failed in every seed: none; "
        "in some only: none",
        "items whose outcome changes between runs: 0 of 3; failing items: 0 (in every run: 0)",
    ]


def test_the_verdicts_benchmark_runs_a_file_twice_as_ci_does() -> None:
    harmless = "tests/data/harmless/move_base.lasertest.yaml"
    lines = printed(
        "benchmarks/verdicts.py", harmless, "--ci", "2", "--workers", "1", "-k", "coverage"
    )
    assert lines == [
        f"{harmless}: 3 items; 0 change with the run; failed in every run: none; "
        "in some only: none",
        "items whose outcome changes between runs: 0 of 3; failing items: 0 (in every run: 0)",
    ]


VERSUS_LINE = re.compile(r"all drives( +[\d.]+ +[\d.]+ +[\d.]+x){2}")


def test_the_side_by_side_benchmark_finds_a_checkout_drives_as_itself() -> None:
    lines = printed("benchmarks/versus.py", str(REPO), "--rounds", "1", "--seconds", "3")
    assert VERSUS_LINE.fullmatch(lines[-1])
    assert lines[2].startswith("start-up ")
    drives = lines[3:-1]
    assert len(drives) == 12  # four stacks in three worlds
    assert all(line.endswith("x  same") for line in drives)


MAIN_JOB_LINE = re.compile(
    r"main job: \d+ s here \(peak \d+ MB\), \d+ s against (.+) \(ratio [\d.]+\); "
    r"([\d.]+) simulated s in (\d+) drives, bare physics alone ([\d.]+) s"
)


def test_the_main_job_benchmark_times_both_checkouts_and_counts_the_drives() -> None:
    selection = ("examples/paper.lasertest.yaml", "-k", "size and no-obstacle")
    lines = printed("benchmarks/main_job.py", "--warm", "--against", str(REPO), "--", *selection)
    # The control item alone: it passes in both, after driving each robot to the goal.
    assert lines[0].startswith("this checkout: ")
    assert lines[0].endswith("; . 1")
    assert lines[1].startswith(f"{REPO}: ")
    assert lines[1].endswith("; . 1")
    line = MAIN_JOB_LINE.fullmatch(lines[-1])
    assert line is not None
    against, simulated, drives, floor = line.groups()
    assert against == str(REPO)
    assert int(drives) == 2
    assert 10.0 < float(simulated) / 2 < 60.0  # s, each robot's 10 m route within its time limit
    assert 0.0 <= float(floor) < float(simulated)


def test_the_main_job_benchmark_starts_cold_as_a_fresh_clone_does(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.syspath_prepend(str(REPO / "benchmarks"))
    main_job = importlib.import_module("main_job")
    cache = tmp_path / "pytest_lasertest" / "nav" / "__pycache__"
    database = tmp_path / ".hypothesis" / "examples"
    compiled = (cache / "kernels.f-1.py312.nbi", cache / "kernels.f-1.py312.1.nbc")
    for path in (*compiled, database / "k"):
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text("")
    (cache / "kernels.cpython-312.pyc").write_text("")
    main_job.cold_start(tmp_path)
    assert [path.name for path in cache.iterdir()] == ["kernels.cpython-312.pyc"]
    assert not database.exists()
    assert database.parent.exists()
