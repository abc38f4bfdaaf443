"""Free bodies of a mooring system: each body's 6-DOF position found by equilibrium of
its lines, its weight, its buoyancy and a constant applied force.

Pure (arrays in, arrays out). The lines' part of the Jacobian is the body stiffness of
:mod:`.system` (free points re-equilibrated, exact); the loads add the turning of their
moment arms: a force W at the body-frame point p has the moment u x W about the
reference point, u = R p, whose derivative by the angles is A x W with A = d(R p)/d
theta, so the stiffness gains [W]x A in its rotational block. Bodies joined by lines
are coupled only through the outer iteration (the Jacobian is block diagonal per
body), which still converges, linearly where the coupling is strong.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np

from .base import STATUS_NOT_CONVERGED, STATUS_NUMERICAL
from .system import (
    BODY,
    FREE,
    MooringSystem,
    SystemFailure,
    SystemResult,
    _line_search,
    _skew,
    rotation,
    rotation_derivatives,
)


def body_loads(system: MooringSystem, body: int, pose: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Weight, buoyancy and applied force on ``body`` at ``pose``: the load [N, N m] (6,)
    about the reference point and its stiffness -d load / d pose (6, 6)."""
    R = rotation(pose[3:])
    dR = rotation_derivatives(pose[3:])
    load = np.zeros(6)
    K = np.zeros((6, 6))
    forces = (
        (np.array([0.0, 0.0, -system.body_weight[body]]), system.body_cog[body]),
        (np.array([0.0, 0.0, system.body_buoyancy[body]]), system.body_cob[body]),
    )
    for f, p in forces:
        load[:3] += f
        load[3:] += np.cross(R @ p, f)
        A = np.stack([dR[k] @ p for k in range(3)], axis=1)
        K[3:, 3:] += _skew(f) @ A
    load[:3] += system.body_applied[body]
    return load, K


def solve_free_bodies(system: MooringSystem, solve: Any) -> SystemResult:
    """Newton on the free bodies' positions; ``solve(system)`` solves the system with the
    bodies where ``system`` puts them (free points re-equilibrated) or raises
    :class:`SystemFailure`. The step length comes from the energy along the step (the
    loads are conservative): see :func:`.system._line_search`."""
    free = np.flatnonzero(system.body_free)
    free_points = system.point_kind == FREE
    state = {"guess": np.array(system.point_position, dtype=float)}
    longest_line = min(ln.problem.line.total_length for ln in system.lines)
    force_scale = max(
        float(np.max(system.body_weight[free], initial=0.0)),
        float(np.max(system.body_buoyancy[free], initial=0.0)),
        float(np.max(np.abs(system.body_applied[free]), initial=0.0)),
        1e-300,
    )
    arm = max(
        float(np.max(np.abs(system.point_position[system.point_kind == BODY]), initial=0.0)),
        float(np.max(np.abs(system.body_cog[free]), initial=0.0)),
        float(np.max(np.abs(system.body_cob[free]), initial=0.0)),
        1.0,
    )

    def evaluate(q: np.ndarray) -> tuple[SystemResult, np.ndarray, np.ndarray]:
        poses = np.array(system.body_position, dtype=float)
        poses[free] = q
        res = solve(replace(system, body_position=poses, point_position=state["guess"]))
        R = np.zeros((len(free), 6))
        K = np.zeros((6 * len(free), 6 * len(free)))
        for k, b in enumerate(free):
            load, k_load = body_loads(system, b, poses[b])
            R[k] = res.body_force[b] + load
            K[6 * k : 6 * k + 6, 6 * k : 6 * k + 6] = res.body_stiffness[b] + k_load
        res.body_position = poses
        return res, R, K

    def size(R: np.ndarray) -> float:
        scale = max(force_scale, max((float(np.max(r.tension)) for r in res.lines), default=0.0))
        return max(
            float(np.max(np.abs(R[:, :3]))) / scale, float(np.max(np.abs(R[:, 3:]))) / (scale * arm)
        )

    q = np.array(system.body_position[free], dtype=float)
    res, R, K = evaluate(q)
    err = size(R)
    it, polished = 0, 0
    while err > system.tolerance or polished == 0:
        if err <= system.tolerance:
            polished = 1
        if it >= system.max_iterations:
            raise SystemFailure(
                STATUS_NOT_CONVERGED,
                f"free-body equilibrium did not converge in {system.max_iterations} "
                f"iterations (net load / largest tension {err:.3g})",
            )
        it += 1
        try:
            step = np.linalg.solve(K, R.ravel()).reshape(-1, 6)
        except np.linalg.LinAlgError:
            raise SystemFailure(
                STATUS_NUMERICAL,
                "the free bodies' stiffness (lines, weight and buoyancy) is singular: a "
                "body free to move without restoring force (a body on a single point, or "
                "with no rotational restraint)",
            ) from None
        phi0 = float(R.ravel() @ step.ravel())
        if not phi0 > 0.0:  # not positive definite here: go downhill
            step = R / max(float(np.max(np.abs(np.diag(K)))), 1e-300)
            phi0 = float(R.ravel() @ step.ravel())
        shrink = min(
            1.0,
            0.5 * longest_line / max(float(np.max(np.abs(step[:, :3]))), 1e-300),
            0.3 / max(float(np.max(np.abs(step[:, 3:]))), 1e-300),
        )
        step *= shrink
        phi0 *= shrink

        def trial(lam: float, q: np.ndarray = q, step: np.ndarray = step) -> Any:
            try:
                out = evaluate(q + lam * step)
            except SystemFailure:
                return None
            return out, float(out[1].ravel() @ step.ravel())

        found = _line_search(trial, phi0, done=err <= system.tolerance)
        if found is None:
            if err <= system.tolerance:
                break
            raise SystemFailure(
                STATUS_NOT_CONVERGED,
                f"line search failed in the free-body equilibrium (net load / largest "
                f"tension {err:.3g})",
            )
        lam, (res, R, K) = found
        q = q + lam * step
        state["guess"] = np.where(free_points[:, None], res.point_position, state["guess"])
        err = size(R)
        if polished:
            break
    res.iterations = it
    res.residual = err if math.isfinite(err) else res.residual
    return res
