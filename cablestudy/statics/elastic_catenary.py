"""Irvine's exact elastic catenary between two fixed points.

A uniform elastic line of unstretched length L [m], weight per length w [N/m] in the
fluid (w > 0 down, w < 0 buoyant, w = 0 weightless) and axial stiffness EA [N] hangs
between A and B. It lies in the vertical plane through A and B. With the horizontal
unit vector e from A towards B, horizontal span l and height difference h = z_B - z_A,
the tension vector along increasing s is (H e, V(s)) with V(s) = V_A + w s (H constant),
and the Lagrangian solution is (Irvine, *Cable Structures*, 1981, eqs. 2.26-2.27)

    x(s) = H s / EA + (H / w) [asinh(V(s)/H) - asinh(V_A/H)]
    z(s) = (V_A s + w s^2 / 2) / EA + (1 / w) [T(s) - T_A],   T = sqrt(H^2 + V^2).

The two unknowns (H, V_A) follow from x(L) = l, z(L) = h by Newton's method with an
analytic Jacobian. Every expression is evaluated in a form without cancellation, so
the same code is exact for heavy, near-weightless, near-vertical and stretched lines:

* z(s): (T - T_A) / w = s (V + V_A) / (T + T_A)   (no division by w);
* x(s): asinh(b) - asinh(a) is rewritten as asinh((b - a)(b + a) / (b sqrt(1+a^2) +
  a sqrt(1+b^2))) when a and b share a sign, with b - a = w s / H exact.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from .base import (
    STATUS_NO_SOLUTION,
    STATUS_NOT_CONVERGED,
    STATUS_OK,
    STATUS_TIME_LIMIT,
    StaticProblem,
    StaticResult,
)

# 5-point Gauss-Legendre nodes and weights on [0, 1], for the Jacobian of nearly
# straight lines where the closed form of d x / d H cancels.
_GL_X, _GL_W = np.polynomial.legendre.leggauss(5)
_GL_X = 0.5 * (_GL_X + 1.0)
_GL_W = 0.5 * _GL_W


@dataclass(frozen=True)
class CatenarySolution:
    """Solution in the vertical plane: H [N] >= 0, V_A [N] (tension vector at A is
    (H e, V_A)), the plane's horizontal unit vector e (2,), and the line data."""

    horizontal_tension: float
    vertical_tension_a: float
    direction: np.ndarray
    length: float
    weight: float
    axial_stiffness: float
    iterations: int
    residual: float


def _inextensible_reach(a: np.ndarray, b: np.ndarray, s: np.ndarray) -> np.ndarray:
    """(H / w) [asinh(b) - asinh(a)] = s [asinh(b) - asinh(a)] / (b - a), with a = V_A / H,
    b = V(s) / H, evaluated without cancellation: the inextensible horizontal reach [m]."""
    a = np.broadcast_to(a, np.shape(b)).astype(float)
    out = np.empty_like(b, dtype=float)
    same = a * b > 0.0
    # opposite signs (or a zero): no cancellation in the plain difference
    opp = ~same
    if np.any(opp):
        d = np.arcsinh(b[opp]) - np.arcsinh(a[opp])
        delta = b[opp] - a[opp]
        with np.errstate(invalid="ignore", divide="ignore"):
            out[opp] = np.where(
                delta != 0.0,
                s[opp] * d / np.where(delta == 0, 1, delta),
                s[opp] / np.sqrt(1.0 + a[opp] ** 2),
            )
    if np.any(same):
        aa, bb, ss = a[same], b[same], s[same]
        aa, bb = np.abs(aa), np.abs(bb)
        delta = bb - aa  # asinh(b) - asinh(a) = +-asinh(delta c); s / (b - a) absorbs the sign
        c = (bb + aa) / (bb * np.sqrt(1.0 + aa * aa) + aa * np.sqrt(1.0 + bb * bb))
        x = delta * c
        # asinh(x) / x, with its series near 0
        small = np.abs(x) < 1e-4
        ratio = np.where(small, 1.0 - x * x / 6.0, np.arcsinh(x) / np.where(small, 1.0, x))
        out[same] = ss * c * ratio
    return out


def profile(sol: CatenarySolution, s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Horizontal reach x(s) [m], height z(s) [m] relative to A, tension T(s) [N]."""
    H, VA, w, EA = sol.horizontal_tension, sol.vertical_tension_a, sol.weight, sol.axial_stiffness
    s = np.asarray(s, dtype=float)
    V = VA + w * s
    TA = math.hypot(H, VA)
    T = np.hypot(H, V)
    if H > 0.0:
        reach = _inextensible_reach(np.full_like(s, VA / H), V / H, s)
        x = H * s / EA + reach
    else:
        x = np.zeros_like(s)
    with np.errstate(invalid="ignore", divide="ignore"):
        sag = np.where(T + TA > 0.0, s * (V + VA) / (T + TA), 0.0)
    z = (VA * s + 0.5 * w * s * s) / EA + sag
    return x, z, T


_GL_XS = tuple(float(v) for v in _GL_X)
_GL_WS = tuple(float(v) for v in _GL_W)


def _reach_scalar(a: float, b: float, s: float) -> float:
    """Scalar :func:`_inextensible_reach` (the Newton loop runs on Python floats: numpy's
    per-call overhead on one-element arrays would dominate)."""
    if a * b <= 0.0:
        if b == a:
            return s / math.sqrt(1.0 + a * a)
        return s * (math.asinh(b) - math.asinh(a)) / (b - a)
    aa, bb = abs(a), abs(b)
    c = (bb + aa) / (bb * math.sqrt(1.0 + aa * aa) + aa * math.sqrt(1.0 + bb * bb))
    x = (bb - aa) * c
    ratio = 1.0 - x * x / 6.0 if abs(x) < 1e-4 else math.asinh(x) / x
    return s * c * ratio


def _end_point(H: float, VA: float, L: float, w: float, EA: float) -> tuple[float, float]:
    """(x(L), z(L)) relative to A."""
    VB = VA + w * L
    TA, TB = math.hypot(H, VA), math.hypot(H, VB)
    x = H * L / EA + (_reach_scalar(VA / H, VB / H, L) if H > 0.0 else 0.0)
    z = (VA * L + 0.5 * w * L * L) / EA + (L * (VB + VA) / (TB + TA) if TA + TB > 0 else 0.0)
    return x, z


def _residual_and_jacobian(
    H: float, VA: float, L: float, w: float, EA: float
) -> tuple[tuple[float, float], tuple[float, float, float]]:
    """End position (x(L), z(L)) and its symmetric Jacobian (dx/dH, dx/dV_A = dz/dH,
    dz/dV_A) with respect to (H, V_A)."""
    f = _end_point(H, VA, L, w, EA)
    VB = VA + w * L
    TA, TB = math.hypot(H, VA), math.hypot(H, VB)
    if abs(w) * L < 0.1 * min(TA, TB):
        # nearly straight: the closed form of dx/dH cancels; integrate the derivatives
        # of the integrands, (V^2, -H V, H^2) / T^3, by 5-point Gauss-Legendre instead
        sxx = sxv = svv = 0.0
        for xi, wi in zip(_GL_XS, _GL_WS, strict=True):
            V = VA + w * L * xi
            T3 = (H * H + V * V) ** 1.5
            sxx += wi * V * V / T3
            sxv -= wi * H * V / T3
            svv += wi * H * H / T3
        return f, (L / EA + L * sxx, L * sxv, L / EA + L * svv)
    dxdH = L / EA + (math.asinh(VB / H) - math.asinh(VA / H) - (VB / TB - VA / TA)) / w
    dxdV = -H * L * (VA + VB) / (TA * TB * (TA + TB))
    dzdV = L / EA + (VB / TB - VA / TA) / w
    return f, (dxdH, dxdV, dzdV)


def _initial_guess(l: float, h: float, L: float, w: float, EA: float) -> tuple[float, float]:
    """Starting (H, V_A) for w > 0, after Peyrot & Goulios (1979), with the elastic
    stretch of a taut chord added."""
    chord = math.hypot(l, h)
    if l <= 0.0:
        return 0.0, -0.5 * w * (L - h) if L > abs(h) else -(w * L)
    if L * L <= chord * chord:
        lam = 0.2
    else:
        lam = math.sqrt(3.0 * ((L * L - h * h) / (l * l) - 1.0))
        lam = max(lam, 1e-3)
    H = abs(w * l / (2.0 * lam))
    VB = 0.5 * w * (h / math.tanh(lam) + L)
    if chord > L:
        T_stretch = EA * (chord / L - 1.0)
        H = max(H, T_stretch * l / chord)
        VB = max(VB, T_stretch * h / chord + 0.5 * w * L)
    return H, VB - w * L


def solve_plane(
    l: float,
    h: float,
    L: float,
    w: float,
    EA: float,
    *,
    tolerance: float = 1e-12,
    max_iterations: int = 100,
    deadline: float | None = None,
) -> tuple[CatenarySolution | None, int, str]:
    """Find (H, V_A) for horizontal span ``l`` >= 0 [m], rise ``h`` [m], length ``L`` [m],
    weight ``w`` [N/m] and stiffness ``EA`` [N]. Returns (solution or None, status,
    message)."""
    e = np.array([1.0, 0.0])
    if w < 0.0:  # buoyant line: mirror in z
        sol, status, msg = solve_plane(
            l, -h, L, -w, EA, tolerance=tolerance, max_iterations=max_iterations, deadline=deadline
        )
        if sol is None:
            return None, status, msg
        mirrored = CatenarySolution(
            sol.horizontal_tension,
            -sol.vertical_tension_a,
            e,
            L,
            w,
            EA,
            sol.iterations,
            sol.residual,
        )
        return mirrored, status, msg
    chord = math.hypot(l, h)
    scale = max(L, chord)
    if w == 0.0:
        if chord <= L:
            return (
                None,
                STATUS_NO_SOLUTION,
                (
                    f"weightless line with chord {chord:.6g} m not longer than its length "
                    f"{L:.6g} m has no unique static shape"
                ),
            )
        T = EA * (chord / L - 1.0)
        sol = CatenarySolution(T * l / chord, T * h / chord, e, L, 0.0, EA, 0, 0.0)
        return sol, STATUS_OK, ""
    if l == 0.0:
        return _solve_vertical(h, L, w, EA, tolerance, max_iterations)

    H, VA = _initial_guess(l, h, L, w, EA)
    (x, z), jac = _residual_and_jacobian(H, VA, L, w, EA)
    rx, rz = x - l, z - h
    norm = max(abs(rx), abs(rz))
    it = 0
    polish = 0
    for it in range(1, max_iterations + 1):
        if deadline is not None and time.monotonic() > deadline:
            return None, STATUS_TIME_LIMIT, f"time limit reached after {it} Newton iterations"
        jxx, jxv, jvv = jac
        det = jxx * jvv - jxv * jxv
        if det == 0.0 or not math.isfinite(det):
            return None, STATUS_NOT_CONVERGED, "singular Jacobian in the catenary Newton iteration"
        dH = (-rx * jvv + rz * jxv) / det
        dV = (-rz * jxx + rx * jxv) / det
        # backtracking: keep H > 0 and reduce the residual
        lam = 1.0
        while True:
            Hn = H + lam * dH
            if Hn <= 0.0:
                Hn = 0.1 * H
            VAn = VA + lam * dV
            (xn, zn), jn = _residual_and_jacobian(Hn, VAn, L, w, EA)
            rxn, rzn = xn - l, zn - h
            nn = max(abs(rxn), abs(rzn))
            if nn < norm or lam < 1e-6 or norm < 1e-14 * scale:
                break
            lam *= 0.5
        H, VA, rx, rz, jac, norm = Hn, VAn, rxn, rzn, jn, nn
        if norm <= max(tolerance, 1e-15) * scale:
            polish += 1
            # Newton converges quadratically: two more steps reach round-off
            if polish > 2 or norm <= 4e-16 * scale:
                break
    converged = norm <= tolerance * scale
    sol = CatenarySolution(H, VA, e, L, w, EA, it, norm / scale)
    if not converged:
        return (
            sol,
            STATUS_NOT_CONVERGED,
            (
                f"catenary Newton did not converge in {max_iterations} iterations "
                f"(relative residual {norm / scale:.3g}, tolerance {tolerance:.3g})"
            ),
        )
    return sol, STATUS_OK, ""


def _solve_vertical(
    h: float, L: float, w: float, EA: float, tolerance: float, max_iterations: int
) -> tuple[CatenarySolution | None, int, str]:
    """Zero horizontal span (H = 0): a vertical line, straight or folded. z(L) is
    monotone in V_A, so a bracketing root find is safe."""
    e = np.array([1.0, 0.0])

    def z_end(VA: float) -> float:
        return _end_point(0.0, VA, L, w, EA)[1] - h

    lo, hi = -w * L - 1.0, 1.0
    while z_end(lo) > 0.0:
        lo = 2.0 * lo - 1.0
    while z_end(hi) < 0.0:
        hi = 2.0 * hi + 1.0
    from scipy.optimize import brentq

    VA, info = brentq(
        z_end, lo, hi, xtol=1e-300, rtol=1e-15, full_output=True, maxiter=max(max_iterations, 200)
    )
    res = abs(z_end(VA)) / max(L, abs(h))
    status = STATUS_OK if res <= max(tolerance, 1e-12) else STATUS_NOT_CONVERGED
    return (
        CatenarySolution(0.0, VA, e, L, w, EA, info.iterations, res),
        status,
        ("" if status == STATUS_OK else f"vertical line did not converge (residual {res:.3g})"),
    )


def solve_between(
    position_a: np.ndarray,
    position_b: np.ndarray,
    length: float,
    weight: float,
    axial_stiffness: float,
    s: np.ndarray,
    *,
    tolerance: float = 1e-12,
    max_iterations: int = 100,
    deadline: float | None = None,
) -> StaticResult:
    """Exact elastic catenary between two fixed points in 3D, sampled at ``s`` [m]."""
    pa = np.asarray(position_a, dtype=float)
    pb = np.asarray(position_b, dtype=float)
    d = pb - pa
    l = math.hypot(d[0], d[1])
    e = d[:2] / l if l > 0.0 else np.array([1.0, 0.0])
    sol, status, msg = solve_plane(
        l,
        d[2],
        length,
        weight,
        axial_stiffness,
        tolerance=tolerance,
        max_iterations=max_iterations,
        deadline=deadline,
    )
    if sol is None:
        return StaticResult.failed(s, status, msg)
    x, z, T = profile(sol, s)
    position = np.empty((len(s), 3))
    position[:, 0] = pa[0] + x * e[0]
    position[:, 1] = pa[1] + x * e[1]
    position[:, 2] = pa[2] + z
    H, VA = sol.horizontal_tension, sol.vertical_tension_a
    VB = VA + weight * length
    force_a = np.array([H * e[0], H * e[1], VA])
    force_b = -np.array([H * e[0], H * e[1], VB])
    result = StaticResult(
        s=s,
        position=position,
        tension=T,
        force_a=force_a,
        force_b=force_b,
        status=status,
        message=msg,
        iterations=sol.iterations,
        residual=sol.residual,
    )
    if status != STATUS_OK:
        result = StaticResult.failed(
            s, status, msg, iterations=sol.iterations, residual=sol.residual
        )
    return result.check_finite()


class ElasticCatenarySolver:
    """Registry entry ``analytic``: Irvine's closed form for one uniform line between two
    fixed ends, in still fluid, without attachments. A line that would pass through the
    seabed is reported as a failure (use a solver with seabed contact)."""

    name = "analytic"

    def unsupported(self, problem: StaticProblem) -> list[str]:
        out = []
        if problem.end_a.kind != "fixed" or problem.end_b.kind != "fixed":
            out.append(
                f"end kinds a={problem.end_a.kind!r}, b={problem.end_b.kind!r} "
                "(only both ends 'fixed')"
            )
        if problem.line.is_nonlinear:
            out.append(
                "a non-linear axial law (line.segments.N.axial: polynomial, steel_wire, "
                "table); the closed form needs T = EA e: use method 'catenary' or 'shooting'"
            )
        elif not problem.line.is_uniform:
            out.append("segments of different weight or axial stiffness")
        if problem.line.attachment_s.size:
            out.append("attachments")
        if problem.medium.has_current:
            out.append("current")
        if problem.is_installation:
            out.append("installation (pay-out speed, touchdown velocity)")
        if problem.stretched_drag_diameter and problem.medium.has_current:
            out.append("drag on the stretched diameter (drag_diameter: stretched)")
        return out

    def solve(self, problem: StaticProblem, *, deadline: float | None = None) -> StaticResult:
        line = problem.line
        s = np.linspace(0.0, line.total_length, problem.n_nodes)
        assert problem.end_a.position is not None and problem.end_b.position is not None
        result = solve_between(
            problem.end_a.position,
            problem.end_b.position,
            line.total_length,
            float(line.weight[0]),
            float(line.axial_stiffness[0]),
            s,
            tolerance=min(problem.tolerance, 1e-12),
            max_iterations=problem.max_iterations,
            deadline=deadline,
        )
        if result.success and problem.medium.depth is not None:
            ground = problem.medium.seabed_z(result.position[:, 0], result.position[:, 1])
            below = result.position[:, 2] < ground - 1e-9 * line.total_length
            if np.any(below):
                depth_below = float(np.max(ground - result.position[:, 2]))
                return StaticResult.failed(
                    s,
                    STATUS_NO_SOLUTION,
                    f"the free-hanging catenary passes {depth_below:.4g} m below the seabed; "
                    "this method has no seabed contact (choose a method with seabed contact)",
                    iterations=result.iterations,
                    residual=result.residual,
                )
        return result
