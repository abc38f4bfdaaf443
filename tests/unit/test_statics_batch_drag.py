"""The compiled drag iteration (:mod:`cablestudy.statics.batch_drag`): lines hanging free
in a current, solved together, each case with its own iteration. It runs the general
solver's drag loop step for step (the same Newton and drag iteration counts, answers to
round-off), a case's numbers do not depend on the batch it is in (bit for bit), the
converged loads balance the end forces, and the cases it does not take are left to the
general solver."""

from __future__ import annotations

import numpy as np

from cablestudy.statics import EndCondition, Medium, StaticProblem
from cablestudy.statics.batch import solve_batch
from cablestudy.statics.batch_drag import drag_eligible, drag_many
from cablestudy.statics.semi_analytic import SemiAnalyticSolver
from tests.statics_helpers import fixed, make_line


def _current(*rows: tuple[float, float, float]) -> tuple[np.ndarray, np.ndarray]:
    """(z, velocity) of a profile given as (z, speed, heading in degrees) rows."""
    z = np.array([r[0] for r in rows])
    h = np.radians([r[2] for r in rows])
    v = np.array([[r[1] * np.cos(a), r[1] * np.sin(a), 0.0] for r, a in zip(rows, h, strict=True)])
    order = np.argsort(z)
    return z[order], v[order]


def problems() -> list[StaticProblem]:
    """Lines a user sweeps: a wire between fixed ends in uniform, sheared and turning
    currents, two segments with a clump, a towed cable and a moored line, at speeds from
    0.1 to 1.5 m/s."""
    out = []
    profiles = [
        _current((0.0, 1.0, 60.0)),
        _current((0.0, 1.0, 0.0), (-250.0, 0.2, 90.0)),
        _current((0.0, 1.0, 90.0), (-100.0, 0.6, 0.0), (-300.0, 0.1, -45.0)),
    ]
    wire = make_line([300.0], [80.0], [2e8], diameter=0.05)
    two = make_line(
        [120.0, 180.0], [40.0, 120.0], [1e8, 3e8], diameter=[0.03, 0.06],
        attachments=[(150.0, (0.0, 0.0, -2000.0))],
    )  # fmt: skip
    for speed in (0.1, 0.6, 1.5):
        for k, (z, v) in enumerate(profiles):
            water = Medium(density=1025.0, gravity=9.80665, current_z=z, current_velocity=speed * v)
            for line in (wire, two):
                for b in (
                    fixed(220.0, 20.0, -200.0),
                    EndCondition(kind="mooring", force=np.array([2e4, 5e3, 0.0]), z=-180.0),
                    EndCondition(kind="force", force=np.array([3e4, 0.0, -1e4])),
                ):
                    out.append(
                        StaticProblem(
                            line=line,
                            medium=water,
                            end_a=fixed(0.0, 0.0, -50.0),
                            end_b=b,
                            n_nodes=21 + 10 * k,
                            tolerance=1e-9,
                        )
                    )
    return out


def test_the_kernel_runs_the_general_drag_loop_step_for_step() -> None:
    """Every case settles with the general solver's Newton and drag iteration counts, and
    its numbers agree with the general solver's to round-off: each iterate is the same
    closed form evaluated in another order (and 3 x 3 solves by elimination, not LAPACK),
    about 1e-15 relative per step; the fixed point contracts, so the differences do not
    grow over the iterations beyond a few hundred ulps (1e-12 of the scale)."""
    probs = problems()
    assert all(drag_eligible(p) for p in probs)
    got = drag_many(probs)
    solver = SemiAnalyticSolver()
    for p, g in zip(probs, got, strict=True):
        ref = solver.solve(p, compiled=False)
        assert ref.status == 0 and g is not None and g.status == 0
        assert (g.iterations, g.drag_iterations) == (ref.iterations, ref.drag_iterations)
        F = float(np.max(ref.tension))
        L = p.line.total_length
        assert np.max(np.abs(g.position - ref.position)) <= 1e-12 * L
        assert np.max(np.abs(g.tension - ref.tension)) <= 1e-12 * F
        assert np.max(np.abs(g.force_a - ref.force_a)) <= 1e-12 * F
        assert np.max(np.abs(g.force_b - ref.force_b)) <= 1e-12 * F
        assert np.max(np.abs(g.state.q - ref.state.q)) <= 1e-12 * np.max(np.abs(ref.state.q))


def test_a_case_in_a_batch_equals_the_case_alone_bit_for_bit() -> None:
    """Each case's arithmetic is its own: the batch, a batch in another order and each
    case alone give the same bits."""
    probs = problems()
    together = drag_many(probs)
    backwards = drag_many(probs[::-1])[::-1]
    for p, a, b in zip(probs, together, backwards, strict=True):
        alone = drag_many([p])[0]
        for other in (b, alone):
            for name in ("position", "tension", "force_a", "force_b"):
                assert np.array_equal(getattr(a, name), getattr(other, name)), name
            assert np.array_equal(a.state.q, other.state.q)
            assert (a.iterations, a.drag_iterations) == (other.iterations, other.drag_iterations)


def test_the_converged_loads_balance_the_end_forces() -> None:
    """The whole line in equilibrium: the end forces the line exerts on its attachments
    sum to its loads, force_a + force_b = sum_p q_p ell_p + point loads, with q the
    converged weight and drag. The shape is solved with the loads of the previous drag
    iterate, which differ from the converged ones by at most the load residual (tolerance
    1e-9 of the loads' scale): the balance holds to that, plus round-off."""
    for p, res in zip(problems(), drag_many(problems()), strict=True):
        lay = res.state.layout
        loads = np.sum(res.state.q * lay.ell[:, None], axis=0) + lay.point.sum(axis=0)
        scale = float(np.sum(np.linalg.norm(res.state.q, axis=1) * lay.ell))
        scale += float(np.abs(lay.point).sum())
        gap = np.abs(res.force_a + res.force_b - loads)
        assert np.max(gap) <= 4.0 * p.tolerance * scale + 1e-12 * np.max(res.tension)
        # the drag is there: a horizontal load the still line would not carry (the
        # slowest current, 0.1 m/s, pulls some 10 N on 24 kN of weight)
        assert np.hypot(*loads[:2]) > 1e-4 * scale


def test_cases_it_does_not_take_go_to_the_general_solver() -> None:
    """A line in a current anchored on a seabed with a clump weight on it is not the
    kernel's (the general solver's touchdown point can stop at the clump,
    :mod:`cablestudy.statics.contact_pin`): ``solve_batch`` solves it with the general
    solver (verified, status 0), beside the kernel's cases, and says so through its
    ``general`` list. A line whose end A is the towed end is the kernel's (solved from B,
    :mod:`tests.unit.test_statics_batch_drag_reversed`), and so is one over a seabed it
    does not reach (:mod:`tests.unit.test_statics_batch_drag_seabed`)."""
    z, v = _current((0.0, 0.5, 30.0))
    line = make_line([300.0], [80.0], [2e8], diameter=0.05)
    clumped = make_line(
        [300.0], [80.0], [2e8], diameter=0.05, attachments=[(100.0, (0.0, 0.0, -2000.0))]
    )
    free = Medium(density=1025.0, gravity=9.80665, current_z=z, current_velocity=v)
    seabed = Medium(density=1025.0, gravity=9.80665, depth=250.0, current_z=z, current_velocity=v)
    base = StaticProblem(
        line=line, medium=free, end_a=fixed(0.0, 0.0, -50.0), end_b=fixed(220.0, 0.0, -200.0),
        n_nodes=21, tolerance=1e-9,
    )  # fmt: skip
    over = StaticProblem(
        **{**base.__dict__, "line": clumped, "medium": seabed, "end_b": fixed(150.0, 0.0, -250.0)}
    )  # anchored on the seabed at B
    towed_a = StaticProblem(
        **{
            **base.__dict__,
            "end_a": EndCondition(kind="force", force=np.array([-3e4, 0.0, -1e4])),
            "end_b": fixed(220.0, 0.0, -200.0),
        }
    )
    assert drag_eligible(base) and not drag_eligible(over) and drag_eligible(towed_a)
    general: list[int] = []
    out = solve_batch([base, over, towed_a], general=general)
    assert general == [1]
    assert all(r.status == 0 for r in out)
    for i, p in ((0, base), (2, towed_a)):
        ref = SemiAnalyticSolver().solve(p, compiled=False)
        assert np.max(np.abs(out[i].force_a - ref.force_a)) <= 1e-12 * np.max(ref.tension)


def test_the_batched_verification_is_check_one_and_catches_a_wrong_answer() -> None:
    """:func:`cablestudy.statics.verify_drag.verified_many` computes :func:`check_one`'s
    checks for many lines at once: each value and allowance equal to round-off of the
    sums (1e-12 of the allowance), and an answer off by 1e-3 of its tension in an end
    force or a node's tension is not verified, with the check named (the allowance is
    set by the drag's quadrature estimate here, about 1e-5 of the tension, far above the
    1e-9 tolerance: the perturbation is 100 times it)."""
    from dataclasses import replace

    from cablestudy.statics.verify import check_one
    from cablestudy.statics.verify_drag import _check_group, verified_many

    probs = problems()
    res = drag_many(probs, verify=False)
    for segments in (1, 2):
        idx = [i for i, p in enumerate(probs) if p.line.length.size == segments]
        idx = [i for i in idx if probs[i].n_nodes == probs[idx[0]].n_nodes]
        checked, ends = _check_group([probs[i] for i in idx], [res[i] for i in idx], False)
        for j, i in enumerate(idx):
            one = check_one(probs[i], res[i], method="catenary")
            for name in one.values:
                value, allow = (
                    (checked.values[name], checked.allowed[name])
                    if name in checked.values
                    else ends[name][:2]
                )
                a = float(one.allowed[name][0])
                assert abs(float(value[j]) - float(one.values[name][0])) <= 1e-12 * a, name
                assert abs(float(allow[j]) - a) <= 1e-12 * a, name
    assert all(r.status == 0 for r in verified_many(probs, res))
    bad = []
    for r in res[:6]:
        F = float(np.max(r.tension))
        tension = r.tension.copy()
        tension[3] += 1e-3 * F  # not at the clump (whose tension is either side's)
        bad += [replace(r, force_a=r.force_a + [1e-3 * F, 0.0, 0.0]), replace(r, tension=tension)]
    out = verified_many([p for p in probs[:6] for _ in (0, 1)], bad)
    assert all(r.status != 0 and "not verified" in r.message for r in out)
    assert all("force balance" in r.message for r in out[::2])
    assert all("tension along s" in r.message for r in out[1::2])
