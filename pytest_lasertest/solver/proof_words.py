"""A proof in words: what rules out each way a misser scan could miss an obstacle (the unsat
core of `proof.py`'s queries, named), and the proof in one sentence."""

from __future__ import annotations

import math

from pytest_lasertest.model.verify import ROLES, Direction, Scene
from pytest_lasertest.solver.search import SearchSettings

# The label of a block that makes one of the misser's earlier scans miss, before its time (s).
EARLIER = "misser at"


def earlier_label(time: float) -> str:
    """The label of the block that makes the misser's scan at `time` (s) miss."""
    return f"{EARLIER} {time:.3f}"


def why(
    scene: Scene, direction: Direction, settings: SearchSettings, way: str, core: set[str]
) -> str:
    """What rules out one way of missing: its unsat core's blocks in words, or, where no block
    was needed, the scanners' own figures."""
    detector_side, _ = ROLES[direction]
    detector = scene.detector(direction)
    others = [label for label in sorted(core) if label != "misser"]
    # A way with no option: the region, or the detector's own range (scans.miss_ways), left none.
    beyond = (
        f"and the {detector_side}'s ({detector.range_max:g} m) reaches no further"
        if detector.range_max <= scene.misser(direction).range_max
        else "and the robot's way lies within it"
    )
    if not others:
        return {
            "below": f"and the {detector_side}'s ({detector.scan_height:.3f} m) is no lower",
            "beyond": beyond,
            "between": f"and nothing {settings.min_size:g} m wide fits between them where the "
            "robot could meet it",
        }[way]
    return "ruled out by " + " and ".join(_named(scene, direction, settings, others))


def _named(
    scene: Scene, direction: Direction, settings: SearchSettings, labels: list[str]
) -> list[str]:
    """The blocks of an unsat core in words; the misser's earlier scans in one phrase."""
    detector_side, _ = ROLES[direction]
    words = {
        "bounds": f"the obstacle's size ({settings.min_size:g}-{settings.max_size:g} m)",
        "robot": f"room for the robot to stop ({scene.robot.braking_distance:.2f} m)",
        "path": "being in the robot's way",
        "goal": "leaving the goal free",
        "walls": "standing clear of the walls",
        "detector": f"the {detector_side}'s reading",
    }
    earlier = [label.removeprefix(EARLIER).strip() for label in labels if label.startswith(EARLIER)]
    named = [
        words[label] if label in words else _constraint(settings, label)
        for label in labels
        if not label.startswith(EARLIER)
    ]
    if earlier:
        scans = "scan" if len(earlier) == 1 else "scans"
        times = ", ".join(f"{float(time):.2f}" for time in sorted(earlier, key=float))
        named.append(f"its earlier {scans} at t = {times} s, from where the robot was then")
    return named


def _constraint(settings: SearchSettings, label: str) -> str:
    constraint = settings.constraints[int(label.split()[1])]
    return f"your constraint {constraint.text!r} ({constraint.location})"


def sentence(
    scene: Scene, direction: Direction, anchor: float, min_size: float, reasons: dict[str, str]
) -> str:
    """The proof in one short sentence, then way by way what rules each way of missing out."""
    detector_side, misser_side = ROLES[direction]
    misser = scene.misser(direction)
    phrases = {
        "below": f"below its scan plane ({misser.scan_height:.3f} m)",
        "outside": f"outside its field of view ({misser.min_angle:g} to {misser.max_angle:g} rad)",
        "beyond": f"beyond its range ({misser.range_max:g} m)",
        "near": f"nearer than its minimum range ({misser.range_min:g} m)",
        "between": f"between two of its beams ({math.degrees(misser.angle_increment):.3f} deg "
        "apart)",
    }
    where = "at the start pose" if anchor == 0.0 else f"at t = {anchor:.2f} s"
    detector = scene.detector(direction)
    return (
        f"no obstacle discriminates {where}: the {misser_side} reads every obstacle "
        f"{min_size:g} m or wider in the robot's way that the {detector_side} reads. In detail, "
        f"the {misser_side} ({misser.describe()}) misses what the {detector_side} "
        f"({detector.describe()}) reads only "
        + "; ".join(f"{phrases[way]}, {why}" for way, why in reasons.items())
    )
