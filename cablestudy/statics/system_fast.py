"""Mooring systems through the compiled system Newton (:mod:`._system_fast`), many cases
at once.

A system whose lines the still-water catenary kernels take (linear axial laws, no drag
in a current, each line hanging free above the seabed or anchored on it at a fixed
point with its other end above it) and whose bodies are prescribed is packed into
arrays (:func:`pack`), its free points solved by the compiled Newton, and then, as
:func:`.system._solve` ends: every line solved again at the solution, sampled at its
nodes, by the batch kernels (:func:`._fast.solve_cases` hanging free,
:func:`.batch.solve_contact_arrays` on the seabed: the numbers :func:`.batch.solve_batch`
gives for those end positions), every line verified (:func:`.verify.check_lines`,
vectorised over lines and cases: status 0 means verified), the free points' equilibrium
checked from those lines' forces, and the bodies' force and stiffness (the Schur
complement of the assembled point stiffness, :func:`.system._bodies`, vectorised).

What the compiled path does not take is said by :func:`ineligible` (a reason) or, for a
case it does not settle, by the case's ``fallback`` text; the caller then solves it by
the general path (:func:`.system.solve_system`), counted. Pure: arrays in, arrays out.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import _fast
from .seabed import Plane
from .semi_analytic import reversed_line
from .system_layout import line_pieces, system_layout
from .system_model import BODY, FIXED, FREE, MooringSystem
from .verify import MULTIPLE, Pieces, check_lines

#: why a case the compiled system Newton tried went to the general path
NOT_SETTLED = "the compiled system Newton did not settle it"
NOT_VERIFIED = "a line at the compiled solution failed verification"
NOT_BALANCED = "the free points' net force at the compiled solution exceeds the tolerance"


@dataclass
class Packed:
    """The arrays of :func:`._system_fast.system_cases` for N cases of one layout, and
    what the final stage needs (see there for the kernel's arrays)."""

    la: np.ndarray
    lb: np.ndarray
    flip: np.ndarray  # (N, M) the line is solved from B (anchored at B)
    poff: np.ndarray
    ell: np.ndarray
    EA: np.ndarray
    w: np.ndarray
    bounds: np.ndarray
    point: np.ndarray
    anchored: np.ndarray
    clear: np.ndarray
    moving: np.ndarray
    fidx: np.ndarray
    free_pts: np.ndarray
    pos: np.ndarray
    pforce: np.ndarray
    plane: Plane | None
    TA0: np.ndarray  # (N, M, 3) each line's starting tension at A hanging free
    ltol: np.ndarray
    lmaxit: np.ndarray
    tol: np.ndarray
    maxit: np.ndarray
    cap: np.ndarray
    n_nodes: int


def ineligible(system: MooringSystem, *, prescribed: bool = False) -> str:
    """Why the compiled path does not take ``system`` ('' when it does, as far as the
    system's definition says; the end positions decide the rest in :func:`pack`).
    ``prescribed``: free bodies are taken where they are (one evaluation of the free-body
    Newton of :mod:`.free_bodies`)."""
    if not prescribed and system.body_free.size and np.any(system.body_free):
        return "free bodies are solved by the general path"
    if not system.lines:
        return "no lines"
    nodes = {ln.problem.n_nodes for ln in system.lines}
    if len(nodes) != 1:
        return "lines with different node counts"
    for ln in system.lines:
        prob = ln.problem
        line, med = prob.line, prob.medium
        if med.has_current:  # drag on lines and free points: the general path's iteration
            return "current: the compiled kernels solve still water"
        if line.is_nonlinear:
            return f"line {ln.name}: a nonlinear axial law has no compiled kernel"
        if getattr(line, "is_spring", False):
            return f"line {ln.name}: a spring line has no compiled kernel"
    return ""


def point_positions_many(
    system: MooringSystem, poses: np.ndarray, offsets: np.ndarray | None, base: np.ndarray
) -> np.ndarray:
    """Positions (N, n, 3) of all points for N body poses (N, m, 6): fixed and free points
    from ``base`` (N, n, 3), body points at pose + R offset (``offsets`` (N, n, 3), or the
    system's)."""
    pos = np.array(base, dtype=float, copy=True)
    on = np.flatnonzero(system.point_kind == BODY)
    if on.size:
        R = rotations(poses[..., 3:])  # (N, m, 3, 3)
        b = system.point_body[on]
        off = system.point_position[on][None] if offsets is None else offsets[:, on]
        pos[:, on] = poses[:, b, :3] + np.einsum(
            "nkij,nkj->nki", R[:, b], np.broadcast_to(off, (len(pos), on.size, 3))
        )
    return pos


def _axis_rotations_many(angles: np.ndarray, derivatives: bool = True) -> tuple[np.ndarray, ...]:
    """:func:`.system._axis_rotations` for angles (..., 3): each (..., 3, 3) (without
    ``derivatives``, the rotations alone)."""
    c1, s1 = np.cos(angles[..., 0]), np.sin(angles[..., 0])
    c2, s2 = np.cos(angles[..., 1]), np.sin(angles[..., 1])
    c3, s3 = np.cos(angles[..., 2]), np.sin(angles[..., 2])
    z, o = np.zeros_like(c1), np.ones_like(c1)
    sh = (*c1.shape, 3, 3)
    rx = np.stack([o, z, z, z, c1, -s1, z, s1, c1], -1).reshape(sh)
    ry = np.stack([c2, z, s2, z, o, z, -s2, z, c2], -1).reshape(sh)
    rz = np.stack([c3, -s3, z, s3, c3, z, z, z, o], -1).reshape(sh)
    if not derivatives:
        return rx, ry, rz
    drx = np.stack([z, z, z, z, -s1, -c1, z, c1, -s1], -1).reshape(sh)
    dry = np.stack([-s2, z, c2, z, z, z, -c2, z, -s2], -1).reshape(sh)
    drz = np.stack([-s3, -c3, z, c3, -s3, z, z, z, z], -1).reshape(sh)
    return rx, ry, rz, drx, dry, drz


def rotations(angles: np.ndarray) -> np.ndarray:
    """R = Rz(yaw) Ry(pitch) Rx(roll) for angles (..., 3), as :func:`.system.rotation`."""
    rx, ry, rz = _axis_rotations_many(angles, derivatives=False)
    return rz @ ry @ rx


def rotation_derivatives_many(angles: np.ndarray) -> np.ndarray:
    """dR/d(roll, pitch, yaw) (..., 3, 3, 3), as :func:`.system.rotation_derivatives`."""
    rx, ry, rz, drx, dry, drz = _axis_rotations_many(angles)
    return np.stack((rz @ ry @ drx, rz @ dry @ rx, drz @ ry @ rx), axis=-3)


def pack(
    system: MooringSystem,
    pos: np.ndarray,
    start: np.ndarray | None = None,
    pforce: np.ndarray | None = None,
) -> tuple[Packed | None, np.ndarray]:
    """The arrays of N cases of ``system`` that differ only in the points' positions
    ``pos`` (N, n, 3) (fixed and body points where they are; free points: the start, or
    ``start``: (k, 3) for all cases or (N, k, 3) per case). Returns the packed cases the
    kernel takes and, per case,
    why it does not ('' where it does)."""
    N, n = pos.shape[0], len(system.point_names)
    M = len(system.lines)
    kind = system.point_kind
    free_pts = np.flatnonzero(kind == FREE).astype(np.int64)
    pos = np.array(pos, dtype=float, copy=True)
    if start is not None:
        pos[:, free_pts] = start
    lay = system_layout(system)
    plane = lay.plane
    why = np.full(N, "", dtype=object)
    P, poff = lay.P, lay.poff
    if plane is not None:
        limit = 1e-6 * lay.L
        ha, hb = plane.height_above(pos[:, lay.a]), plane.height_above(pos[:, lay.b])
        gra = (np.abs(ha) <= limit) & (kind[lay.a] == FIXED) & (hb > limit)
        grb = (np.abs(hb) <= limit) & (kind[lay.b] == FIXED) & (ha > limit)
        hang = (ha > limit) & (hb > limit)
        bad = ~(gra | grb | hang)
        for m in np.flatnonzero(np.any(bad, axis=0)):
            why[bad[:, m] & (why == "")] = (
                f"line {system.lines[m].name} has an end on or below the seabed that is not "
                "an anchor (a fixed point with the line's other end above the seabed)"
            )
    else:
        gra = grb = np.zeros((N, M), dtype=bool)
    ell = np.repeat(lay.ell[None], N, axis=0)
    EA = np.repeat(lay.EA[None], N, axis=0)
    w = np.repeat(lay.w[None], N, axis=0)
    bounds = np.repeat(lay.bounds[None], N, axis=0)
    point = np.repeat(lay.point[None], N, axis=0)
    clear = np.repeat(lay.clear[None], N, axis=0)
    args = np.repeat(lay.guess[None], N, axis=0)  # (N, M, 11)
    for m in np.flatnonzero(np.any(grb, axis=0)):  # anchored at B: laid from B
        o, ob, p = poff[m], poff[m] + m, P[m]
        rows = grb[:, m]
        e_, ea_, w_, pt_, bd_ = line_pieces(reversed_line(system.lines[m].problem.line))
        ell[rows, o : o + p] = e_
        EA[rows, o : o + p] = ea_
        w[rows, o : o + p] = w_
        bounds[rows, ob : ob + p + 1] = bd_
        point[rows, ob : ob + p + 1] = pt_
        down = bool(np.all(w_ >= 0.0))
        if plane is not None:
            down = down and bool(np.all(pt_ @ plane.normal <= 0.0))
        clear[rows, m] = down
        args[rows, m, 3] = bounds[rows, ob + p]
        args[rows, m, 4:7] = point[rows, ob : ob + p + 1].sum(axis=1)
        args[rows, m, 6] -= np.sum(w[rows, o : o + p] * ell[rows, o : o + p], axis=1)
        args[rows, m, 7] = args[rows, m, 3] / np.sum(
            ell[rows, o : o + p] / EA[rows, o : o + p], axis=1
        )
        args[rows, m, 8:] = point[rows, ob]
    la = np.where(grb, lay.b, lay.a)
    lb = np.where(grb, lay.a, lay.b)
    flip = grb.copy()
    anchored = gra | grb
    fidx = np.full(n, -1, dtype=np.int64)
    fidx[free_pts] = np.arange(free_pts.size)
    moving = (kind[lay.a] == FREE) | (kind[lay.b] == FREE)
    on_free = [
        ln.problem.line.total_length
        for ln in system.lines
        if kind[ln.a] == FREE or kind[ln.b] == FREE
    ]
    cap = 0.5 * min(on_free) if on_free else math.inf
    if pforce is None:  # the free points' constant forces (N, n, 3) [N], or the system's
        pforce = np.broadcast_to(system.point_force, (N, n, 3))
    pforce = np.array(pforce, dtype=float, copy=True)
    prob = system.lines[0].problem
    keep = why == ""
    packed = None
    if np.any(keep):
        k = keep
        # each line's starting tension hanging free (batch._guess, as _solve_group)
        from .batch_kernels import _guess

        Nk = int(k.sum())
        args = args[k]
        args[:, :, :3] = (
            pos[k][np.arange(Nk)[:, None], lb[k]] - pos[k][np.arange(Nk)[:, None], la[k]]
        )
        a = args.reshape(Nk * M, 11)
        TA0 = _guess(a[:, :3], a[:, 3], a[:, 4:7], a[:, 7], a[:, 8:]).reshape(Nk, M, 3)
        packed = Packed(
            la=la[k], lb=lb[k], flip=flip[k], poff=poff, ell=ell[k], EA=EA[k], w=w[k],
            bounds=bounds[k], point=point[k], anchored=anchored[k], clear=clear[k],
            moving=moving, fidx=fidx, free_pts=free_pts, pos=pos[k], pforce=pforce[k],
            plane=plane, TA0=TA0,
            ltol=np.full(Nk, prob.tolerance), lmaxit=np.full(Nk, prob.max_iterations, np.int64),
            tol=np.full(Nk, system.tolerance), maxit=np.full(Nk, system.max_iterations, np.int64),
            cap=np.full(Nk, cap), n_nodes=int(prob.n_nodes),
        )  # fmt: skip
    return packed, why


@dataclass
class Solved:
    """N cases solved by :func:`solve_packed`: per case and line (the lines as defined, A
    to B) ``position`` (N, M, n, 3) [m], ``tension`` (N, M, n) [N], ``force_a``,
    ``force_b`` (N, M, 3) [N], ``laid_length`` (N, M) [m]; per case the points'
    positions (N, n, 3) [m], the bodies' force (N, m, 6) and stiffness (N, m, 6, 6),
    Newton ``iterations`` and ``residual``, and ``fallback``: '' where verified, else why
    the case is for the general path (its other values are then NaN)."""

    s: np.ndarray
    position: np.ndarray
    tension: np.ndarray
    force_a: np.ndarray
    force_b: np.ndarray
    laid_length: np.ndarray
    point_position: np.ndarray
    body_force: np.ndarray
    body_stiffness: np.ndarray
    iterations: np.ndarray
    residual: np.ndarray
    fallback: np.ndarray
    #: (N, M, 2, 2, 3, 3) [N/m] each line's end stiffness blocks K[i, j] = -d f_i / d r_j
    #: (ends A, B as defined; NaN at an end anchored on the seabed)
    stiffness: np.ndarray | None = None


def solve_packed(system: MooringSystem, pk: Packed, poses: np.ndarray) -> Solved:
    """The free points of the packed cases by the compiled Newton, then the lines
    re-solved, sampled and verified at the solution, the equilibrium checked, and the
    bodies' force and stiffness at ``poses`` (N, m, 6) (see the module docstring)."""
    N, M = pk.la.shape
    n_pts = pk.pos.shape[1]
    from . import _system_fast as ks

    pos, mode, fa, fb, K, iters, resid, status = _settle(pk)
    fallback = np.full(N, "", dtype=object)
    for code, text in ks.SYS_REASONS.items():
        fallback[status == code] = f"{NOT_SETTLED} ({text})"
    fallback[(status != 0) & (fallback == "")] = NOT_SETTLED
    n = pk.n_nodes
    L_line = np.array(
        [pk.bounds[0, pk.poff[m] + m + pk.poff[m + 1] - pk.poff[m]] for m in range(M)]
    )
    s_all = np.linspace(np.zeros(M), L_line, n, axis=1)  # (M, n), as np.linspace(0, L, n)
    out_pos = np.full((N, M, n, 3), np.nan)
    out_ten = np.full((N, M, n), np.nan)
    out_fa = np.full((N, M, 3), np.nan)
    out_fb = np.full((N, M, 3), np.nan)
    laid = np.zeros((N, M))
    ok = status == 0
    # every line of every settled case, grouped by piece count: one call of each batch
    # kernel and of the verification per group
    sizes = np.diff(pk.poff)
    for p in np.unique(sizes):
        rows = np.flatnonzero(ok)
        if not rows.size:
            break
        ms = np.flatnonzero(sizes == p)
        good = _final_lines(
            pk, pos, rows, ms, int(p), n, out_pos, out_ten, out_fa, out_fb, laid, mode
        )
        bad = rows[~np.all(good, axis=1)]
        fallback[bad] = NOT_VERIFIED
        ok[bad] = False
    # the free points' equilibrium from the verified lines' forces
    ka = np.where(pk.flip, pk.lb, pk.la)  # the lines' own ends A, B
    kb = np.where(pk.flip, pk.la, pk.lb)
    net = np.zeros((N, n_pts, 3))
    rows_n = np.arange(N)[:, None]
    np.add.at(net, (rows_n, ka), np.nan_to_num(out_fa))
    np.add.at(net, (rows_n, kb), np.nan_to_num(out_fb))
    net += pk.pforce
    fr = pk.free_pts
    if fr.size:
        scale = np.maximum(
            np.max(np.linalg.norm(np.concatenate((out_fa, out_fb), axis=1), axis=2), axis=1),
            np.max(np.abs(pk.pforce[:, fr]).reshape(N, -1), axis=1),
        )
        eps = float(np.finfo(float).eps)
        allow = MULTIPLE * np.maximum(pk.tol, 64.0 * eps) * scale
        off = np.max(np.abs(net[:, fr]).reshape(N, -1), axis=1)
        unbalanced = ok & ~(off <= allow)
        fallback[unbalanced] = NOT_BALANCED
        ok &= ~unbalanced
    # stiffness blocks per line as defined: (N, M, 2, 2, 3, 3)
    Kl = np.full((N, M, 2, 2, 3, 3), np.nan)
    free_mode = (mode == 0)[..., None, None]
    Kl[:, :, 0, 0] = np.where(free_mode, K, np.nan)
    Kl[:, :, 0, 1] = np.where(free_mode, -K, np.nan)
    Kl[:, :, 1, 0] = np.where(free_mode, -K, np.nan)
    Kl[:, :, 1, 1] = K
    Kl = np.where(pk.flip[..., None, None, None, None], Kl[:, :, ::-1, ::-1], Kl)
    body_force, body_stiffness = _bodies_many(system, pos, poses, net - pk.pforce, Kl, ka, kb)
    # a singular free-point stiffness (see _solve_each): the general solver decides
    singular = ok & ~np.isfinite(body_stiffness).reshape(N, -1).all(axis=1)
    fallback[singular] = f"{NOT_SETTLED} (singular free-point stiffness)"
    ok &= ~singular
    bad = ~ok
    if np.any(bad):
        for arr in (out_pos, out_ten, out_fa, out_fb, laid, body_force, body_stiffness, pos):
            arr[bad] = np.nan
    return Solved(
        s=s_all, position=out_pos, tension=out_ten, force_a=out_fa, force_b=out_fb,
        laid_length=laid, point_position=pos, body_force=body_force,
        body_stiffness=body_stiffness, iterations=iters, residual=resid,
        fallback=fallback, stiffness=Kl,
    )  # fmt: skip


def _settle(pk: Packed) -> tuple[np.ndarray, ...]:
    """The compiled system Newton on the packed cases: the points' positions (N, n, 3),
    each line's mode, end forces and stiffness, the iterations, residuals and status."""
    from . import _system_fast as ks

    N, M = pk.la.shape
    plane = pk.plane
    if plane is not None:
        e1, e2 = plane.basis
        normal, basis = np.tile(plane.normal, (N, 1)), np.tile(np.stack((e1, e2), 1), (N, 1, 1))
        depth, mu = np.full(N, plane.depth), np.full(N, plane.friction)
        still, has = np.full(N, plane.slope == 0.0), np.ones(N, dtype=bool)
    else:
        normal, basis = np.zeros((N, 3)), np.zeros((N, 3, 2))
        depth, mu = np.zeros(N), np.zeros(N)
        still, has = np.zeros(N, dtype=bool), np.zeros(N, dtype=bool)
    pos = np.ascontiguousarray(pk.pos, dtype=float).copy()
    mode = np.zeros((N, M), dtype=np.int64)
    fa = np.zeros((N, M, 3))
    fb = np.zeros((N, M, 3))
    K = np.zeros((N, M, 3, 3))
    iters = np.zeros(N, dtype=np.int64)
    resid = np.zeros(N)
    status = np.zeros(N, dtype=np.int64)
    ks.system_cases(
        pk.la, pk.lb, pk.poff, pk.ell, pk.EA, pk.w, pk.bounds, pk.point, pk.anchored,
        pk.clear, pk.moving, pk.fidx, pk.free_pts, pos, pk.pforce, pk.TA0, normal, basis,
        depth, mu, still, has, pk.ltol, pk.lmaxit, pk.tol, pk.maxit, pk.cap,
        mode, fa, fb, K, iters, resid, status,
    )  # fmt: skip
    return pos, mode, fa, fb, K, iters, resid, status


def hanging_shapes(pk: Packed, lines: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """The shapes of ``lines`` (indices, each hanging free, not anchored on the seabed in
    any case) at the packed cases' equilibrium, by :func:`_settle` and the final stage
    of :func:`solve_packed` on those lines alone (solved again at the points, sampled at
    the nodes, verified): positions (N, len(lines), n, 3) [m] and whether each case's
    line is settled and verified (N, len(lines)); None where a case did not settle."""
    N, M = pk.la.shape
    pos, _, _, _, _, _, _, status = _settle(pk)
    if np.any(status != 0):
        return None
    n = pk.n_nodes
    out_pos = np.full((N, M, n, 3), np.nan)
    out_ten = np.full((N, M, n), np.nan)
    out_fa = np.full((N, M, 3), np.nan)
    out_fb = np.full((N, M, 3), np.nan)
    laid = np.zeros((N, M))
    good = np.zeros((N, M), dtype=bool)
    sizes = np.diff(pk.poff)
    rows = np.arange(N)
    for p in np.unique(sizes[lines]):
        ms = lines[sizes[lines] == p]
        good[:, ms] = _final_lines(
            pk, pos, rows, ms, int(p), n, out_pos, out_ten, out_fa, out_fb, laid
        )
    return out_pos[:, lines], good[:, lines]


def _final_lines(
    pk: Packed,
    pos: np.ndarray,
    rows: np.ndarray,
    ms: np.ndarray,
    p: int,
    n: int,
    out_pos: np.ndarray,
    out_ten: np.ndarray,
    out_fa: np.ndarray,
    out_fb: np.ndarray,
    laid: np.ndarray,
    mode: np.ndarray | None = None,
) -> np.ndarray:
    """Lines ``ms`` (all of ``p`` pieces) of cases ``rows`` solved again at the points
    ``pos`` and sampled at ``n`` nodes by the batch kernels (hanging free:
    :func:`._fast.solve_cases` from :func:`.batch._guess`, as :func:`.batch.solve_batch`
    does; anchored on the seabed: :func:`.batch.solve_contact_arrays`), written as each
    line is defined (A to B) into the ``out_*`` arrays (N, M, ...), and verified
    (:func:`.verify.check_lines`, with the seabed for the anchored ones). Returns per
    case and line (len(rows), len(ms)) whether the line is settled and verified.

    An anchored line that the system Newton left hanging free (``mode`` (N, M) 0, as
    :func:`._system_fast.system_cases` gives it), its loads all pointing down, is solved
    hanging first and kept so where it leaves its anchor (not below the seabed) upwards:
    then it rises all along (:func:`.batch_kernels._hang_free`), and the contact solve
    would lift it off and hand it on to the same free-hanging solve from the same start
    (the same numbers, without the contact solve and its second verification pass).
    Otherwise it goes to the contact solve."""
    from .batch_kernels import _guess, solve_contact_arrays

    R, nm = rows.size, ms.size
    cols = pk.poff[ms][:, None] + np.arange(p)  # (nm, p)
    bcols = (pk.poff[ms] + ms)[:, None] + np.arange(p + 1)  # (nm, p + 1)
    r2, c2 = rows[:, None, None], cols[None]
    ell = pk.ell[r2, c2].reshape(R * nm, p)
    EA = pk.EA[r2, c2].reshape(R * nm, p)
    w = pk.w[r2, c2].reshape(R * nm, p)
    bounds = pk.bounds[rows[:, None, None], bcols[None]].reshape(R * nm, p + 1)
    point = pk.point[rows[:, None, None], bcols[None]].reshape(R * nm, p + 1, 3)
    rA = pos[rows[:, None], pk.la[rows][:, ms]].reshape(R * nm, 3)
    rB = pos[rows[:, None], pk.lb[rows][:, ms]].reshape(R * nm, 3)
    flip = pk.flip[rows][:, ms].reshape(-1)
    anch = pk.anchored[rows][:, ms].reshape(-1)
    tol = np.repeat(pk.ltol[rows], nm)
    maxit = np.repeat(pk.lmaxit[rows], nm)
    plane = pk.plane
    L = bounds[:, -1]
    s = np.linspace(np.zeros(R * nm), L, n, axis=1)
    good = np.zeros(R * nm, dtype=bool)
    P_ = np.full((R * nm, n, 3), np.nan)
    T_ = np.full((R * nm, n), np.nan)
    FA = np.full((R * nm, 3), np.nan)
    FB = np.full((R * nm, 3), np.nan)
    LL = np.zeros(R * nm)
    first = ~anch  # solved hanging free
    if mode is not None and plane is not None:
        first |= anch & pk.clear[rows][:, ms].reshape(-1) & (mode[rows][:, ms].reshape(-1) == 0)
    groups = [(np.flatnonzero(first), False), (np.flatnonzero(~first), True)]
    for g, on_bed in groups:
        if not g.size:
            continue
        sg = np.where(flip[g, None], L[g, None] - s[g], s[g])
        if on_bed:
            got = solve_contact_arrays(
                ell[g], EA[g], w[g], point[g], bounds[g], rA[g], rB[g], plane,
                tol[g], maxit[g], sg,
            )  # fmt: skip
            P_[g], T_[g] = got["position"], got["tension"]
            FA[g], FB[g] = got["force_a"], got["force_b"]
            LL[g] = got["laid_length"]
            settled = got["status"] == 0
        else:
            Cend = point[g].sum(axis=1)
            Cend[:, 2] -= np.sum(w[g] * ell[g], axis=1)
            target = rB[g] - rA[g]
            EAeff = L[g] / np.sum(ell[g] / EA[g], axis=1)
            TA0 = _guess(target, L[g], Cend, EAeff, point[g, 0])
            TAo, TL = np.empty((g.size, 3)), np.empty((g.size, 3))
            it_, rs_ = np.zeros(g.size, np.int64), np.zeros(g.size)
            st_ = np.zeros(g.size, np.int64)
            pg, tg = np.empty((g.size, n, 3)), np.empty((g.size, n))
            _fast.solve_cases(
                ell[g], EA[g], w[g], point[g], bounds[g], np.zeros(g.size, dtype=np.int64),
                rA[g], target, TA0, tol[g], maxit[g], sg, pg, tg, TAo, TL, it_, rs_, st_,
            )  # fmt: skip
            P_[g], T_[g], FA[g], FB[g] = pg, tg, TAo, -TL
            settled = st_ == 0
            if plane is not None:  # a line touching the seabed between raised ends
                height = (pg - np.array([0.0, 0.0, -plane.depth])) @ plane.normal
                settled &= ~np.any(height < -1e-6 * L[g, None], axis=1)
                on = anch[g]
                if np.any(on):  # anchored: kept where it leaves the anchor upwards
                    nrm = plane.normal
                    anchor = (rA[g] - np.array([0.0, 0.0, -plane.depth])) @ nrm
                    keep = ~on | (settled & (TAo @ nrm >= 0.0) & (anchor >= -1e-9 * L[g]))
                    settled &= keep
                    # the others to the contact solve, the group taken next
                    groups[1] = (np.sort(np.concatenate((groups[1][0], g[~keep]))), True)
        settled &= (
            np.all(np.isfinite(P_[g]), axis=(1, 2))
            & np.all(np.isfinite(T_[g]), axis=1)
            & np.all(np.isfinite(FA[g]), axis=1)
            & np.all(np.isfinite(FB[g]), axis=1)
        )
        # checked as the line is defined, A to B (grid._compiled_solve's seabed_checked)
        idx = g[settled]
        if idx.size:
            fl = flip[idx]

            def fw(x: np.ndarray, fl: np.ndarray = fl) -> np.ndarray:
                return np.where(fl.reshape(-1, *[1] * (x.ndim - 1)), x[:, ::-1], x)

            bd = np.where(fl[:, None], L[idx, None] - bounds[idx][:, ::-1], bounds[idx])
            good[idx] = check_lines(
                s=s[idx],
                position=P_[idx],
                tension=T_[idx],
                force_a=np.where(fl[:, None], FB[idx], FA[idx]),
                force_b=np.where(fl[:, None], FA[idx], FB[idx]),
                pieces=Pieces(
                    bounds=bd,
                    weight=fw(w[idx]),
                    axial_stiffness=fw(EA[idx]),
                    point=fw(point[idx]),
                ),
                tolerance=tol[idx],
                position_a=np.where(fl[:, None], rB[idx], rA[idx]),
                position_b=np.where(fl[:, None], rA[idx], rB[idx]),
                plane=plane if on_bed else None,
            ).ok
    # back to the line as defined (A to B)
    at = (rows[:, None], ms[None])
    out_pos[at] = P_.reshape(R, nm, n, 3)
    out_ten[at] = T_.reshape(R, nm, n)
    out_fa[at] = np.where(flip[:, None], FB, FA).reshape(R, nm, 3)
    out_fb[at] = np.where(flip[:, None], FA, FB).reshape(R, nm, 3)
    laid[at] = LL.reshape(R, nm)
    return good.reshape(R, nm)


def _skew_many(v: np.ndarray) -> np.ndarray:
    z = np.zeros(v.shape[:-1])
    x, y, w = v[..., 0], v[..., 1], v[..., 2]
    return np.stack([z, -w, y, w, z, -x, -y, x, z], -1).reshape(*v.shape[:-1], 3, 3)


def _bodies_many(
    system: MooringSystem,
    pos: np.ndarray,
    poses: np.ndarray,
    force: np.ndarray,
    Kl: np.ndarray,
    ka: np.ndarray,
    kb: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`.system._bodies` for N cases: the bodies' force (N, m, 6) and stiffness
    (N, m, 6, 6) from the lines' forces on the points ``force`` (N, n, 3) and their end
    stiffness blocks ``Kl`` (N, M, 2, 2, 3, 3) between points ``ka``, ``kb`` (N, M)."""
    N, n = pos.shape[:2]
    m = len(system.body_names)
    body_force = np.zeros((N, m, 6))
    body_stiffness = np.zeros((N, m, 6, 6))
    kind = system.point_kind
    on = np.flatnonzero(kind == BODY)
    if not on.size:
        return body_force, body_stiffness
    fr = np.flatnonzero(kind == FREE)
    # the assembled stiffness of the body and free points (moving ones only)
    sel = np.concatenate((on, fr))
    where = np.full(n, -1)
    where[sel] = np.arange(sel.size)
    Kall = np.zeros((N, sel.size, 3, sel.size, 3))
    # each line's blocks between its moving ends (the line's own ends: every case's),
    # added in the order line, i, j (np.add.at adds in index order: the same sums)
    ends = where[np.stack((ka[0], kb[0]), axis=1)]  # (M, 2)
    line, i, j = np.nonzero((ends[:, :, None] >= 0) & (ends[:, None, :] >= 0))
    blocks = np.nan_to_num(Kl[:, line, i, j]).transpose(1, 0, 2, 3)  # (K, N, 3, 3)
    np.add.at(Kall, (slice(None), ends[line, i], slice(None), ends[line, j]), blocks)
    Kall = Kall.reshape(N, 3 * sel.size, 3 * sel.size)
    nb = 3 * on.size
    Kc = Kall[:, :nb, :nb]
    if fr.size:
        Kc = Kc - Kall[:, :nb, nb:] @ _solve_each(Kall[:, nb:, nb:], Kall[:, nb:, :nb])
    dR = rotation_derivatives_many(poses[..., 3:])  # (N, m, 3 angles, 3, 3)
    for b in range(m):
        mine = np.flatnonzero(system.point_body[on] == b)
        if not mine.size:
            continue
        pts = on[mine]
        u = pos[:, pts] - poses[:, b, None, :3]  # (N, p, 3)
        f = force[:, pts]
        A = np.einsum("naij,pj->npia", dR[:, b], system.point_position[pts])  # (N, p, 3, 3)
        body_force[:, b, :3] = f.sum(axis=1)
        body_force[:, b, 3:] = np.cross(u, f).sum(axis=1)
        lever = np.concatenate((np.broadcast_to(np.eye(3), u.shape + (3,)), _skew_many(u)), axis=2)
        trans = np.concatenate((np.broadcast_to(np.eye(3), u.shape + (3,)), A), axis=3)
        body_stiffness[:, b, 3:, 3:] += np.einsum("npij,npjk->nik", _skew_many(f), A)
        blk = Kc.reshape(N, on.size, 3, on.size, 3)[:, mine][:, :, :, mine].transpose(0, 1, 3, 2, 4)
        body_stiffness[:, b] += np.einsum("npia,npqab,nqbj->nij", lever, blk, trans)
    return body_force, body_stiffness


def _solve_each(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """``A^-1 B`` per case (A (N, k, k), B (N, k, j)); NaN in the cases whose A is singular
    (a case the compiled Newton did not settle has zero stiffness blocks), so that one
    such case does not fail the others of its chunk (the caller hands it to the general
    solver)."""
    try:
        return np.linalg.solve(A, B)
    except np.linalg.LinAlgError:
        out = np.full(B.shape, np.nan)
        for i in range(len(A)):
            try:
                out[i] = np.linalg.solve(A[i], B[i])
            except np.linalg.LinAlgError:
                pass
        return out


def solve_fast(
    system: MooringSystem, *, prescribed: bool = False, extra_poses: np.ndarray | None = None
) -> tuple[object | None, str]:
    """``system`` through the compiled path: (its :class:`.system.SystemResult`, '') or
    (None, why the general path must solve it). ``prescribed``: free bodies taken where
    ``system`` puts them (see :func:`ineligible`). ``extra_poses`` (K, m, 6): the system
    solved at those body poses too, as more cases of the same call (each case's numbers
    are its own: the system's are those of a call without them), into the result's
    ``extra`` where every one settles and verifies."""
    from .base import StaticResult
    from .system_model import SystemResult

    why = ineligible(system, prescribed=prescribed)
    if why:
        return None, why
    # the points as a sweep's chunk places them (cablestudy.system_grid): the same bits
    poses = np.asarray(system.body_position, dtype=float)[None]
    if extra_poses is not None and len(extra_poses):
        poses = np.concatenate((poses, np.asarray(extra_poses, dtype=float)))
    base = np.repeat(np.asarray(system.point_position, dtype=float)[None], len(poses), 0)
    pos = point_positions_many(system, poses, None, base)
    pk, whys = pack(system, pos)
    if len(poses) > 1 and any(whys[1:]):  # an extra pose the compiled path cannot take
        return solve_fast(system, prescribed=prescribed)
    if pk is None:
        return None, str(whys[0])
    try:
        sol = solve_packed(system, pk, poses)
    except np.linalg.LinAlgError as exc:  # a singular point stiffness: the general path
        if len(poses) > 1:
            return solve_fast(system, prescribed=prescribed)
        return None, f"{NOT_SETTLED} ({exc})"
    if sol.fallback[0]:
        return None, str(sol.fallback[0])
    extra = None
    if len(poses) > 1 and not any(sol.fallback[1:]):
        extra = {
            "poses": poses[1:],
            "position": sol.position[1:],
            "laid_length": sol.laid_length[1:],
            "anchored": pk.anchored[1:],
        }
    lines = [
        StaticResult(
            s=sol.s[m],
            position=sol.position[0, m],
            tension=sol.tension[0, m],
            force_a=sol.force_a[0, m],
            force_b=sol.force_b[0, m],
            laid_length=float(sol.laid_length[0, m]),
        )
        for m in range(len(system.lines))
    ]
    return (
        SystemResult(
            lines=lines,
            point_position=sol.point_position[0],
            body_force=sol.body_force[0],
            body_stiffness=sol.body_stiffness[0],
            iterations=int(sol.iterations[0]),
            residual=float(sol.residual[0]),
            body_position=np.array(system.body_position, dtype=float),
            extra=extra,
        ),
        "",
    )


def template_start(system: MooringSystem) -> tuple[np.ndarray, ...] | None:
    """Where a sweep starts its cases: the free points' equilibrium of ``system`` (k, 3)
    [m] by the compiled path, all points' positions there (n, 3) [m], the free points'
    first-order response to the other points' displacements, S = -K_FF^-1 K_FP (3k, 3n)
    (zero columns for the free points, and for an end anchored on the seabed, whose
    stiffness is not modelled), their loads (k, 3) [N] and K_FF^-1 (3k, 3k), their
    response to a change of load. None where the compiled path does not settle it."""
    why = ineligible(system)
    if why:
        return None
    base = np.asarray(system.point_position, dtype=float)[None]
    poses = np.asarray(system.body_position, dtype=float)[None]
    pk, whys = pack(system, point_positions_many(system, poses, None, base))
    if pk is None:
        return None
    try:
        sol = solve_packed(system, pk, poses)
    except np.linalg.LinAlgError:
        return None
    if sol.fallback[0]:
        return None
    n = len(system.point_names)
    free = np.flatnonzero(system.point_kind == FREE)
    K = np.zeros((3 * n, 3 * n))
    for m, ln in enumerate(system.lines):
        ends = (ln.a, ln.b)
        for i in range(2):
            for j in range(2):
                blk = np.nan_to_num(sol.stiffness[0, m, i, j])
                K[3 * ends[i] : 3 * ends[i] + 3, 3 * ends[j] : 3 * ends[j] + 3] += blk
    F = (3 * free[:, None] + np.arange(3)).ravel()
    S = np.zeros((3 * free.size, 3 * n))
    flex = np.zeros((3 * free.size, 3 * free.size))
    if free.size:
        flex = np.linalg.inv(K[np.ix_(F, F)])
        S = -flex @ K[F]
        S[:, F] = 0.0
    load = np.array(system.point_force[free], dtype=float)
    return sol.point_position[0][free], sol.point_position[0], S, load, flex
