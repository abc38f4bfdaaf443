"""The whole-line verification of :func:`.verify.check_one` for many lines hanging free in
a current at once (:func:`verified_many`): the answers of the compiled drag iteration
(:mod:`.batch_drag`), checked by the same checks with the same allowances, the cases of
equal piece, segment and sample counts as arrays.

For these lines (one end fixed, hanging free, no installation, linear axial laws) the
checks of :func:`.verify.check_one` are: the whole-line force balance with the drag
recomputed from the returned shape (each sample interval's drag law on its chord, at
the current of its mid-height, in each segment's share), allowed four times the
Richardson estimate of its quadrature error; the ends, A and B alike (a fixed end where
it was put, a mooring end at its height and carrying its horizontal force, a towed end
its force, the end tensions); the tension along s from end A; the stretched length. A
line resting on the seabed from its anchor has the seabed's reaction left by the
balance checked as admissible (the laid weight carried, Coulomb friction), no drag on
its laid intervals, and its tension along s checked from the end not cut off by the
contact, as there; those on one plane are checked together. A line with lumped drag
bodies (``attachment_drag_area``) or a lateral friction coefficient, or one over a
seabed with a node within its contact gap, is checked by :func:`.verify.check_one`
itself.

Pure: arrays in, results out.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..physics.current import current_velocity
from ..physics.hydro import drag_per_length
from .base import STATUS_NOT_VERIFIED, STATUS_OK, StaticProblem, StaticResult
from .seabed import Plane, seabed_of
from .semi_analytic_shape import make_layout
from .verify import CONTACT_GAP, MULTIPLE, Pieces, _checks, verified


def verified_many(problems: list[StaticProblem], results: list[StaticResult]) -> list:
    """:func:`.verify.verified` of each result (method ``catenary``), the cases of equal
    shapes checked together."""
    out: list[StaticResult] = list(results)
    groups: dict[tuple, list[int]] = {}
    made: dict[int, tuple] = {}  # per line object (a grid's cases share theirs)
    layouts = []
    for i, (p, r) in enumerate(zip(problems, results, strict=True)):
        line = p.line
        if id(line) not in made:
            lay = make_layout(line)
            made[id(line)] = (
                lay,
                bool(line.attachment_drag_area.size and np.any(line.attachment_drag_area > 0.0)),
                (len(lay.ell), line.length.size, bool(np.any(line.bending_stiffness > 0))),
            )
        lay, bodies, shape = made[id(line)]
        layouts.append(lay)
        if r.status != STATUS_OK:
            continue
        plane = seabed_of(p.medium) if r.laid_length > 0.0 else None
        if bodies or (plane is None and _near_seabed(p, r)) or p.friction_lateral is not None:
            out[i] = verified(p, r, method="catenary")
            continue
        groups.setdefault((*shape, len(r.s), plane), []).append(i)
    for (_, _, bending, _, plane), members in groups.items():
        checked, end_vals = _check_group(
            [problems[i] for i in members],
            [results[i] for i in members],
            bending,
            [layouts[i] for i in members],
            plane,
        )
        ok = checked.ok
        for j, i in enumerate(members):
            good = bool(ok[j])
            parts = []
            for name, (v, a, u) in end_vals.items():
                if not (v[j] <= a[j]):
                    good = False
                    parts.append(f"{name} off by {v[j]:.3g} {u} (allowed {a[j]:.3g} {u})")
            if good:
                continue
            message = checked.message(j)
            if parts:
                message = (message + "; " if message else "not verified: ") + "; ".join(parts)
            out[i] = replace(results[i], status=STATUS_NOT_VERIFIED, message=message)
    return out


def _near_seabed(problem: StaticProblem, result: StaticResult) -> bool:
    """Whether a node of ``result`` lies within :func:`.verify.check_one`'s contact gap
    of the seabed (then that checks it, with the seabed's reaction; further off, its
    checks are those here)."""
    plane = seabed_of(problem.medium)
    if plane is None:
        return False
    height = plane.height_above(np.asarray(result.position, dtype=float))
    return bool(np.any(height <= CONTACT_GAP * problem.line.total_length))


def _check_group(  # noqa: ANN202
    problems: list[StaticProblem],
    results: list[StaticResult],
    bending: bool,
    layouts: list | None = None,
    plane: Plane | None = None,
):
    """:func:`.verify.check_one`'s checks of lines with equal piece, segment and sample
    counts (their :func:`.semi_analytic_shape.make_layout` ``layouts``, made here if not
    given), resting on the seabed ``plane`` from an anchor where given (its reaction
    admissible, no drag on the laid intervals): the :class:`.verify.Checked` of
    :func:`.verify._checks` and the end checks (name: (value, allowance, unit), each
    (N,))."""
    N = len(problems)
    lays = layouts if layouts is not None else [make_layout(p.line) for p in problems]
    pieces = Pieces(
        bounds=np.stack([lay.bounds for lay in lays]),
        weight=np.stack([lay.weight for lay in lays]),
        axial_stiffness=np.stack([lay.EA for lay in lays]),
        point=np.stack([lay.point for lay in lays]),
    )
    s = np.stack([np.asarray(r.s, dtype=float) for r in results])
    pos = np.stack([np.asarray(r.position, dtype=float) for r in results])
    tension = np.stack([np.asarray(r.tension, dtype=float) for r in results])
    fa = np.stack([np.asarray(r.force_a, dtype=float) for r in results])
    fb = np.stack([np.asarray(r.force_b, dtype=float) for r in results])
    n = s.shape[1]
    requested = np.array([p.tolerance for p in problems], dtype=float)
    tol = np.maximum(requested, 16.0 * float(np.finfo(float).eps) * n)
    L = pieces.bounds[:, -1]  # the line's total length, as make_layout ends it
    per_line: dict[int, float] = {}
    for p in problems:
        if id(p.line) not in per_line:
            per_line[id(p.line)] = float(np.sum(np.abs(p.line.weight) * p.line.length)) + float(
                np.sum(np.linalg.norm(p.line.attachment_force, axis=1))
            )
    f_scale = np.array([per_line[id(p.line)] for p in problems])
    f_scale = f_scale + np.linalg.norm(fa, axis=1) + np.linalg.norm(fb, axis=1)
    f_allow = MULTIPLE * tol * f_scale
    x_allow = MULTIPLE * tol * np.maximum(L, np.max(np.abs(pos), axis=(1, 2)))
    end_vals: dict[str, tuple[np.ndarray, np.ndarray, str]] = {}
    # ends other than fixed (either end: a towed or moored end A is a reversed line)
    for label, attr, force, k in (("A", "end_a", fa, 0), ("B", "end_b", fb, -1)):
        ends = [getattr(p, attr) for p in problems]
        kinds = np.array([e.kind for e in ends])
        given = np.zeros((N, 3))
        height = np.zeros(N)
        for i, e in enumerate(ends):
            if e.kind != "fixed":
                given[i] = e.force
                if e.kind == "mooring":
                    height[i] = float(e.z)
        if np.any(kinds == "force"):
            v = np.where(kinds == "force", np.linalg.norm(force + given, axis=1), 0.0)
            end_vals[f"end {label} force"] = (v, f_allow, "N")
        if np.any(kinds == "mooring"):
            moor = kinds == "mooring"
            v = np.where(moor, np.linalg.norm(force[:, :2] + given[:, :2], axis=1), 0.0)
            end_vals[f"end {label} horizontal force"] = (v, f_allow, "N")
            v = np.where(moor, np.abs(pos[:, k, 2] - height), 0.0)
            end_vals[f"end {label} height"] = (v, x_allow, "m")
    seabed: dict = {}
    if plane is not None:  # as check_one marks the samples on and near the seabed
        height = (pos - np.array([0.0, 0.0, -plane.depth])) @ plane.normal
        reach = np.maximum(np.maximum(L, np.max(np.abs(pos), axis=(1, 2))), plane.depth)
        seabed = {
            "contact": height <= CONTACT_GAP * L[:, None],
            "laid": height <= 64.0 * float(np.finfo(float).eps) * reach[:, None],
            "seabed": plane,
            "friction": plane.friction,
        }
    drag, drag_allow = _drag(problems, s, pos, seabed.get("laid"), seabed.get("contact"))
    # fixed ends where they were put (rows of NaN: that end is not fixed)
    ra, rb = np.full((N, 3), np.nan), np.full((N, 3), np.nan)
    for i, p in enumerate(problems):
        if p.end_a.kind == "fixed":
            ra[i] = p.end_a.position
        if p.end_b.kind == "fixed":
            rb[i] = p.end_b.position
    checked = _checks(
        s=s,
        position=pos,
        tension=tension,
        force_a=fa,
        force_b=fb,
        pieces=pieces,
        tolerance=requested,
        position_a=ra if np.any(np.isfinite(ra)) else None,
        position_b=rb if np.any(np.isfinite(rb)) else None,
        laws=None,
        resolution=np.zeros(N),
        drag=drag,
        drag_allow=drag_allow,
        bending=bending,
        **seabed,
    )
    return checked, end_vals


def _drag(  # noqa: ANN202
    problems: list[StaticProblem],
    s: np.ndarray,
    pos: np.ndarray,
    laid: np.ndarray | None,
    contact: np.ndarray | None,
):
    """:func:`.verify._drag` of N lines: the drag on each sample interval (N, n - 1, 3)
    [N] (none on those between two samples ``laid`` (N, n) on the seabed; the whole of
    it allowed on those near the touchdown point, within ``contact`` but not laid) and
    its allowance (N, n - 1)."""
    force = _interval_drag(problems, s, pos)
    if laid is not None:
        force[laid[:, :-1] & laid[:, 1:]] = 0.0
    mag = np.linalg.norm(force, axis=2)
    m = (s.shape[1] - 1) // 2
    if m >= 1:
        idx = np.arange(0, 2 * m + 1, 2)
        coarse = _interval_drag(problems, s[:, idx], pos[:, idx])
        if laid is not None:
            coarse[laid[:, idx[:-1]] & laid[:, idx[1:]]] = 0.0
        fine = force[:, : 2 * m].reshape(len(problems), m, 2, 3).sum(axis=2)
        size = np.sum(np.linalg.norm(fine, axis=2), axis=1)
        diff = np.sum(np.linalg.norm(fine - coarse, axis=2), axis=1)
        rho = np.where(size > 0.0, diff / np.where(size > 0.0, size, 1.0), 0.0)
    else:
        rho = np.ones(len(problems))
    allow = 4.0 * np.minimum(rho, 1.0)[:, None] * mag
    if laid is not None and contact is not None:  # partly laid: no drag there
        edge = (contact[:, :-1] | contact[:, 1:]) & ~(laid[:, :-1] & laid[:, 1:])
        allow = np.where(edge, mag, allow)
    return force, allow


def _interval_drag(problems: list[StaticProblem], s: np.ndarray, pos: np.ndarray) -> np.ndarray:
    """:func:`.verify._interval_drag` of N lines (equal segment counts, no pay-out, no
    laying frame motion)."""
    h = np.diff(s, axis=1)
    chord = np.diff(pos, axis=1)
    lc = np.linalg.norm(chord, axis=2)
    t = chord / np.where(lc > 0.0, lc, 1.0)[..., None]
    mid = 0.5 * (pos[:, :-1, 2] + pos[:, 1:, 2])
    U = np.empty(chord.shape)
    media: dict[int, list[int]] = {}  # the cases of one medium object (a grid's share it)
    for i, p in enumerate(problems):
        media.setdefault(id(p.medium), []).append(i)
    for rows in media.values():
        med = problems[rows[0]].medium
        U[rows] = current_velocity(mid[rows], med.current_z, med.current_velocity)
    seg_ends: dict[int, np.ndarray] = {}
    for p in problems:
        if id(p.line) not in seg_ends:
            seg_ends[id(p.line)] = p.line.segment_ends
    ends = np.stack([seg_ends[id(p.line)] for p in problems])  # (N, K + 1)
    rho = np.array([p.medium.density for p in problems])
    f = np.zeros(chord.shape)
    for k in range(ends.shape[1] - 1):
        lo, hi = ends[:, k, None], ends[:, k + 1, None]
        share = np.clip(s[:, 1:], lo, hi) - np.clip(s[:, :-1], lo, hi)
        part = share > 0.0
        if not np.any(part):
            continue
        width = np.ones(h.shape)
        d = np.array([p.line.diameter[k] for p in problems])[:, None] * width
        cn = np.array([p.line.drag_normal[k] for p in problems])[:, None] * width
        ct = np.array([p.line.drag_tangential[k] for p in problems])[:, None] * width
        per = drag_per_length(
            U, t, density=rho[:, None, None], diameter=d, drag_normal=cn, drag_tangential=ct
        )
        ratio = share / np.where(part, h, 1.0)
        f += np.where(part[..., None], per * ratio[..., None], 0.0)
    stretch = np.where(h > 0.0, lc / np.where(h > 0.0, h, 1.0), 1.0)
    return f * (stretch * h)[..., None]
