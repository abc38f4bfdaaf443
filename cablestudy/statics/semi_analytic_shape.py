"""The semi-analytic line's geometry (:mod:`.semi_analytic`): its pieces
(:class:`Layout`: cut at segment boundaries, attachments and drag elements), the shape
they take from the tension at end A (:class:`Shape`, in closed form per piece by
:func:`.pieces.piece_integrals`), the laid part on the seabed, the end conditions
(:class:`Ends`), and the internal failure that carries its status (:class:`_Failure`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from .base import (
    SEGMENT_ARRAYS,
    STATUS_NO_SOLUTION,
    STATUS_NUMERICAL,
    STATUS_TIME_LIMIT,
    EndCondition,
    LineModel,
    StaticResult,
)
from .law_pieces import piece_increments
from .seabed import LaidPart, Plane, laid_part

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
    seg = {name: getattr(line, name)[::-1].copy() for name in ("length", *SEGMENT_ARRAYS)}
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
    #: the line's length [m] where A here is the problem's B (messages count s from A)
    flip: float | None = None


def _check_deadline(deadline: float | None, it: int, what: str) -> None:
    if deadline is not None and time.monotonic() > deadline:
        raise _Failure(STATUS_TIME_LIMIT, f"time limit reached in {what} after {it} iterations")


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


def _laid(
    lay: Layout, s_td: float, T_td: np.ndarray, plane: Plane, tension: float | None = None
) -> LaidPart:
    """The laid part up to s_td along T_td; ``tension`` [N]: its tension at s_td when it
    is not |T_td| (a load resting on the seabed at the TDP, :mod:`.contact_pin`)."""
    tn = float(np.linalg.norm(T_td))
    e = T_td / tn if tn > 0.0 else plane.basis[0]
    if tension is not None:
        tn = max(tension, 0.0)
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
    lay: Layout,
    q: np.ndarray,
    rA: np.ndarray,
    s_td: float,
    T_td: np.ndarray,
    plane: Plane,
    jump: np.ndarray | None = None,
    laid_tension: float | None = None,
) -> Shape:
    """The line on the seabed up to s_td; ``jump`` [N] and ``laid_tension`` [N]: with a
    point load resting on the seabed exactly at the TDP (:mod:`.contact_pin`), the
    tension past it is T_td - jump and the laid part's tension at s_td- laid_tension."""
    laid = _laid(lay, s_td, T_td, plane, laid_tension)
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
    T_up = T_td if jump is None else T_td - jump  # tension at s_td+, past a pinned load
    T0s = T_up - C
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
        tension_end=T_up - Cend,
        laid_length=s_td,
        contact=True,
        law=laws,
        slack=np.array(slack + [False] * len(s0s), dtype=bool) if any(slack) else None,
    )


def _laid_between(
    line: LineModel, ends: Ends, s_eval: np.ndarray, s: np.ndarray, reverse: bool
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


def laid_pulled(
    line: LineModel,
    ends: tuple[np.ndarray, np.ndarray],
    plane: Plane,
    s: np.ndarray,
    pulled: int,
    *,
    compress: bool = False,
) -> tuple[StaticResult, float] | None:
    """A line lying wholly on the seabed between ``ends`` (r_A, r_B [m]), pulled at end
    ``pulled`` (0: A, 1: B) and anchored at the other, as MoorPy's catenary takes a fully
    laid line: the tension T at the pulled end falls by the mobilised friction towards the
    anchor (mu w per metre, mu times each point load's weight), to zero, as the laid part
    of a line anchored there (:func:`.seabed.laid_part`); T [N] makes that laid length,
    stretched, the chord. Without friction the tension is uniform (:func:`_laid_between`).
    Returns the result at arc lengths ``s`` [m] and d|chord|/dT [m/N] (the stiffness of
    :func:`.line_stiffness.laid_stiffness`). Where the chord is not longer than the line
    it lies slack, its shape not determined: None, or with ``compress`` the end forces of
    T = (|chord| - L) / sum(l / EA) <= 0, the line's own stiffness pushing it straight (a
    system Newton's stand-in that puts a point held by friction where the line lies
    straight at its length; the result's tension is zero)."""
    ra, rb = ends
    if pulled == 0:
        line, ra, rb, s = reversed_line(line), rb, ra, line.total_length - s
    lay = make_layout(line)
    L = line.total_length
    chord = float(np.linalg.norm(rb - ra))
    e = (rb - ra) / chord
    flex = float(np.sum(lay.ell / lay.EA))
    T = (chord - L) / flex  # uniform: from below (the stretch is convex in T)
    if T <= 0.0 and not compress:
        return None
    gap = 0.0
    for _ in range(100 if T > 0.0 else 0):
        laid = _laid(lay, L, e, plane, T)
        gap, flex = laid.stretched - chord, laid.positive_flex
        if abs(gap) <= 1e-14 * L:
            break
        T -= gap / flex
    shape = _contact_shape(lay, lay.gravity, ra, L, max(T, 0.0) * e, plane)
    pos, tension = shape.sample(s)
    if T <= 0.0:  # straight at its length
        pos = ra + np.outer(s / L * chord, e)
    force = (shape.force_a + min(T, 0.0) * e, -shape.tension_end - min(T, 0.0) * e)
    result = StaticResult(
        s=s if pulled else L - s, position=pos, tension=tension, force_a=force[pulled - 1],
        force_b=force[-pulled], laid_length=L, residual=abs(gap) / L,
    )  # fmt: skip
    return result, flex


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
