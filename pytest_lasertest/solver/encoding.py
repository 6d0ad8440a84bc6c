"""Linear constraints on an obstacle, written as SMT-LIB text for Z3 to parse in one go.

The obstacle is an upright square box of side S at a fixed yaw, or a cylinder of diameter S,
centred at (X, Y), of height H. Every condition is linear in X, Y, S, H and the margin M because
beam directions, robot poses and the obstacle's yaw are fixed in each query: along a unit axis n
the obstacle covers `n . (X, Y) +- k_n (S/2 + M)` when grown by M, with k_n = |n . u| + |n . v|
for a box with axes u, v, and k_n = 1 for a cylinder. Text instead of the Python API because a
720-beam scan is thousands of inequalities, and Z3 parses them far faster than Python builds them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from pytest_lasertest.model.geometry import FloatArray

Shape = Literal["box", "cylinder"]
VARIABLES = ("X", "Y", "S", "H", "M")


def number(value: float) -> str:
    """A real as an SMT-LIB decimal (no exponent, negatives as `(- v)`)."""
    text = f"{abs(value):.5f}".rstrip("0")
    text = f"{text}0" if text.endswith(".") else text
    return f"(- {text})" if value < 0 else text


def linear(**coefficients: float) -> str:
    """An SMT-LIB sum of `coefficient * variable` terms, zero coefficients left out."""
    terms = [f"(* {number(value)} {name})" for name, value in coefficients.items() if value != 0]
    if not terms:
        return "0.0"
    return terms[0] if len(terms) == 1 else f"(+ {' '.join(terms)})"


def all_of(parts: list[str]) -> str:
    """Conjunction; `true` when empty."""
    if not parts:
        return "true"
    return parts[0] if len(parts) == 1 else f"(and {' '.join(parts)})"


def any_of(parts: list[str]) -> str:
    """Disjunction; `false` when empty."""
    if not parts:
        return "false"
    return parts[0] if len(parts) == 1 else f"(or {' '.join(parts)})"


@dataclass(frozen=True)
class HalfPlane:
    """Where the obstacle, grown by the margin M, must lie: normal . p >= offset (m)."""

    normal: tuple[float, float]
    offset: float

    def room(self, point: FloatArray) -> float:
        """How far inside the half-plane `point` lies (m); negative outside."""
        return self.normal[0] * float(point[0]) + self.normal[1] * float(point[1]) - self.offset


@dataclass(frozen=True)
class ObstacleShape:
    """The fixed part of a query's obstacle: its shape and yaw."""

    shape: Shape
    yaw: float = 0.0  # rad, boxes only

    def axes(self) -> list[FloatArray]:
        """The box's own axes u and v; none for a cylinder."""
        if self.shape == "cylinder":
            return []
        u = np.array([math.cos(self.yaw), math.sin(self.yaw)])
        return [u, np.array([-u[1], u[0]])]

    def spread(self, axis: FloatArray) -> float:
        """k_n: the obstacle's half-extent along `axis` per unit of (S/2 + M)."""
        if self.shape == "cylinder":
            return 1.0
        u, v = self.axes()
        return abs(float(axis @ u)) + abs(float(axis @ v))

    def at_least(self, axis: FloatArray, value: float, grow: int = 1) -> str:
        """The obstacle, grown by M (grow=1) or shrunk by M (grow=-1), lies where n . p >= value."""
        k = self.spread(axis)
        return f"(>= {linear(X=axis[0], Y=axis[1], S=-k / 2, M=-grow * k)} {number(value)})"

    def at_most(self, axis: FloatArray, value: float, grow: int = 1) -> str:
        """The obstacle, grown by M (grow=1) or shrunk by M (grow=-1), lies where n . p <= value."""
        k = self.spread(axis)
        return f"(<= {linear(X=axis[0], Y=axis[1], S=k / 2, M=grow * k)} {number(value)})"

    def beyond(self, plane: HalfPlane) -> str:
        """The obstacle, grown by M, lies where plane.normal . p >= plane.offset."""
        return self.at_least(np.array(plane.normal), plane.offset)

    def holds(self, point: FloatArray) -> str:
        """The obstacle, shrunk by M, holds the point (a cylinder: its inscribed octagon does)."""
        if self.shape == "box":
            return all_of(
                [
                    self.overlaps(axis, float(axis @ point), float(axis @ point))
                    for axis in self.axes()
                ]
            )
        shrink = math.cos(math.pi / 8.0)
        parts = []
        for angle in np.arange(4) * math.pi / 4.0:
            axis = np.array([math.cos(angle), math.sin(angle)])
            along = float(axis @ point)
            parts.append(
                f"(<= {linear(X=axis[0], Y=axis[1], S=-shrink / 2, M=shrink)} {number(along)})"
            )
            parts.append(
                f"(>= {linear(X=axis[0], Y=axis[1], S=shrink / 2, M=-shrink)} {number(along)})"
            )
        return all_of(parts)

    def overlaps(self, axis: FloatArray, low: float, high: float) -> str:
        """The obstacle, shrunk by M, overlaps [low, high] along `axis`."""
        k = self.spread(axis)
        upper = f"(>= {linear(X=axis[0], Y=axis[1], S=k / 2, M=-k)} {number(low)})"
        lower = f"(<= {linear(X=axis[0], Y=axis[1], S=-k / 2, M=k)} {number(high)})"
        return all_of([upper, lower])

    def clear_of_polygon(self, polygon: FloatArray) -> str:
        """The obstacle grown by M is separated from a convex polygon (shape (V, 2), CCW)."""
        options = []
        for normal, offset in _edges(polygon):
            options.append(self.at_least(normal, offset))
        for axis in self.axes():
            projection = polygon @ axis
            options.append(self.at_least(axis, float(projection.max())))
            options.append(self.at_most(axis, float(projection.min())))
        return any_of(options)

    def inside_polygon(self, polygon: FloatArray) -> str:
        """The obstacle shrunk by M still overlaps a convex polygon (a cylinder: centre inside)."""
        if self.shape == "cylinder":
            return all_of(
                [f"(<= {linear(X=n[0], Y=n[1])} {number(offset)})" for n, offset in _edges(polygon)]
            )
        parts = []
        for normal, _ in _edges(polygon):
            projection = polygon @ normal
            parts.append(self.overlaps(normal, float(projection.min()), float(projection.max())))
        for axis in self.axes():
            projection = polygon @ axis
            parts.append(self.overlaps(axis, float(projection.min()), float(projection.max())))
        return all_of(parts)

    def crossed_by(
        self, origin: FloatArray, direction: FloatArray, start: float, end: float
    ) -> str:
        """The obstacle shrunk by M meets the beam segment {o + t d : start <= t <= end}."""
        normal = np.array([-direction[1], direction[0]])
        line = float(origin @ normal)
        if self.shape == "cylinder":
            along = float(origin @ direction)
            centre_on_segment = [
                f"(>= {linear(X=direction[0], Y=direction[1])} {number(along + start)})",
                f"(<= {linear(X=direction[0], Y=direction[1])} {number(along + end)})",
            ]
            return all_of([*centre_on_segment, self.overlaps(normal, line, line)])
        ends = np.array([origin + start * direction, origin + end * direction])
        parts = [self.overlaps(normal, line, line)]
        for axis in self.axes():
            projection = ends @ axis
            parts.append(self.overlaps(axis, float(projection.min()), float(projection.max())))
        return all_of(parts)


def _edges(polygon: FloatArray) -> list[tuple[FloatArray, float]]:
    """Outward unit normals of a counter-clockwise polygon's edges, and n . p on each edge."""
    result = []
    for here, following in zip(polygon, np.roll(polygon, -1, axis=0), strict=True):
        edge = following - here
        length = float(np.hypot(*edge))
        if length == 0.0:
            continue
        normal = np.array([edge[1], -edge[0]]) / length
        result.append((normal, float(here @ normal)))
    return result
