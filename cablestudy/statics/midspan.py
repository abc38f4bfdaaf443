"""Seabed contact between the ends: a line whose ends are both above the seabed but
which sags onto it (a U-shaped cable between two structures, a riser's sag bend).

The line touches down at s1 and lifts off at s2 > s1; between them it lies straight on
the seabed along the direction e of the tension at s1 (which lies in the seabed plane),
the seabed carries the normal part of its weight, and the tension changes along the
laid part only by the component of the weight along it, w (e . z) per metre, and by the
along-line part of point loads resting there. No friction acts on a laid part between
two suspended parts: the usual convention (friction mobilised towards an anchor) has no
anchor to point to here, so this is the frictionless equilibrium. On a slope the laid
tension grows uphill, so a line longer than its taut shape with zero tension at the
laid part's lower end has no straight laid part: the excess slides down and lies slack
(refused as such, not as a non-convergence).

Unknowns: the tension at s1 in the seabed plane (two components), s1 and s2. Equations:
the touchdown point lies on the seabed, and the end B is reached (three components).
Newton's method with a forward-difference Jacobian and a backtracking line search on the
residual norm, started from the free-hanging solution that dips into the seabed.
"""

from __future__ import annotations

import math
import time

import numpy as np

from .base import STATUS_NO_SOLUTION, STATUS_NOT_CONVERGED, STATUS_TIME_LIMIT
from .contact_pin import arch_refusal
from .law_pieces import piece_increments
from .seabed import Plane, _law_stretch
from .semi_analytic_shape import Ends, Layout, Shape, _Failure, _suspended


def _prefix(lay: Layout, q: np.ndarray, s1: float) -> tuple[np.ndarray, ...]:
    """Pieces from 0 to s1: (s0, ell, EA, q, C, C_end) with T(start of piece p) =
    T_A - C[p] and T(s1) = T_A - C_end."""
    k = int(np.clip(np.searchsorted(lay.bounds, s1, side="right") - 1, 0, len(lay.ell) - 1))
    s0 = lay.bounds[: k + 1].copy()
    ell = np.append(lay.ell[:k], s1 - lay.bounds[k])
    EA = lay.EA[: k + 1]
    qs = q[: k + 1]
    Q = qs * ell[:, None]
    C = np.cumsum(lay.point[: k + 1], axis=0)
    C[1:] += np.cumsum(Q[:-1], axis=0)
    Cend = lay.point[: k + 1].sum(axis=0) + Q.sum(axis=0)
    return s0, ell, EA, qs, C, Cend


def _laid_mid(
    lay: Layout, s1: float, s2: float, tension: float, e: np.ndarray
) -> tuple[list[tuple[float, float, float, float, float]], float, float]:
    """March the laid part from s1 to s2: pieces (start, length, tension at start,
    rate [N/m], EA), the stretched length [m], the tension at s2 [N]."""
    cuts = lay.bounds[(lay.bounds > s1) & (lay.bounds < s2)]
    pts = np.concatenate(([s1], cuts, [s2]))
    out = []
    stretched = 0.0
    t = tension
    for a, b in zip(pts[:-1], pts[1:], strict=True):
        k = int(
            np.clip(
                np.searchsorted(lay.bounds, 0.5 * (a + b), side="right") - 1, 0, len(lay.ell) - 1
            )
        )
        if a > s1:  # point load resting at a boundary: its along-line part
            j = int(np.argmin(np.abs(lay.bounds - a)))
            t -= float(lay.point[j] @ e)
        rate = float(lay.weight[k] * e[2])
        t_end = t + rate * (b - a)
        if min(t, t_end) <= 0.0:
            raise _Failure(
                STATUS_NO_SOLUTION,
                "the laid part between the touchdown and lift-off "
                "points would be slack (it slides down the slope)",
            )
        law = lay.law[k] if lay.law is not None else None
        out.append((float(a), float(b - a), t, rate, float(lay.EA[k]), law))
        if law is None:
            stretched += (b - a) + 0.5 * (b - a) * (t + t_end) / float(lay.EA[k])
        else:
            # the tension runs linearly from t to t_end (either way): the law's integral
            lo_t, hi_t = min(t, t_end), max(t, t_end)
            stretched += (b - a) + _law_stretch(law, lo_t, hi_t, b - a)[0]
        t = t_end
    return out, stretched, t


def _evaluate(
    y: np.ndarray, lay: Layout, q: np.ndarray, ends: Ends, plane: Plane, basis: np.ndarray
) -> tuple[np.ndarray, dict]:
    assert ends.rB is not None
    L = lay.total
    T_td = basis @ y[:2]
    tn = float(np.linalg.norm(T_td))
    if not tn > 0.0:
        raise _Failure(STATUS_NO_SOLUTION, "zero tension where the line touches the seabed")
    e = T_td / tn
    s1, s2 = float(y[2]), float(y[3])
    s0p, ellp, EAp, qp, Cp, Cend1 = _prefix(lay, q, s1)
    TA = T_td + Cend1
    T0p = TA - Cp
    lawp = None if lay.law is None else lay.law[: len(ellp)]
    drp, _, _ = piece_increments(T0p, qp, ellp, EAp, lawp, jacobian=False)
    r1 = ends.rA + drp.sum(axis=0)
    laid, stretched, t2 = _laid_mid(lay, s1, s2, tn, e)
    r2 = r1 + e * stretched
    s0s, ells, EAs, qs, C2, k2, Cend2 = _suspended(lay, q, s2)
    T0s = t2 * e - C2
    laws = None if lay.law is None else lay.law[k2:]
    drs, _, _ = piece_increments(T0s, qs, ells, EAs, laws, jacobian=False)
    rB = r2 + drs.sum(axis=0)
    R = np.concatenate(([float(plane.height_above(r1))], rB - ends.rB)) / L
    parts = dict(
        s0p=s0p,
        ellp=ellp,
        EAp=EAp,
        qp=qp,
        T0p=T0p,
        drp=drp,
        laid=laid,
        e=e,
        s0s=s0s,
        ells=ells,
        EAs=EAs,
        qs=qs,
        T0s=T0s,
        drs=drs,
        TA=TA,
        TL=t2 * e - Cend2,
        s1=s1,
        s2=s2,
        lawp=lawp,
        laws=laws,
    )
    return R, parts


# A stalled Newton whose iterate has driven the laid part's lowest tension below this
# fraction of the line's weight is at the slack limit, not near a solution: a laid part
# with a determined shape carries a tension bounded away from zero (the regression
# examples stall at 1e-68 to 1e-80 of the weight; a converging one never goes below it).
SLID_SLACK_TENSION = 1e-6


def _refuse_if_slid_slack(parts: dict, weight: float, it: int, res: float) -> None:
    """On a sloping seabed the laid part's tension grows uphill by w (e . z) per metre,
    so its lower end carries the least. If the line is longer than the taut shape with
    zero tension there (the lower end hanging straight down, the upper one lifted off
    with the tension the laid weight gives it), no straight laid part fits: the excess
    slides down the slope and lies slack at its foot, with no determined shape. The
    Newton then drives that lowest tension to zero and stalls with a finite residual:
    say so, in place of a bare non-convergence."""
    lowest = min(min(t, t + rate * length) for _, length, t, rate, _, _ in parts["laid"])
    if lowest < SLID_SLACK_TENSION * weight:
        raise _Failure(
            STATUS_NO_SOLUTION,
            f"the tension at the lower end of the part resting on the seabed between the "
            f"ends falls to zero ({lowest:.3g} N) while B is still not reached (residual "
            f"{res:.3g}): the line is longer than its taut shape over the sloping seabed, "
            "the excess slides down the slope and lies slack there, so its laid shape is "
            "not determined",
            it,
            res,
        )


def _shape(parts: dict, rA: np.ndarray) -> Shape:
    e = parts["e"]
    s0 = [parts["s0p"]]
    ell = [parts["ellp"]]
    T0 = [parts["T0p"]]
    qq = [parts["qp"]]
    EA = [parts["EAp"]]
    laws: list = list(parts["lawp"]) if parts["lawp"] is not None else []
    for a, length, t, rate, ea, law in parts["laid"]:
        s0.append(np.array([a]))
        ell.append(np.array([length]))
        T0.append((t * e)[None, :])
        qq.append((-rate * e)[None, :])
        EA.append(np.array([ea]))
        laws.append(law)
    s0 += [parts["s0s"]]
    ell += [parts["ells"]]
    T0 += [parts["T0s"]]
    qq += [parts["qs"]]
    EA += [parts["EAs"]]
    if parts["laws"] is not None:
        laws += list(parts["laws"])
    all_laws = tuple(laws) if parts["lawp"] is not None else None
    s0a, ella, T0a, qa, EAa = (np.concatenate(x) for x in (s0, ell, T0, qq, EA))
    dr, _, _ = piece_increments(T0a, qa, ella, EAa, all_laws, jacobian=False)
    r0 = rA + np.concatenate((np.zeros((1, 3)), np.cumsum(dr, axis=0)))[:-1]
    return Shape(
        s0=s0a,
        ell=ella,
        T0=T0a,
        q=qa,
        EA=EAa,
        r0=r0,
        force_a=parts["TA"],
        tension_end=parts["TL"],
        laid_length=parts["s2"] - parts["s1"],
        laid_start=parts["s1"],
        contact=True,
        law=all_laws,
    )


def initial_midspan(free: Shape, plane: Plane, L: float) -> np.ndarray:
    """(alpha, beta, s1, s2) from the free-hanging shape that dips into the seabed: the
    range where it is below, and its tension at the lowest point projected on the plane."""
    s = np.linspace(0.0, L, 2001)
    pos, _ = free.sample(s)
    h = plane.height_above(pos)
    below = np.flatnonzero(h < 0.0)
    i = int(np.argmin(h))
    k = int(np.clip(np.searchsorted(free.s0, s[i], side="right") - 1, 0, len(free.s0) - 1))
    T = free.T0[k] - free.q[k] * (s[i] - free.s0[k])
    n = plane.normal
    T = T - (T @ n) * n
    e1, e2 = plane.basis
    s1 = s[below[0]] if below.size else s[i] - 1e-3 * L
    s2 = s[below[-1]] if below.size else s[i] + 1e-3 * L
    return np.array([float(T @ e1), float(T @ e2), s1, max(s2, s1 + 1e-6 * L)])


def solve_midspan(
    lay: Layout,
    q: np.ndarray,
    ends: Ends,
    plane: Plane,
    guess: np.ndarray,
    *,
    tol: float,
    max_iterations: int,
    deadline: float | None,
) -> Shape:
    """Both ends fixed above the seabed, the line resting on it between s1 and s2."""
    if ends.kind != "fixed":
        raise _Failure(
            STATUS_NO_SOLUTION,
            "the line would rest on the seabed between its ends; "
            "this is modelled for two fixed ends only",
        )
    L = lay.total
    n = plane.normal
    ha = float(plane.height_above(ends.rA))
    hb = float(plane.height_above(ends.rB))  # type: ignore[arg-type]
    d = ends.rB - ends.rA  # type: ignore[operator]
    along = float(np.linalg.norm(d - (d @ n) * n))
    # an upward load inside (an attachment pulling up, a piece lighter than the fluid)
    # can hold the line off the seabed between two laid stretches, not this one shape
    why = arch_refusal(lay, n, (0.0, L), "catenary", ends.flip)
    if L >= ha + along + hb and why:
        raise _Failure(STATUS_NO_SOLUTION, why, final=True)
    if L >= ha + along + hb:
        raise _Failure(
            STATUS_NO_SOLUTION,
            f"the line ({L:.6g} m) is not shorter than the path "
            f"down to the seabed, along it and up to the other end "
            f"({ha + along + hb:.6g} m): it lies slack on the seabed and its laid "
            "shape is not determined",
            final=True,
        )
    e1, e2 = plane.basis
    basis = np.stack((e1, e2), axis=1)
    weight = float(np.sum(np.abs(lay.weight) * lay.ell))  # load scale [N]
    y = guess.astype(float).copy()
    R, parts = _evaluate(y, lay, q, ends, plane, basis)
    res = float(np.max(np.abs(R)))
    it = 0
    polished = False
    while True:
        if res <= tol:
            if polished or res <= 1e-15:
                break
            polished = True
        if it >= max_iterations:
            _refuse_if_slid_slack(parts, weight, it, res)
            raise _Failure(
                STATUS_NOT_CONVERGED,
                "seabed-contact (between the ends) Newton did "
                f"not converge in {max_iterations} iterations (residual {res:.3g})",
                it,
                res,
            )
        if deadline is not None and time.monotonic() > deadline:
            raise _Failure(
                STATUS_TIME_LIMIT,
                f"time limit reached after {it} iterations of the seabed-contact Newton iteration",
                it,
                res,
            )
        it += 1
        J = np.empty((4, 4))
        for j in range(4):
            h = 1e-7 * (max(abs(y[j]), 1e-3 * float(np.linalg.norm(y[:2]))) if j < 2 else L)
            yp = y.copy()
            yp[j] += h if j != 3 or yp[3] + h < L else -h
            Rp, _ = _evaluate(yp, lay, q, ends, plane, basis)
            J[:, j] = (Rp - R) / (yp[j] - y[j])
        try:
            step = np.linalg.solve(J, -R)
        except np.linalg.LinAlgError:
            step = -np.linalg.lstsq(J, R, rcond=None)[0]
        lam = 1.0
        norm0 = float(np.linalg.norm(R))
        for _ in range(40):
            yn = y + lam * step
            yn[2] = min(max(yn[2], 0.0), L)
            yn[3] = min(max(yn[3], yn[2]), L)
            try:
                Rn, pn = _evaluate(yn, lay, q, ends, plane, basis)
            except _Failure:
                lam *= 0.5
                continue
            if np.all(np.isfinite(Rn)) and float(np.linalg.norm(Rn)) <= (1 - 1e-4 * lam) * norm0:
                break
            lam *= 0.5
        else:
            _refuse_if_slid_slack(parts, weight, it, res)
            tn = float(np.linalg.norm(y[:2]))
            if tn < 1e-2 * weight:
                raise _Failure(
                    STATUS_NO_SOLUTION,
                    f"the tension of the part resting on the seabed between the ends falls to "
                    f"zero ({tn:.3g} N): with no friction there it would be pushed into a curve "
                    "(slack on the seabed), so its shape is not determined",
                    it,
                    res,
                )
            raise _Failure(
                STATUS_NOT_CONVERGED,
                "line search failed in the seabed-contact "
                f"(between the ends) Newton iteration (residual {res:.3g})",
                it,
                res,
            )
        y, R, parts = yn, Rn, pn
        res = float(np.max(np.abs(R)))
    if not (0.0 < y[2] < y[3] < L) or not math.isfinite(res):
        raise _Failure(
            STATUS_NO_SOLUTION,
            "the seabed contact between the ends did not settle "
            f"inside the line (touchdown {y[2]:.6g} m, lift-off {y[3]:.6g} m)",
            it,
            res,
        )
    why = arch_refusal(lay, n, (y[2], y[3]), "catenary", ends.flip)
    if why:  # a laid stretch the seabed would have to pull down
        raise _Failure(STATUS_NO_SOLUTION, why, it, res, final=True)
    shape = _shape(parts, ends.rA)
    shape.iterations = it
    shape.residual = res
    return shape
