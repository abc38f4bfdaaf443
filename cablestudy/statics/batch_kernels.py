"""Many still-water problems of the semi-analytic solver at once (one compiled Newton
iteration over all cases, :func:`._fast.solve_cases`).

The per-case solver spends most of its time in numpy overhead on arrays of a few
elements; a study sweeping end positions, lengths or loads has thousands of such cases
that differ only in numbers. Here the cases of one chunk with the same number of
pieces and output points are stacked along a leading axis and solved together by the
same damped Newton iteration on the convex complementary energy as
:func:`.semi_analytic_newton.solve_free` (with a per-case Armijo line search and per-case
convergence). A line anchored at end A on the seabed with end B fixed above it takes
the compiled seabed-contact kernel (:mod:`._fast_contact`, :func:`solve_contact_arrays`).
Lines hanging free in a current (over a seabed too, until they reach it) and lines
anchored on the seabed in a current take the compiled drag iteration
(:mod:`.batch_drag`). Cases that need more (contact between the ends, a line in a
current that reaches the seabed between its ends, a weightless slack piece, no fixed end
A in still water, a case a kernel does not settle) are solved one by one by
:class:`.semi_analytic.SemiAnalyticSolver`, so the answer never depends on which path a
case took beyond round-off.
"""

from __future__ import annotations

import numpy as np

from .base import STATUS_OK, StaticProblem, StaticResult
from .seabed import Plane, seabed_of
from .semi_analytic_shape import make_layout, reversed_line
from .verify import Pieces, check_lines, verified

#: why the batch kernel leaves a case to the one-by-one solver
NOT_SETTLED = "not settled there"
ON_SEABED = "its solution touches the seabed"


def batchable(problem: StaticProblem) -> bool:
    """Whether ``problem`` can take the batch path: still water (or no drag), end A
    fixed, end A not resting on a seabed, linear axial laws."""
    med = problem.medium
    line = problem.line
    if problem.end_a.kind != "fixed" or line.is_nonlinear:
        return False
    if med.drags(line):
        return False
    plane = seabed_of(med)
    if plane is not None:
        assert problem.end_a.position is not None
        if float(plane.height_above(problem.end_a.position)) <= 1e-6 * line.total_length:
            return False
        if problem.end_b.kind == "fixed":
            assert problem.end_b.position is not None
            if float(plane.height_above(problem.end_b.position)) <= 1e-6 * line.total_length:
                return False
    return True


def contact_end(problem: StaticProblem) -> str | None:
    """The end (``"a"`` or ``"b"``) anchored on the seabed when ``problem`` can take the
    compiled seabed-contact kernel (:mod:`._fast_contact`), else None: still water (or
    no drag), linear axial laws, both ends fixed, one on the seabed (within 1e-6 L of
    it, not below) and the other above it; or end A fixed on the seabed and end B a
    mooring or towed end (a known force). The same decisions as
    :meth:`.semi_analytic.SemiAnalyticSolver._solve`, which describes a line anchored at
    B from B (the reversed line)."""
    plane = seabed_of(problem.medium)
    line = problem.line
    if plane is None or problem.end_a.kind != "fixed":
        return None
    if line.is_nonlinear or problem.medium.drags(line):
        return None
    assert problem.end_a.position is not None
    limit = 1e-6 * line.total_length
    ha = float(plane.height_above(problem.end_a.position))
    if problem.end_b.kind in ("mooring", "force"):  # a known force at B: anchored at A
        return "a" if -limit <= ha <= limit else None
    if problem.end_b.kind != "fixed":
        return None
    assert problem.end_b.position is not None
    hb = float(plane.height_above(problem.end_b.position))
    if -limit <= ha <= limit and hb > limit:
        return "a"
    if -limit <= hb <= limit and ha > limit:
        return "b"
    return None


def contact_eligible(problem: StaticProblem) -> bool:
    """Whether ``problem`` can take the compiled seabed-contact kernel (:func:`contact_end`)."""
    return contact_end(problem) is not None


def solve_contact_arrays(
    ell: np.ndarray,
    EA: np.ndarray,
    weight: np.ndarray,
    point: np.ndarray,
    bounds: np.ndarray,
    rA: np.ndarray,
    rB: np.ndarray,
    plane: Plane,
    tol: np.ndarray,
    maxit: np.ndarray,
    s: np.ndarray,
    kind: np.ndarray | None = None,
    force: np.ndarray | None = None,
) -> dict[str, np.ndarray]:
    """Lines anchored at A on ``plane`` with B fixed above it (or, by ``kind`` (N,) 1 and
    2, a mooring or towed end B with ``force`` (N, 3) [N] as there), through the compiled
    kernel :func:`._fast_contact.contact_cases` (arrays as there: (N, P) pieces,
    (N, P + 1, 3) point loads, (N, 3) ends, (N, n) arc lengths [m]). Returns ``position``,
    ``tension``, ``force_a``, ``force_b``, ``laid_length``, ``iterations``, ``residual``
    and ``status`` (nonzero: the kernels did not settle the case, which is for the
    general solver).

    A line the contact Newton lifts off the seabed (the touchdown point driven to the
    anchor), or does not settle, may hang free: it is solved by the free-hanging kernel
    :func:`._fast.solve_cases` from the start :func:`_guess` gives, and kept (laid length
    0) where it converges and stays above the seabed within the general solver's margin,
    max(1e-6 L, 1e3 tol L). That is the general solver's answer for such a line: when
    its seabed-contact solve lifts off from the same start it returns the free-hanging
    solution; when that solve fails, it returns the free-hanging solution if that does
    not dip into the seabed (for a contact failure the kernel keeps it only where that
    is certain: see :func:`_hang_free`)."""
    from .aot import kernel
    from .contact_status import LIFT_OFF, NOT_CONVERGED, NUMERICAL

    N = ell.shape[0]
    n = s.shape[1]
    e1, e2 = plane.basis
    out = {
        "position": np.empty((N, n, 3)),
        "tension": np.empty((N, n)),
        "force_a": np.empty((N, 3)),
        "force_b": np.empty((N, 3)),
        "laid_length": np.empty(N),
        "iterations": np.zeros(N, dtype=np.int64),
        "residual": np.zeros(N),
        "status": np.zeros(N, dtype=np.int64),
    }
    kernel("contact_cases")(  # compiled ahead of time where built: no numba to load
        np.ascontiguousarray(ell, dtype=float),
        np.ascontiguousarray(EA, dtype=float),
        np.ascontiguousarray(weight, dtype=float),
        np.ascontiguousarray(point, dtype=float),
        np.ascontiguousarray(bounds, dtype=float),
        np.ascontiguousarray(rA, dtype=float),
        np.ascontiguousarray(rB, dtype=float),
        np.zeros(N, dtype=np.int64) if kind is None else np.ascontiguousarray(kind, np.int64),
        np.zeros((N, 3)) if force is None else np.ascontiguousarray(force, dtype=float),
        np.tile(plane.normal, (N, 1)),
        np.tile(np.stack((e1, e2), axis=1), (N, 1, 1)),
        np.full(N, float(plane.depth)),
        np.full(N, float(plane.friction)),
        np.full(N, plane.slope == 0.0),
        np.ascontiguousarray(tol, dtype=float),
        np.ascontiguousarray(maxit, dtype=np.int64),
        np.ascontiguousarray(s, dtype=float),
        out["position"],
        out["tension"],
        out["force_a"],
        out["force_b"],
        out["laid_length"],
        out["iterations"],
        out["residual"],
        out["status"],
    )
    st = out["status"]
    _hand_on_laid_lift(out, point, bounds, plane)
    free = np.flatnonzero(
        ((st == LIFT_OFF) | (st == NOT_CONVERGED) | (st == NUMERICAL))
        & (True if kind is None else kind == 0)  # B fixed (else: the general solver)
    )
    if free.size:
        _hang_free(free, out, ell, EA, weight, point, bounds, rA, rB, plane, tol, maxit, s)
    return out


def _hand_on_laid_lift(
    out: dict[str, np.ndarray], point: np.ndarray, bounds: np.ndarray, plane: Plane
) -> None:
    """Hand on (status :data:`.contact_status.LIFTING_LOAD_LAID`) the settled cases whose
    touchdown point lies past a point load lifting the line (a buoy, f . n > 0): the
    kernel's laid part holds it on the seabed, which only pushes. The general solver's
    contact Newton keeps the touchdown point short of it
    (:func:`.contact_pin.first_lift`)."""
    from .contact_status import LIFTING_LOAD_LAID

    lifts = (point[:, 1:-1] @ plane.normal) > 0.0  # (N, P - 1) interior boundaries
    if not lifts.any():
        return
    s_in = bounds[:, 1:-1]
    laid = out["laid_length"][:, None]
    bad = (out["status"] == 0) & np.any(lifts & (s_in < laid), axis=1)
    out["status"][bad] = LIFTING_LOAD_LAID


def _hang_free(
    rows: np.ndarray,
    out: dict[str, np.ndarray],
    ell: np.ndarray,
    EA: np.ndarray,
    weight: np.ndarray,
    point: np.ndarray,
    bounds: np.ndarray,
    rA: np.ndarray,
    rB: np.ndarray,
    plane: Plane,
    tol: np.ndarray,
    maxit: np.ndarray,
    s: np.ndarray,
) -> None:
    """Cases ``rows`` of :func:`solve_contact_arrays` the contact kernel did not settle,
    solved hanging free (into ``out``; status 0 where settled).

    A case that lifted off keeps the free-hanging solution (the general solver's answer).
    One whose contact solve failed keeps it only where it certainly does not dip into the
    seabed (where the general solver would keep it too): the anchor not below the plane
    by more than 1e-9 L and the line's tension at it not pointing into the seabed
    (T_A . n >= 0), with no load that turns the line back towards the seabed (weights
    >= 0, point loads f . n <= 0). Then T . n grows along the line, and with it the
    height above the seabed, d(r . n)/ds = (T . n)(1 / EA + 1 / |T|) >= 0."""
    from .aot import kernel
    from .contact_status import LIFT_OFF

    r = rows
    lifted = out["status"][r] == LIFT_OFF
    m, n = r.size, s.shape[1]
    Ltot = bounds[r, -1]
    Cend = point[r].sum(axis=1)
    Cend[:, 2] -= np.sum(weight[r] * ell[r], axis=1)
    target = rB[r] - rA[r]
    EAeff = Ltot / np.sum(ell[r] / EA[r], axis=1)
    TA0 = _guess(target, Ltot, Cend, EAeff, point[r, 0])
    pos = np.empty((m, n, 3))
    tension = np.empty((m, n))
    TA, TL = np.empty((m, 3)), np.empty((m, 3))
    iters, resid = np.zeros(m, dtype=np.int64), np.zeros(m)
    status = np.zeros(m, dtype=np.int64)
    kernel("solve_cases")(
        np.ascontiguousarray(ell[r]),
        np.ascontiguousarray(EA[r]),
        np.ascontiguousarray(weight[r]),
        np.ascontiguousarray(point[r]),
        np.ascontiguousarray(bounds[r]),
        np.zeros(m, dtype=np.int64),  # kind: end B fixed
        np.ascontiguousarray(rA[r]),
        target,
        TA0,
        np.ascontiguousarray(tol[r]),
        np.ascontiguousarray(maxit[r]),
        np.ascontiguousarray(s[r]),
        pos,
        tension,
        TA,
        TL,
        iters,
        resid,
        status,
    )
    height = (pos - np.array([0.0, 0.0, -plane.depth])) @ plane.normal  # (m, n)
    margin = np.maximum(1e-6 * Ltot, 1e3 * tol[r] * Ltot)
    good = (
        (status == 0)
        & np.all(np.isfinite(pos), axis=(1, 2))
        & np.all(np.isfinite(tension), axis=1)
        & np.all(np.isfinite(TA), axis=1)
        & np.all(np.isfinite(TL), axis=1)
        & (-height.min(axis=1) <= margin)
    )
    n_up = plane.normal
    anchor = (rA[r] - np.array([0.0, 0.0, -plane.depth])) @ n_up
    clear = (
        (TA @ n_up >= 0.0)
        & (anchor >= -1e-9 * Ltot)
        & np.all(weight[r] >= 0.0, axis=1)
        & np.all(point[r] @ n_up <= 0.0, axis=1)
    )
    good &= lifted | clear
    k = r[good]
    out["position"][k] = pos[good]
    out["tension"][k] = tension[good]
    out["force_a"][k] = TA[good]
    out["force_b"][k] = -TL[good]
    out["laid_length"][k] = 0.0
    out["iterations"][k] += iters[good]
    out["residual"][k] = resid[good]
    out["status"][k] = 0


def _contact_inputs(problem: StaticProblem) -> dict:
    """The arrays of ``problem`` for :func:`solve_contact_arrays` (a leading axis of
    one), its plane, and which end it is anchored at (``end``)."""
    end = contact_end(problem)
    assert end is not None
    line = problem.line if end == "a" else reversed_line(problem.line)
    if line.length.size == 1 and line.attachment_s.size == 0:
        ell = np.array([[line.length[0]]])
        EA = np.array([[line.axial_stiffness[0]]])
        weight = np.array([[line.weight[0]]])
        point = np.zeros((1, 2, 3))
        bounds = np.array([[0.0, line.length[0]]])
    else:
        lay = make_layout(line)
        ell, EA, weight = lay.ell[None], lay.EA[None], lay.weight[None]
        point, bounds = lay.point[None], lay.bounds[None]
    anchor, top = (problem.end_a, problem.end_b) if end == "a" else (problem.end_b, problem.end_a)
    kind = {"fixed": 0, "mooring": 1, "force": 2}[top.kind]
    force = np.zeros((1, 3))
    if kind == 0:
        target = np.asarray(top.position, dtype=float)[None]
    else:  # the known force on the line at B (mooring: its horizontal part), B's height
        assert top.force is not None
        force[0] = np.asarray(top.force, dtype=float)
        target = np.zeros((1, 3))
        if kind == 1:
            force[0, 2] = 0.0
            target[0, 2] = float(top.z)
    plane = seabed_of(problem.medium)
    assert plane is not None
    L = bounds[:, -1]
    s = np.linspace(np.zeros(1), L, problem.n_nodes, axis=1)
    return {
        "end": end,
        "plane": plane,
        "s": s,
        "arrays": (
            ell,
            EA,
            weight,
            point,
            bounds,
            np.asarray(anchor.position, dtype=float)[None],
            target,
        ),
        "tol": np.array([problem.tolerance], dtype=float),
        "maxit": np.array([problem.max_iterations], dtype=np.int64),
        "sample": s if end == "a" else L[:, None] - s,
        "kind": np.array([kind]),
        "force": force,
    }


def _contact_call(x: dict) -> tuple:
    """The arguments of :func:`solve_contact_arrays` for :func:`_contact_inputs` ``x``."""
    return (*x["arrays"], x["plane"], x["tol"], x["maxit"], x["sample"], x["kind"], x["force"])


def _contact_result(x: dict, out: dict, j: int) -> StaticResult | None:
    """The result of case ``j`` of :func:`solve_contact_arrays`'s ``out`` for the problem
    of :func:`_contact_inputs` ``x`` (None: not settled)."""
    if out["status"][j] != 0:
        return None
    fa, fb = ("force_a", "force_b") if x["end"] == "a" else ("force_b", "force_a")
    return StaticResult(
        s=x["s"][0],
        position=out["position"][j],
        tension=out["tension"][j],
        force_a=out[fa][j],
        force_b=out[fb][j],
        status=STATUS_OK,
        laid_length=float(out["laid_length"][j]),
        iterations=int(out["iterations"][j]),
        residual=float(out["residual"][j]),
    )


def solve_compiled(
    problem: StaticProblem,
    *,
    why: dict[int, str] | None = None,
    drag: bool = True,
    deadline: float | None = None,
) -> StaticResult | None:
    """One problem through the compiled batch kernels (free-hanging, anchored on the
    seabed, or hanging free in a current with ``drag``: :func:`_kernels` of one problem),
    or None when it does not take that path (or does not settle there: then ``why[0]``,
    if given, says why)."""
    results, reasons, tried = _kernels([problem], drag=drag, deadline=deadline)
    if results[0] is not None and results[0].success:
        return results[0]
    if why is not None and tried:  # status 0 means verified: the general solver takes it
        why[0] = reasons.get(0, NOT_SETTLED)
    return None


def contact_many(problems: list[StaticProblem]) -> list[StaticResult | None]:
    """The seabed-contact kernel's answer for each problem (seabed-contact eligible; None
    where the kernel does not settle it), those of the same pieces, nodes and seabed
    plane in one call. A line anchored at B is solved from B, as the reversed line
    (sampled at L - s), as the general solver does."""
    inputs = [_contact_inputs(p) for p in problems]
    groups: dict[tuple, list[int]] = {}
    for i, x in enumerate(inputs):
        pl = x["plane"]
        key = (
            x["arrays"][0].shape[1],
            x["s"].shape[1],
            pl.depth,
            pl.slope,
            pl.heading,
            pl.friction,
        )
        groups.setdefault(key, []).append(i)
    results: list[StaticResult | None] = [None] * len(problems)
    for idx in groups.values():
        calls = [_contact_call(inputs[i]) for i in idx]
        args = [
            calls[0][k] if k == 7 else np.concatenate([c[k] for c in calls])
            for k in range(len(calls[0]))
        ]
        out = solve_contact_arrays(*args)
        for j, i in enumerate(idx):
            results[i] = _contact_result(inputs[i], out, j)
    return results


def _kernels(
    problems: list[StaticProblem],
    *,
    contact: bool = True,
    verify: bool = True,
    drag: bool = True,
    deadline: float | None = None,
) -> tuple[list[StaticResult | None], dict[int, str], set[int]]:
    """The kernels' answers (None where a kernel does not take a problem or does not
    settle it), why the batch kernel left a case it tried, and the cases a kernel tried.
    Batchable problems with equal piece and node counts are solved together; lines
    anchored on the seabed (``contact``) by the contact kernel, those of one plane
    together, their answers verified (``verify``) as the batch kernel verifies its own;
    lines hanging free in a current (``drag``) by the compiled drag iteration
    (:mod:`.batch_drag`, which keeps no answer past ``deadline``)."""
    from .batch_drag import DRAG_NOT_SETTLED, drag_eligible, drag_many

    results: list[StaticResult | None] = [None] * len(problems)
    groups: dict[tuple[int, int], list[int]] = {}
    layouts: dict = {}
    seabed = []
    current = []
    for i, prob in enumerate(problems):
        if contact and contact_eligible(prob):  # never batchable: anchored on the seabed
            seabed.append(i)
            continue
        if drag and drag_eligible(prob):  # never batchable: in a current
            current.append(i)
            continue
        if not batchable(prob):
            continue
        line = prob.line
        if line.length.size == 1 and line.attachment_s.size == 0:
            P = 1
        else:
            layouts[i] = make_layout(line)
            P = len(layouts[i].ell)
        groups.setdefault((P, prob.n_nodes), []).append(i)
    why: dict[int, str] = {}
    for (P, n_nodes), members in groups.items():
        left: dict[int, str] = {}
        for i, res in zip(
            members,
            _solve_group(
                [problems[i] for i in members],
                P,
                n_nodes,
                [layouts.get(i) for i in members],
                why=left,
                verify=verify,
            ),
            strict=True,
        ):
            results[i] = res
        why.update({members[j]: reason for j, reason in left.items()})
    if seabed:
        for i, res in zip(seabed, contact_many([problems[i] for i in seabed]), strict=True):
            if res is not None and verify:  # status 0 means verified: else the general
                res = verified(problems[i], res, method="catenary")  # solver
            results[i] = res
    if current:
        left: dict[int, str] = {}  # a line over a seabed that reaches it: ON_SEABED
        for k, (i, res) in enumerate(
            zip(
                current,
                drag_many(
                    [problems[i] for i in current], verify=verify, deadline=deadline, why=left
                ),
                strict=True,
            )
        ):
            results[i] = res
            if res is None:
                why[i] = left.get(k, DRAG_NOT_SETTLED)
    tried = {i for members in groups.values() for i in members} | set(seabed) | set(current)
    return results, why, tried


def _guess(
    d: np.ndarray, L: np.ndarray, Cend: np.ndarray, EA: np.ndarray, point0: np.ndarray
) -> np.ndarray:
    """Vectorised starting T_A for fixed-fixed cases (same rule as
    :func:`.semi_analytic_newton.initial_tension`)."""
    W = np.linalg.norm(Cend, axis=1)
    chord = np.linalg.norm(d, axis=1)
    stretch = EA * np.maximum(chord / L - 1.0, 0.0)
    with np.errstate(all="ignore"):
        up = np.where(W[:, None] > 0.0, -Cend / np.where(W > 0.0, W, 1.0)[:, None], [0, 0, 1.0])
        w = W / L
        h = np.sum(d * up, axis=1)
        dh = d - h[:, None] * up
        l = np.linalg.norm(dh, axis=1)
        vertical = l <= 1e-12 * chord
        e = dh / np.where(vertical, 1.0, l)[:, None]
        if np.any(vertical):  # a horizontal direction across the vertical chord
            alt = np.cross(up, [1.0, 0.0, 0.0])
            alt = np.where(
                np.linalg.norm(alt, axis=1)[:, None] < 0.5, np.cross(up, [0.0, 1.0, 0.0]), alt
            )
            alt = alt / np.linalg.norm(alt, axis=1)[:, None]
            e = np.where(vertical[:, None], alt, e)
        lam = np.where(
            L <= chord,
            0.2,
            np.maximum(
                np.sqrt(
                    3.0 * np.maximum((L * L - h * h) / np.where(vertical, 1.0, l * l) - 1.0, 0.0)
                ),
                1e-3,
            ),
        )
        H = np.where(vertical, 0.0, w * l / (2.0 * lam))
        VB = np.where(
            vertical,
            np.where(L > np.abs(h), 0.5 * w * (L + h), w * L + stretch),
            0.5 * w * (h / np.tanh(lam) + L),
        )
        taut = (chord > L) & ~vertical
        H = np.where(taut, np.maximum(H, stretch * l / chord), H)
        VB = np.where(taut, np.maximum(VB, stretch * h / chord + 0.5 * w * L), VB)
        TA = H[:, None] * e + (VB - w * L)[:, None] * up + point0
        straight = W <= 0.0
        t = np.where(stretch > 0.0, stretch, 1e-6 * EA)
        TA = np.where(straight[:, None], t[:, None] * d / np.maximum(chord, 1e-300)[:, None], TA)
    return TA


def _solve_group(
    problems: list[StaticProblem],
    P: int,
    n_nodes: int,
    layouts: list,
    why: dict[int, str] | None = None,
    verify: bool = True,
) -> list[StaticResult | None]:
    """The problems of one group through the batch kernel; None for a case it leaves to
    the one-by-one solver, with the reason in ``why`` (by position), if given."""
    from . import _fast  # imports numba: on first use, not with this module

    why = {} if why is None else why
    N = len(problems)
    ell = np.empty((N, P))
    EA = np.empty((N, P))
    q = np.zeros((N, P, 3))
    point = np.zeros((N, P + 1, 3))
    bounds = np.empty((N, P + 1))
    if all(lay is None for lay in layouts):  # single segments, no attachments
        lines = [p.line for p in problems]
        ell[:, 0] = [ln.length[0] for ln in lines]
        EA[:, 0] = [ln.axial_stiffness[0] for ln in lines]
        q[:, 0, 2] = [-ln.weight[0] for ln in lines]
        bounds[:, 0] = 0.0
        bounds[:, 1] = ell[:, 0]
    else:
        for i, prob in enumerate(problems):
            lay = layouts[i] if layouts[i] is not None else make_layout(prob.line)
            ell[i], EA[i], bounds[i], point[i] = lay.ell, lay.EA, lay.bounds, lay.point
            q[i, :, 2] = -lay.weight
    kind = np.array([p.end_b.kind for p in problems])
    rA = np.array([p.end_a.position for p in problems], dtype=float)
    Ltot = bounds[:, -1]
    Q = q * ell[..., None]
    Cend = point.sum(axis=1) + Q.sum(axis=1)
    target = np.zeros((N, 3))
    TA = np.zeros((N, 3))
    fixed = kind == "fixed"
    moor = kind == "mooring"
    force = kind == "force"
    if np.any(fixed):
        target[fixed] = (
            np.array(
                [p.end_b.position for p, f in zip(problems, fixed, strict=True) if f], dtype=float
            )
            - rA[fixed]
        )
    if np.any(moor):
        mp = [p.end_b for p, m in zip(problems, moor, strict=True) if m]
        target[moor, 2] = np.array([b.z for b in mp], dtype=float) - rA[moor, 2]
        TA[moor, :2] = np.array([b.force[:2] for b in mp], dtype=float) + Cend[moor, :2]
    if np.any(force):
        TA[force] = (
            np.array(
                [p.end_b.force for p, f in zip(problems, force, strict=True) if f], dtype=float
            )
            + Cend[force]
        )
    EAeff = Ltot / np.sum(ell / EA, axis=1)
    if np.any(fixed):
        TA[fixed] = _guess(target[fixed], Ltot[fixed], Cend[fixed], EAeff[fixed], point[fixed, 0])
    if np.any(moor):
        Hh = np.hypot(TA[moor, 0], TA[moor, 1])
        Wz = -Cend[moor, 2]
        h = target[moor, 2]
        with np.errstate(all="ignore"):
            w = Wz / Ltot[moor]
            c = Wz / np.maximum(Hh, 1e-300)
            a = np.arcsinh(w * h / (2.0 * Hh * np.sinh(0.5 * np.minimum(c, 600.0)))) - 0.5 * c
            Vz = np.where((c < 600.0) & (Hh > 0.0), Hh * np.sinh(a), 0.5 * (w * h - Wz))
        TA[moor, 2] = np.where(Wz > 0.0, Vz, -0.5 * Wz)
    tol = np.array([p.tolerance for p in problems])
    maxit = np.array([p.max_iterations for p in problems])
    # the same arc lengths as np.linspace(0, L, n) of the one-by-one path, bit for bit;
    # C order, the layout cablestudy compile warms the kernel for (linspace's is F)
    s = np.ascontiguousarray(np.linspace(np.zeros(N), Ltot, n_nodes, axis=1))
    pos = np.empty((N, n_nodes, 3))
    tension = np.empty((N, n_nodes))
    TL = np.empty((N, 3))
    TAo = np.empty((N, 3))
    iters = np.zeros(N, dtype=np.int64)
    resid = np.zeros(N)
    status = np.zeros(N, dtype=np.int64)
    kind_code = np.where(fixed, 0, np.where(moor, 1, 2)).astype(np.int64)
    _fast.solve_cases(
        ell,
        EA,
        -q[..., 2].copy(),
        point,
        bounds,
        kind_code,
        rA,
        target,
        TA,
        tol,
        maxit.astype(np.int64),
        s,
        pos,
        tension,
        TAo,
        TL,
        iters,
        resid,
        status,
    )
    TA = TAo
    good = (
        (status == 0)
        & np.all(np.isfinite(pos), axis=(1, 2))
        & np.all(np.isfinite(tension), axis=1)
        & np.all(np.isfinite(TA), axis=1)
        & np.all(np.isfinite(TL), axis=1)
    )
    if verify:
        good &= _verified_group(
            problems, good, s, pos, tension, TA, -TL, bounds, -q[..., 2], EA, point, rA, tol
        )
    out: list[StaticResult | None] = []
    force_b = -TL
    iters_l = iters.tolist()
    resid_l = resid.tolist()
    for i, prob in enumerate(problems):
        if not good[i]:
            why[i] = NOT_SETTLED
            out.append(None)
            continue
        res = StaticResult(
            s=s[i],
            position=pos[i],
            tension=tension[i],
            force_a=TA[i],
            force_b=force_b[i],
            status=STATUS_OK,
            iterations=iters_l[i],
            residual=resid_l[i],
        )
        plane = seabed_of(prob.medium)
        if plane is not None and np.any(plane.height_above(res.position) < -1e-6 * Ltot[i]):
            why[i] = ON_SEABED
            out.append(None)  # touches the seabed: the one-by-one solver decides
            continue
        out.append(res)
    return out


def _verified_group(
    problems: list[StaticProblem],
    good: np.ndarray,
    s: np.ndarray,
    pos: np.ndarray,
    tension: np.ndarray,
    force_a: np.ndarray,
    force_b: np.ndarray,
    bounds: np.ndarray,
    weight: np.ndarray,
    EA: np.ndarray,
    point: np.ndarray,
    rA: np.ndarray,
    tol: np.ndarray,
) -> np.ndarray:
    """Per case whether the kernel's answer passes :func:`.verify.check_lines` (cases not
    ``good`` are False); the others go to the one-by-one solver, as any case the kernel
    does not settle."""
    idx = np.flatnonzero(good)
    ok = np.zeros(len(problems), dtype=bool)
    if not idx.size:
        return ok
    N = idx.size
    pos_b = np.full((N, 3), np.nan)
    f_b = np.full((N, 3), np.nan)
    z_b = np.full(N, np.nan)
    for j, i in enumerate(idx.tolist()):
        end = problems[i].end_b
        if end.kind == "fixed":
            pos_b[j] = end.position
        elif end.kind == "force":
            f_b[j] = end.force
        else:
            f_b[j, :2] = end.force[:2]
            z_b[j] = end.z
    checked = check_lines(
        s=s[idx],
        position=pos[idx],
        tension=tension[idx],
        force_a=force_a[idx],
        force_b=force_b[idx],
        pieces=Pieces(
            bounds=bounds[idx], weight=weight[idx], axial_stiffness=EA[idx], point=point[idx]
        ),
        tolerance=tol[idx],
        position_a=rA[idx],
        position_b=pos_b,
        given_force_b=f_b,
        given_height_b=z_b,
    )
    ok[idx] = checked.ok
    return ok
