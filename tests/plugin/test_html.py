"""pytest-html: a failing item's picture shown inline in the HTML report, and a link to each of
its other artifacts, written beside the report when --laser-artifacts names no directory."""

from __future__ import annotations

import html
import json
import re
from pathlib import Path

import pytest

RUN = ("-k", "distance and no-obstacle", "--laser-seed=1", "--laser-profile=ci")


def results(report: Path) -> list[dict[str, object]]:
    """pytest-html's test results, from the JSON its page renders."""
    blob = re.search(r'data-jsonblob="([^"]*)"', report.read_text())
    assert blob is not None
    found: list[dict[str, object]] = json.loads(html.unescape(blob[1]))["tests"][
        "examples/paper.lasertest.yaml::distance[no-obstacle]"
    ]
    return found


def test_a_failing_item_s_picture_is_inline_in_the_html_report_with_links_to_the_rest(
    pytester: pytest.Pytester, paper: Path
) -> None:
    (pytester.path / "examples").mkdir()
    paper.rename(pytester.path / "examples" / paper.name)
    result = pytester.runpytest(*RUN, "--laser-artifacts=out", "--html=report.html")
    result.assert_outcomes(failed=1)
    (call,) = [entry for entry in results(pytester.path / "report.html") if entry["extras"]]
    extras = {str(extra["name"]): extra for extra in call["extras"]}  # type: ignore[union-attr]
    picture = extras["distance_no-obstacle.png"]
    assert picture["format_type"] == "image"
    # Shown from the report's own assets: the artifact's picture, byte for byte.
    shown = pytester.path / str(picture["content"])
    drawn = pytester.path / "out/examples/paper.lasertest.yaml/distance_no-obstacle.png"
    assert shown.read_bytes() == drawn.read_bytes()
    links = {name: extra["content"] for name, extra in extras.items() if name != picture["name"]}
    assert links == {
        name: (drawn.parent / name).resolve().as_uri()
        for name in (
            "distance_no-obstacle.world",
            "distance_no-obstacle.json",
            "distance_no-obstacle",  # the rosbag2's directory
        )
    }


def test_without_laser_artifacts_the_html_report_shows_pictures_written_beside_it(
    pytester: pytest.Pytester, paper: Path
) -> None:
    (pytester.path / "examples").mkdir()
    paper.rename(pytester.path / "examples" / paper.name)
    result = pytester.runpytest(*RUN, "--html=reports/report.html")
    result.assert_outcomes(failed=1)
    beside = pytester.path / "reports/.lasertest-artifacts/examples/paper.lasertest.yaml"
    result.stdout.fnmatch_lines([f"lasertest: * artifacts in {beside.parents[1]}"])
    (call,) = [entry for entry in results(pytester.path / "reports/report.html") if entry["extras"]]
    names = {str(extra["name"]) for extra in call["extras"]}  # type: ignore[union-attr]
    assert "distance_no-obstacle.png" in names
    assert (beside / "distance_no-obstacle.png").is_file()
    # A repro written there (as a placement item's is) is not collected by the next run.
    repro = beside / "size_candidate-misses-0.lasertest.yaml"
    repro.write_text((pytester.path / "examples" / paper.name).read_text())
    assert "::size[" not in pytester.runpytest("--collect-only", "-q", "reports").stdout.str()
    assert "::size[" in pytester.runpytest("--collect-only", "-q", str(repro)).stdout.str()
