"""Statics of a catenary line over up to two fixed pulleys (aqwa seed 5.8.1.1, issue 12).

A line A -> P1 (-> P2) -> B passing over fixed pulleys is a chain of sub-lines, each a
catenary between fixed points (A, the pulleys, B: both line ends must be fixed), whose
unstretched lengths L_1 + ... + L_{m+1} = L. The split S_k = L_1 + ... + L_k [m] (arc
length from A at pulley k) is the unknown, one scalar per pulley; the segments and
attachments of the line are cut where the split falls, so a composite line keeps its
make-up along s.

Frictionless equilibrium: the line slides until the tension magnitude is continuous
over each pulley, |F_B of sub-line k| = |F_A of sub-line k + 1| (a frictionless sheave
turns the tension's direction, not its magnitude). Each sub-line is solved by the
study's static method as a fixed-fixed line; the m equations in the m split values are
solved by Newton with a forward-difference Jacobian, steps kept inside the ordered
interval 0 < S_1 < S_2 < L and halved until the mismatch falls. Where Newton stalls
(after 12 iterations, or a step no halving improves: a sub-line turning taut or lifting
off within a step of the split, as a mooring over a fairlead pulley does), the split is
bracketed instead: Illinois regula falsi on the mismatch of one pulley, nested (the
second pulley's split solved for each trial of the first's) for two, a split where a
sub-line has no solution shortening the step towards the bound. For one pulley the
mismatch T_end(sub 1) - T_start(sub 2) falls monotonically as S_1 grows (the first
sub-line slackens, the second tightens), so the root is unique; Newton is started from
the split proportional to the chords (equal straight-line strain).

With friction (``friction_factor`` f > 1) the seed's law lets the larger tension over
the smaller reach f^(wrap / 180 deg) before the line slides, so every split whose
tension ratio is within that bound is an equilibrium and the static state depends on
the history that led to it. The statics report the frictionless equilibrium (ratio 1,
within every bound), as the statics of a spring line over pulleys do: the state of a
line tensioned while sliding over its pulleys. The friction acts in the dynamics.

Outputs as any line: positions and tension on the whole line's ``s`` (each sub-line is
solved at 8 times the output density, and at least 8 points per smooth piece between
its joints and loads, and interpolated by a cubic spline in s within each piece: its
error is of order h^4 times the fourth derivative of the shape, h the sub-line's point
spacing, far below the solver tolerance for lines whose curvature radius exceeds a few
output spacings; a point on a load takes the tension after it, as the solvers do), end forces
of the first and last sub-lines, ``laid_length`` the sum of the sub-lines', and
``pulley_force`` [N] (m, 3), the force of the line on each pulley:
F_B(sub k) + F_A(sub k + 1).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np
from scipy.interpolate import CubicSpline

from .base import (
    SEGMENT_ARRAYS,
    STATUS_NO_SOLUTION,
    STATUS_NOT_CONVERGED,
    STATUS_OK,
    STATUS_TIME_LIMIT,
    EndCondition,
    LineModel,
    StaticProblem,
    StaticResult,
    StaticSolver,
)

#: output points of a sub-line per output point of the whole line (cubic spline in s)
OVERSAMPLE = 8


def cut_line(line: LineModel, s0: float, s1: float) -> LineModel:
    """The part of ``line`` between unstretched arc lengths ``s0`` < ``s1`` [m] from A:
    its segments clipped to [s0, s1] (empty pieces dropped) and the attachments with
    s0 <= s < s1 (s <= s1 for the part that ends at the line's end), measured from s0."""
    ends = line.segment_ends
    lo = np.maximum(ends[:-1], s0)
    hi = np.minimum(ends[1:], s1)
    keep = np.nonzero(hi - lo > 1e-12 * max(line.total_length, 1.0))[0]
    if len(keep) == 0:
        keep = np.array([int(np.clip(np.searchsorted(ends, s0, side="right") - 1, 0, len(lo) - 1))])
        lengths = np.array([s1 - s0])
    else:
        lengths = hi[keep] - lo[keep]
        lengths[-1] += (s1 - s0) - float(np.sum(lengths))  # exact total
    last = s1 >= line.total_length
    s_att = np.asarray(line.attachment_s, dtype=float)
    on = (s_att >= s0) & ((s_att <= s1) if last else (s_att < s1))
    return LineModel(
        length=lengths,
        **{name: np.asarray(getattr(line, name))[keep].copy() for name in SEGMENT_ARRAYS},
        attachment_s=s_att[on] - s0,
        attachment_force=np.asarray(line.attachment_force, dtype=float).reshape(-1, 3)[on],
        attachment_mass=np.asarray(line.attachment_mass, dtype=float)[on],
        attachment_volume=np.asarray(line.attachment_volume, dtype=float)[on],
        axial_law=tuple(line.axial_law[i] for i in keep) if line.axial_law else (),
    )


def chord_split(problem: StaticProblem, pulleys: np.ndarray) -> np.ndarray:
    """Split points S_k [m] proportional to the chords A -> P1 (-> P2) -> B: the split
    of a straight line of uniform strain, the Newton start."""
    P = _points(problem, pulleys)
    d = np.linalg.norm(np.diff(P, axis=0), axis=1)
    return problem.line.total_length * np.cumsum(d)[:-1] / float(np.sum(d))


def sub_problems(
    problem: StaticProblem, pulleys: np.ndarray, split: np.ndarray
) -> list[StaticProblem]:
    """The fixed-fixed sub-problems of the line cut at ``split`` [m] (3 nodes each: a
    caller that solves them sets its own)."""
    P = _points(problem, pulleys)
    S = np.concatenate(([0.0], split, [problem.line.total_length]))
    return [
        replace(
            problem,
            line=cut_line(problem.line, float(S[k]), float(S[k + 1])),
            end_a=EndCondition(kind="fixed", position=P[k].copy()),
            end_b=EndCondition(kind="fixed", position=P[k + 1].copy()),
            n_nodes=3,
        )
        for k in range(len(S) - 1)
    ]


def _points(problem: StaticProblem, pulleys: np.ndarray) -> np.ndarray:
    assert problem.end_a.position is not None and problem.end_b.position is not None
    return np.vstack(
        (
            np.asarray(problem.end_a.position, dtype=float),
            np.asarray(pulleys, dtype=float).reshape(-1, 3),
            np.asarray(problem.end_b.position, dtype=float),
        )
    )


class _SubFailed(Exception):
    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status


def solve_over_pulleys(
    problem: StaticProblem,
    pulleys: np.ndarray,
    solver: StaticSolver,
    *,
    deadline: float | None = None,
) -> StaticResult:
    """Frictionless static equilibrium of ``problem``'s line over fixed ``pulleys`` [m]
    (m, 3), m = 1 or 2, both ends fixed, each sub-line solved by ``solver`` (see the
    module docstring). ``residual`` is the largest tension mismatch over a pulley
    divided by the largest end tension; ``iterations`` the Newton steps on the split."""
    L = problem.line.total_length
    s_out = np.linspace(0.0, L, problem.n_nodes)
    m = len(pulleys)
    if problem.end_a.kind != "fixed" or problem.end_b.kind != "fixed":
        return StaticResult.failed(
            s_out, STATUS_NO_SOLUTION, "a line over pulleys needs both ends fixed"
        )
    sub_tol = max(problem.tolerance * 1e-2, 1e-13)
    tol = max(problem.tolerance, 1e-12)

    def solve(split: np.ndarray, n: int | list[int] = 3) -> list[StaticResult]:
        if deadline is not None and time.monotonic() > deadline:
            raise _SubFailed(STATUS_TIME_LIMIT, "time limit reached while splitting the line")
        out = []
        subs = sub_problems(problem, pulleys, split)
        for k, sub in enumerate(subs):
            nk = n[k] if isinstance(n, list) else n
            r = solver.solve(
                replace(sub, n_nodes=nk, tolerance=sub_tol), deadline=deadline
            ).check_finite()
            if r.status != STATUS_OK:
                raise _SubFailed(r.status, f"sub-line {k + 1} of {len(subs)}: {r.message}")
            out.append(r)
        return out

    def mismatch(res: list[StaticResult]) -> np.ndarray:
        """Tension arriving minus tension leaving each pulley, over the largest."""
        Tb = np.array([np.linalg.norm(r.force_b) for r in res[:-1]])
        Ta = np.array([np.linalg.norm(r.force_a) for r in res[1:]])
        return (Tb - Ta) / max(float(np.max(Ta)), float(np.max(Tb)), 1e-300)

    def inside(split: np.ndarray) -> bool:
        S = np.concatenate(([0.0], split, [L]))
        return bool(np.all(np.diff(S) > 1e-9 * L))

    def attempt(S: np.ndarray) -> tuple[list[StaticResult], np.ndarray] | None:
        """The sub-lines and their mismatch at split S; None where a sub-line has no
        solution (a split outside the feasible range: the time limit still stops)."""
        try:
            res = solve(S)
        except _SubFailed as exc:
            if exc.status == STATUS_TIME_LIMIT:
                raise
            return None
        return res, mismatch(res)

    split = chord_split(problem, pulleys)
    its = 0
    try:
        res = solve(split)
        r = mismatch(res)
        stalled = False
        while np.max(np.abs(r)) > tol and not stalled:
            if its >= NEWTON_ITERATIONS:
                stalled = True
                break
            its += 1
            # forward differences: a step well above the sub-solvers' noise (sub_tol of
            # the tension) and small against the split
            J = np.empty((m, m))
            gaps = np.diff(np.concatenate(([0.0], split, [L])))
            for j in range(m):
                h = min(1e-6 * L, 0.25 * float(np.min(gaps)))
                trial = split.copy()
                trial[j] += h
                if not inside(trial):
                    trial[j] -= 2.0 * h
                    h = -h
                got = attempt(trial)
                if got is None:
                    stalled = True
                    break
                J[:, j] = (got[1] - r) / h
            if stalled:
                break
            try:
                step = np.linalg.solve(J, -r)
            except np.linalg.LinAlgError:
                stalled = True
                break
            lam = 1.0
            for _ in range(20):
                trial = split + lam * step
                got = attempt(trial) if inside(trial) else None
                if got is not None and np.max(np.abs(got[1])) < np.max(np.abs(r)):
                    split, (res, r) = trial, got
                    break
                lam *= 0.5
            else:
                stalled = True
        if stalled:
            # Newton stalls where a sub-line turns taut or lifts off within a step of
            # the split: bracket each pulley's root instead (the mismatch falls as the
            # split moves away from A: the sub-line before the pulley slackens, the one
            # after tightens), with the sub-lines' feasible range found on the way
            split, res, r, n_eval = _bracketed(attempt, split, L, m, tol)
            its += n_eval
        # the converged split, sampled densely for the output points
        S = np.concatenate(([0.0], split, [L]))
        subs = sub_problems(problem, pulleys, split)
        density = (problem.n_nodes - 1) / L
        res = solve(split, [dense_nodes(sub.line, density) for sub in subs])
    except _SubFailed as exc:
        return StaticResult.failed(s_out, exc.status, f"line over pulleys: {exc}", iterations=its)
    return _assemble(s_out, S, res, its, float(np.max(np.abs(r))), subs)


#: Newton iterations on the split before the bracketed fallback takes over
NEWTON_ITERATIONS = 12


def _bracketed(
    attempt: Callable[[np.ndarray], tuple[list[StaticResult], np.ndarray] | None],
    split: np.ndarray,
    L: float,
    m: int,
    tol: float,
) -> tuple[np.ndarray, list[StaticResult], np.ndarray, int]:
    """The split by bracketing: one pulley, Illinois regula falsi on its mismatch; two,
    the same on the first pulley's mismatch with the second's solved for each trial
    (nested). Returns (split, sub-line results, mismatch, evaluations)."""
    count = [0]

    def at(S: np.ndarray) -> tuple[list[StaticResult], np.ndarray] | None:
        count[0] += 1
        return attempt(S)

    if m == 1:

        def f1(x: float) -> tuple[float, tuple] | None:
            got = at(np.array([x]))
            return None if got is None else (float(got[1][0]), got)

        got0 = f1(float(split[0]))
        if got0 is None:
            raise _SubFailed(STATUS_NOT_CONVERGED, "no sub-line solution at the first split")
        x, _, payload = _root_1d(f1, float(split[0]), got0, 0.0, L, tol, L)
        return np.array([x]), payload[0], payload[1], count[0]

    inner_guess = [float(split[1])]

    def f_outer(x: float) -> tuple[float, tuple] | None:
        def f_inner(y: float) -> tuple[float, tuple] | None:
            got = at(np.array([x, y]))
            return None if got is None else (float(got[1][1]), got)

        y0 = min(max(inner_guess[0], x + 1e-6 * L), L - 1e-6 * L)
        first = f_inner(y0)
        if first is None:
            return None
        try:
            y, _, payload = _root_1d(f_inner, y0, first, x, L, tol, L)
        except _SubFailed as exc:
            if exc.status == STATUS_TIME_LIMIT:
                raise
            return None
        inner_guess[0] = y
        return float(payload[1][0]), payload

    got0 = f_outer(float(split[0]))
    if got0 is None:
        raise _SubFailed(STATUS_NOT_CONVERGED, "no sub-line solution at the first split")
    _, _, payload = _root_1d(f_outer, float(split[0]), got0, 0.0, L, tol, L)
    res, r = payload
    # the split [m]: the sub-lines' cumulative unstretched lengths
    return np.cumsum([float(r.s[-1]) for r in res])[:-1], res, r, count[0]


def _root_1d(
    f: Callable[[float], tuple[float, Any] | None],
    x0: float,
    first: tuple[float, Any],
    lo: float,
    hi: float,
    tol: float,
    scale: float,
) -> tuple[float, float, Any]:
    """Root of a decreasing function on (lo, hi) from ``x0`` (``first`` = f(x0)), f
    returning (value, payload) or None where undefined (outside the feasible range,
    taken to be an interval): a bracket by halving the distance to the bound on the
    side of the root (and the step where f is undefined), then Illinois regula falsi
    until |f| <= ``tol`` or the bracket is a few ulps of ``scale`` wide (the mismatch is
    then as small as the arithmetic allows). Returns (x, f(x), payload)."""
    x, (fx, px) = x0, first
    if abs(fx) <= tol:
        return x, fx, px
    bracket = None
    for _ in range(200):
        bound = hi if fx > 0.0 else lo
        step = 0.5 * (bound - x)
        got = None
        while abs(step) > 4.0 * np.finfo(float).eps * scale:
            got = f(x + step)
            if got is not None:
                break
            step *= 0.5
        if got is None:
            break
        y, (fy, py) = x + step, got
        if abs(fy) <= tol:
            return y, fy, py
        if (fy > 0.0) != (fx > 0.0):
            bracket = ((x, fx, px), (y, fy, py))
            break
        x, fx, px = y, fy, py
    if bracket is None:
        raise _SubFailed(
            STATUS_NOT_CONVERGED,
            f"no split brackets an equal tension over the pulley (last mismatch {fx:.3g} "
            "of the tension): the line cannot pass over the pulleys as given",
        )
    (a, fa, pa), (b, fb, pb) = sorted(bracket, key=lambda item: item[0])
    side = 0
    for _ in range(200):
        if b - a <= 8.0 * np.finfo(float).eps * scale:
            break
        c = b - fb * (b - a) / (fb - fa)
        if not a < c < b:
            c = 0.5 * (a + b)
        got = f(c)
        if got is None:
            c = 0.5 * (a + b)
            got = f(c)
            if got is None:
                raise _SubFailed(
                    STATUS_NOT_CONVERGED,
                    "a sub-line has no solution inside the bracket of the split",
                )
        fc, pc = got
        if abs(fc) <= tol:
            return c, fc, pc
        if fc > 0.0:  # the root lies above c (f decreasing)
            a, fa, pa = c, fc, pc
            if side == -1:
                fb *= 0.5  # Illinois: the end that stays loses half its weight
            side = -1
        else:
            b, fb, pb = c, fc, pc
            if side == 1:
                fa *= 0.5
            side = 1
    # the bracket has closed to the arithmetic's resolution
    return (a, fa, pa) if abs(fa) <= abs(fb) else (b, fb, pb)


def breakpoints(line: LineModel) -> np.ndarray:
    """Arc lengths [m] from the sub-line's start where its shape or tension may be
    non-smooth: its ends, the joints between segments and the attachments."""
    pts = np.concatenate((line.segment_ends, np.asarray(line.attachment_s, dtype=float)))
    return np.unique(np.clip(pts, 0.0, line.total_length))


def dense_nodes(line: LineModel, n_out: float) -> int:
    """Output points of a sub-line: ``OVERSAMPLE`` times the whole line's density
    ``n_out`` [1/m], and at least 8 in each smooth piece (capped at 100,001)."""
    pieces = np.diff(breakpoints(line))
    pieces = pieces[pieces > 0.0]
    L = line.total_length
    need = max(OVERSAMPLE * n_out * L, 8.0 * L / float(np.min(pieces)))
    return int(min(max(math.ceil(need) + 1, 5), 100_001))


def _piecewise(s: np.ndarray, values: np.ndarray, breaks: np.ndarray, at: np.ndarray) -> np.ndarray:
    """``values`` sampled at ``s`` (from 0 to the sub-line's length), interpolated at ``at``
    by a cubic spline within each smooth piece between ``breaks``: a point on a break
    belongs to the piece after it (as the solvers report a jump of tension at a load);
    each piece's spline uses the samples strictly inside it and the sub-line's own end
    samples (the side of a break a sample on it stands for is not known)."""
    out = np.empty((len(at),) + values.shape[1:])
    piece = np.clip(np.searchsorted(breaks, at, side="right") - 1, 0, len(breaks) - 2)
    end = s[-1]
    for p in np.unique(piece):
        lo, hi = breaks[p], breaks[p + 1]
        use = ((s > lo) & (s < hi)) | ((s == lo) & (lo == 0.0)) | ((s == hi) & (hi == end))
        on = piece == p
        if np.count_nonzero(use) >= 4:
            out[on] = CubicSpline(s[use], values[use], axis=0)(at[on])
        else:  # a piece shorter than the samples (the cap): linear between neighbours
            k = np.clip(np.searchsorted(s, at[on]), 1, len(s) - 1)
            w = ((at[on] - s[k - 1]) / (s[k] - s[k - 1])).reshape((-1,) + (1,) * (values.ndim - 1))
            out[on] = (1.0 - w) * values[k - 1] + w * values[k]
    return out


def _assemble(
    s_out: np.ndarray,
    S: np.ndarray,
    res: list[StaticResult],
    its: int,
    residual: float,
    subs: list[StaticProblem],
) -> StaticResult:
    """The whole line's result from its sub-lines' (piecewise cubic splines in s)."""
    pos = np.empty((len(s_out), 3))
    ten = np.empty(len(s_out))
    k_of = np.clip(np.searchsorted(S, s_out, side="right") - 1, 0, len(res) - 1)
    for k, r in enumerate(res):
        on = k_of == k
        if not np.any(on):
            continue
        local = np.clip(s_out[on] - S[k], 0.0, r.s[-1])
        breaks = breakpoints(subs[k].line)
        pos[on] = _piecewise(r.s, r.position, breaks, local)
        ten[on] = _piecewise(r.s, r.tension, breaks, local)
    out = StaticResult(
        s=s_out,
        position=pos,
        tension=ten,
        force_a=res[0].force_a.copy(),
        force_b=res[-1].force_b.copy(),
        laid_length=float(sum(r.laid_length for r in res)),
        iterations=its,
        residual=residual,
        drag_iterations=int(sum(r.drag_iterations for r in res)),
    )
    out.pulley_force = np.array(  # type: ignore[attr-defined]
        [res[k].force_b + res[k + 1].force_a for k in range(len(res) - 1)]
    )
    out.split = S[1:-1].copy()  # type: ignore[attr-defined]
    return out
