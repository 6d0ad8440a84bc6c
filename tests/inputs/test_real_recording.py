"""A recording made by a real driver: SICK's sick_scan_xd publishing an LMS1xx, a ROS 1 bag from
the driver's own documentation (SICKAG/sick_scan_xd, develop at 2d479669,
doc/combination_rms_1xxx_lms_1xx/rms_1xxx_lms_1xx_movement_off.bag, Apache-2.0). The project does
not carry it: it lies beside the project in ../shared/recordings/, whose README names its source
and its figures; where that folder is absent the test says so and is skipped."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import yaml

from pytest_lasertest.cli import main
from pytest_lasertest.inputs.inferred import profile_from_bag
from pytest_lasertest.pairsfile.bundled import LIDARS_DIR

RECORDINGS = Path(__file__).resolve().parents[3] / "shared" / "recordings"
SICK_BAG = (
    RECORDINGS
    / "sick_scan_xd/develop/doc/combination_rms_1xxx_lms_1xx/rms_1xxx_lms_1xx_movement_off.bag"
)


@pytest.fixture
def sick_bag() -> Path:
    if not SICK_BAG.is_file():
        pytest.skip(f"the real driver's recording is not at {SICK_BAG}")
    return SICK_BAG


def test_an_lms1xx_recorded_by_sick_scan_xd_gives_the_catalogues_lms111_and_its_driver(
    sick_bag: Path,
) -> None:
    found = profile_from_bag(sick_bag, "/sick_lms_1xx/scan")
    catalogued = yaml.safe_load((LIDARS_DIR / "sick_lms111.yaml").read_text())
    profile = found.profile
    assert found.messages == 89
    assert profile.samples == catalogued["samples"] == 541
    assert math.isclose(profile.min_angle, catalogued["min_angle"], abs_tol=1e-6)
    assert math.isclose(profile.max_angle, catalogued["max_angle"], abs_tol=1e-6)
    assert math.isclose(profile.update_rate, catalogued["update_rate"], rel_tol=1e-3)
    # The driver's launch file's limits, not the datasheet's 0.5 m to 20 m.
    assert (profile.range_min, profile.range_max) == pytest.approx((0.05, 25.0))
    assert profile.driver.no_return == catalogued["driver"]["no_return"] == "zero"
    assert profile.driver.range_max == "fixed"
    assert profile.driver.beam_order == "counter-clockwise"
    assert profile.driver.stamp == "start"


def test_a_real_bag_without_the_topic_asked_for_names_its_laser_scan_topic(
    sick_bag: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["profile", "--bag", str(sick_bag), "--topic", "/scan"]) != 0
    error = capsys.readouterr().err
    assert f"{sick_bag}: has no topic /scan; its LaserScan topics: /sick_lms_1xx/scan" in error
