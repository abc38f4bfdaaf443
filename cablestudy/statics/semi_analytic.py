"""Semi-analytic 3D statics of a segmented elastic line (registry name ``catenary``).

After Dodaran & Park (dodaran-park seed): the line is cut into pieces at segment
boundaries, attachments and (with current) drag elements; each piece carries its weight
and a constant drag load, and its end position follows in closed form from the tension
at its start (:func:`.pieces.piece_integrals`, the seed's eqs. 23-25 for a load of any
direction). The tension at end A, ``T_A``, is the only unknown of a free-hanging line:

* both ends fixed (submersible cable, seed 3.1): three equations r_B(T_A) = r_B. The end
  position is the gradient of the convex complementary energy
  Psi(T_A) = sum int(|T| + |T|^2 / 2EA) ds - (r_B - r_A) . T_A, whose Hessian is the
  analytic flexibility matrix; Newton's method with an Armijo line search on Psi
  therefore converges from any start;
* one end fixed, known force at the other (towing, seed 3.2): T_A follows explicitly;
* one end fixed, known horizontal force and height at the other (mooring, seed 3.3):
  one unknown, the vertical component of T_A, by the same Newton restricted to z.

If end A is the free end it is solved as the reversed line. Drag (seed eqs. 38-39) is
piecewise constant along drag elements and updated from the shape by an outer
fixed-point iteration, accelerated by Anderson mixing and damped, with the seed's
current-speed continuation as fallback. Seabed contact: a line anchored on the
seabed is :mod:`.seabed` (the laid part, with friction) plus a Newton on (tension at
the touchdown point, laid length); a line whose ends are both above the seabed but
which sags onto it is :mod:`.midspan`.

Force conventions: ``force_a`` = T_A and ``force_b`` = -T(L) are the forces the line
exerts on its end attachments; a given ``force`` end is the force applied to the line,
so T(L) = given force.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ..physics.current import current_velocity
from ..physics.hydro import drag_per_length
from .base import (
    STATUS_NO_SOLUTION,
    STATUS_NOT_CONVERGED,
    STATUS_NUMERICAL,
    STATUS_TIME_LIMIT,
    EndCondition,
    LineModel,
    StaticProblem,
    StaticResult,
)
from .law_pieces import piece_increments
from .line_state import CatenaryState
from .seabed import LaidPart, Plane, laid_part
from .vertical import solve_vertical

_Z = np.array([0.0, 0.0, 1.0])


class _Failure(Exception):
    """Internal: a numerical failure with its status (turned into a failed result)."""

    def __init__(
        self,
        status: int,
        message: str,
        iterations: int = 0,
        residual: float = math.nan,
        *,
        final: bool = False,
    ) -> None:
        super().__init__(message)
        self.status = status
        self.message = message
        self.iterations = iterations
        self.residual = residual
        #: a geometric fact (e.g. a line too long for a straight laid part), not a
        #: numerical failure: retrying with continuation cannot help
        self.final = final


# --------------------------------------------------------------------------- layout


@dataclass
class Layout:
    """Pieces of the line from A to B: boundaries ``bounds`` [m] (P + 1,), per piece
    ``ell`` [m], ``EA`` [N], ``weight`` [N/m], ``segment`` index, and point loads
    ``point`` [N] (P + 1, 3) applied to the line at the boundaries."""

    bounds: np.ndarray
    ell: np.ndarray
    EA: np.ndarray
    weight: np.ndarray
    segment: np.ndarray
    point: np.ndarray
    #: per piece its non-linear axial law (None where linear); None: all linear
    law: tuple | None = None

    @property
    def gravity(self) -> np.ndarray:
        q = np.zeros((len(self.ell), 3))
        q[:, 2] = -self.weight
        return q

    @property
    def total(self) -> float:
        return float(self.bounds[-1])


def make_layout(line: LineModel, drag_elements: int = 0) -> Layout:
    """Cut the line at segment ends, attachments and ``drag_elements`` equal elements."""
    L = line.total_length
    pts = [line.segment_ends, line.attachment_s]
    if drag_elements > 0:
        pts.append(np.linspace(0.0, L, drag_elements + 1))
    raw = np.sort(np.concatenate(pts))
    raw = raw[(raw > 0.0) & (raw < L)]
    keep = [0.0]
    for v in raw:
        if v - keep[-1] > 1e-12 * L:
            keep.append(float(v))
    if L - keep[-1] <= 1e-12 * L:
        keep.pop()
    bounds = np.array([*keep, L])
    mids = 0.5 * (bounds[:-1] + bounds[1:])
    seg = np.clip(
        np.searchsorted(line.segment_ends, mids, side="right") - 1, 0, len(line.length) - 1
    )
    point = np.zeros((len(bounds), 3))
    for s, f in zip(line.attachment_s, line.attachment_force, strict=True):
        point[int(np.argmin(np.abs(bounds - s)))] += f
    return Layout(
        bounds=bounds,
        ell=np.diff(bounds),
        EA=line.axial_stiffness[seg].astype(float),
        weight=line.weight[seg].astype(float),
        segment=seg,
        point=point,
        law=tuple(line.law_of(int(k)) for k in seg) if line.is_nonlinear else None,
    )


def reversed_line(line: LineModel) -> LineModel:
    """The same line described from B to A."""
    L = line.total_length
    order = np.argsort(L - line.attachment_s, kind="stable")
    seg = {
        name: getattr(line, name)[::-1].copy()
        for name in (
            "length",
            "weight",
            "mass",
            "axial_stiffness",
            "diameter",
            "drag_normal",
            "drag_tangential",
            "added_mass_normal",
            "added_mass_tangential",
            "bending_stiffness",
            "damping_ratio",
        )
    }
    return LineModel(
        **seg,
        axial_law=tuple(reversed(line.axial_law)),
        attachment_s=(L - line.attachment_s)[order],
        attachment_force=line.attachment_force[order],
        attachment_mass=line.attachment_mass[order],
        attachment_volume=line.attachment_volume[order],
    )


# --------------------------------------------------------------------------- shape

#: [N] tension vector magnitude of a piece that lies slack (no tension): carries only its
#: direction through :func:`.pieces.piece_integrals` (a straight unloaded piece advances
#: by ell T0/|T0| whatever |T0|); never an output (:attr:`Shape.slack` zeroes it)
_DIRECTION_ONLY = 1e-150


@dataclass
class Shape:
    """A solved line as pieces in order along s: start ``s0`` [m], ``ell`` [m], tension
    vector at start ``T0`` [N], load ``q`` [N/m], ``EA`` [N], start position ``r0`` [m];
    end tensions ``force_a`` = T(0), ``tension_end`` = T(L) (vectors, N)."""

    s0: np.ndarray
    ell: np.ndarray
    T0: np.ndarray
    q: np.ndarray
    EA: np.ndarray
    r0: np.ndarray
    force_a: np.ndarray
    tension_end: np.ndarray
    laid_length: float = 0.0
    #: arc length where the laid part starts [m] (0: at end A)
    laid_start: float = 0.0
    iterations: int = 0
    residual: float = 0.0
    contact: bool = False
    #: positions at the piece boundaries (P + 1, 3) where known [m]
    nodes: np.ndarray | None = None
    #: per piece its non-linear axial law (None: all linear)
    law: tuple | None = None
    #: per piece True where it lies slack on the seabed (no tension; its ``T0`` holds
    #: only the direction it lies in, at :data:`_DIRECTION_ONLY` newtons); None: none
    slack: np.ndarray | None = None

    def sample(self, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Positions [m] (n, 3) and tension [N] (n,) at arc lengths ``s`` [m]."""
        s = np.asarray(s, dtype=float)
        k = np.clip(np.searchsorted(self.s0, s, side="right") - 1, 0, len(self.s0) - 1)
        sigma = np.clip(s - self.s0[k], 0.0, self.ell[k])
        laws = None if self.law is None else [self.law[i] for i in k]
        dr, _, _ = piece_increments(self.T0[k], self.q[k], sigma, self.EA[k], laws, jacobian=False)
        pos = self.r0[k] + dr
        T = self.T0[k] - self.q[k] * sigma[:, None]
        tension = np.linalg.norm(T, axis=1)
        if self.slack is not None:
            tension = np.where(self.slack[k], 0.0, tension)  # zero tension is 0
        L = self.s0[-1] + self.ell[-1]
        tension = np.where(s <= 0.0, np.linalg.norm(self.force_a), tension)
        tension = np.where(s >= L, np.linalg.norm(self.tension_end), tension)
        return pos, tension


def _free_shape(
    lay: Layout, q: np.ndarray, rA: np.ndarray, TA: np.ndarray, dr: np.ndarray | None = None
) -> Shape:
    C, Cend = _offsets(lay, q)
    T0 = TA - C
    if dr is None:
        dr, _, _ = piece_increments(T0, q, lay.ell, lay.EA, lay.law, jacobian=False)
    r0 = rA + np.concatenate((np.zeros((1, 3)), np.cumsum(dr, axis=0)))
    return Shape(
        s0=lay.bounds[:-1],
        ell=lay.ell,
        T0=T0,
        q=q,
        EA=lay.EA,
        r0=r0[:-1],
        force_a=TA.copy(),
        tension_end=TA - Cend,
        nodes=r0,
        law=lay.law,
    )


def _offsets(lay: Layout, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """C_p with T(start of piece p) = T_A - C_p, and C_end with T(L) = T_A - C_end."""
    Q = q * lay.ell[:, None]
    C = np.cumsum(lay.point[:-1], axis=0)
    C[1:] += np.cumsum(Q[:-1], axis=0)
    return C, lay.point.sum(axis=0) + Q.sum(axis=0)


# --------------------------------------------------------------------------- ends


@dataclass
class Ends:
    """End conditions with A fixed: ``rA`` [m]; B 'fixed' (``rB``), 'force' (``force``
    on the line) or 'mooring' (``force`` horizontal on the line, ``zB``)."""

    rA: np.ndarray
    kind: str
    rB: np.ndarray | None = None
    force: np.ndarray | None = None
    zB: float = 0.0


def _check_deadline(deadline: float | None, it: int, what: str) -> None:
    if deadline is not None and time.monotonic() > deadline:
        raise _Failure(STATUS_TIME_LIMIT, f"time limit reached in {what} after {it} iterations")


# --------------------------------------------------------------------------- free line


def initial_tension(lay: Layout, q: np.ndarray, ends: Ends) -> np.ndarray:
    """Starting T_A for a free-hanging line: the uniform line with the same total load
    (direction and size) between the same ends, after Peyrot & Goulios (1979), with the
    elastic stretch added for taut chords."""
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
        Hh = math.hypot(TA[0], TA[1])
        Wz = -float(Cend[2])  # total downward load
        h = ends.zB - float(ends.rA[2])
        if Wz <= 0.0:
            TA[2] = -0.5 * Wz
            return TA
        w = Wz / L
        c = Wz / max(Hh, 1e-300)
        if c < 600.0 and Hh > 0.0:
            a = math.asinh(w * h / (2.0 * Hh * math.sinh(0.5 * c))) - 0.5 * c
            TA[2] = Hh * math.sinh(a)
        else:
            TA[2] = 0.5 * (w * h - Wz)
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
    if l <= 1e-12 * chord:
        H = 0.0
        VB = 0.5 * w * (L + h) if L > abs(h) else w * L + max(stretch, 0.0)
    else:
        if L <= chord:
            lam = 0.2
        else:
            lam = max(math.sqrt(3.0 * max((L * L - h * h) / (l * l) - 1.0, 0.0)), 1e-3)
        H = w * l / (2.0 * lam)
        VB = 0.5 * w * (h / math.tanh(lam) + L)
        if chord > L:
            H = max(H, stretch * l / chord)
            VB = max(VB, stretch * h / chord + 0.5 * w * L)
    VA = VB - w * L
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

    if _fast.AVAILABLE and lay.law is None:
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


def _finite(shape: Shape, what: str) -> None:
    if not (np.all(np.isfinite(shape.r0)) and np.all(np.isfinite(shape.T0))):
        raise _Failure(
            STATUS_NUMERICAL,
            f"non-finite shape of the {what} (zero tension somewhere on an unloaded piece?)",
            shape.iterations,
            shape.residual,
        )


# --------------------------------------------------------------------------- seabed


def _suspended(
    lay: Layout, q: np.ndarray, s_td: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, int, np.ndarray]:
    """Suspended pieces from s_td to L: (s0, ell, EA, q, C offsets, index of the TDP piece,
    C_end) with T(start of piece j) = T_td - C_j and T(L) = T_td - C_end."""
    k = int(np.clip(np.searchsorted(lay.bounds, s_td, side="right") - 1, 0, len(lay.ell) - 1))
    s0 = np.concatenate(([s_td], lay.bounds[k + 1 : -1]))
    ell = np.concatenate(([lay.bounds[k + 1] - s_td], lay.ell[k + 1 :]))
    EA = lay.EA[k:]
    qs = q[k:]
    pts = lay.point[k + 1 :]  # boundaries k+1 .. P
    Q = qs * ell[:, None]
    C = np.zeros((len(ell), 3))
    C[1:] = np.cumsum(pts[:-1], axis=0) + np.cumsum(Q[:-1], axis=0)
    Cend = pts.sum(axis=0) + Q.sum(axis=0)
    return s0, ell, EA, qs, C, k, Cend


def _laid(lay: Layout, s_td: float, T_td: np.ndarray, plane: Plane) -> LaidPart:
    tn = float(np.linalg.norm(T_td))
    e = T_td / tn if tn > 0.0 else plane.basis[0]
    mask = (lay.bounds < s_td) & np.any(lay.point != 0.0, axis=1)
    return laid_part(
        s_td,
        tn,
        e,
        lay.bounds,
        lay.weight,
        lay.EA,
        lay.bounds[mask],
        lay.point[mask],
        plane,
        lay.law,
    )


def _contact_shape(
    lay: Layout, q: np.ndarray, rA: np.ndarray, s_td: float, T_td: np.ndarray, plane: Plane
) -> Shape:
    laid = _laid(lay, s_td, T_td, plane)
    tn = float(np.linalg.norm(T_td))
    e = T_td / tn if tn > 0.0 else plane.basis[0]
    s0l, elll, T0l, ql, EAl, lawl, slack = [], [], [], [], [], [], []
    for j in range(len(laid.s) - 1):
        lo, hi = laid.s[j], laid.s[j + 1]
        piece = min(
            int(np.searchsorted(lay.bounds, 0.5 * (lo + hi), side="right")) - 1,
            len(lay.ell) - 1,
        )
        seg_ea = lay.EA[piece]
        seg_law = lay.law[piece] if lay.law is not None else None
        k = laid.rate[j]
        t_lo, t_hi = laid.tension_lo[j], laid.tension_hi[j]
        slack_len = 0.0
        if t_hi <= 0.0:
            slack_len = hi - lo
        elif t_hi - k * (hi - lo) < 0.0 and k > 0.0:
            slack_len = (hi - lo) - t_hi / k
        if slack_len > 0.0:
            s0l.append(lo)
            elll.append(slack_len)
            T0l.append(_DIRECTION_ONLY * e)
            ql.append(np.zeros(3))
            EAl.append(seg_ea)
            lawl.append(seg_law)
            slack.append(True)
        if hi - lo - slack_len > 0.0:
            s0l.append(lo + slack_len)
            elll.append(hi - lo - slack_len)
            T0l.append(max(t_lo, 0.0) * e)
            ql.append(-k * e)
            EAl.append(seg_ea)
            lawl.append(seg_law)
            slack.append(False)
    s0s, ells, EAs, qs, C, k_td, Cend = _suspended(lay, q, s_td)
    T0s = T_td - C
    s0 = np.concatenate((np.array(s0l), s0s))
    ell = np.concatenate((np.array(elll), ells))
    T0 = np.concatenate((np.array(T0l).reshape(-1, 3), T0s))
    qa = np.concatenate((np.array(ql).reshape(-1, 3), qs))
    EA = np.concatenate((np.array(EAl), EAs))
    laws = None if lay.law is None else (*lawl, *lay.law[k_td:])
    dr, _, _ = piece_increments(T0, qa, ell, EA, laws, jacobian=False)
    r0 = rA + np.concatenate((np.zeros((1, 3)), np.cumsum(dr, axis=0)))[:-1]
    force_a = laid.tension[0] * e
    return Shape(
        s0=s0,
        ell=ell,
        T0=T0,
        q=qa,
        EA=EA,
        r0=r0,
        force_a=force_a,
        tension_end=T_td - Cend,
        laid_length=s_td,
        contact=True,
        law=laws,
        slack=np.array(slack + [False] * len(s0s), dtype=bool) if any(slack) else None,
    )


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
    driven to zero)."""
    L = lay.total
    e1, e2 = plane.basis
    basis = np.stack((e1, e2), axis=1)  # (3, 2)
    T_td, s_td = guess
    y = np.array([float(T_td @ e1), float(T_td @ e2), s_td])
    Fscale = max(float(np.sum(np.abs(lay.weight) * lay.ell)), 1e-300)
    if ends.kind != "fixed":
        assert ends.force is not None
        Fscale = max(Fscale, float(np.linalg.norm(ends.force)))

    def evaluate(y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        T_td = basis @ y[:2]
        s_td = float(y[2])
        tn = float(np.linalg.norm(T_td))
        e = T_td / tn
        laid = _laid(lay, s_td, T_td, plane)
        s0, ell, EA, qs, C, k_td, Cend = _suspended(lay, q, s_td)
        laws = None if lay.law is None else lay.law[k_td:]
        dr, jac, _ = piece_increments(T_td - C, qs, ell, EA, laws)
        assert jac is not None
        Js = jac.sum(axis=0)
        rB = ends.rA + e * laid.stretched + dr.sum(axis=0)
        dlaid = (
            laid.stretched * (np.eye(3) - np.outer(e, e)) / tn + np.outer(e, e) * laid.positive_flex
        )
        dT = (Js + dlaid) @ basis  # d rB / d (alpha, beta)
        drs = Js @ qs[0] - e * laid.rate_td * laid.positive_flex  # d rB / d s_td
        TL = T_td - Cend
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
                    np.column_stack((basis[:2], qs[0][:2, None])) / Fscale,
                    np.append(dT[2], drs[2])[None, :] / L,
                )
            )
        else:
            assert ends.force is not None
            R = (TL - ends.force) / Fscale
            Jm = np.column_stack((basis, qs[0])) / Fscale
        return R, Jm

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
        lam = 1.0
        norm0 = float(np.linalg.norm(R))
        for _ in range(40):
            yn = y + lam * step
            # keep the TDP on the line and the tension positive
            yn[2] = min(max(yn[2], 0.0), L * (1.0 - 1e-9))
            if np.linalg.norm(yn[:2]) <= 1e-3 * np.linalg.norm(y[:2]):
                yn[:2] = y[:2] * 1e-3
            Rn, Jn = evaluate(yn)
            if np.all(np.isfinite(Rn)) and np.linalg.norm(Rn) <= (1.0 - 1e-4 * lam) * norm0 + 1e-15:
                break
            lam *= 0.5
        else:
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
    shape = _contact_shape(lay, q, ends.rA, float(y[2]), basis @ y[:2], plane)
    shape.iterations = it
    shape.residual = res
    _finite(shape, "line on the seabed")
    return shape


# --------------------------------------------------------------------------- drag


@dataclass
class DragModel:
    """Drag per piece of a layout: ``diameter`` [m], ``cn``, ``ct`` [-] per piece,
    fluid ``density`` [kg/m^3], current profile (``z`` [m], ``velocity`` [m/s])."""

    diameter: np.ndarray
    cn: np.ndarray
    ct: np.ndarray
    density: float
    z: np.ndarray
    velocity: np.ndarray

    def load(self, shape: Shape, lay: Layout, factor: float) -> np.ndarray:
        """Drag per unstretched length [N/m] (P, 3) on each layout piece, from the chord
        of the piece in ``shape`` and the current at its mid-height times ``factor``
        (seed eqs. 38-39; the seed's l is the stretched chord). Zero on the laid part."""
        if shape.nodes is not None and len(shape.nodes) == len(lay.bounds):
            r = shape.nodes
        else:
            r, _ = shape.sample(lay.bounds)
        chord = np.diff(r, axis=0)
        lc = np.linalg.norm(chord, axis=1)
        t = chord / np.where(lc > 0.0, lc, 1.0)[:, None]
        U = factor * current_velocity(0.5 * (r[:-1, 2] + r[1:, 2]), self.z, self.velocity)
        f = drag_per_length(
            U,
            t,
            density=self.density,
            diameter=self.diameter,
            drag_normal=self.cn,
            drag_tangential=self.ct,
        )
        D = f * (lc / lay.ell)[:, None]
        if shape.laid_length > 0.0:
            mid = 0.5 * (lay.bounds[:-1] + lay.bounds[1:])
            lo = shape.laid_start
            D[(mid >= lo) & (mid <= lo + shape.laid_length)] = 0.0
        return D


class _Anderson:
    """Anderson acceleration (type II, depth ``m``, mixing ``beta``) of x = G(x)."""

    def __init__(self, m: int = 5, beta: float = 0.7) -> None:
        self.m = m
        self.beta = beta
        self.xs: list[np.ndarray] = []
        self.fs: list[np.ndarray] = []

    def reset(self) -> None:
        self.xs.clear()
        self.fs.clear()

    def step(self, x: np.ndarray, gx: np.ndarray) -> np.ndarray:
        f = gx - x
        self.xs.append(x.copy())
        self.fs.append(f.copy())
        if len(self.xs) > self.m + 1:
            self.xs.pop(0)
            self.fs.pop(0)
        if len(self.xs) == 1:
            return x + self.beta * f
        dX = np.stack([self.xs[i + 1] - self.xs[i] for i in range(len(self.xs) - 1)], axis=1)
        dF = np.stack([self.fs[i + 1] - self.fs[i] for i in range(len(self.fs) - 1)], axis=1)
        gamma, *_ = np.linalg.lstsq(dF, f, rcond=None)
        return x + self.beta * f - (dX + self.beta * dF) @ gamma


# --------------------------------------------------------------------------- solver


@dataclass
class _State:
    TA: np.ndarray | None = None
    contact: tuple[np.ndarray, float] | None = None
    newton: int = 0
    drag: int = 0
    mid: np.ndarray | None = None


class SemiAnalyticSolver:
    """Registry entry ``catenary``: the general 3D semi-analytic solver (segments,
    attachments, sheared and turning currents with drag, the three boundary types,
    seabed contact with friction). See the module docstring."""

    name = "catenary"

    def __init__(
        self,
        *,
        drag_elements: int | None = None,
        max_drag_iterations: int = 300,
        continuation_steps: tuple[int, ...] = (4, 16),
    ) -> None:
        self.drag_elements = drag_elements
        self.max_drag_iterations = max_drag_iterations
        self.continuation_steps = continuation_steps

    def unsupported(self, problem: StaticProblem) -> list[str]:
        out = []
        if problem.end_a.kind != "fixed" and problem.end_b.kind != "fixed":
            out.append("lines with no fixed end (one end must be 'fixed')")
        if problem.is_installation:
            out.append("installation (pay-out speed, touchdown velocity): use method 'shooting'")
        if problem.stretched_drag_diameter and problem.medium.has_current:
            out.append(
                "drag on the stretched diameter (drag_diameter: stretched): use method 'shooting'"
            )
        return out

    # ------------------------------------------------------------------ public

    def solve(
        self,
        problem: StaticProblem,
        *,
        deadline: float | None = None,
        drag_elements: int | None = None,
        compiled: bool = True,
    ) -> StaticResult:
        """Solve ``problem``. A still-water problem hanging free, or anchored at end A on
        the seabed with end B fixed above it, first takes the compiled kernels of
        :mod:`.batch` (when numba is available and ``compiled``); anything they do not
        settle takes the general path below, which gives the same answer."""
        from . import _fast  # numba is imported on first use, not with the package

        if compiled and _fast.AVAILABLE:
            from .batch import solve_compiled

            left: dict[int, str] = {}
            fast = solve_compiled(problem, deadline=deadline, why=left)
            if fast is not None:
                return fast
            fallback = left.get(0, "")
        else:
            fallback = ""
        line = problem.line
        L = line.total_length
        s = np.linspace(0.0, L, problem.n_nodes)
        state = _State()
        try:
            result = self._solve(problem, s, deadline, drag_elements, state)
        except _Failure as exc:
            result = StaticResult.failed(
                s,
                exc.status,
                exc.message,
                iterations=state.newton + exc.iterations,
                residual=exc.residual,
            )
        except (FloatingPointError, np.linalg.LinAlgError, ValueError, ZeroDivisionError) as exc:
            result = StaticResult.failed(
                s,
                STATUS_NUMERICAL,
                f"{type(exc).__name__} in the catenary solver: {exc}",
                iterations=state.newton,
            )
        result.drag_iterations = state.drag
        result = result.check_finite()
        result.fallback = fallback
        return result

    # ------------------------------------------------------------------ internals

    def _solve(
        self,
        problem: StaticProblem,
        s: np.ndarray,
        deadline: float | None,
        drag_elements: int | None,
        state: _State,
    ) -> StaticResult:
        a, b = problem.end_a, problem.end_b
        vertical = solve_vertical(problem, s)  # ends on one vertical: closed form
        if vertical is not None:
            return vertical
        line = problem.line
        L = line.total_length
        medium = problem.medium
        plane = None
        if medium.depth is not None:
            plane = Plane(medium.depth, medium.seabed_slope, medium.seabed_heading, medium.friction)
        reverse = a.kind != "fixed"
        if a.kind == "fixed" and b.kind == "fixed" and plane is not None:
            assert a.position is not None and b.position is not None
            ha = float(plane.height_above(a.position))
            hb = float(plane.height_above(b.position))
            reverse = hb <= 1e-6 * L and ha > 1e-6 * L
        if a.kind != "fixed" and b.kind != "fixed":
            raise _Failure(STATUS_NO_SOLUTION, "neither end is fixed; one end must be 'fixed'")
        if reverse:
            line = reversed_line(line)
            a, b = b, a
            s_eval = L - s
        else:
            s_eval = s
        ends = _ends(a, b)
        grounded = False
        if plane is not None:
            for label, pos in (("A", ends.rA), ("B", ends.rB)):
                if pos is not None and float(plane.height_above(pos)) < -1e-6 * L:
                    name = label if not reverse else ("B" if label == "A" else "A")
                    raise _Failure(
                        STATUS_NO_SOLUTION,
                        f"end {name} lies {-float(plane.height_above(pos)):.4g} m below the seabed",
                    )
            grounded = float(plane.height_above(ends.rA)) <= 1e-6 * L
        if grounded and ends.kind == "fixed" and plane is not None:
            assert ends.rB is not None
            if float(plane.height_above(ends.rB)) <= 1e-6 * L:
                return _laid_between(line, ends, plane, s_eval, s, reverse)
        has_current = (
            medium.has_current
            and medium.density > 0.0
            and bool(np.any(line.diameter * (line.drag_normal + line.drag_tangential) > 0.0))
        )
        n_el = 0
        if has_current:
            n_el = (
                drag_elements
                or problem.drag_elements
                or self.drag_elements
                or max(problem.n_nodes - 1, 20)
            )
        lay = make_layout(line, n_el)
        tol = problem.tolerance
        maxit = problem.max_iterations
        grav = lay.gravity

        def inner(q: np.ndarray, tol_inner: float, polish: bool = True) -> Shape:
            return self._inner(
                lay, q, ends, plane, state, tol_inner, maxit, deadline, polish, grounded
            )

        loads = None  # the drag-frozen loads per piece (line_state), in a current
        if not has_current:
            shape = inner(grav, tol)
            drag_res = 0.0
        else:
            seg = lay.segment
            drag = DragModel(
                line.diameter[seg],
                line.drag_normal[seg],
                line.drag_tangential[seg],
                medium.density,
                medium.current_z,
                medium.current_velocity,
            )
            shape, drag_res, D = self._drag_loop(lay, grav, drag, inner, tol, deadline, state, ends)
            loads = CatenaryState(layout=lay, q=grav + D, reversed=reverse)
        pos, tension = shape.sample(s_eval)
        if plane is not None:
            height = plane.height_above(pos)
            depth_below = float(-np.min(height))
            if depth_below > max(1e-6 * L, 1e3 * tol * L):
                where = "" if grounded else " between its ends"
                raise _Failure(
                    STATUS_NO_SOLUTION,
                    f"the line passes {depth_below:.4g} m below the seabed{where} "
                    "(a contact the solver could not resolve)",
                    state.newton,
                    shape.residual,
                )
        force_a = shape.force_a
        force_b = -shape.tension_end
        if reverse:
            force_a, force_b = force_b, force_a
        res = max(shape.residual, drag_res)
        return StaticResult(
            s=s,
            position=pos,
            tension=tension,
            force_a=np.asarray(force_a),
            force_b=np.asarray(force_b),
            laid_length=shape.laid_length,
            iterations=state.newton,
            residual=res,
            state=loads,
        )

    def _inner(
        self,
        lay: Layout,
        q: np.ndarray,
        ends: Ends,
        plane: Plane | None,
        state: _State,
        tol: float,
        maxit: int,
        deadline: float | None,
        polish: bool = True,
        grounded: bool = False,
    ) -> Shape:
        """One solve with known loads: free-hanging, or with a laid part (from an end
        anchored on the seabed, or between the ends)."""
        if plane is not None and not grounded:
            return self._inner_midspan(lay, q, ends, plane, state, tol, maxit, deadline, polish)
        if plane is not None and state.contact is not None:
            shape = solve_contact(
                lay, q, ends, plane, state.contact, tol=tol, max_iterations=maxit, deadline=deadline
            )
            if shape is not None:
                state.newton += shape.iterations
                state.contact = (_td_tension(shape), shape.laid_length)
                return shape
            state.contact = None
        if plane is not None and state.TA is None and not np.any(q[:, :2]) and plane.slope == 0.0:
            # first solve of a line anchored on a flat seabed in still water: when the
            # classical mooring formula lays part of it, solve with the laid part at
            # once (the free-hanging solve would only find the line through the seabed)
            try:
                guess = initial_contact(lay, ends, plane, still=True)
            except _Failure:
                guess = None
            if guess is not None and guess[1] > 0.0:
                try:
                    cshape = solve_contact(
                        lay, q, ends, plane, guess, tol=tol, max_iterations=maxit, deadline=deadline
                    )
                except _Failure as exc:  # the usual path below decides, as before
                    if exc.status == STATUS_TIME_LIMIT:
                        raise
                    cshape = None
                if cshape is not None:
                    state.newton += cshape.iterations
                    state.contact = (_td_tension(cshape), cshape.laid_length)
                    return cshape
        TA = state.TA if state.TA is not None else initial_tension(lay, q, ends)
        try:
            try:
                shape = solve_free(
                    lay,
                    q,
                    ends,
                    TA,
                    tol=tol,
                    max_iterations=maxit,
                    deadline=deadline,
                    polish=polish,
                )
            except _Failure as exc:
                if exc.status == STATUS_TIME_LIMIT:
                    raise
                shape = self._regularised(lay, q, ends, tol, maxit, deadline, polish, exc)
            free_ok = True
        except _Failure:
            if plane is None:
                raise
            free_ok = False
            shape = None
        if free_ok:
            assert shape is not None
            state.newton += shape.iterations
            state.TA = shape.force_a.copy()
            if plane is None or not _penetrates(shape, lay, plane):
                return shape
        assert plane is not None
        still = not np.any(q[:, :2]) and plane.slope == 0.0
        guess = initial_contact(lay, ends, plane, still=still)
        cshape = solve_contact(
            lay, q, ends, plane, guess, tol=tol, max_iterations=maxit, deadline=deadline
        )
        if cshape is None:
            if shape is not None:
                return shape
            raise _Failure(
                STATUS_NOT_CONVERGED,
                "neither the free-hanging nor the seabed-contact solution converged",
            )
        state.newton += cshape.iterations
        state.contact = (_td_tension(cshape), cshape.laid_length)
        return cshape

    def _inner_midspan(
        self,
        lay: Layout,
        q: np.ndarray,
        ends: Ends,
        plane: Plane,
        state: _State,
        tol: float,
        maxit: int,
        deadline: float | None,
        polish: bool,
    ) -> Shape:
        """Neither end on the seabed: free-hanging, unless that dips into the seabed, then
        resting on it between the ends (:mod:`.midspan`)."""
        from .midspan import initial_midspan, solve_midspan

        if state.mid is not None:
            try:
                shape = solve_midspan(
                    lay,
                    q,
                    ends,
                    plane,
                    state.mid,
                    tol=tol,
                    max_iterations=maxit,
                    deadline=deadline,
                )
                state.newton += shape.iterations
                state.mid = _mid_unknowns(shape, plane)
                return shape
            except _Failure as exc:
                if exc.status == STATUS_TIME_LIMIT:
                    raise
                state.mid = None
        shape = self._inner(lay, q, ends, None, state, tol, maxit, deadline, polish)
        if not _penetrates(shape, lay, plane, anchored=False):
            return shape
        guess = initial_midspan(shape, plane, lay.total)
        mshape = solve_midspan(
            lay, q, ends, plane, guess, tol=tol, max_iterations=maxit, deadline=deadline
        )
        state.newton += mshape.iterations
        state.mid = _mid_unknowns(mshape, plane)
        return mshape

    @staticmethod
    def _regularised(
        lay: Layout,
        q: np.ndarray,
        ends: Ends,
        tol: float,
        maxit: int,
        deadline: float | None,
        polish: bool,
        failure: _Failure,
    ) -> Shape:
        """Retry a line with unloaded (weightless) pieces with a small weight on them,
        reduced from 1e-2 to 1e-10 (at least 1e-6) of the point loads per length. A
        weightless piece that goes slack has no determined shape and its energy a kink at
        zero tension where Newton stalls; the
        light chain is its physical limit; the end forces change by that fraction of the
        loads (1e-10 to 1e-6)."""
        unloaded = np.linalg.norm(q, axis=1) == 0.0
        if not np.any(unloaded):
            raise failure
        _, Cend = _offsets(lay, q)
        scale = float(np.sum(np.linalg.norm(lay.point, axis=1)))
        if ends.force is not None:
            scale += float(np.linalg.norm(ends.force))
        if scale <= 0.0:
            raise failure
        qr = q.copy()
        TA = None
        shape = None
        # continuation in the regularising weight, each level warm-starting the next. A
        # slack light piece folds, and the height of its far end moves by 2/w per newton
        # of vertical force: with w -> 0 the position tolerance becomes unattainable in
        # double precision, so the smallest level that converges (at least 1e-6) stands
        for level in (1e-2, 1e-4, 1e-6, 1e-8, 1e-10):
            qr[unloaded, 2] = -level * scale / lay.total
            if TA is None:
                TA = initial_tension(lay, qr, ends)
            try:
                shape = solve_free(
                    lay,
                    qr,
                    ends,
                    TA,
                    tol=tol if level <= 1e-6 else max(tol, 1e-6),
                    max_iterations=maxit,
                    deadline=deadline,
                    polish=polish and level <= 1e-6,
                )
            except _Failure as exc:
                if exc.status == STATUS_TIME_LIMIT or level > 1e-6:
                    raise _Failure(
                        exc.status,
                        f"{failure.message}; retried with a small "
                        f"regularising weight on the weightless pieces: "
                        f"{exc.message}",
                        exc.iterations,
                        exc.residual,
                    ) from None
                break
            TA = shape.force_a
        assert shape is not None
        return shape

    def _drag_loop(
        self,
        lay: Layout,
        grav: np.ndarray,
        drag: DragModel,
        inner,
        tol: float,  # noqa: ANN001
        deadline: float | None,
        state: _State,
        ends: Ends,
    ) -> tuple[Shape, float, np.ndarray]:
        """Outer iteration on the drag loads; continuation in current speed on failure.
        Returns the shape, the load residual and the converged drag loads (P, 3)."""
        Fscale = float(np.sum(np.abs(lay.weight) * lay.ell) + np.sum(np.abs(lay.point)))
        attempts: list[int] = [1, *self.continuation_steps]
        last: _Failure | None = None
        for n_steps in attempts:
            D = np.zeros_like(grav)
            saved_TA, saved_contact = state.TA, state.contact
            try:
                shape, res = None, math.inf
                for k in range(1, n_steps + 1):
                    factor = k / n_steps
                    final = k == n_steps
                    if k > 1:  # drag grows with the square of the speed
                        D = D * (k / (k - 1)) ** 2
                    shape, D, res = self._drag_fixed_point(
                        lay,
                        grav,
                        drag,
                        D,
                        factor,
                        inner,
                        tol if final else max(tol, 1e-4),
                        Fscale,
                        deadline,
                        state,
                        first=shape is None,
                        ends=ends,
                        lenient=not final,
                    )
                assert shape is not None
                return shape, res, D
            except _Failure as exc:
                if exc.status == STATUS_TIME_LIMIT:
                    raise
                last = exc
                state.TA, state.contact = saved_TA, saved_contact
                if exc.final or (exc.status == STATUS_NO_SOLUTION and n_steps > 1):
                    break  # confirmed with continuation: no static solution
        assert last is not None
        raise _Failure(
            last.status,
            f"drag iteration failed even with current-speed "
            f"continuation in {n_steps} steps: {last.message}",
            0,
            last.residual,
        )

    def _drag_fixed_point(
        self,
        lay: Layout,
        grav: np.ndarray,
        drag: DragModel,
        D: np.ndarray,
        factor: float,
        inner,
        tol: float,
        Fscale: float,  # noqa: ANN001
        deadline: float | None,
        state: _State,
        first: bool,
        ends: Ends,
        lenient: bool = False,
    ) -> tuple[Shape, np.ndarray, float]:
        """Fixed point on the drag loads, Anderson-accelerated. ``lenient`` (an
        intermediate continuation step, which only has to give the next step a start)
        accepts the best iterate when the loop stalls within 1e-2 of the loads."""
        if first:
            try:
                shape = inner(grav + D, max(tol, 1e-6))
            except _Failure:
                shape = self._straight_start(lay, ends)
            D = drag.load(shape, lay, factor)
        acc = _Anderson()
        best = math.inf
        best_res, best_iterate = math.inf, None
        stall = 0
        res = math.inf
        for it in range(1, self.max_drag_iterations + 1):
            _check_deadline(deadline, it, "the drag iteration")
            state.drag += 1
            # inexact inner solves while the loads are still far from converged
            tol_inner = max(tol, min(1e-4, 1e-2 * res))
            shape = inner(grav + D, tol_inner, False)
            Dn = drag.load(shape, lay, factor)
            scale = Fscale + float(np.sum(np.linalg.norm(Dn, axis=1) * lay.ell))
            # summed change of the drag loads: bounds the force imbalance of the line
            res = float(np.sum(np.linalg.norm(Dn - D, axis=1) * lay.ell)) / max(scale, 1e-300)
            if res <= tol and tol_inner <= tol:
                return shape, Dn, res
            if res < best_res:
                best_res, best_iterate = res, (shape, Dn)
            if res < 0.5 * best:
                best = res
                stall = 0
            else:
                stall += 1
                if stall >= 12:
                    acc.reset()
                    acc.beta = max(acc.beta * 0.5, 0.05)
                    stall = 0
            D = acc.step(D.ravel(), Dn.ravel()).reshape(D.shape)
        if lenient and best_iterate is not None and best_res < 1e-2:
            return best_iterate[0], best_iterate[1], best_res
        raise _Failure(
            STATUS_NOT_CONVERGED,
            f"drag iteration did not converge in "
            f"{self.max_drag_iterations} iterations (relative load residual "
            f"{res:.3g}, tolerance {tol:.3g})",
            0,
            res,
        )

    @staticmethod
    def _straight_start(lay: Layout, ends: Ends) -> Shape:
        """A straight line from A (to B, or along the given end force, or down) whose only
        use is a first drag estimate when the still-water problem has no solution (a
        slack weightless line)."""
        if ends.kind == "fixed":
            assert ends.rB is not None
            d = ends.rB - ends.rA
        else:
            assert ends.force is not None
            d = ends.force.copy() if np.linalg.norm(ends.force) > 0.0 else -_Z
            if ends.kind == "mooring":
                d[2] = ends.zB - float(ends.rA[2])
        n = float(np.linalg.norm(d))
        e = d / n if n > 0.0 else -_Z
        L = lay.total
        return Shape(
            s0=np.zeros(1),
            ell=np.array([L]),
            T0=(_DIRECTION_ONLY * e)[None, :],
            q=np.zeros((1, 3)),
            EA=np.array([1.0]),
            r0=ends.rA[None, :],
            force_a=np.zeros(3),
            tension_end=np.zeros(3),
        )


def _laid_between(
    line: LineModel, ends: Ends, plane: Plane, s_eval: np.ndarray, s: np.ndarray, reverse: bool
) -> StaticResult:
    """Both ends fixed on the seabed: a line no longer than the distance between them
    lies straight on the seabed with the uniform tension that stretches it to that
    distance (the seabed carries its weight; friction is not mobilised in a uniform
    stretch); a longer one lies slack, with no determined shape."""
    assert ends.rB is not None
    d = ends.rB - ends.rA
    chord = float(np.linalg.norm(d))
    L = line.total_length
    flex = float(np.sum(line.length / line.axial_stiffness))  # stretch per newton [m/N]
    if chord <= L:
        raise _Failure(
            STATUS_NO_SOLUTION,
            f"both ends lie on the seabed {chord:.6g} m apart "
            f"and the line ({L:.6g} m) is not shorter: it lies slack on the seabed "
            "and its shape is not determined",
        )

    def strains(T: float) -> np.ndarray:
        return np.array(
            [
                T / ea if (law := line.law_of(i)) is None else float(law.strain(T))
                for i, ea in enumerate(line.axial_stiffness)
            ]
        )

    T = (chord - L) / flex
    if line.is_nonlinear:
        # sum l_i (1 + e_i(T)) = chord: increasing in T, bracketed and bisected
        lo, hi = 0.0, max(T, 1.0)
        while float(np.sum(line.length * strains(hi))) < chord - L:
            lo, hi = hi, 2.0 * hi
        for _ in range(200):
            T = 0.5 * (lo + hi)
            if float(np.sum(line.length * strains(T))) < chord - L:
                lo = T
            else:
                hi = T
            if hi - lo <= 1e-15 * hi:
                break
        T = 0.5 * (lo + hi)
    e = d / chord
    bounds = line.segment_ends
    stretched = np.concatenate(([0.0], np.cumsum(line.length * (1.0 + strains(T)))))
    along = np.interp(s_eval, bounds, stretched)
    pos = ends.rA + along[:, None] * e
    force_a, force_b = T * e, -T * e
    if reverse:
        force_a, force_b = force_b, force_a
    return StaticResult(
        s=s,
        position=pos,
        tension=np.full(len(s), T),
        force_a=force_a,
        force_b=force_b,
        laid_length=L,
        iterations=0,
        residual=0.0,
    )


def _mid_unknowns(shape: Shape, plane: Plane) -> np.ndarray:
    """(alpha, beta, s1, s2) of a solution resting on the seabed between its ends."""
    T = _td_tension_at(shape, shape.laid_start)
    e1, e2 = plane.basis
    return np.array(
        [float(T @ e1), float(T @ e2), shape.laid_start, shape.laid_start + shape.laid_length]
    )


def _td_tension_at(shape: Shape, s: float) -> np.ndarray:
    k = min(int(np.searchsorted(shape.s0, s, side="left")), len(shape.s0) - 1)
    return shape.T0[k].copy()


def _td_tension(shape: Shape) -> np.ndarray:
    """Tension vector at the TDP: the start of the first suspended piece."""
    k = min(int(np.searchsorted(shape.s0, shape.laid_length, side="left")), len(shape.s0) - 1)
    return shape.T0[k].copy()


def _penetrates(shape: Shape, lay: Layout, plane: Plane, anchored: bool = True) -> bool:
    """Whether a free-hanging solution dips into the seabed (for a line anchored on it:
    also when its tension at the anchor points into the seabed)."""
    if anchored and float(shape.force_a @ plane.normal) < 0.0:
        return True
    r, _ = shape.sample(np.linspace(0.0, lay.total, max(4 * len(lay.ell) + 1, 401)))
    return bool(np.any(plane.height_above(r) < -1e-9 * lay.total))


def _ends(a: EndCondition, b: EndCondition) -> Ends:
    assert a.kind == "fixed" and a.position is not None
    rA = np.asarray(a.position, dtype=float)
    if b.kind == "fixed":
        assert b.position is not None
        return Ends(rA=rA, kind="fixed", rB=np.asarray(b.position, dtype=float))
    if b.kind == "force":
        assert b.force is not None
        return Ends(rA=rA, kind="force", force=np.asarray(b.force, dtype=float))
    if b.kind == "mooring":
        assert b.force is not None and b.z is not None
        f = np.asarray(b.force, dtype=float).copy()
        f[2] = 0.0
        return Ends(rA=rA, kind="mooring", force=f, zB=float(b.z))
    raise _Failure(STATUS_NO_SOLUTION, f"unknown end kind {b.kind!r}")
