"""Lines in a current solved together (:func:`drag_many`): the drag iteration of the
semi-analytic solver runs per case inside the compiled batch (:func:`._drag_fast.drag_cases`).

A problem takes it (:func:`drag_eligible`) when the general solver
(:class:`.semi_analytic.SemiAnalyticSolver`) would solve it hanging free with its drag
loop: a current that drags the line, one end fixed and the other fixed, towed or moored,
linear axial laws, no installation, no seabed or one below both fixed ends; or when it
would lay it on the seabed from an anchor (the end it solves from on the seabed, the
other above it; no attachments, every segment heavier than the fluid).

A line whose end A is towed or moored (end B fixed) is solved as the general solver
solves it, from B: the reversed line (:func:`.semi_analytic_shape.reversed_line`:
segments, attachments and drag coefficients in reverse order; the current is a function
of height and needs no change), its ends swapped, sampled at L - s, its end forces
swapped back.

Over a seabed the general solver hangs the line free, exactly as without one, until a
shape of its iteration reaches the seabed (then it lays it, :mod:`.midspan`). The kernel
runs the same iteration and tests every shape against the seabed
(:mod:`._drag_seabed`); a case one of whose shapes has a sample below the seabed is
handed on with :data:`ON_SEABED` (the general solver lays a line from 1e-9 L below:
the margin keeps round-off from making the two decide differently). A line resting on
the seabed between its ends in a current is the general solver's.

A line anchored on the seabed (a mooring line: the anchor at A, or at B for a line
solved from B) rests on it from the anchor in every inner solve of the iteration, as
the general solver lays it (:mod:`._drag_inner`: the laid part under its weight with
friction towards the anchor, the suspended part under weight and drag, no drag on the
laid pieces). Where that solver would leave the contact path (the touchdown point
driven to the anchor, a contact Newton that fails, a line below the seabed) the case
is handed on with the reason (:data:`ANCHORED_REASONS`).

Its pieces are the general solver's (:func:`.semi_analytic_shape.make_layout` with the
same drag elements), the cases with the same numbers of pieces, output points and
current-profile points are stacked, and each case iterates until its own convergence
test passes, with its own arithmetic: a case gives the same numbers alone as in any
batch, bit for bit. Every settled answer is then checked by :func:`.verify.verified`
exactly as the general solver's is; a case the kernel does not settle, or whose answer
fails a check, is None here (the general solver's).

Pure: problems in, results out.
"""

from __future__ import annotations

import math
import time

import numpy as np

from .base import STATUS_OK, LineModel, StaticProblem, StaticResult
from .line_state import CatenaryState
from .seabed import Plane, seabed_of
from .semi_analytic_shape import Layout, make_layout, reversed_line

#: the general solver's drag-loop settings the kernel runs with
#: (:class:`.semi_analytic.SemiAnalyticSolver` defaults)
MAX_DRAG_ITERATIONS = 300
CONTINUATION = (4, 16)

#: why the drag kernel left a case to the general solver
DRAG_NOT_SETTLED = "not settled by the drag kernel"
ON_SEABED = "its solution touches the seabed"
#: ... and why it left a line anchored on the seabed (by the kernel's status)
ANCHORED_REASONS = {
    4: "anchored on the seabed, it may hang free of it (the free-hanging path)",
    5: "anchored on the seabed, its seabed-contact Newton did not settle",
    6: "anchored on the seabed, its solution passes below the seabed",
}


def drag_eligible(problem: StaticProblem) -> bool:
    """Whether ``problem`` takes the compiled drag iteration (module docstring)."""
    med, line = problem.medium, problem.line
    if not med.drags(line) or line.is_nonlinear:
        return False
    a, b = problem.end_a.kind, problem.end_b.kind
    known = ("force", "mooring")  # an end of known force: the other one fixed
    if not ((a == "fixed" and (b == "fixed" or b in known)) or (b == "fixed" and a in known)):
        return False
    if problem.is_installation or problem.stretched_drag_diameter:
        return False
    plane, ha, hb, limit = _seabed_ends(problem)
    # over a seabed: both fixed ends above it, as the general solver tells an end on it
    # (1e-6 L); that solver then hangs the line free until a shape reaches the seabed
    if plane is None or (ha > limit and hb > limit):
        return True
    # anchored on it: the end solved from on the seabed (not below), the other above it;
    # no attachment (a clump resting on the seabed, a buoy: the general solver's), every
    # segment heavier than the fluid
    if _reversed(problem, ha, hb, limit):
        ha, hb = hb, ha
    return (
        abs(ha) <= limit
        and hb > limit
        and line.attachment_s.size == 0
        and bool(np.all(line.weight > 0.0))
    )


def _seabed_ends(problem: StaticProblem) -> tuple[Plane | None, float, float, float]:
    """(the seabed or None, the heights above it of ends A and B (inf where an end is not
    fixed, or there is no seabed) [m], the general solver's margin 1e-6 L [m])."""
    plane = seabed_of(problem.medium)
    h = [math.inf, math.inf]
    if plane is not None:
        n, base = plane.normal, np.array([0.0, 0.0, -plane.depth])
        for k, end in enumerate((problem.end_a, problem.end_b)):
            if end.kind == "fixed":
                h[k] = float((np.asarray(end.position, dtype=float) - base) @ n)
    return plane, h[0], h[1], 1e-6 * float(np.sum(problem.line.length))


def _reversed(problem: StaticProblem, ha: float, hb: float, limit: float) -> bool:
    """Whether the general solver solves ``problem`` from end B: its end A not fixed, or
    both fixed and B, not A, on the seabed (within ``limit`` = 1e-6 L of it), from the
    end heights ``ha``, ``hb`` [m] of :func:`_seabed_ends`."""
    return problem.end_a.kind != "fixed" or hb <= limit < ha


def _sides(problem: StaticProblem) -> tuple[bool, bool]:
    """(:func:`_reversed`, whether the end it is solved from is anchored on the seabed,
    within 1e-6 L of it: the general solver then lays it from there)."""
    _, ha, hb, limit = _seabed_ends(problem)
    rev = _reversed(problem, ha, hb, limit)
    return rev, (hb if rev else ha) <= limit


def drag_elements(problem: StaticProblem) -> int:
    """The drag elements the general solver cuts ``problem``'s line into."""
    return problem.drag_elements or max(problem.n_nodes - 1, 20)


def drag_many(
    problems: list[StaticProblem],
    *,
    verify: bool = True,
    deadline: float | None = None,
    why: dict[int, str] | None = None,
) -> list[StaticResult | None]:
    """The drag kernel's verified answer per problem (all :func:`drag_eligible`), None
    where it leaves the case to the general solver (``why``, if given, gets
    :data:`ON_SEABED` for a line over a seabed that reaches it, an
    :data:`ANCHORED_REASONS` text for a line anchored on it). Problems of equal piece,
    node and current-profile counts are solved in one call. Past ``deadline``
    (``time.monotonic``) no answer is kept: the general solver then reports the time
    limit, as for a case it iterates itself (the kernel does not look at the clock
    inside its loops)."""
    from .verify_drag import verified_many

    if deadline is not None and time.monotonic() > deadline:
        return [None] * len(problems)

    # a grid's cases share their line objects: one reversed line and layout per object
    flipped: dict[int, LineModel] = {}
    made: dict[tuple[int, bool, int], Layout] = {}
    layouts = []
    sides = [_sides(p) for p in problems]
    for p, (rev, _) in zip(problems, sides, strict=True):
        if rev and id(p.line) not in flipped:
            flipped[id(p.line)] = reversed_line(p.line)
        key = (id(p.line), rev, drag_elements(p))
        if key not in made:
            made[key] = make_layout(flipped[id(p.line)] if rev else p.line, key[2])
        layouts.append(made[key])
    groups: dict[tuple[int, int, int], list[int]] = {}
    for i, (p, lay) in enumerate(zip(problems, layouts, strict=True)):
        key = (len(lay.ell), p.n_nodes, len(p.medium.current_z))
        groups.setdefault(key, []).append(i)
    out: list[StaticResult | None] = [None] * len(problems)
    for members in groups.values():
        left: dict[int, str] = {}
        try:
            got = _solve_group(
                [problems[i] for i in members],
                [layouts[i] for i in members],
                [sides[i] for i in members],
                flipped,
                left,
            )
        except Exception:  # noqa: BLE001 - a fault in the kernel: each case alone
            got, left = [], {}
            for j, i in enumerate(members):
                one: dict[int, str] = {}
                try:
                    got += _solve_group([problems[i]], [layouts[i]], [sides[i]], flipped, one)
                except Exception:  # noqa: BLE001 - the general solver takes it
                    got.append(None)
                if one:  # its own reason
                    left[j] = one[0]
        if why is not None:
            why.update({members[j]: r for j, r in left.items()})
        if deadline is not None and time.monotonic() > deadline:
            got = [None] * len(members)  # the time limit is the general solver's to say
        if verify:  # status 0 means verified: else the general solver's
            settled = [j for j, res in enumerate(got) if res is not None]
            checked = verified_many(
                [problems[members[j]] for j in settled], [got[j] for j in settled]
            )
            for j, res in zip(settled, checked, strict=True):
                got[j] = res if res.status == STATUS_OK else None
        for i, res in zip(members, got, strict=True):
            out[i] = res
    return out


def _solve_group(
    problems: list[StaticProblem],
    layouts: list[Layout],
    sides: list[tuple[bool, bool]],
    flipped: dict[int, LineModel],
    left: dict[int, str],
) -> list:
    """One stacked call of the kernel; the settled cases as results (None otherwise, why
    in ``left`` by index for a line that reaches the seabed or is anchored on it). A
    reversed problem (``sides``: :func:`_sides` per problem) goes in as the general
    solver states it: the line ``flipped[id(line)]`` from end B, sampled at L - s."""
    from ._drag_fast import DIPS, SETTLED, drag_cases
    from ._drag_inner import SEABED_COLUMNS

    N = len(problems)
    P = len(layouts[0].ell)
    n = problems[0].n_nodes
    M = len(problems[0].medium.current_z)
    ell, EA, weight = np.empty((N, P)), np.empty((N, P)), np.empty((N, P))
    diam, cn, ct = np.empty((N, P)), np.empty((N, P)), np.empty((N, P))
    point, bounds = np.empty((N, P + 1, 3)), np.empty((N, P + 1))
    rho, pz, pv = np.empty(N), np.empty((N, M)), np.empty((N, M, 3))
    kind = np.empty(N, dtype=np.int64)
    rA, rB, force, zB = np.zeros((N, 3)), np.zeros((N, 3)), np.zeros((N, 3)), np.zeros(N)
    tol, maxit = np.empty(N), np.empty(N, dtype=np.int64)
    s = np.empty((N, n))
    s_eval = np.empty((N, n))
    mode, seabed = np.zeros(N, dtype=np.int64), np.zeros((N, SEABED_COLUMNS))
    planes = [seabed_of(p.medium) for p in problems]
    rev = np.array([r for r, _ in sides])
    # the general solver's np.linspace(0, L, n) (and L - s from B), bit for bit; once
    # per line object
    samples: dict[int, tuple[np.ndarray, np.ndarray]] = {}
    rows: dict[Plane, list[float]] = {}  # a seabed's row, once per plane
    for i, (prob, lay) in enumerate(zip(problems, layouts, strict=True)):
        med = prob.medium
        line = flipped[id(prob.line)] if rev[i] else prob.line
        seg = lay.segment
        ell[i], EA[i], weight[i], point[i], bounds[i] = (
            lay.ell,
            lay.EA,
            lay.weight,
            lay.point,
            lay.bounds,
        )
        diam[i], cn[i], ct[i] = line.diameter[seg], line.drag_normal[seg], line.drag_tangential[seg]
        rho[i], pz[i], pv[i] = med.density, med.current_z, med.current_velocity
        a, b = (prob.end_b, prob.end_a) if rev[i] else (prob.end_a, prob.end_b)
        rA[i] = a.position
        kind[i] = {"fixed": 0, "mooring": 1, "force": 2}[b.kind]
        if b.kind == "fixed":
            rB[i] = b.position
        else:
            force[i] = b.force
            if b.kind == "mooring":
                force[i, 2] = 0.0
                zB[i] = float(b.z)
        tol[i], maxit[i] = prob.tolerance, prob.max_iterations
        plane = planes[i]
        if plane is not None:  # normal, depth, basis (3, 2) by rows, friction, flat
            mode[i] = 2 if sides[i][1] else 1
            if plane not in rows:
                rows[plane] = [
                    *plane.normal, plane.depth, *np.stack(plane.basis, axis=1).ravel(),
                    plane.friction, plane.slope == 0.0,
                ]  # fmt: skip
            seabed[i] = rows[plane]
        if id(prob.line) not in samples:
            L = prob.line.total_length
            at = np.linspace(0.0, L, n)
            samples[id(prob.line)] = (at, L - at)
        s[i] = samples[id(prob.line)][0]
        s_eval[i] = samples[id(prob.line)][1] if rev[i] else s[i]
    pos, tension = np.empty((N, n, 3)), np.empty((N, n))
    TA, TL, loads = np.empty((N, 3)), np.empty((N, 3)), np.empty((N, P, 3))
    counts, resid = np.zeros((N, 2), dtype=np.int64), np.zeros(N)
    status = np.zeros(N, dtype=np.int64)
    laid = np.zeros(N)
    drag_cases(
        ell, EA, weight, point, bounds, diam, cn, ct, rho, pz, pv, kind, rA, rB, force, zB,
        tol, maxit, MAX_DRAG_ITERATIONS, np.array([1, *CONTINUATION], dtype=np.int64), mode,
        seabed, s_eval,
        pos, tension, TA, TL, loads, counts, resid, status, laid,
    )  # fmt: skip
    out: list[StaticResult | None] = []
    for i, lay in enumerate(layouts):
        plane = planes[i]
        if status[i] == SETTLED and mode[i] == 1 and not np.all(plane.height_above(pos[i]) >= 0.0):
            status[i] = DIPS  # a node below the seabed: the general solver's to say
        if status[i] != SETTLED:
            if status[i] == DIPS or status[i] in ANCHORED_REASONS:
                left[i] = ANCHORED_REASONS.get(int(status[i]), ON_SEABED)
            out.append(None)
            continue
        # the forces on the end attachments, of the line as solved (from B if reversed)
        fa, fb = TA[i], -TL[i]
        res = StaticResult(
            s=s[i],
            position=pos[i],
            tension=tension[i],
            force_a=fb if rev[i] else fa,
            force_b=fa if rev[i] else fb,
            status=STATUS_OK,
            laid_length=float(laid[i]),
            iterations=int(counts[i, 0]),
            residual=float(resid[i]),
            state=CatenaryState(layout=lay, q=loads[i], reversed=bool(rev[i])),
        ).check_finite()
        res.drag_iterations = int(counts[i, 1])
        out.append(res if res.status == STATUS_OK else None)
    return out
