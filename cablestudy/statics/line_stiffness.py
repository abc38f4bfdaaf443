"""The end stiffness of one line between two points, for a system's Newton
(:mod:`.system`): ``K[i, j] = -d f_i / d r_j`` for ends i, j in (A, B), f the force of
the line on the end's attachment. Exact where the line's model gives it
(:func:`line_end_stiffness`: the cable solution's flexibility, the seabed-contact
Newton's Jacobian, the discrete model's condensed tangent), else by central
differences of the line's own solves (:func:`numeric_stiffness`). Pure: arrays in,
arrays out (SI units).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from .base import STATUS_NO_SOLUTION, STATUS_OK, EndCondition, StaticProblem, StaticResult
from .law_pieces import piece_increments
from .line_state import CatenaryState, DiscreteState, discrete_end_stiffness
from .seabed import seabed_of
from .semi_analytic_shape import _laid, _offsets, _suspended, make_layout, reversed_line
from .system_model import SystemFailure
from .system_pin import pinned_stiffness


def line_end_stiffness(problem: StaticProblem, result: StaticResult) -> np.ndarray:
    """Exact end stiffness of a solved line with both ends fixed, shape (2, 2, 3, 3):
    ``K[i, j]`` = -d f_i / d r_j for ends i, j in (A, B), f the force of the line on the
    end's attachment. NaN blocks where the line's model does not give them (the end
    of a line that lies on the seabed from that end). Raises :class:`SystemFailure` for
    shapes whose stiffness is not modelled (a line touching the seabed between two
    raised ends, or lying wholly on it).

    The catenary model's complementary energy is the potential of the end forces, so
    for a conservative line (no friction) K is symmetric."""
    assert problem.end_a.position is not None and problem.end_b.position is not None
    if isinstance(result.state, DiscreteState):  # method discrete: its condensed tangent
        return discrete_end_stiffness(result.state)
    line = problem.line
    L = line.total_length
    plane = seabed_of(problem.medium)
    ra, rb = problem.end_a.position, problem.end_b.position
    fa, fb = result.force_a, result.force_b
    reverse = False
    if plane is not None:
        ha, hb = float(plane.height_above(ra)), float(plane.height_above(rb))
        reverse = hb <= 1e-6 * L and ha > 1e-6 * L
    if reverse:
        line = reversed_line(line)
        fa, fb = fb, fa
    if isinstance(result.state, CatenaryState):
        # in a current: the solver's pieces and their converged loads, drag frozen
        assert result.state.reversed == reverse
        lay, q = result.state.layout, result.state.q
    else:
        lay = make_layout(line)
        q = lay.gravity
    K = np.full((2, 2, 3, 3), np.nan)
    if result.laid_length > 0.0:
        assert plane is not None
        grounded_end = rb if reverse else ra
        if float(plane.height_above(grounded_end)) > 1e-6 * L:
            raise SystemFailure(
                STATUS_NO_SOLUTION,
                "the line touches the seabed between two raised ends; method catenary "
                "models its end stiffness for a line lying on the seabed from an anchored "
                "end only (analysis.static.method: discrete models it)",
            )
        s_td = float(result.laid_length)
        if s_td >= L * (1.0 - 1e-9):
            raise SystemFailure(
                STATUS_NO_SOLUTION,
                "the line lies wholly on the seabed: method catenary gives no end stiffness "
                "(analysis.static.method: discrete models it)",
            )
        # a TDP resting at a clump (.contact_pin's pinned state): its own derivative
        pinned = pinned_stiffness(lay, q, plane, s_td, np.asarray(fb, dtype=float))
        if pinned is not None:
            K[1, 1] = pinned
            return K[::-1, ::-1].copy() if reverse else K
        _, ell, EA, qs, C, k_td, Cend = _suspended(lay, q, s_td)
        T_td = -np.asarray(fb, dtype=float) + Cend
        e1, e2 = plane.basis
        basis = np.stack((e1, e2), axis=1)
        tn = float(np.linalg.norm(T_td))
        e = T_td / tn
        laid = _laid(lay, s_td, T_td, plane)
        laws = None if lay.law is None else lay.law[k_td:]
        _, jac, _ = piece_increments(T_td - C, qs, ell, EA, laws)
        assert jac is not None
        Js = jac.sum(axis=0)
        dlaid = (
            laid.stretched * (np.eye(3) - np.outer(e, e)) / tn + np.outer(e, e) * laid.positive_flex
        )
        M = np.column_stack(
            ((Js + dlaid) @ basis, Js @ qs[0] - e * laid.rate_td * laid.positive_flex)
        )
        N = np.column_stack((basis, qs[0]))  # d T(L) / d (alpha, beta, s_td)
        # f_b = -T(L): K_bb = -d f_b / d r_B = N M^-1
        K[1, 1] = np.linalg.solve(M.T, N.T).T
    else:
        C, _ = _offsets(lay, q)
        TA = np.asarray(fa, dtype=float)
        _, jac, _ = piece_increments(TA - C, q, lay.ell, lay.EA, lay.law)
        assert jac is not None
        G = np.linalg.inv(jac.sum(axis=0))
        K[0, 0] = K[1, 1] = G
        K[0, 1] = K[1, 0] = -G
    if reverse:
        K = K[::-1, ::-1].copy()
    return K


def laid_stiffness(chord: np.ndarray, tension: float, flex: float) -> np.ndarray:
    """End stiffness (2, 2, 3, 3) of a line lying straight on the seabed from end A to
    end B (``chord`` = r_B - r_A [m]), ``tension`` [N] at its pulled end and ``flex`` =
    d|chord|/dT [m/N] (:func:`.semi_analytic_shape.laid_pulled`): a bar, K_BB = e e^T /
    flex + T / |chord| (I - e e^T) (its stretch along it, its tension turning across),
    K_AA = K_BB = -K_AB = -K_BA."""
    length = float(np.linalg.norm(chord))
    e = chord / length
    G = np.outer(e, e) / flex + tension / length * (np.eye(3) - np.outer(e, e))
    return np.array([[G, -G], [-G, G]])


def numeric_stiffness(
    name: str, prob: StaticProblem, res: StaticResult, solve_all: Any, moving: list[bool]
) -> np.ndarray:
    """End stiffness (2, 2, 3, 3) of a solved line by central differences of its end
    forces, each moving end stepped by 1e-4 of the line's length along x, y and z;
    one-sided (forward) where the backward step would go below the seabed, as lifting
    an end that rests on it (a body's point keeps that column; a free point resting
    there drops it: its motion across the seabed is held). The differences' error: the
    solves' tolerance (1e-9 of the tension) over the step and the step squared over the
    catenary's length scale, both near 1e-5 of the stiffness: enough for the Newton,
    whose residual is the lines' exact forces."""
    L = prob.line.total_length
    h = 1e-4 * L
    plane = seabed_of(prob.medium)
    ends = [np.asarray(prob.end_a.position, float), np.asarray(prob.end_b.position, float)]
    base = np.stack((res.force_a, res.force_b))
    K = np.zeros((2, 2, 3, 3))
    for j in range(2):
        if not moving[j]:
            continue
        for d in np.eye(3):
            steps = [h, -h]
            if plane is not None and float(plane.height_above(ends[j] - h * d)) < 0.0:
                steps = [h]
            probs = []
            for sgn in steps:
                moved = EndCondition(kind="fixed", position=ends[j] + sgn * d)
                probs.append(replace(prob, end_a=moved) if j == 0 else replace(prob, end_b=moved))
            out = [r.check_finite() for r in solve_all(probs)]
            if any(r.status != STATUS_OK for r in out):
                raise SystemFailure(
                    STATUS_NO_SOLUTION,
                    f"line {name}: its end stiffness could not be differenced (a solve "
                    f"{h:.3g} m from the end failed: {next(r.message for r in out if r.status)})",
                )
            plus = np.stack((out[0].force_a, out[0].force_b))
            minus = np.stack((out[1].force_a, out[1].force_b)) if len(out) == 2 else base
            dF = (plus - minus) / (h * len(out))
            for i in range(2):
                K[i, j] -= np.outer(dF[i], d)
    return K
