"""`lasertest doctor` checks the installation and says what to fix; the console script runs it
without PyBullet's banner."""

from __future__ import annotations

import subprocess
import sys

import pytest

from pytest_lasertest import cli
from pytest_lasertest.cli import doctor


def test_the_doctor_passes_on_this_installation(capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["doctor"]) == 0
    output = capsys.readouterr().out
    for check in ("python", "packages", "z3", "pybullet", "bundled robots", "pytest plugin"):
        assert f"ok    {check}: " in output
    assert output.rstrip().endswith("all checks passed")


def test_the_doctor_says_what_to_fix_when_a_check_fails(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    def broken() -> str:
        raise ImportError("libz3.so: cannot open shared object file")

    checks = tuple(
        doctor.Check(check.name, broken, check.fix) if check.name == "z3" else check
        for check in doctor.CHECKS
    )
    monkeypatch.setattr(doctor, "CHECKS", checks)
    assert cli.main(["doctor"]) == 1
    output = capsys.readouterr().out
    assert "FAIL  z3: ImportError: libz3.so: cannot open shared object file" in output
    assert "      fix: pip install --force-reinstall z3-solver" in output
    assert output.rstrip().endswith("1 check(s) failed")


def test_the_console_script_runs_and_prints_no_pybullet_banner() -> None:
    result = subprocess.run(
        [sys.executable, "-m", "pytest_lasertest.cli", "doctor"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert "build time" not in result.stdout + result.stderr
