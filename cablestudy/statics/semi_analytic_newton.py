"""The semi-analytic solver's Newton iterations on the end forces
(:mod:`.semi_analytic`): a line hanging free, on the tension at end A (:func:`solve_free`:
damped Newton with an Armijo line search on the convex complementary energy, the
compiled kernel first where it applies), and a line anchored on the seabed, on the
tension at the touchdown point and the laid length (:func:`solve_contact`), with their
starting values.
"""

from __future__ import annotations

import math

import numpy as np

from .base import (
    STATUS_NO_SOLUTION,
    STATUS_NOT_CONVERGED,
    STATUS_NUMERICAL,
    STATUS_TIME_LIMIT,
)
from .contact_pin import arch_refusal, first_lift, pin_jump, pin_map
from .law_pieces import piece_increments
from .seabed import Plane
from .semi_analytic_shape import (
    Ends,
    Layout,
    Shape,
    _check_deadline,
    _contact_shape,
    _Failure,
    _finite,
    _free_shape,
    _laid,
    _offsets,
    _suspended,
)

# --------------------------------------------------------------------------- free line


def initial_tension(lay: Layout, q: np.ndarray, ends: Ends) -> np.ndarray:
    """Starting T_A for a free-hanging line: the uniform line with the same total load
    (direction and size) between the same ends, after Peyrot & Goulios (1979), with the
    elastic stretch added for taut chords."""
    from ._drag_inner import mooring_vertical, uniform_end_tension  # numba: not at import

    C, Cend = _offsets(lay, q)
    L = lay.total
    EA = L / float(np.sum(lay.ell / lay.EA))
    if ends.kind == "force":
        assert ends.force is not None
        return ends.force + Cend
    W = float(np.linalg.norm(Cend))
    if ends.kind == "mooring":
        assert ends.force is not None
        TA = np.array([ends.force[0] + Cend[0], ends.force[1] + Cend[1], 0.0])
        h = ends.zB - float(ends.rA[2])
        TA[2] = mooring_vertical(math.hypot(TA[0], TA[1]), -float(Cend[2]), h, L)
        return TA
    assert ends.rB is not None
    d = ends.rB - ends.rA
    chord = float(np.linalg.norm(d))
    stretch = EA * max(chord / L - 1.0, 0.0)
    if W <= 1e-12 * max(EA, 1.0) * 1e-6 or W == 0.0:
        t = stretch if stretch > 0.0 else 1e-6 * EA
        return t * d / max(chord, 1e-300) + C[0] * 0.0
    up = -Cend / W
    w = W / L
    h = float(d @ up)
    dh = d - h * up
    l = float(np.linalg.norm(dh))
    if l > 1e-12 * chord:
        e = dh / l
    else:
        e = np.cross(up, [1.0, 0.0, 0.0])
        if np.linalg.norm(e) < 0.5:
            e = np.cross(up, [0.0, 1.0, 0.0])
        e = e / np.linalg.norm(e)
    H, VA = uniform_end_tension(w, L, h, l, chord, stretch)
    # T_A is the tension just before the point load at s = 0: add it back
    return H * e + VA * up + lay.point[0]


def solve_free(
    lay: Layout,
    q: np.ndarray,
    ends: Ends,
    TA: np.ndarray,
    *,
    tol: float,
    max_iterations: int,
    deadline: float | None,
    polish: bool = True,
) -> Shape:
    """Solve a free-hanging line for T_A (Newton on the complementary energy). With
    ``polish`` one more Newton step is taken once the tolerance is met (quadratic
    convergence then brings the residual to round-off)."""
    C, Cend = _offsets(lay, q)
    L = lay.total
    if ends.kind == "force":
        assert ends.force is not None
        shape = _free_shape(lay, q, ends.rA, ends.force + Cend)
        _finite(shape, "towed line")
        return shape
    if ends.kind == "fixed":
        assert ends.rB is not None
        target = ends.rB - ends.rA
        idx = np.array([0, 1, 2])
    else:
        assert ends.force is not None
        TA = TA.copy()
        TA[:2] = ends.force[:2] + Cend[:2]
        target = np.array([0.0, 0.0, ends.zB - float(ends.rA[2])])
        idx = np.array([2])
    scale = max(L, float(np.linalg.norm(target)))

    last: list[np.ndarray] = []
    from . import _fast

    if lay.law is None:
        qc = np.ascontiguousarray(q, dtype=float)
        Cc = np.ascontiguousarray(C)

        def evaluate(T: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
            dr = np.empty((len(lay.ell), 3))
            r = np.empty(3)
            J = np.empty((3, 3))
            E = _fast.line_sums(
                np.ascontiguousarray(T, dtype=float), Cc, qc, lay.ell, lay.EA, dr, r, J, True
            )
            last[:] = [dr]
            return r, J, E
    else:

        def evaluate(T: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
            dr, jac, en = piece_increments(T - C, q, lay.ell, lay.EA, lay.law)
            assert jac is not None
            last[:] = [dr]
            return dr.sum(axis=0), jac.sum(axis=0), float(en.sum())

    r, J, E = evaluate(TA)
    dr_acc = last[0]
    g = r[idx] - target[idx]
    psi = E - float(target[idx] @ TA[idx])
    it = 0
    polished = 0 if polish else 1
    res = float(np.max(np.abs(g))) / scale
    while True:
        if not np.isfinite(res):
            raise _Failure(
                STATUS_NUMERICAL,
                "non-finite residual in the end-force Newton "
                "iteration (a piece with zero tension and no load?)",
                it,
                res,
            )
        if res <= tol:
            if polished >= 1 or res <= 1e-15:
                break
            polished += 1
        if it >= max_iterations:
            raise _Failure(
                STATUS_NOT_CONVERGED,
                f"end-force Newton did not converge in "
                f"{max_iterations} iterations (relative residual {res:.3g}, "
                f"tolerance {tol:.3g})",
                it,
                res,
            )
        _check_deadline(deadline, it, "the end-force Newton iteration")
        it += 1
        Jf = J[np.ix_(idx, idx)]
        try:
            step = np.linalg.solve(Jf, -g)
        except np.linalg.LinAlgError:
            step = -g / max(float(np.trace(Jf)), 1e-300)
        slope = float(g @ step)
        lam = 1.0
        slack = 1e-13 * (abs(E) + abs(float(target[idx] @ TA[idx])))
        for _ in range(80):
            Tn = TA.copy()
            Tn[idx] += lam * step
            rn, Jn, En = evaluate(Tn)
            psin = En - float(target[idx] @ Tn[idx])
            if (
                np.isfinite(psin)
                and np.all(np.isfinite(Jn))
                and psin <= psi + 1e-4 * lam * slope + slack
            ):
                break
            lam *= 0.5
        else:
            raise _Failure(
                STATUS_NOT_CONVERGED,
                "line search failed in the end-force Newton "
                f"iteration (relative residual {res:.3g})",
                it,
                res,
            )
        TA, r, J, E, psi = Tn, rn, Jn, En, psin
        dr_acc = last[0]
        g = r[idx] - target[idx]
        res = float(np.max(np.abs(g))) / scale
    shape = _free_shape(lay, q, ends.rA, TA, dr_acc)
    shape.iterations = it
    shape.residual = res
    _finite(shape, "free-hanging line")
    return shape


def initial_contact(
    lay: Layout, ends: Ends, plane: Plane, *, still: bool = False
) -> tuple[np.ndarray, float]:
    """Starting (T_td, s_td): the inextensible uniform line with the same weight, lying
    on the seabed from the anchor and hanging to B (classical mooring-line formulas:
    suspended length sqrt(h^2 + 2 h H / w), reach (H/w) acosh(1 + w h / H))."""
    L = lay.total
    n = plane.normal
    w = max(float(np.sum(lay.weight * lay.ell)) / L * float(n[2]), 1e-12)
    e1, _ = plane.basis
    if ends.kind == "fixed":
        assert ends.rB is not None
        d = ends.rB - ends.rA
        h = max(float(d @ n), 1e-9 * L)
        dp = d - (d @ n) * n
        X = float(np.linalg.norm(dp))
        e = dp / X if X > 0.0 else e1

        def excess(H: float) -> float:
            Ls = math.sqrt(h * h + 2.0 * h * H / w)
            return L - Ls + H / w * math.acosh(1.0 + w * h / H) - X

        Hmax = w * (L * L - h * h) / (2.0 * h) if L > h else w * L
        lo, hi = 1e-9 * w * L, Hmax
        # a piece lighter than the fluid (or an attachment pulling up) can hold a line
        # longer than that path off the seabed: then the contact Newton decides
        lifted = bool(np.any(lay.weight < 0.0)) or bool(np.any(lay.point @ plane.normal > 0.0))
        if still and L - h - X > 1e-9 * L and not lifted:
            raise _Failure(
                STATUS_NO_SOLUTION,
                f"the line ({L:.6g} m) is longer than the path "
                f"along the seabed and straight up to B ({X + h:.6g} m): it lies slack "
                "on the seabed and its laid shape is not determined",
                final=True,
            )
        # the reach grows with H (a tauter line lifts more of itself off the seabed and
        # reaches further), so the excess is increasing: bisect on its sign change
        if excess(hi) <= 0.0:
            H = hi
        elif excess(lo) >= 0.0:
            H = lo
        else:
            for _ in range(60):
                mid = math.sqrt(lo * hi)
                if excess(mid) > 0.0:
                    hi = mid
                else:
                    lo = mid
                if hi <= lo * (1.0 + 1e-12):
                    break
            H = math.sqrt(lo * hi)
    else:
        assert ends.force is not None
        h = max(ends.zB - float(ends.rA[2]), 1e-9 * L)
        fh = np.array([ends.force[0], ends.force[1], 0.0])
        H = float(np.linalg.norm(fh))
        e = fh - (fh @ n) * n
        e = e / np.linalg.norm(e) if np.linalg.norm(e) > 0.0 else e1
    Ls = min(math.sqrt(h * h + 2.0 * h * H / w), L)
    s_td = max(L - Ls, 0.0)
    buoyant = np.flatnonzero(lay.weight < 0.0)
    if buoyant.size:
        # the uniform line's guess can lay a buoyant piece (a lazy wave's floats), which
        # the laid part cannot hold and Newton cannot leave: start the touchdown halfway
        # to the first buoyant piece
        s_td = min(s_td, 0.5 * float(lay.bounds[buoyant[0]]))
    return H * e, s_td


def _slack_hint(lay: Layout, *, current: bool = False) -> str:
    """Why the touchdown tension of a contact solve vanishes, for its message ("; ..."):
    a buoyant piece (which the laid-part model would lay on the seabed, where it cannot
    stay), else a line longer than the path along the seabed and up to B."""
    buoyant = np.flatnonzero(lay.weight < 0.0)
    if buoyant.size:
        k = int(buoyant[0])
        return (
            "; the tension at the touchdown point tends to zero: the line holds a buoyant "
            f"piece (weight in the fluid {float(lay.weight[k]):.4g} N/m, s = "
            f"{float(lay.bounds[k]):.6g} to {float(lay.bounds[k + 1]):.6g} m), which "
            "rises off the seabed; the seabed-contact model lays the line straight on "
            "the seabed from the anchor to its touchdown point and cannot hold a piece "
            "lighter than the fluid there (make it heavier than the fluid, or shorten "
            "the laid part)"
        )
    why = " (or the current pushes it back towards the anchor)" if current else ""
    return (
        "; the tension at the touchdown point tends to zero: the line is longer than "
        f"the straight path along the seabed and up to B{why}, so it lies slack on the "
        "seabed and its laid shape is not determined"
    )


def solve_contact(
    lay: Layout,
    q: np.ndarray,
    ends: Ends,
    plane: Plane,
    guess: tuple[np.ndarray, float],
    *,
    tol: float,
    max_iterations: int,
    deadline: float | None,
) -> Shape | None:
    """Line anchored at A on the seabed with a laid part: Newton on (T_td in the seabed
    plane, s_td) with an analytic Jacobian. Returns None if the line lifts off (s_td
    driven to zero).

    With a point load lifting the line (a lazy wave's buoyancy modules) the TDP is first
    kept short of it (:func:`.contact_pin.first_lift`), starting halfway to it when the
    guess lies past it (the uniform line's guess ignores the lift). If that state does
    not exist (Newton held at the load) or its suspended line dips below the seabed
    (the modules' stretch would rest on the seabed, or arch off it between two laid
    stretches, which one laid part from the anchor cannot represent), the unbounded
    Newton from the given guess answers instead: if it fails or its state lays the load
    (which the seabed would have to pull down), the line is refused by name
    (:func:`.contact_pin.arch_refusal`)."""
    s_up, k_up = first_lift(lay.bounds, lay.point, plane.normal)
    if k_up >= 0:
        T_td, s_td = guess
        start = (T_td, s_td if s_td < s_up else 0.5 * s_up)
        try:
            shape = _solve_contact(lay, q, ends, plane, start, tol, max_iterations, deadline, True)
        except _Failure as exc:
            if exc.status != STATUS_NOT_CONVERGED:
                raise
        else:
            if shape is None or not _dips(shape, lay, plane, tol):
                return shape
    failed: _Failure | None = None
    try:
        shape = _solve_contact(lay, q, ends, plane, guess, tol, max_iterations, deadline, False)
    except _Failure as exc:
        if k_up < 0 or exc.status == STATUS_TIME_LIMIT:
            raise
        shape, failed = None, exc
    laid = lay.total if failed else 0.0 if shape is None else shape.laid_length
    why = arch_refusal(lay, plane.normal, (0.0, laid), "catenary", ends.flip)
    if why:  # the state lays a load lifting the line, which the seabed cannot hold down
        raise _Failure(STATUS_NO_SOLUTION, why, final=True) from failed
    return shape


def _held_across(plane: Plane, T_td: np.ndarray, tol: float, it: int, res: float) -> None:
    """Refuse a laid line that friction cannot hold on the slope across it: its weight's
    part down the slope across the line, c per unit weight, exceeds mu n_z by more than
    the solve's relative tolerance ``tol`` (the laid part then takes no friction along
    itself, :func:`.seabed.along_friction`)."""
    n, mu = plane.normal, plane.friction
    e = T_td / float(np.linalg.norm(T_td))
    c = abs(float(n[0] * e[1] - n[1] * e[0]))
    if c <= mu * float(n[2]) + tol:
        return
    raise _Failure(
        STATUS_NO_SOLUTION,
        f"no straight laid line: it lies across the seabed slope, whose fall across it "
        f"(gradient {c / float(n[2]):.3g}) exceeds the friction coefficient {mu:.3g}, so "
        "friction cannot hold it from sliding sideways (this method lays the line "
        "straight along the touchdown tension; method 'discrete' models it sliding)",
        it,
        res,
    )


def _dips(shape: Shape, lay: Layout, plane: Plane, tol: float) -> bool:
    """Whether the suspended line of a contact state passes below the seabed (by more
    than the solve's tolerance on positions, as the solver's own penetration check)."""
    L = lay.total
    s = np.linspace(shape.laid_length, L, 401)
    pos, _ = shape.sample(s)
    return bool(-np.min(plane.height_above(pos)) > max(1e-6 * L, 1e3 * tol * L))


def _solve_contact(
    lay: Layout,
    q: np.ndarray,
    ends: Ends,
    plane: Plane,
    guess: tuple[np.ndarray, float],
    tol: float,
    max_iterations: int,
    deadline: float | None,
    bounded: bool,
) -> Shape | None:
    """:func:`solve_contact`'s Newton; ``bounded``: the TDP kept short of the first
    load lifting the line."""
    L = lay.total
    e1, e2 = plane.basis
    basis = np.stack((e1, e2), axis=1)  # (3, 2)
    T_td, s_td = guess
    # the TDP coordinate: s_td, extended by an interval at each downward point load over
    # which the TDP stays at the load and the seabed takes up its weight (.contact_pin)
    pins = pin_map(lay.bounds, lay.point, lay.weight, plane.normal)
    # the TDP stays short of the first load lifting the line (.contact_pin.first_lift)
    s_up, k_up = first_lift(lay.bounds, lay.point, plane.normal) if bounded else (math.inf, -1)
    sig_max = min(L + pins.extra, pins.to_sigma(s_up) if k_up >= 0 else math.inf) - 1e-9 * L
    y = np.array([float(T_td @ e1), float(T_td @ e2), min(pins.to_sigma(s_td), sig_max)])
    eye = np.eye(3)
    Fscale = max(float(np.sum(np.abs(lay.weight) * lay.ell)), 1e-300)
    if ends.kind != "fixed":
        assert ends.force is not None
        Fscale = max(Fscale, float(np.linalg.norm(ends.force)))

    def evaluate(y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        T_td = basis @ y[:2]
        s_td, pin, jsig, t_lo, dtT, dtsig = _pinned(y[2], T_td)
        tn = float(np.linalg.norm(T_td))
        e = T_td / tn
        laid = _laid(lay, s_td, T_td, plane, t_lo)
        s0, ell, EA, qs, C, k_td, Cend = _suspended(lay, q, s_td)
        laws = None if lay.law is None else lay.law[k_td:]
        dr, jac, _ = piece_increments(T_td - pin - C, qs, ell, EA, laws)
        assert jac is not None
        Js = jac.sum(axis=0)
        rB = ends.rA + e * laid.stretched + dr.sum(axis=0)
        # d (e stretched) / d T_td; positive_flex = d stretched / d (laid tension at s_td)
        dlaid = laid.stretched * (eye - np.outer(e, e)) / tn + np.outer(e, dtT) * laid.positive_flex
        dT = (Js + dlaid) @ basis  # d rB / d (alpha, beta)
        if jsig is None:
            g = qs[0]  # d T(L) / d sigma
            drs = Js @ qs[0] - e * laid.rate_td * laid.positive_flex  # d rB / d sigma
        else:  # pinned: sigma moves the seabed reaction, the TDP stays
            g = -jsig
            drs = Js @ g + e * laid.positive_flex * dtsig
        TL = T_td - pin - Cend
        if ends.kind == "fixed":
            assert ends.rB is not None
            R = (rB - ends.rB) / L
            Jm = np.column_stack((dT, drs)) / L
        elif ends.kind == "mooring":
            assert ends.force is not None
            R = np.array(
                [
                    (TL[0] - ends.force[0]) / Fscale,
                    (TL[1] - ends.force[1]) / Fscale,
                    (rB[2] - ends.zB) / L,
                ]
            )
            Jm = np.vstack(
                (
                    np.column_stack((basis[:2], g[:2, None])) / Fscale,
                    np.append(dT[2], drs[2])[None, :] / L,
                )
            )
        else:
            assert ends.force is not None
            R = (TL - ends.force) / Fscale
            Jm = np.column_stack((basis, g)) / Fscale
        return R, Jm

    def _pinned(
        sigma: float, T_td: np.ndarray
    ) -> tuple[float, np.ndarray, np.ndarray | None, float | None, np.ndarray, float]:
        """(s_td, tension jump at s_td, d jump / d sigma, laid tension at s_td, its
        derivatives by T_td and sigma); not pinned: (s_td, 0, None, None, e, 0)."""
        s_td, i, R, rate = pins.to_line(float(sigma))
        if i < 0:
            tn = float(np.linalg.norm(T_td))
            return s_td, np.zeros(3), None, None, T_td / tn, 0.0
        k = pins.index[i]
        j, dj_dR, t_lo, dt_dT, dt_dR = pin_jump(
            lay.point[k], R, float(pins.r_max[i]), T_td, plane.normal, plane.friction
        )
        return s_td, j, dj_dR * rate, t_lo, dt_dT, dt_dR * rate

    def kink_step(y: np.ndarray, R: np.ndarray, step: np.ndarray) -> tuple[np.ndarray, float]:
        """At a kink of the TDP coordinate, the Newton step of the piece it goes into;
        and the largest step fraction that stays within one piece (the line search
        starts there, landing on the next kink)."""
        if not kinks.size or step[2] == 0.0:
            return step, 1.0
        if np.any(np.abs(kinks - y[2]) <= 1e-12 * L):
            side = y.copy()
            side[2] += math.copysign(1e-9 * L, step[2])
            _, Jside = evaluate(side)
            try:
                other = np.linalg.solve(Jside, -R)
            except np.linalg.LinAlgError:
                other = step
            if other[2] * step[2] > 0.0:
                step = other
        frac = (kinks - y[2]) / step[2]
        ahead = frac[(frac > 1e-12) & (frac < 1.0)]
        return step, float(ahead.min()) if ahead.size else 1.0

    kinks = pins.kinks
    R, Jm = evaluate(y)
    res = float(np.max(np.abs(R)))
    it = 0
    polish = 0
    at_zero = 0
    while True:
        if not np.isfinite(res):
            raise _Failure(
                STATUS_NUMERICAL,
                "non-finite residual in the seabed-contact Newton iteration",
                it,
                res,
            )
        if res <= tol:
            if polish >= 1 or res <= 1e-15:
                break
            polish += 1
        if it >= max_iterations:
            raise _Failure(
                STATUS_NOT_CONVERGED,
                f"seabed-contact Newton did not converge in "
                f"{max_iterations} iterations (residual {res:.3g})",
                it,
                res,
            )
        _check_deadline(deadline, it, "the seabed-contact Newton iteration")
        it += 1
        try:
            step = np.linalg.solve(Jm, -R)
        except np.linalg.LinAlgError:
            step = -np.linalg.lstsq(Jm, R, rcond=None)[0]
        step, lam = kink_step(y, R, step)
        lam_kink = lam if lam < 1.0 else None
        norm0 = float(np.linalg.norm(R))
        for _ in range(40):
            yn = y + lam * step
            if lam == lam_kink:
                yn[2] = kinks[np.argmin(np.abs(kinks - yn[2]))]  # exactly on it
            # keep the TDP on the line and the tension positive
            yn[2] = min(max(yn[2], 0.0), sig_max)
            if np.linalg.norm(yn[:2]) <= 1e-3 * np.linalg.norm(y[:2]):
                yn[:2] = y[:2] * 1e-3
            Rn, Jn = evaluate(yn)
            if np.all(np.isfinite(Rn)) and np.linalg.norm(Rn) <= (1.0 - 1e-4 * lam) * norm0 + 1e-15:
                break
            lam *= 0.5
        else:
            if k_up >= 0 and y[2] >= sig_max - 1e-9 * L:
                raise _Failure(STATUS_NOT_CONVERGED, "the touchdown point runs into a buoy")
            hint = ""
            if float(np.linalg.norm(y[:2])) < 1e-3 * Fscale:
                hint = _slack_hint(lay)
            raise _Failure(
                STATUS_NO_SOLUTION if hint else STATUS_NOT_CONVERGED,
                "line search failed in the seabed-contact Newton iteration "
                f"(residual {res:.3g}){hint}",
                it,
                res,
            )
        y, R, Jm = yn, Rn, Jn
        res = float(np.max(np.abs(R)))
        if float(np.linalg.norm(y[:2])) < 1e-9 * Fscale and res > tol:
            raise _Failure(STATUS_NO_SOLUTION, _slack_hint(lay, current=True)[2:], it, res)
        if y[2] <= 0.0:
            at_zero += 1
            if at_zero >= 2:
                return None
        else:
            at_zero = 0
    if y[2] <= 0.0:
        return None
    T_td = basis @ y[:2]
    s_td, pin, jsig, t_lo, _, _ = _pinned(y[2], T_td)
    _held_across(plane, T_td, tol, it, res)
    shape = _contact_shape(lay, q, ends.rA, s_td, T_td, plane, None if jsig is None else pin, t_lo)
    shape.iterations = it
    shape.residual = res
    _finite(shape, "line on the seabed")
    return shape
