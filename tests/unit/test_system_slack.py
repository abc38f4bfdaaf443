"""Lines lying slack on the seabed in a system's Newton trials
(:mod:`cablestudy.statics.system_slack`) and the end stiffness of a line whose
touchdown rests at a clump (:mod:`cablestudy.statics.system_pin`).

Checks: the hanging part of a uniform elastic line against its closed form; a clump at
the foot of the hanging part carried in proportion; the slack forces as the limit of
the taut contact solution (the force field continuous where a line goes slack); and
the pinned-state stiffness against central differences of the solved end forces."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from cablestudy.statics import STATIC_SOLVERS, EndCondition, Medium, StaticProblem
from cablestudy.statics.line_stiffness import line_end_stiffness
from cablestudy.statics.system_slack import hanging, slack_forces
from tests.line_models import one_segment

SOLVER = STATIC_SOLVERS["catenary"]
W, EA = 981.0, 4.9e8  # chain [N/m], [N]


def _problem(length: float, ra: list[float], rb: list[float], **kw: object) -> StaticProblem:
    line = one_segment(length=length, weight=W, mass=115.0, axial_stiffness=EA)
    mu = float(kw.get("mu", 0.0))  # type: ignore[arg-type]
    if kw.get("clump_s") is not None:
        line = replace(
            line,
            attachment_s=np.array([kw["clump_s"]]),
            attachment_force=np.array([[0.0, 0.0, -float(kw["clump_w"])]]),  # type: ignore[arg-type]
            attachment_mass=np.array([0.0]),
            attachment_volume=np.array([0.0]),
        )
    return StaticProblem(
        line=line,
        medium=Medium(density=1025.0, gravity=9.80665, depth=200.0, friction=mu),
        end_a=EndCondition(kind="fixed", position=np.asarray(ra, dtype=float)),
        end_b=EndCondition(kind="fixed", position=np.asarray(rb, dtype=float)),
        tolerance=1e-12,
    )


def test_hanging_part_matches_the_closed_form() -> None:
    # uniform elastic line hanging h with zero tension at its foot: h = S + w S^2/(2 EA),
    # so S = EA/w (sqrt(1 + 2 w h / EA) - 1), W = w S, dW/dh = w / sqrt(1 + 2 w h / EA);
    # the bisection stops at 1e-15 of the piece, so 1e-12 relative bounds its error
    h = 150.0
    root = math.sqrt(1.0 + 2.0 * W * h / EA)
    S, Wtop, k = hanging(np.array([400.0]), np.array([W]), np.array([EA]), np.zeros(2), h)  # type: ignore[misc]
    np.testing.assert_allclose(
        [S, Wtop, k], [EA / W * (root - 1.0), W * EA / W * (root - 1.0), W / root], rtol=1e-12
    )
    # too short to reach the seabed: no hanging state
    assert hanging(np.array([100.0]), np.array([W]), np.array([EA]), np.zeros(2), h) is None


def test_clump_at_the_foot_is_carried_in_proportion() -> None:
    # two pieces of 100 m from the end, a clump F at their joint. With the foot at the
    # joint the height runs from H0 (clump on the seabed) to H0 + F l / EA (clump hung):
    # in between the clump is carried in proportion, so W is linear in h with slope
    # EA / l (the stretch of the piece above), and S stays at the joint
    ell, F = 100.0, 5.0e4
    args = (np.array([ell, ell]), np.array([W, W]), np.array([EA, EA]), np.array([0.0, F, 0.0]))
    H0 = ell + 0.5 * W * ell * ell / EA
    for frac in (0.25, 0.75):
        h = H0 + frac * F * ell / EA
        S, Wtop, k = hanging(*args, h)  # type: ignore[misc]
        # the height is linear in the carried fraction: exact to round-off on h (1e-14 of
        # 100 m over a slope F l/EA ~ 1e-2 m gives 1e-10 of F)
        assert S == ell
        np.testing.assert_allclose(Wtop, W * ell + frac * F, rtol=1e-9)
        np.testing.assert_allclose(k, EA / ell, rtol=1e-12)


def test_slack_forces_are_the_limit_of_the_taut_line() -> None:
    # a 300 m chain from an anchor on the seabed to B 100 m up: slack beyond the reach
    # X* = L - S(h). Approaching X* from the taut side the contact solution's force on B
    # tends to the slack force (0, 0, -w S(h)): its horizontal tension H vanishes (the
    # catenary's excess length over the vertical-plus-laid path is about
    # (H/w) ln(2 w h / H), so H falls faster than the gap), and the vertical force tends
    # to w S. Each tenfold smaller gap must shrink the difference at least fivefold.
    L, h = 300.0, 100.0
    S = EA / W * (math.sqrt(1.0 + 2.0 * W * h / EA) - 1.0)
    reach = L - S
    ra = [0.0, 0.0, -200.0]
    slack = slack_forces(_problem(L, ra, [reach - 1.0, 0.0, -100.0]))
    assert slack is not None
    fa, fb, K = slack
    np.testing.assert_allclose(fb, [0.0, 0.0, -W * S], rtol=1e-12)
    assert np.all(fa == 0.0)
    assert K[1, 1, 2, 2] > 0.0 and np.all(K[1, 1, :2] == 0.0) and np.all(K[0] == 0.0)
    assert slack_forces(_problem(L, ra, [reach + 1.0, 0.0, -100.0])) is None  # taut
    gaps = [1.0, 0.1, 0.01]
    diffs = []
    for gap in gaps:
        res = SOLVER.solve(_problem(L, ra, [reach + gap, 0.0, -100.0]))
        assert res.status == 0, res.message
        diffs.append(float(np.linalg.norm(res.force_b - fb)))
    assert diffs[1] < diffs[0] / 5.0 and diffs[2] < diffs[1] / 5.0, diffs
    assert diffs[2] < 1e-3 * W * S


def _pinned_case(mu: float) -> tuple[StaticProblem, np.ndarray, np.ndarray]:
    # an 800 m chain with a 5 t clump (49 kN in water) at s = 500 m, the fairlead moved
    # out until the touchdown rests at the clump (laid length = 500 m)
    ra = np.array([0.0, 0.0, -200.0])
    for x in np.arange(660.0, 760.0, 1.0):
        prob = _problem(800.0, list(ra), [x, 0.0, -20.0], clump_s=500.0, clump_w=49033.0, mu=mu)
        res = SOLVER.solve(prob)
        if res.status == 0 and abs(res.laid_length - 500.0) <= 1e-9:
            return prob, ra, np.array([x, 5.0, -20.0])
    raise AssertionError("no fairlead position rests the touchdown at the clump")


def test_pinned_touchdown_stiffness_is_the_central_difference() -> None:
    for mu in (0.0, 0.3):
        prob, ra, rb = _pinned_case(mu)
        prob = replace(prob, end_b=EndCondition(kind="fixed", position=rb))
        res = SOLVER.solve(prob)
        assert res.status == 0 and abs(res.laid_length - 500.0) <= 1e-9, res.message
        K = line_end_stiffness(prob, res)[1, 1]
        h = 1e-3
        Kfd = np.zeros((3, 3))
        for c in range(3):
            d = np.zeros(3)
            d[c] = h
            plus = SOLVER.solve(replace(prob, end_b=EndCondition(kind="fixed", position=rb + d)))
            minus = SOLVER.solve(replace(prob, end_b=EndCondition(kind="fixed", position=rb - d)))
            assert abs(plus.laid_length - 500.0) <= 1e-9 and abs(minus.laid_length - 500.0) <= 1e-9
            Kfd[:, c] = -(plus.force_b - minus.force_b) / (2 * h)
        # as test_statics_system: central differences err by h^2 f''' / 6 (~1e-10
        # relative at h = 1 mm) and by the solver's force error over h (tolerance 1e-12
        # of the tension / 1 mm, ~1e-7 of the stiffness): 1e-6 of the largest entry.
        # The free-TDP formula this replaces is off by far more (the TDP does not move).
        scale = float(np.max(np.abs(K)))
        assert np.max(np.abs(K - Kfd)) <= 1e-6 * scale, (K, Kfd)


SLACK_START = """\
name: slackstart
environment: {fluid: water, depth: 100.0}
points:
  anchor1: {kind: fixed, position: [-300.0, 0.0, -100.0]}
  clump:   {kind: free, position: [-150.0, 0.0, -90.0], mass: 3000.0, volume: 0.2}
  fair1:   {kind: body, body: buoy, offset: [-5.0, 0.0, -10.0]}
bodies:
  buoy: {kind: prescribed, position: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]}
lines:
  leg1:
    a: anchor1
    b: clump
    segments: [{length: 280.0, diameter: 0.1, mass_per_length: 100.0, axial_stiffness: 5.0e8}]
  bridle:
    a: clump
    b: fair1
    segments: [{length: 70.0, diameter: 0.1, mass_per_length: 100.0, axial_stiffness: 5.0e8}]
"""


def test_slack_start_compiled_equals_general() -> None:
    # leg1 slack at the start (seabed path 150 m + rise 10 m < 280 m): the compiled
    # Newton (its slack lines by _system_lines._slack_line) takes the case and agrees with
    # the general path (its slack lines by system_slack.slack_forces) to the bar of
    # test_system_fast (1e-9 relative: both converge the same equations past tolerance)
    from cablestudy.analyses.system import system_model
    from cablestudy.statics.system_fast import solve_fast
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text
    from tests.unit.test_system_fast import _compare

    _, cases = expand_cases(parse_study_text(SLACK_START, "<slack>"))
    system = system_model(cases[0].study)
    ln = system.lines[0].problem
    start = slack_forces(
        replace(
            ln,
            end_a=EndCondition(kind="fixed", position=np.array([-300.0, 0.0, -100.0])),
            end_b=EndCondition(kind="fixed", position=np.array([-150.0, 0.0, -90.0])),
        )
    )
    assert start is not None  # slack there
    _compare(system)
    got, _ = solve_fast(system)
    assert got is not None and got.status == 0
