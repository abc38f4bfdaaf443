"""Mooring systems for tests, built directly as :class:`MooringSystem` (SI units)."""

from __future__ import annotations

import math

import numpy as np

from cablestudy.statics import EndCondition, Medium, StaticProblem
from cablestudy.statics.system_model import BODY, FIXED, FREE, MooringSystem, SystemLine
from tests.line_models import one_segment

RHO, G = 1025.0, 9.81


def polyester(length: float, *, depth: float | None = 100.0) -> StaticProblem:
    """MoorPy's tests/case8.dat line type 'polyester': d 0.15 m, 25 kg/m, EA 30e6 N."""
    d, m = 0.15, 25.0
    w = (m - RHO * math.pi / 4.0 * d * d) * G
    return StaticProblem(
        line=one_segment(length=length, weight=w, mass=m, axial_stiffness=30e6, diameter=d),
        medium=Medium(density=RHO, gravity=G, depth=depth),
        end_a=EndCondition(kind="fixed", position=np.zeros(3)),
        end_b=EndCondition(kind="fixed", position=np.ones(3)),
        tolerance=1e-12,
    )


def system_of(
    points: list[tuple[str, int, list[float]]],
    lines: list[tuple[int, int, float]],
    pose: list[float] | np.ndarray,
    *,
    point_force: np.ndarray | None = None,
    depth: float | None = 100.0,
) -> MooringSystem:
    """Points (name, kind, position or offset), lines (a, b, length) with 1-based point
    numbers as in a MoorDyn file, all body points on one body at ``pose``."""
    n = len(points)
    kinds = np.array([p[1] for p in points])
    return MooringSystem(
        point_names=tuple(p[0] for p in points),
        point_kind=kinds,
        point_position=np.array([p[2] for p in points], dtype=float),
        point_body=np.where(kinds == BODY, 0, -1),
        point_force=np.zeros((n, 3)) if point_force is None else point_force,
        body_names=("body",),
        body_position=np.array([pose], dtype=float),
        lines=tuple(
            SystemLine(name=str(i + 1), problem=polyester(L, depth=depth), a=a - 1, b=b - 1)
            for i, (a, b, L) in enumerate(lines)
        ),
        tolerance=1e-12,
    )


#: MoorPy tests/case8.dat (Shared Moorings Project, Hywind-like spar): three legs of
#: 160 m from anchors on the seabed (depth 100 m) to free junctions, each with a bridle
#: of two 45.36 m lines to fairleads on the body.
CASE8_POINTS = [
    ("1", FIXED, [172.7, -100.0, -100.0]),
    ("2", BODY, [6.82, 3.9375, -21.0]),
    ("3", BODY, [0.0, -7.875, -21.0]),
    ("4", FREE, [34.64, -20.0, -50.0]),
    ("5", FIXED, [0.0, 200.0, -100.0]),
    ("6", BODY, [-6.82, 3.9375, -21.0]),
    ("7", BODY, [6.82, 3.9375, -21.0]),
    ("8", FREE, [0.0, 40.0, -50.0]),
    ("9", FIXED, [-172.7, -100.0, -100.0]),
    ("10", BODY, [0.0, -7.875, -21.0]),
    ("11", BODY, [-6.82, 3.9375, -21.0]),
    ("12", FREE, [-34.64, -20.0, -50.0]),
]
CASE8_LINES = [
    (4, 2, 45.36),
    (4, 3, 45.36),
    (1, 4, 160.0),
    (8, 6, 45.36),
    (8, 7, 45.36),
    (5, 8, 160.0),
    (12, 10, 45.36),
    (12, 11, 45.36),
    (9, 12, 160.0),
]


def rotated_points(
    points: list[tuple[str, int, list[float]]], angle: float
) -> list[tuple[str, int, list[float]]]:
    """The points turned about z by ``angle`` [rad] (positions and body offsets)."""
    c, s = math.cos(angle), math.sin(angle)
    q = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    return [(name, kind, list(q @ np.asarray(p, dtype=float))) for name, kind, p in points]
