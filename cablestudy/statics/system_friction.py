"""Seabed friction on a system's free points resting on the seabed (:func:`.system._solve`).

MoorPy's convention, as the single line takes it: each line takes friction as its own
catenary does (from its touchdown towards its end lying on the seabed, as if that end
were anchored; a line lying wholly on the seabed pulled at its end nearer a line rising
from the seabed, :func:`pulled_ends`, :func:`.semi_analytic_shape.laid_pulled`), and a
free point resting on the seabed takes, besides the seabed's normal reaction N, the
friction a point load on a single line's laid stretch takes (:func:`.seabed.laid_part`):
mu N against the pull of the line that lifts from it or lies on the seabed from it
towards a raised end, at most that pull (the lines lying wholly on the seabed from it
hold the rest). So a chain split at a junction resting on its laid stretch is the one
line with the junction's load as an attachment. Where two such lines pull the point (a
laid stretch between two suspended parts) which way friction acts is not determined by
the statics: refused by name. Pure: arrays in, arrays out (SI units).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .base import STATUS_NO_SOLUTION, StaticResult
from .system_model import FIXED, FREE, MooringSystem, SystemFailure


def pulled_ends(system: MooringSystem, pos: np.ndarray, plane: Any) -> np.ndarray:
    """Per line, for one lying with both ends on the seabed at ``pos`` [m] (n, 3), the end
    pulled (0: A, 1: B), -1 where that is not determined: the end nearer, along such
    lines, to a point that a line rising from the seabed pulls (anchors pass no pull on).
    A chain split at several junctions on its laid part is pulled from the fairlead's
    side, each line anchored towards the anchor, as the single line is."""
    low = np.array(
        [plane.height_above(pos[[ln.a, ln.b]]) <= 1e-6 * ln.problem.line.total_length
         for ln in system.lines]
    ).reshape(-1, 2)  # fmt: skip
    dist = np.full(len(pos), np.inf)
    for ln, (la, lb) in zip(system.lines, low, strict=True):
        if la != lb:  # rising from the seabed at its low end
            dist[ln.a if la else ln.b] = 0.0
    for _ in system.lines:
        for ln, flat in zip(system.lines, low.all(axis=1), strict=True):
            for p, q in ((ln.a, ln.b), (ln.b, ln.a)):
                if flat and system.point_kind[p] != FIXED:
                    dist[q] = min(dist[q], dist[p] + 1.0)
    da, db = dist[[ln.a for ln in system.lines]], dist[[ln.b for ln in system.lines]]
    return np.where(da < db, 0, np.where(db < da, 1, -1))


def point_friction(
    system: MooringSystem,
    pos: np.ndarray,
    results: list[StaticResult],
    plane: Any,
    verify: bool = True,
) -> np.ndarray:
    """The seabed's friction force [N] (n, 3) on each free point resting on the seabed at
    ``pos`` [m] (n, 3), the lines solved there (``results``, one per line); zero where a
    point is off the seabed or not pressed onto it, and (``verify=False``, a Newton trial)
    where it is not determined."""
    friction = np.zeros_like(pos)
    L = min(ln.problem.line.total_length for ln in system.lines)
    for p in np.flatnonzero(system.point_kind == FREE):
        if abs(float(plane.height_above(pos[p]))) > 1e-9 * L:
            continue
        net = np.array(system.point_force[p], dtype=float)
        pull = np.zeros(3)
        pulling, lying = [], False
        for ln, res in zip(system.lines, results, strict=True):
            for end, f in ((ln.a, res.force_a), (ln.b, res.force_b)):
                if end != p:
                    continue
                net += f
                if res.laid_length < (1 - 1e-9) * ln.problem.line.total_length:
                    pull += f
                    pulling.append(ln.name)
                    lying = lying or res.laid_length > 0.0
        normal = -float(net @ plane.normal)  # the seabed's reaction
        if lying and len(pulling) > 1:
            if not verify:
                continue
            raise SystemFailure(
                STATUS_NO_SOLUTION,
                f"free point {system.point_names[p]} rests on the seabed between lines "
                f"{', '.join(pulling)}, a laid stretch between two suspended parts, with "
                f"seabed friction {plane.friction:g}: which way friction acts along it is "
                "not determined by the statics (friction: 0 solves it)",
            )
        pull -= (pull @ plane.normal) * plane.normal
        size = float(np.linalg.norm(pull))
        if normal > 0.0 and size > 0.0:
            friction[p] = -min(plane.friction * normal, size) / size * pull
    return friction
