"""A line anchored on the seabed in a current in the compiled drag iteration
(:mod:`cablestudy.statics.batch_drag`, :mod:`cablestudy.statics._drag_inner`): each
inner solve lays the line from the anchor (friction towards it, no drag on the laid
part) as the general solver's seabed-contact Newton does. Its answers are the general
solver's step for step; the cases it hands on are the general solver's, with the
reason; the still-water limit is the still-water seabed kernel's; a mirrored current
gives the mirrored line; the drag discretisation converges at second order."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from cablestudy.statics import EndCondition, Medium, StaticProblem
from cablestudy.statics.base import STATUS_NOT_VERIFIED
from cablestudy.statics.batch import solve_batch
from cablestudy.statics.batch_drag import ANCHORED_REASONS, drag_eligible, drag_many
from cablestudy.statics.batch_kernels import contact_many
from cablestudy.statics.semi_analytic import SemiAnalyticSolver
from cablestudy.statics.verify_drag import verified_many
from tests.statics_helpers import fixed, make_line

DEPTH, L = 100.0, 300.0
#: a studless chain (76 mm, 1090 N/m in water, EA 5e8 N)
CHAIN = make_line([L], [1090.0], [5e8], diameter=0.076, cn=2.4, ct=0.4)


def water(speed: float, heading_deg: float = 30.0, slope_deg: float = 0.0, **kw) -> Medium:  # noqa: ANN003
    """Sea water 100 m deep, friction 0.5, a uniform current (speed [m/s], heading)."""
    h = math.radians(heading_deg)
    return Medium(
        density=1025.0, gravity=9.80665, depth=DEPTH, friction=0.5,
        seabed_slope=math.radians(slope_deg), current_z=np.array([0.0]),
        current_velocity=np.array([[speed * math.cos(h), speed * math.sin(h), 0.0]]), **kw,
    )  # fmt: skip


def anchored(medium: Medium, x: float = 250.0, y: float = 0.0, **kw) -> StaticProblem:  # noqa: ANN003
    """The chain from an anchor on the seabed at the origin to a fairlead 10 m deep."""
    return StaticProblem(
        line=CHAIN, medium=medium, end_a=fixed(0.0, 0.0, -DEPTH), end_b=fixed(x, y, -10.0),
        n_nodes=21, tolerance=1e-9, **kw,
    )  # fmt: skip


def problems() -> list[StaticProblem]:
    """Chains a mooring engineer sweeps: flat and sloped (2 deg) seabeds, currents of
    0.3 to 1.5 m/s across and along the line, fairlead offsets from slack to nearly
    taut; a moored and a towed end B; and a line anchored at B (solved from B)."""
    out = [
        anchored(water(v, head, slope), x)
        for slope in (0.0, 2.0)
        for v, head in ((0.3, 90.0), (1.5, 30.0), (1.0, 180.0))
        for x in (220.0, 250.0, 282.0)
    ]
    moored = EndCondition(kind="mooring", force=np.array([2e5, 3e4, 0.0]), z=-10.0)
    towed = EndCondition(kind="force", force=np.array([2e5, 0.0, 1.2e5]))
    out += [replace(out[1], end_b=moored), replace(out[1], end_b=towed)]
    out.append(replace(out[1], end_a=out[1].end_b, end_b=out[1].end_a))
    return out


def test_the_kernel_runs_the_general_drag_loop_step_for_step() -> None:
    """Every case takes the kernel; those it settles (resting on the seabed) have the
    general solver's Newton and drag iteration counts, laid length and numbers to
    round-off: each inner solve is the same contact Newton from the same start (the
    still-water start found by false position to 1e-12 where the solver bisects, which
    the Newton's polishing step removes), its closed forms summed in another order and
    its 3 x 3 systems solved by elimination, about 1e-15 relative per iterate; the fixed
    point contracts, so the difference stays within a few hundred ulps (1e-12 of the
    scale), far inside the solver tolerance (1e-9 of the scale). The cases handed on
    say why."""
    probs = problems()
    assert all(drag_eligible(p) for p in probs)
    why: dict[int, str] = {}
    got = drag_many(probs, why=why)
    solver = SemiAnalyticSolver()
    for i, (p, g) in enumerate(zip(probs, got, strict=True)):
        ref = solver.solve(p, compiled=False)
        if g is None:
            assert why[i] in ANCHORED_REASONS.values()
            continue
        assert ref.status == 0 and g.laid_length > 0.0 and i not in why
        assert (g.iterations, g.drag_iterations) == (ref.iterations, ref.drag_iterations)
        F = float(np.max(ref.tension))
        assert abs(g.laid_length - ref.laid_length) <= 1e-12 * L
        assert np.max(np.abs(g.position - ref.position)) <= 1e-12 * L
        assert np.max(np.abs(g.tension - ref.tension)) <= 1e-12 * F
        assert np.max(np.abs(g.force_a - ref.force_a)) <= 1e-12 * F
        assert np.max(np.abs(g.force_b - ref.force_b)) <= 1e-12 * F
    # handed on: three nearly taut lines whose iteration lifts off the anchor (the
    # general solver hangs them free on the way, then lays 0 to 1.2 m), and a slack one
    # pushed back towards the anchor up the slope, which has no determined laid shape
    assert why == {
        2: ANCHORED_REASONS[4], 5: ANCHORED_REASONS[4], 8: ANCHORED_REASONS[4],
        15: ANCHORED_REASONS[5],
    }  # fmt: skip


def test_a_case_handed_on_is_the_general_solvers_with_the_reason() -> None:
    """``solve_batch`` gives a case the kernel hands on (a nearly taut chain in a strong
    current, which lifts off the anchor) the general solver's verified answer, its
    ``fallback`` naming the reason; a chain with a clump weight is not the kernel's."""
    lifted = anchored(water(1.5), 282.0)
    clumped = replace(
        lifted,
        line=make_line(
            [L], [1090.0], [5e8], diameter=0.076, cn=2.4, ct=0.4,
            attachments=[(150.0, (0.0, 0.0, -5e3))],
        ),
    )  # fmt: skip
    assert drag_eligible(lifted) and not drag_eligible(clumped)
    general: list[int] = []
    out = solve_batch([anchored(water(1.5)), lifted, clumped], general=general)
    assert general == [1, 2] and not out[0].fallback
    assert out[1].fallback == ANCHORED_REASONS[4] and not out[2].fallback
    ref = SemiAnalyticSolver().solve(lifted, compiled=False)
    assert out[1].status == 0 and np.array_equal(out[1].position, ref.position)


def test_still_water_is_the_limit_of_a_weak_current() -> None:
    """As the current vanishes the kernel's line tends to the still-water seabed
    kernel's (:mod:`cablestudy.statics._fast_contact`). The drag per length is at most
    rho C_N d U^2 / 2 = 93 U^2 N/m (U in m/s) against the weight 1090 N/m: at U = 1e-5
    m/s a relative load of 1e-12, which moves the line by about that fraction of its
    scale (the contact Newton's polished residual, 1e-15, is far below); at 1e-3 m/s,
    1e-8, and the difference grows as U^2 between the two (a factor 1e4, to 1 %)."""
    still = replace(
        anchored(water(0.0)),
        medium=Medium(density=1025.0, gravity=9.80665, depth=DEPTH, friction=0.5),
    )
    ref = contact_many([still])[0]
    assert ref is not None
    F = float(np.linalg.norm(ref.force_b))
    diff = []
    for U in (1e-5, 1e-3):
        g = drag_many([anchored(water(U, 90.0))])[0]
        assert g is not None
        d = max(
            float(np.max(np.abs(g.position - ref.position))) / L,
            float(np.max(np.abs(g.force_b - ref.force_b))) / F,
        )
        assert d <= 2.0 * 93.0 * U * U / 1090.0 + 1e-14
        diff.append(d)
    assert abs(diff[1] / diff[0] / 1e4 - 1.0) <= 1e-2


def test_a_mirrored_current_gives_the_mirrored_line() -> None:
    """A flat seabed has no preferred side: the fairlead at y = -40 m in a current
    heading -30 deg is the line at y = +40 m in one heading +30 deg mirrored in the
    x-z plane (y -> -y), to round-off of the scale (1e-12)."""
    a, b = drag_many([anchored(water(1.0, 30.0), y=40.0), anchored(water(1.0, -30.0), y=-40.0)])
    assert a is not None and b is not None
    mirror = np.array([1.0, -1.0, 1.0])
    assert np.max(np.abs(a.position - b.position * mirror)) <= 1e-12 * L
    F = float(np.max(a.tension))
    assert np.max(np.abs(a.tension - b.tension)) <= 1e-12 * F
    assert np.max(np.abs(a.force_b - b.force_b * mirror)) <= 1e-12 * F
    assert abs(a.laid_length - b.laid_length) <= 1e-12 * L
    assert float(np.max(np.abs(a.position[:, 1]))) > 1.0  # the current moves it sideways


def test_the_drag_elements_converge_at_second_order() -> None:
    """Drag is piecewise constant along the drag elements, each taken from its chord at
    its mid-height (the midpoint rule): the fairlead force errs by O(h^2). With the
    current along the line's plane (both ways) the error against 2,560 elements falls by
    4 +- 0.3 per halving from 20 to 160 elements (h^-2), to 2e-6 of the force. (With a
    current across the line the element holding the touchdown point takes its drag or
    none by where its middle lies, which the general solver does too: there the error
    jumps by up to 1e-3 as the touchdown point crosses element middles.)"""
    line = make_line([L], [1090.0], [5e8], diameter=0.076, cn=2.4, ct=0.01)
    for heading in (0.0, 180.0):

        def force(n: int, heading: float = heading) -> np.ndarray:
            p = replace(anchored(water(1.0, heading)), line=line, tolerance=1e-11)
            g = drag_many([replace(p, drag_elements=n)])[0]
            assert g is not None and g.laid_length > 0.0
            return g.force_b

        ref = force(2560)
        err = [float(np.linalg.norm(force(n) - ref)) for n in (20, 40, 80, 160)]
        ratios = np.array(err[:-1]) / np.array(err[1:])
        assert np.all(np.abs(ratios - 4.0) <= 0.3), ratios
        assert err[-1] <= 4e-6 * float(np.linalg.norm(ref))


def test_a_wrong_answer_on_the_seabed_is_rejected() -> None:
    """The kernel's answers resting on the seabed are verified (:func:`verified_many`,
    with the seabed's reaction, as :func:`check_one`): all pass; one with the tension of
    a node on the suspended part off by 0.2 of the largest does not (the allowance, set
    by the drag's quadrature estimate on 15 m intervals, is up to 0.11 of it, for the
    cross current over the slope), nor one with its fairlead moved by 1e-3 L (allowed:
    1e3 times the tolerance, 1e-6 L). (A fairlead force turned in the
    horizontal plane by 1e-2 rad passes: the seabed's friction, up to 0.5 times the laid
    weight, can hold the imbalance, so the answer is admissible to the balance.)"""
    probs = [p for p in problems()[:9] if p.end_b.position[0] < 280.0]
    res = drag_many(probs, verify=False)
    assert all(r.status == 0 for r in verified_many(probs, res))
    bad = []
    for r in res:
        t = r.tension.copy()
        t[18] += 0.2 * float(np.max(t))
        pos = r.position.copy()
        pos[-1, 0] += 1e-3 * L
        bad += [replace(r, tension=t), replace(r, position=pos)]
    checked = verified_many([p for p in probs for _ in range(2)], bad)
    assert all(r.status == STATUS_NOT_VERIFIED for r in checked)
