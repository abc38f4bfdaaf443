"""A line in a current over a seabed in the compiled drag iteration
(:mod:`cablestudy.statics.batch_drag`): the general solver hangs it free, exactly as
without a seabed, until a shape of its drag iteration reaches the seabed. The kernel
runs the same iteration, tests each shape against the seabed, and hands a case on as
soon as one reaches it. Its answers equal the general solver's to round-off and the
no-seabed kernel's bit for bit; the cases it hands on are the general solver's, counted
with the reason; a wrong answer over a seabed is rejected."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from cablestudy.statics import Medium, StaticProblem
from cablestudy.statics.base import STATUS_NOT_VERIFIED
from cablestudy.statics.batch import solve_batch
from cablestudy.statics.batch_drag import ON_SEABED, drag_eligible, drag_many
from cablestudy.statics.semi_analytic import SemiAnalyticSolver
from cablestudy.statics.verify_drag import verified_many
from tests.statics_helpers import fixed
from tests.unit.test_statics_batch_drag import problems

#: a seabed far below every line, and one that the slack lines' sag reaches (the
#: lowest of these lines hang to about -230 m; their ends are at -50 and -200 m)
DEPTHS = (400.0, 215.0)


def over(depth: float) -> list[StaticProblem]:
    """:func:`problems` over a seabed at ``depth`` (friction 0.3)."""
    out = []
    for p in problems():
        m = p.medium
        sea = Medium(
            density=m.density, gravity=m.gravity, depth=depth, friction=0.3,
            current_z=m.current_z, current_velocity=m.current_velocity,
        )  # fmt: skip
        out.append(replace(p, medium=sea))
    return out


def test_over_a_seabed_the_kernel_runs_the_general_drag_loop_step_for_step() -> None:
    """Every case over a seabed takes the kernel; those it settles have the general
    solver's Newton and drag iteration counts and its numbers to round-off (1e-12 of the
    scale, as in the free-hanging tests: the same closed forms in another order), and the
    general solver lays none of them. Over the deep seabed the kernel settles all; over
    the shallow one it hands on some, with :data:`ON_SEABED` (a shape of their iteration
    reached the seabed; the converged line may or may not rest on it)."""
    solver = SemiAnalyticSolver()
    for depth in DEPTHS:
        probs = over(depth)
        assert all(drag_eligible(p) for p in probs)
        why: dict[int, str] = {}
        got = drag_many(probs, why=why)
        settled = [i for i, g in enumerate(got) if g is not None]
        if depth == DEPTHS[0]:
            assert len(settled) == len(probs)
        else:
            assert 0 < len(settled) < len(probs)
            assert set(why) == set(range(len(probs))) - set(settled)
            assert set(why.values()) == {ON_SEABED}
        for p, g in zip(probs, got, strict=True):
            ref = solver.solve(p, compiled=False)
            if g is None:  # a shape reached the seabed: the general solver's case
                continue
            assert ref.status == 0 and ref.laid_length == 0.0
            assert (g.iterations, g.drag_iterations) == (ref.iterations, ref.drag_iterations)
            F = float(np.max(ref.tension))
            assert np.max(np.abs(g.position - ref.position)) <= 1e-12 * p.line.total_length
            assert np.max(np.abs(g.tension - ref.tension)) <= 1e-12 * F
            assert np.max(np.abs(g.force_a - ref.force_a)) <= 1e-12 * F
            assert np.max(np.abs(g.force_b - ref.force_b)) <= 1e-12 * F


def test_a_seabed_the_line_does_not_reach_changes_nothing() -> None:
    """The kernel's iteration does not depend on a seabed no shape reaches: its answers
    over the seabed are the no-seabed answers bit for bit."""
    free = drag_many(problems())
    for depth in DEPTHS:
        for a, b in zip(free, drag_many(over(depth)), strict=True):
            if b is None:
                continue
            for name in ("position", "tension", "force_a", "force_b"):
                assert np.array_equal(getattr(a, name), getattr(b, name)), name
            assert (a.iterations, a.drag_iterations) == (b.iterations, b.drag_iterations)


def test_a_line_that_reaches_the_seabed_is_the_general_solvers_with_the_reason() -> None:
    """``solve_batch`` gives each case the kernel hands on the general solver's verified
    answer, its ``fallback`` saying why: the solution touches the seabed. A line anchored
    on the seabed in a current is the kernel's too (resting on it from the anchor,
    :mod:`cablestudy.statics._drag_inner`), settled there with no fallback."""
    probs = over(DEPTHS[1])
    handed = [i for i, g in enumerate(drag_many(probs)) if g is None]
    anchored = replace(probs[0], end_b=fixed(150.0, 0.0, -DEPTHS[1]))
    assert drag_eligible(anchored)
    general: list[int] = []
    out = solve_batch([*probs, anchored], general=general)
    assert general == handed and not out[-1].fallback
    solver = SemiAnalyticSolver()
    for i in handed:  # the general solver's answer (for a towed or moored line resting
        # on the seabed between its ends: status 4, a contact it does not model)
        ref = solver.solve(probs[i], compiled=False)
        assert out[i].fallback == ON_SEABED
        assert (out[i].status, out[i].message) == (ref.status, ref.message)
        if ref.status == 0:
            assert np.array_equal(out[i].position, ref.position)
    assert out[-1].status == 0 and out[-1].laid_length > 0.0


def test_a_wrong_answer_over_a_seabed_is_rejected() -> None:
    """The kernel's answers over a seabed are verified; one with a node's tension off by
    5e-2 of the largest is not (the allowance is set by the drag's quadrature estimate on
    15 m intervals: from 1e-6 of the tension at 0.1 m/s to 5.5e-3 at 1.5 m/s), and
    one with a node moved 1e-3 L into the seabed (which check_one then checks with the
    seabed's reaction) is not either."""
    probs = over(DEPTHS[0])
    res = drag_many(probs, verify=False)
    assert all(r.status == 0 for r in verified_many(probs, res))
    bad_t, bad_z = [], []
    for p, r in zip(probs, res, strict=True):
        t = r.tension.copy()
        t[3] += 5e-2 * float(np.max(t))  # not at the clump (its tension is either side's)
        bad_t.append(replace(r, tension=t))
        pos = r.position.copy()
        pos[3, 2] = -DEPTHS[0] - 1e-3 * p.line.total_length
        bad_z.append(replace(r, position=pos))
    for bad in (bad_t, bad_z):
        assert all(r.status == STATUS_NOT_VERIFIED for r in verified_many(probs, bad))
