"""Statics of a massless tension-only spring line (``line.kind: spring``).

A massless cable of unstretched length L [m] between its ends is straight when taut, and
its tension is the axial law of its extension e = |r_B - r_A| - L [m] (aqwa seed
5.8.1.1-5.8.1.3: "the extension is the distance between the end points minus the
unstretched length ... if the distance is less than [L], the tension is zero").

End conditions (A fixed, as every study; or B fixed and A given by force, solved as the
reversed line):

* both ends fixed: T = law(D - L), D = |r_B - r_A|; slack (T = 0) when D <= L. A slack
  massless cable has no determined shape; its points are reported on the chord.
* fixed + ``force`` F on the line at the other end: a massless line in equilibrium is
  along the force, so it points along F, T = |F|, and the free end lies at
  r_A + (L + e(|F|)) F / |F| (the law's inverse). F = 0 is refused at validation (no
  unique position).
* fixed + ``mooring`` (horizontal force H [N] on the line and the end's height z_B):
  along the line T (u_h, u_z) with u_z = h / D, h = z_B - z_A, D = L + e(T), and
  T sqrt(1 - (h / D)^2) = |H|: one equation in T, increasing in T once D > |h|, solved
  by bracketed Newton (bisection fallback) to round-off.

Outputs like any line: positions and tension on ``s`` (uniform strain along a taut
spring, so a point at unstretched s lies at r_A + (s / L)(r_B - r_A)), end forces (the
force of the line on the attachment: at A towards B), ``laid_length`` 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..physics.axial import AxialLaw
from .base import STATUS_NO_SOLUTION, STATUS_NOT_CONVERGED, EndCondition, StaticResult


@dataclass(frozen=True, kw_only=True)
class SpringProblem:
    """A massless spring line: ``law`` tension [N] of extension [m], ``length`` [m]
    unstretched, the ends and the output points ``n_nodes``; ``pulleys`` [m] (m, 3)
    fixed points it passes over (both ends then fixed) with their ``friction`` factors."""

    law: AxialLaw
    length: float
    end_a: EndCondition
    end_b: EndCondition
    n_nodes: int = 101
    tolerance: float = 1e-12
    pulleys: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    friction: np.ndarray = field(default_factory=lambda: np.zeros(0))


def wrap_angles(points: np.ndarray) -> np.ndarray:
    """Angle [rad] through which the line turns at each inner point of the polyline
    ``points`` (k + 2, 3): 0 straight on, pi doubled back."""
    seg = np.diff(points, axis=0)
    u = seg / np.linalg.norm(seg, axis=1)[:, None]
    c = np.clip(np.einsum("ik,ik->i", u[:-1], u[1:]), -1.0, 1.0)
    return np.arccos(c)


def over_pulleys(problem: SpringProblem) -> StaticResult:
    """A spring between fixed ends over fixed pulleys, slid freely to the frictionless
    equilibrium (each span's unstretched length in proportion to its chord): one strain,
    T = law(path length - L) on every span -- the state of a line tensioned sliding over
    its pulleys, which every friction factor >= 1 also holds (with friction the static
    state depends on the history; the dynamics starts from this one). Outputs on s
    follow the spans; ``pulley_force`` is the force of the line on each pulley [N]."""
    L = problem.length
    rA = np.asarray(problem.end_a.position, dtype=float)
    rB = np.asarray(problem.end_b.position, dtype=float)
    P = np.vstack((rA, problem.pulleys, rB))
    d = np.linalg.norm(np.diff(P, axis=0), axis=1)
    D = float(np.sum(d))
    lengths = L * d / D
    # each span's tension: the law at the extension its strain gives the whole cable
    T = problem.law.tension(L * (d / lengths - 1.0)) if D > 0.0 else np.zeros(len(d))
    u = np.diff(P, axis=0) / np.where(d > 0.0, d, 1.0)[:, None]
    s = np.linspace(0.0, L, problem.n_nodes)
    S = np.concatenate(([0.0], np.cumsum(lengths)))
    k = np.clip(np.searchsorted(S, s, side="right") - 1, 0, len(d) - 1)
    frac = np.clip((s - S[k]) / lengths[k], 0.0, 1.0)
    pos = P[k] + frac[:, None] * (P[k + 1] - P[k])
    res = StaticResult(
        s=s,
        position=pos,
        tension=T[k],
        force_a=T[0] * u[0],
        force_b=-T[-1] * u[-1],
    )
    res.pulley_force = T[1:, None] * u[1:] - T[:-1, None] * u[:-1]  # type: ignore[attr-defined]
    return res


def _straight(
    s: np.ndarray, rA: np.ndarray, rB: np.ndarray, T: float, L: float, **extra: object
) -> StaticResult:
    d = rB - rA
    D = float(np.linalg.norm(d))
    u = d / D if D > 0.0 else np.zeros(3)
    pos = rA + np.outer(s / L, d)
    return StaticResult(
        s=s,
        position=pos,
        tension=np.full(len(s), T),
        force_a=T * u,
        force_b=-T * u,
        laid_length=0.0,
        **extra,  # type: ignore[arg-type]
    )


def _mooring_tension(
    law: AxialLaw, L: float, h: float, H: float, tol: float
) -> tuple[float, int] | None:
    """T with T sqrt(1 - (h / (L + e(T)))^2) = H (H > 0), or None. Bracketed: the left
    side is 0 at the tension where L + e = |h| (or at T = 0 when L > |h|) and grows
    past H by T = H + law(|h| + ... ) bounds found by doubling."""

    def f(T: float) -> float:
        D = L + law.strain_scalar(T)
        if D <= abs(h):
            return -H
        return T * math.sqrt(max(1.0 - (h / D) ** 2, 0.0)) - H

    lo = 0.0
    if abs(h) > L:
        lo = float(law.tension(abs(h) - L))
    hi = max(lo, H) * 2.0 + 1.0
    for _ in range(400):
        if f(hi) >= 0.0:
            break
        lo, hi = hi, 2.0 * hi
    else:
        return None
    it = 0
    while it < 300 and hi - lo > tol * hi + 1e-300:
        it += 1
        mid = 0.5 * (lo + hi)
        if f(mid) < 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi), it


def solve_spring(problem: SpringProblem) -> StaticResult:
    """Static solution of a massless spring line (see the module docstring)."""
    L = problem.length
    law = problem.law
    s = np.linspace(0.0, L, problem.n_nodes)
    a, b = problem.end_a, problem.end_b
    if len(problem.pulleys):
        if a.kind != "fixed" or b.kind != "fixed":
            return StaticResult.failed(
                s, STATUS_NO_SOLUTION, "a spring over pulleys needs both ends fixed"
            )
        return over_pulleys(problem)
    reverse = a.kind != "fixed"
    if reverse:
        a, b = b, a
    if a.kind != "fixed" or a.position is None:
        return StaticResult.failed(s, STATUS_NO_SOLUTION, "neither end of the spring is fixed")
    rA = np.asarray(a.position, dtype=float)
    if b.kind == "fixed":
        assert b.position is not None
        rB = np.asarray(b.position, dtype=float)
        T = float(law.tension(np.asarray(float(np.linalg.norm(rB - rA)), dtype=float) - L))
        its = 0
    elif b.kind == "force":
        assert b.force is not None
        F = np.asarray(b.force, dtype=float)
        T = float(np.linalg.norm(F))
        if T == 0.0:
            return StaticResult.failed(
                s, STATUS_NO_SOLUTION, "zero force on a massless spring: no unique position"
            )
        rB = rA + (L + law.strain_scalar(T)) * F / T
        its = 0
    else:
        assert b.force is not None and b.z is not None
        Hv = np.array([b.force[0], b.force[1], 0.0], dtype=float)
        H = float(np.linalg.norm(Hv))
        h = float(b.z) - float(rA[2])
        if H == 0.0:
            if abs(h) < L:
                return StaticResult.failed(
                    s,
                    STATUS_NO_SOLUTION,
                    f"zero horizontal force and a height difference {abs(h):.6g} m below "
                    f"the spring length {L:.6g} m: the slack spring has no unique position",
                )
            T = float(law.tension(abs(h) - L))
            rB = rA + np.array([0.0, 0.0, h])
            its = 0
        else:
            found = _mooring_tension(law, L, h, H, problem.tolerance)
            if found is None:
                return StaticResult.failed(
                    s, STATUS_NOT_CONVERGED, "no spring tension balances the mooring force"
                )
            T, its = found
            D = L + law.strain_scalar(T)
            horiz = math.sqrt(max(D * D - h * h, 0.0))
            rB = rA + horiz * Hv / H + np.array([0.0, 0.0, h])
    res = _straight(s, rA, rB, T, L, iterations=its)
    if reverse:
        # described from the fixed end: turn back to A -> B
        res = StaticResult(
            s=s,
            position=res.position[::-1].copy(),
            tension=res.tension[::-1].copy(),
            force_a=res.force_b,
            force_b=res.force_a,
            iterations=its,
        )
    return res


def reachable_extension(
    length: float, end_a: EndCondition, end_b: EndCondition, motion_amplitude: float
) -> float | None:
    """Largest extension [m] the spring between fixed ends can reach: the end distance
    plus the sum of the excitation amplitudes ``motion_amplitude`` [m], minus the length
    (None when an end is given by force: the law's range is then what the force needs)."""
    if end_a.kind != "fixed" or end_b.kind != "fixed":
        return None
    assert end_a.position is not None and end_b.position is not None
    D = float(np.linalg.norm(np.asarray(end_b.position) - np.asarray(end_a.position)))
    return max(D + motion_amplitude - length, 0.0)
