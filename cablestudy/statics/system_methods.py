"""A system solved by a study's static method (:func:`solve_system_by`).

Pure: arrays and frozen dataclasses in, arrays out (SI units, no I/O).

Method ``catenary`` solves the system directly (:func:`.system.solve_system`). Method
``discrete`` (lines with bending stiffness EI, or anything else the lumped-mass model
carries) first solves the same system as cables (EI set to zero, method catenary: the
discrete model differs from it by its mesh error and the bending), and starts its own
Newton from that equilibrium: the free points and free bodies then need a few Newton
steps instead of a full descent from the file's guess, each step re-solving every line
by the slower discrete model. Where the cable pre-solve fails (a line the catenary
cannot settle), the discrete Newton starts from the study's own guess. The answer is
the discrete equilibrium either way (the start only changes the path to it).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from .base import STATUS_OK
from .system import FREE, MooringSystem, SystemResult, solve_system


def as_cables(system: MooringSystem) -> MooringSystem:
    """The same system with every line's bending stiffness set to zero."""
    return replace(
        system,
        lines=tuple(
            replace(
                ln,
                problem=replace(
                    ln.problem,
                    line=replace(
                        ln.problem.line,
                        bending_stiffness=np.zeros_like(ln.problem.line.bending_stiffness),
                    ),
                ),
            )
            for ln in system.lines
        ),
    )


def solve_system_by(
    system: MooringSystem, method: str, solvers: dict[str, Any], *, deadline: float | None = None
) -> SystemResult:
    """Solve ``system`` by static ``method`` (``solvers[method]``, a registered solver):
    method discrete starts from the cable solution of the same system (module doc)."""
    solver = solvers[method]
    moving = bool(np.any(system.point_kind == FREE)) or bool(np.any(system.body_free))
    if method != "discrete" or not moving:
        return solve_system(system, solver, deadline=deadline)
    start = solve_system(as_cables(system), solvers["catenary"], deadline=deadline)
    if start.status == STATUS_OK:
        free = system.point_kind == FREE
        guess = np.where(free[:, None], start.point_position, system.point_position)
        system = replace(system, point_position=guess)
        if start.body_position is not None and np.any(system.body_free):
            poses = np.where(system.body_free[:, None], start.body_position, system.body_position)
            system = replace(system, body_position=poses)
    return solve_system(system, solver, deadline=deadline)


def point_drag(system: MooringSystem, pos: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """Current drag on the free points at positions ``pos`` [m] (n, 3): the force
    ``c |U| U`` [N] (n, 3) with ``c = 1/2 rho C_D A`` [kg/m] (``system.point_drag``) and U
    the current at the point's height, and its stiffness ``-d f / d r`` (3n, 3n), exact:
    the force changes with the point's height only, through the profile's slope U'(z)
    (piecewise linear: the slope of the piece the point is in, 0 beyond the profile's
    ends), ``d f / d z = c (|U| I + U U^T / |U|) U'``. None when no point has drag."""
    c = np.asarray(system.point_drag, dtype=float)
    if c.size == 0 or not np.any(c > 0.0) or not system.lines:
        return None
    medium = system.lines[0].problem.medium
    pz, pv = medium.current_z, medium.current_velocity
    n = len(pos)
    force = np.zeros((n, 3))
    K = np.zeros((3 * n, 3 * n))
    if pz.size == 0:
        return force, K
    for i in np.flatnonzero(c > 0.0):
        z = float(pos[i, 2])
        U = np.array([np.interp(z, pz, pv[:, k]) for k in range(3)])
        speed = float(np.linalg.norm(U))
        force[i] = c[i] * speed * U
        k = int(np.searchsorted(pz, z, side="right")) - 1
        if speed == 0.0 or k < 0 or k >= pz.size - 1:
            continue  # beyond the profile's ends the current is constant
        slope = (pv[k + 1] - pv[k]) / (pz[k + 1] - pz[k])
        dfdz = c[i] * (speed * np.eye(3) + np.outer(U, U) / speed) @ slope
        K[3 * i : 3 * i + 3, 3 * i + 2] -= dfdz
    return force, K
