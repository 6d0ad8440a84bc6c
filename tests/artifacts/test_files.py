"""Where artifacts go and how they are written: paths kept inside the artifacts directory, and
atomic writes that keep the old file when one fails."""

from __future__ import annotations

from pathlib import Path
from typing import IO

import pytest

from pytest_lasertest.artifacts.files import artifact_path, write_atomically


@pytest.mark.parametrize(
    ("nodeid", "expected"),
    [
        (
            "examples/paper.lasertest.yaml::size[coverage]",
            "examples/paper.lasertest.yaml/size_coverage.json",
        ),
        ("../up/gate.yaml::a.b-c[coverage]", "__/up/gate.yaml/a.b-c_coverage.json"),
    ],
)
def test_artifact_paths_stay_inside_the_directory(
    nodeid: str, expected: str, tmp_path: Path
) -> None:
    assert artifact_path(tmp_path, nodeid, ".json") == tmp_path / expected


def test_a_write_that_fails_halfway_keeps_the_old_file_and_no_temporary(tmp_path: Path) -> None:
    path = tmp_path / "item.png"
    path.write_bytes(b"the old picture")

    def fail_halfway(handle: IO[bytes]) -> None:
        handle.write(b"half a picture")
        raise RuntimeError("the renderer fell over")

    with pytest.raises(RuntimeError, match="fell over"):
        write_atomically(path, fail_halfway)
    assert path.read_bytes() == b"the old picture"
    assert list(tmp_path.iterdir()) == [path]
