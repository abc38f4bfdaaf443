"""A line in a current whose end A is towed or moored (end B fixed) in the compiled drag
iteration (:mod:`cablestudy.statics.batch_drag`): it is solved as the general solver
solves it, the reversed line from B. The kernel runs the general solver's drag loop step
for step on it (same iteration counts, answers to round-off); swapping the ends of a
problem (and reversing its line) mirrors the answer to round-off; and a wrong answer for
such a line is rejected by the batched verification with the end named."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from cablestudy.statics import StaticProblem
from cablestudy.statics.base import STATUS_NOT_VERIFIED
from cablestudy.statics.batch_drag import drag_eligible, drag_many
from cablestudy.statics.semi_analytic import SemiAnalyticSolver
from cablestudy.statics.semi_analytic_shape import reversed_line
from cablestudy.statics.verify_drag import verified_many
from tests.unit.test_statics_batch_drag import problems


def reversed_problems() -> list[StaticProblem]:
    """The towed and moored lines of :func:`problems` described from the other end: end A
    the towed or moored end, end B fixed, the line (one segment, or two with a clump)
    reversed so that each is the same physical line."""
    out = []
    for p in problems():
        if p.end_b.kind == "fixed":
            continue
        out.append(replace(p, line=reversed_line(p.line), end_a=p.end_b, end_b=p.end_a))
    return out


def test_a_towed_or_moored_end_a_runs_the_general_drag_loop_step_for_step() -> None:
    """Every reversed case takes the kernel and settles with the general solver's Newton
    and drag iteration counts, its numbers equal to the general solver's to round-off.
    The kernel is handed the problem the general solver builds (the reversed line, ends
    swapped, samples at L - s): each iterate is the same closed form evaluated in another
    order, about 1e-15 relative per step, and the contracting fixed point keeps the
    difference within a few hundred ulps (1e-12 of the scale; measured 2e-16)."""
    probs = reversed_problems()
    assert len(probs) == 36 and all(drag_eligible(p) for p in probs)
    solver = SemiAnalyticSolver()
    for p, g in zip(probs, drag_many(probs), strict=True):
        ref = solver.solve(p, compiled=False)
        assert ref.status == 0 and g is not None and g.status == 0
        assert (g.iterations, g.drag_iterations) == (ref.iterations, ref.drag_iterations)
        F = float(np.max(ref.tension))
        L = p.line.total_length
        assert np.max(np.abs(g.position - ref.position)) <= 1e-12 * L
        assert np.max(np.abs(g.tension - ref.tension)) <= 1e-12 * F
        assert np.max(np.abs(g.force_a - ref.force_a)) <= 1e-12 * F
        assert np.max(np.abs(g.force_b - ref.force_b)) <= 1e-12 * F
        assert g.state.reversed and ref.state.reversed
        assert np.max(np.abs(g.state.q - ref.state.q)) <= 1e-12 * np.max(np.abs(ref.state.q))


def test_swapping_the_ends_mirrors_the_answer() -> None:
    """The same line written from either end: tensions along s and positions mirrored
    (read from the other end), the forces on the two end attachments swapped. The two
    problems reach the kernel as the same numbers except the sample points (L - s against
    s: one ulp of L) and, for the line with a clump, its arc length L - (L - s) (one ulp
    of L), which moves a drag element's boundary by that: the answers differ by round-off
    of the solve, bounded like the kernel against the general solver above (1e-12 of the
    scale)."""
    fwd = [p for p in problems() if p.end_b.kind != "fixed"]
    back = reversed_problems()
    got_f, got_b = drag_many(fwd), drag_many(back)
    for p, f, b in zip(fwd, got_f, got_b, strict=True):
        assert f is not None and b is not None
        F = float(np.max(f.tension))
        L = p.line.total_length
        assert np.max(np.abs(b.tension[::-1] - f.tension)) <= 1e-12 * F
        assert np.max(np.abs(b.position[::-1] - f.position)) <= 1e-12 * L
        assert np.max(np.abs(b.force_a - f.force_b)) <= 1e-12 * F
        assert np.max(np.abs(b.force_b - f.force_a)) <= 1e-12 * F


def test_a_wrong_answer_for_a_towed_end_a_is_rejected() -> None:
    """The batched verification checks a towed or moored end A as
    :func:`cablestudy.statics.verify.check_one` does: the kernel's answers pass, and an
    answer whose force on end A is off by 1e-3 of the tension (100 times the drag
    quadrature's allowance, about 1e-5 of it) is not verified, the end A check named;
    a moored end A put 1e-3 L off its height likewise."""
    probs = reversed_problems()
    res = drag_many(probs, verify=False)
    ok = verified_many(probs, res)
    assert all(r.status == 0 for r in ok)
    wrong = []
    for p, r in zip(probs, res, strict=True):
        F = float(np.max(r.tension))
        if p.end_a.kind == "force":
            wrong.append(replace(r, force_a=r.force_a + np.array([1e-3 * F, 0.0, 0.0])))
        else:
            pos = r.position.copy()
            pos[0, 2] += 1e-3 * p.line.total_length
            wrong.append(replace(r, position=pos))
    for p, r in zip(probs, verified_many(probs, wrong), strict=True):
        assert r.status == STATUS_NOT_VERIFIED
        name = "end A force" if p.end_a.kind == "force" else "end A height"
        assert name in r.message, r.message
