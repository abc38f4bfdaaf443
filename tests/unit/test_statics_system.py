"""Mooring systems (cablestudy.statics.system): the lines' exact end stiffness against
central differences of the solved end forces, the body stiffness' symmetry, invariance
under a rotation of the system about z, and its first-order accuracy (the remainder of
a small offset is second order)."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from cablestudy.statics import STATIC_SOLVERS, EndCondition
from cablestudy.statics.system import (
    line_end_stiffness,
    rotation,
    rotation_derivatives,
    solve_system,
)
from cablestudy.statics.system_model import BODY, FIXED, FREE
from tests.system_models import (
    CASE8_LINES,
    CASE8_POINTS,
    G,
    polyester,
    rotated_points,
    system_of,
)

SOLVER = STATIC_SOLVERS["catenary"]


def _forces(problem, ra, rb):  # type: ignore[no-untyped-def]
    res = SOLVER.solve(
        replace(
            problem,
            end_a=EndCondition(kind="fixed", position=np.asarray(ra, dtype=float)),
            end_b=EndCondition(kind="fixed", position=np.asarray(rb, dtype=float)),
        )
    )
    assert res.status == 0, res.message
    return res


def _central_stiffness(problem, ra, rb, h, moving):  # type: ignore[no-untyped-def]
    """K[i, j] = -d f_i / d r_j by central differences with step h [m] (NaN for the
    ends j not in ``moving``)."""
    K = np.full((2, 2, 3, 3), np.nan)
    for j in moving:
        for c in range(3):
            step = np.zeros((2, 3))
            step[j, c] = h
            plus = _forces(problem, ra + step[0], rb + step[1])
            minus = _forces(problem, ra - step[0], rb - step[1])
            K[0, j, :, c] = -(plus.force_a - minus.force_a) / (2 * h)
            K[1, j, :, c] = -(plus.force_b - minus.force_b) / (2 * h)
    return K


def _check_line(problem, ra, rb, *, contact: bool) -> None:  # type: ignore[no-untyped-def]
    ra, rb = np.asarray(ra, dtype=float), np.asarray(rb, dtype=float)
    res = _forces(problem, ra, rb)
    assert (res.laid_length > 0.0) == contact
    K = line_end_stiffness(
        replace(
            problem,
            end_a=EndCondition(kind="fixed", position=ra),
            end_b=EndCondition(kind="fixed", position=rb),
        ),
        res,
    )
    # a central difference errs by h^2/6 f''' (relative (h/L)^2 ~ 1e-10 with h = 1 mm) and
    # by the solver's force error / h (tolerance 1e-12 of the tension over 1 mm: ~1e-9 of
    # the tension per metre, 1e-7 of the stiffness): 1e-6 of the largest entry covers both
    moving = [j for j in range(2) if np.all(np.isfinite(K[j, j]))]
    Kfd = _central_stiffness(problem, ra, rb, 1e-3, moving)
    finite = np.isfinite(K) & np.isfinite(Kfd)
    assert finite.sum() >= 9
    scale = float(np.max(np.abs(K[finite])))
    assert np.max(np.abs(K[finite] - Kfd[finite])) <= 1e-6 * scale
    for i in range(2):
        for j in range(2):
            if np.all(np.isfinite(K[i, j])):
                # the line is conservative (complementary energy): K[i, j] = K[j, i]^T,
                # to the solver's round-off (1e-12 relative) amplified by the inversion
                np.testing.assert_allclose(K[i, j], K[j, i].T, rtol=0, atol=1e-9 * scale)
    if contact:
        assert np.isnan(K[0, 0]).all() or np.isnan(K[1, 1]).all()


def test_free_hanging_line_stiffness_is_the_central_difference() -> None:
    _check_line(polyester(100.0, depth=None), [0.0, 0.0, 0.0], [80.0, 10.0, -30.0], contact=False)


def test_line_on_the_seabed_stiffness_is_the_central_difference() -> None:
    _check_line(polyester(160.0), [0.0, 0.0, -100.0], [130.0, 20.0, -30.0], contact=True)
    # the anchor at B: the solver describes the line from B, the stiffness follows
    _check_line(polyester(160.0), [130.0, 20.0, -30.0], [0.0, 0.0, -100.0], contact=True)


def test_rotation_derivatives_are_exact_at_large_angles() -> None:
    angles = np.array([0.7, -1.1, 2.5])
    R = rotation(angles)
    np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-15)
    h = 1e-5  # central difference: error h^2/6 ~ 2e-11 (entries of R are O(1))
    for k, dR in enumerate(rotation_derivatives(angles)):
        e = np.zeros(3)
        e[k] = h
        fd = (rotation(angles + e) - rotation(angles - e)) / (2 * h)
        np.testing.assert_allclose(dR, fd, atol=1e-9)


def _symmetric_spread(pose: list[float]):  # type: ignore[no-untyped-def]
    """Three identical legs 120 degrees apart (case8 with its anchors exactly on a
    200 m circle), each a bridle to two fairleads."""
    pts = []
    for k in range(3):
        th = math.radians(90.0 + 120.0 * k)
        c, s = math.cos(th), math.sin(th)
        base = 4 * k
        pts += [
            (str(base + 1), FIXED, [200.0 * c, 200.0 * s, -100.0]),
            (str(base + 2), FREE, [40.0 * c, 40.0 * s, -50.0]),
        ]
        for dth in (-60.0, 60.0):
            t = th + math.radians(dth)
            pts.append((str(base + 3), BODY, [7.875 * math.cos(t), 7.875 * math.sin(t), -21.0]))
    names = [(n, k, p) for n, k, p in pts]
    lines = []
    for k in range(3):
        base = 4 * k
        lines += [
            (base + 1, base + 2, 160.0),
            (base + 2, base + 3, 45.36),
            (base + 2, base + 4, 45.36),
        ]
    return system_of(names, lines, pose)


def test_symmetric_spread_has_a_symmetric_stiffness() -> None:
    res = solve_system(_symmetric_spread([0.0] * 6), SOLVER)
    assert res.status == 0, res.message
    K = res.body_stiffness[0]
    scale = float(np.max(np.diag(K)))
    # exact symmetries, spoilt only by the solves' round-off (tolerance 1e-12 on forces,
    # amplified by the condensation): 1e-8 of the largest diagonal entry
    tol = 1e-8 * scale
    assert abs(K[0, 0] - K[1, 1]) <= tol
    assert abs(K[3, 3] - K[4, 4]) <= tol
    assert abs(K[0, 4] + K[1, 3]) <= tol
    np.testing.assert_allclose(K, K.T, rtol=0, atol=tol)
    allowed = np.zeros((6, 6), dtype=bool)
    allowed[np.diag_indices(6)] = True
    allowed[0, 4] = allowed[4, 0] = allowed[1, 3] = allowed[3, 1] = True
    assert np.max(np.abs(K[~allowed])) <= tol
    # the coupling of surge and pitch is real (the fairleads are 21 m deep)
    assert abs(K[0, 4]) > 1e3 * tol
    f = res.body_force[0]
    assert np.max(np.abs(f[[0, 1, 3, 4, 5]])) <= 1e-8 * abs(f[2])


def test_rotated_system_gives_the_rotated_stiffness() -> None:
    lines = [*CASE8_LINES[:2], (1, 4, 150.0), *CASE8_LINES[3:]]  # one leg shorter
    angle = math.radians(30.0)
    base = solve_system(system_of(CASE8_POINTS, lines, [0.0] * 6), SOLVER)
    turned = solve_system(system_of(rotated_points(CASE8_POINTS, angle), lines, [0.0] * 6), SOLVER)
    assert base.status == 0 and turned.status == 0
    c, s = math.cos(angle), math.sin(angle)
    q = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    Q = np.zeros((6, 6))
    Q[:3, :3] = Q[3:, 3:] = q
    K, Kt = base.body_stiffness[0], turned.body_stiffness[0]
    scale = float(np.max(np.diag(K)))
    assert np.max(np.abs(Kt - Q @ K @ Q.T)) <= 1e-8 * scale  # round-off only, as above
    np.testing.assert_allclose(
        turned.body_force[0],
        Q @ base.body_force[0],
        rtol=0,
        atol=1e-9 * np.abs(base.body_force).max(),
    )
    # the check has teeth: the turned stiffness differs from the unturned by far more
    assert np.max(np.abs(Kt - K)) > 1e3 * 1e-8 * scale


def test_offset_step_remainder_is_second_order() -> None:
    """F(q + h d) - F(q) + K h d = O(h^2) at a pose with large angles, with clumps of
    2 t (in water) on the free junctions: the fitted order of the remainder is 2."""
    n = len(CASE8_POINTS)
    pf = np.zeros((n, 3))
    for i, (_, kind, _) in enumerate(CASE8_POINTS):
        if kind == FREE:
            pf[i, 2] = -2000.0 * G
    pose = np.array([4.0, -3.0, 1.0, 0.05, -0.04, 0.6])
    direction = np.array([1.0, -0.5, 0.3, 0.01, 0.02, -0.015])

    def body(q: np.ndarray):  # type: ignore[no-untyped-def]
        res = solve_system(system_of(CASE8_POINTS, CASE8_LINES, q, point_force=pf), SOLVER)
        assert res.status == 0, res.message
        return res

    ref = body(pose)
    # each clump is in equilibrium: the lines' forces on it balance its weight, to the
    # tolerance asked (1e-12 of the largest tension)
    net = pf.copy()
    for (a, b, _), line in zip(CASE8_LINES, ref.lines, strict=True):
        net[a - 1] += line.force_a
        net[b - 1] += line.force_b
    free = [i for i, p in enumerate(CASE8_POINTS) if p[1] == FREE]
    largest = max(float(np.max(line.tension)) for line in ref.lines)
    assert np.max(np.abs(net[free])) <= 1e-12 * largest
    K = ref.body_stiffness[0]
    hs = np.array([0.2, 0.1, 0.05])
    err = []
    for h in hs:
        df = body(pose + h * direction).body_force[0] - ref.body_force[0]
        err.append(float(np.linalg.norm(df + K @ (h * direction))))
    order = np.polyfit(np.log(hs), np.log(err), 1)[0]
    # a Taylor remainder: order 2 (3 if the curvature term vanished, 1 if K were wrong);
    # the fit over a factor 4 in h tolerates the third-order term's share, +-0.15
    assert abs(order - 2.0) <= 0.15, (order, err)
    # and the linear term dominates: the remainder is a small part of the change
    assert err[-1] <= 1e-2 * float(np.linalg.norm(K @ (hs[-1] * direction)))


def _free_spar(applied_x: float):  # type: ignore[no-untyped-def]
    """case8 with its body free: 1 MN of weight 30 m below the reference point, 2.2 MN of
    buoyancy 10 m below it (the lines pull down by about 1.18 MN), and a force along x."""
    return replace(
        system_of(CASE8_POINTS, CASE8_LINES, [0.0] * 6),
        body_free=np.array([True]),
        body_weight=np.array([1.0e6]),
        body_buoyancy=np.array([2.2e6]),
        body_cog=np.array([[0.0, 0.0, -30.0]]),
        body_cob=np.array([[0.0, 0.0, -10.0]]),
        body_applied=np.array([[applied_x, 0.0, 0.0]]),
    )


def test_free_body_is_in_equilibrium_and_responds_through_its_stiffness() -> None:
    from cablestudy.statics.system import body_loads

    rest = solve_system(_free_spar(0.0), SOLVER)
    assert rest.status == 0, rest.message
    load, k_load = body_loads(_free_spar(0.0), 0, rest.body_position[0])
    net = rest.body_force[0] + load
    largest = max(float(np.max(line.tension)) for line in rest.lines)
    # equilibrium to the tolerance asked (1e-12 of the largest tension; moments over the
    # 30 m arm)
    assert np.max(np.abs(net[:3])) <= 1e-11 * largest
    assert np.max(np.abs(net[3:])) <= 1e-11 * largest * 30.0
    # the same pose prescribed gives the same line forces (the free solve is the system's)
    again = solve_system(
        replace(_free_spar(0.0), body_free=np.array([False]), body_position=rest.body_position),
        SOLVER,
    )
    assert np.max(np.abs(again.body_force - rest.body_force)) <= 1e-9 * largest
    # a small applied force moves the body by K_total^-1 F, to second order in F
    K = rest.body_stiffness[0] + k_load
    forces = np.array([4.0e4, 2.0e4, 1.0e4])
    err = []
    for f in forces:
        moved = solve_system(_free_spar(f), SOLVER)
        assert moved.status == 0, moved.message
        predicted = np.linalg.solve(K, np.array([f, 0.0, 0.0, 0.0, 0.0, 0.0]))
        err.append(
            float(np.linalg.norm(moved.body_position[0] - rest.body_position[0] - predicted))
        )
    order = np.polyfit(np.log(forces), np.log(err), 1)[0]
    assert abs(order - 2.0) <= 0.15, (order, err)  # a Taylor remainder, as above


def test_differenced_stiffness_is_the_exact_one_where_both_exist() -> None:
    """The system's differenced end stiffness (:func:`.line_stiffness.numeric_stiffness`,
    used where no closed form exists) against the exact one, on a line lying on the
    seabed from its anchor (exact K_BB) and a hanging one (every block). Its step is
    1e-4 of the line (16 mm here): the solver's force error over the step (1e-9 of the
    tension over 1.6e-2 m) and the step squared over the catenary's length scale are
    near 1e-6 of the stiffness; 1e-4 of the largest entry covers both."""
    from cablestudy.statics.line_stiffness import numeric_stiffness

    def solve_all(problems):  # type: ignore[no-untyped-def]
        return [SOLVER.solve(p) for p in problems]

    for problem, ra, rb, moving in (
        (polyester(160.0), [0.0, 0.0, -100.0], [130.0, 20.0, -30.0], [False, True]),
        (polyester(100.0, depth=None), [0.0, 0.0, 0.0], [80.0, 10.0, -30.0], [True, True]),
    ):
        ra, rb = np.asarray(ra, dtype=float), np.asarray(rb, dtype=float)
        fixed = replace(
            problem,
            end_a=EndCondition(kind="fixed", position=ra),
            end_b=EndCondition(kind="fixed", position=rb),
        )
        res = _forces(problem, ra, rb)
        exact = line_end_stiffness(fixed, res)
        got = numeric_stiffness("leg", fixed, res, solve_all, moving)
        for i in range(2):
            for j in range(2):
                if moving[i] and moving[j]:
                    scale = float(np.max(np.abs(exact[i, j])))
                    assert np.max(np.abs(got[i, j] - exact[i, j])) <= 1e-4 * scale
