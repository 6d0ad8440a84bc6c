"""What a placement item's failure report says of a placement both scanners read that the
candidate reads too near (`reports/failure.py`)."""

from __future__ import annotations

import dataclasses

from pytest_lasertest.model.obstacles import Cylinder
from pytest_lasertest.model.verify import Placement, Scene, verify
from pytest_lasertest.reports.failure import margins_text, too_near_lines
from tests.helpers.paper import scene

# Beside the straight route, clear of the Husky, 0.7 m from its scanner's line.
BESIDE = Placement(Cylinder(x=4.0, y=0.9, radius=0.2, height=1.0), None, 4.0, 4.0)


def hidden(range_min: float) -> Scene:
    """The size pair with the candidate's range_min set to `range_min`."""
    size = scene("size")
    return dataclasses.replace(
        size, candidate=dataclasses.replace(size.candidate, range_min=range_min)
    )


def test_the_report_says_when_and_with_which_beams_the_candidate_reads_it_too_near() -> None:
    (line,) = too_near_lines(hidden(0.9), BESIDE.obstacle)
    assert line.startswith("  too near   at t = ")
    assert "read it nearer than range_min 0.9 m (-inf), the baseline in range" in line
    assert "candidate beams " in line


def test_the_margins_name_the_too_near_depth_only_where_it_was_judged() -> None:
    assert "read too near 197.7 mm" in margins_text(verify(hidden(0.9), BESIDE))
    assert "read too near" not in margins_text(verify(hidden(0.1), BESIDE))
    assert "concealment" not in margins_text(verify(hidden(0.9), BESIDE))


def test_no_too_near_line_when_no_scan_of_the_candidate_comes_that_near() -> None:
    assert too_near_lines(hidden(0.5), BESIDE.obstacle) == []
