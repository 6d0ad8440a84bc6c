"""The bundled examples: the paper's downgrades fail on the attribute each one changed, and the
16-beam robot of the paper's size pair drives into the thin pole the 32-beam robot passes."""

from __future__ import annotations

import shutil

import pytest

from tests.conftest import EXAMPLES


def test_the_examples_fail_on_each_downgrade_and_pass_the_upgrade(
    pytester: pytest.Pytester,
) -> None:
    shutil.copytree(EXAMPLES, pytester.path / "examples")
    result = pytester.runpytest("examples", "-rA", "--laser-seed=1")
    failed = {line.split()[1] for line in result.stdout.lines if line.startswith("FAILED ")}
    assert {item for item in failed if not item.endswith("[coverage]")} == {
        # The 16-beam robot drives into the thin pole; the 32-beam robot passes it.
        "examples/paper.lasertest.yaml::size[candidate-misses-1]",
        # Boxes and a pole 0.328 m high on the last leg: below the TiM571's raised scan plane
        # (0.408 m), so the candidate drives into each; the LMS111 reads them and passes.
        *(
            f"examples/husky.lasertest.yaml::lms111_to_tim571_raised[candidate-misses-{index}]"
            for index in range(3)
        ),
    }
    result.stdout.fnmatch_lines(
        [
            "PASSED examples/husky.lasertest.yaml::ust10_to_ust20[[]coverage[]]",
            "PASSED examples/paper.lasertest.yaml::size[[]no-obstacle[]]",
            "PASSED examples/paper.lasertest.yaml::size[[]candidate-misses-0[]]",
            "PASSED examples/paper.lasertest.yaml::size[[]baseline-misses-0[]]",
        ]
    )
    result.stdout.fnmatch_lines(
        [
            "*_ size[[]candidate-misses-1[]] _*",
            "the candidate fails where witness candidate-misses-1 stands: *",
            "  obstacle   cylinder of radius 0.025 m at *",
            "  baseline   clearpath_lms1xx_gazebo: passed: *",
            "  candidate  clearpath_lms1xx_gazebo: FAILED: collided at t = * s; *",
        ]
    )
    output = result.stdout.str()
    for pair, loss in [
        ("blind_spot", "    field of view: 3.14 -> 2 rad; no longer scans [-1.570, -1.000] rad"),
        (
            "distance",
            "    range.max: 10 -> 5 m; obstacles between 5.00 and 10.00 m are no longer seen",
        ),
        (
            "size",
            "    beam spacing: 0.10129 -> 0.209333 rad; a 0.051 m wide obstacle is sure to be",
        ),
        ("lms111_to_tim571_raised", "    update_rate: 50 -> 15 Hz; a scan every 66.7 ms"),
        ("lms111_to_tim571_raised", "    scan height: 0.30795 -> 0.40795 m; scan plane raised"),
    ]:
        section = output.split(f" {pair}[coverage] ")[1]
        assert loss in section.split("  other changes:")[0].split("  replay")[0]
