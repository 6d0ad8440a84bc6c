"""What `lasertest catalogue` prints: each scanner model's figures that matter for a 2D scan."""

from __future__ import annotations

import math
from dataclasses import dataclass

from pytest_lasertest.model.driver import Driver
from pytest_lasertest.model.sensor import LaserProfile


@dataclass(frozen=True)
class ModelFigures:
    """One catalogue model as `lasertest catalogue` shows it."""

    model: str
    name: str
    fov_deg: float
    beams: int
    step_deg: float
    range_min_m: float
    range_max_m: float
    update_rate_hz: float
    noise_stddev_m: float | None
    no_return: str  # how its driver publishes a beam that met nothing (model/driver.py)
    stamp: str  # the sweep instant its driver stamps, and how much later

    @classmethod
    def of(cls, model: str, name: str, profile: LaserProfile) -> ModelFigures:
        return cls(
            model=model,
            name=name,
            fov_deg=round(math.degrees(profile.max_angle - profile.min_angle), 2),
            beams=profile.beam_count,
            step_deg=round(math.degrees(profile.angle_increment), 4),
            range_min_m=profile.range_min,
            range_max_m=profile.range_max,
            update_rate_hz=profile.update_rate,
            noise_stddev_m=profile.noise.stddev if profile.noise else None,
            no_return=profile.driver.no_return,
            stamp=_stamp(profile.driver),
        )

    def cells(self) -> tuple[str, ...]:
        noise = "-" if self.noise_stddev_m is None else f"{self.noise_stddev_m * 1e3:g}"
        return (
            self.model,
            f"{self.fov_deg:g}",
            str(self.beams),
            f"{self.step_deg:.3f}",
            f"{self.range_min_m:g}-{self.range_max_m:g}",
            f"{self.update_rate_hz:g}",
            noise,
            self.no_return,
            self.stamp,
            self.name,
        )


CATALOGUE_HEADER = (
    "model",
    "FOV deg",
    "beams",
    "step deg",
    "range m",
    "rate Hz",
    "noise mm",
    "no return",
    "stamp",
    "name",
)


def _stamp(driver: Driver) -> str:
    """`start`, or `end`, with what the driver adds to it in ms."""
    added = f" +{driver.latency * 1e3:.1f} ms" if driver.latency else ""
    return f"{driver.stamp}{added}"


def catalogue_table(rows: list[ModelFigures]) -> str:
    """The models as a table with a header row, columns left-aligned."""
    return _table([CATALOGUE_HEADER, *(row.cells() for row in rows)])


def _table(lines: list[tuple[str, ...]]) -> str:
    widths = [max(len(line[column]) for line in lines) for column in range(len(lines[0]))]
    return "\n".join(
        "  ".join(cell.ljust(width) for cell, width in zip(line, widths, strict=True)).rstrip()
        for line in lines
    )
