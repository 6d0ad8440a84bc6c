"""The explanation of a witness: which beams of each scan read its obstacle, which meet it nearer
than range_min, and the text that lists them."""

from __future__ import annotations

from pathlib import Path

from pytest_lasertest.model.obstacles import Box
from pytest_lasertest.model.plan import Witness
from pytest_lasertest.model.route import nominal_path
from pytest_lasertest.model.verify import Placement, Scene, Verification
from pytest_lasertest.pairsfile import load_pairs_file
from pytest_lasertest.reports.explain import explain_scans, explain_text
from tests.helpers.texts import SIZE_PAIR

NEAR_PAIR = SIZE_PAIR.replace("range: {max: 10.0}}", "range: {min: 0.5, max: 10.0}}", 1)


def test_beams_that_meet_the_obstacle_before_range_min_are_listed_as_too_near(
    tmp_path: Path,
) -> None:
    pairs = tmp_path / "near.lasertest.yaml"
    pairs.write_text(NEAR_PAIR)
    spec = load_pairs_file(pairs)
    (pair,) = spec.pairs
    robot, world = spec.robot, spec.world
    path = nominal_path(world.start, world.route, robot.nominal_speed, robot.nominal_turn_rate)
    scene = Scene(pair.baseline.profile, pair.candidate.profile, robot, path)
    box = Box(x=0.337 + 0.3, y=0.0, yaw=0.0, length=0.1, width=0.16, height=1.0)
    verification = Verification(0.0, 0.0, 0.0, 0.0, (), 0.0, late=False)
    witness = Witness(0, Placement(box, "baseline-misses", 0.0, 0.0), verification, (0, 0, 0))
    detector, misser, _ = explain_scans(scene, witness)
    assert detector.scanner == "candidate"
    assert [hit.beam for hit in detector.hits] == [7, 8]
    assert (misser.hits, misser.too_near, misser.misses) == ((), (14, 15, 16, 17), 28)
    text = explain_text("size", witness, (detector, misser))
    assert "    beams 7-8 (angles -0.157..0.157 rad): 0.25 m\n" in text
    assert "    nearer than range_min (-inf): beams 14-17\n" in text
