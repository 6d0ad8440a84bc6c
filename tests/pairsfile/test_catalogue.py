"""The catalogue of scanner models: every bundled file names its datasheet, and a broken file is
reported at its own line."""

from __future__ import annotations

from pathlib import Path

import pytest

from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.pairsfile.catalogue import load_catalogue


def test_every_catalogue_file_names_its_source() -> None:
    from pytest_lasertest.pairsfile.bundled import LIDARS_DIR

    for path in sorted(LIDARS_DIR.glob("*.yaml")):
        assert "# Source:" in path.read_text(), f"{path.name} does not name its datasheet"


def test_a_broken_catalogue_file_is_reported_at_its_own_line(tmp_path: Path) -> None:
    (tmp_path / "bad_lidar.yaml").write_text(
        "name: Bad\nsamples: 10\nmin_angle: 1\nmax_angle: 0\n"
        "range: {min: 0, max: 1}\nupdate_rate: 5\n"
    )
    with pytest.raises(SpecError) as error:
        load_catalogue(tmp_path)
    assert error.value.location.path == tmp_path / "bad_lidar.yaml"
    assert (error.value.location.line, error.value.field) == (3, "min_angle")


def test_a_catalogue_file_without_a_name_is_refused(tmp_path: Path) -> None:
    (tmp_path / "nameless.yaml").write_text(
        "samples: 10\nmin_angle: -1\nmax_angle: 1\nrange: {min: 0, max: 1}\nupdate_rate: 5\n"
    )
    with pytest.raises(SpecError, match="name is missing"):
        load_catalogue(tmp_path)
