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
from .system import solve_system
from .system_model import FREE, MooringSystem, SystemResult


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
    system: MooringSystem,
    method: str,
    solvers: dict[str, Any],
    *,
    deadline: float | None = None,
    extra_poses: np.ndarray | None = None,
) -> SystemResult:
    """Solve ``system`` by static ``method`` (``solvers[method]``, a registered solver):
    method discrete starts from the cable solution of the same system (module doc)."""
    solver = solvers[method]
    moving = bool(np.any(system.point_kind == FREE)) or bool(np.any(system.body_free))
    if method != "discrete" or not moving:
        return solve_system(system, solver, deadline=deadline, extra_poses=extra_poses)
    start = solve_system(as_cables(system), solvers["catenary"], deadline=deadline)
    if start.status == STATUS_OK:
        free = system.point_kind == FREE
        guess = np.where(free[:, None], start.point_position, system.point_position)
        system = replace(system, point_position=guess)
        if start.body_position is not None and np.any(system.body_free):
            poses = np.where(system.body_free[:, None], start.body_position, system.body_position)
            system = replace(system, body_position=poses)
    return solve_system(system, solver, deadline=deadline)
