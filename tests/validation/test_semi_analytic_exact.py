"""The semi-analytic solver (method 'catenary') against exact and independently derived
solutions. Each test says where its expected numbers come from."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, fsolve

from cablestudy.statics import EndCondition, Medium, StaticProblem
from cablestudy.statics.elastic_catenary import solve_between
from cablestudy.statics.semi_analytic import SemiAnalyticSolver

from ..statics_helpers import fixed, make_line

SOLVER = SemiAnalyticSolver()


# ---------------------------------------------------------------- exact elastic catenary

GEOMETRIES = {
    # name: (end B [m], weight [N/m]) for L = 100 m, EA = 6.283e7 N, A at the origin
    "seed-fig4": ((92.5, 0.0, -8.6), 24.18),
    "3d-heading": ((30.0, 40.0, -8.6), 24.18),
    "taut": ((99.9, 0.0, 0.0), 24.18),
    "stretched-chord": ((100.05, 0.0, 0.0), 24.18),
    "near-vertical": ((1e-3, 0.0, -50.0), 24.18),
    "vertical-folded": ((0.0, 0.0, -50.0), 24.18),
    "very-slack": ((3.0, 0.0, 0.0), 24.18),
    "u-shape": ((60.0, 0.0, 0.0), 24.18),
    "steep-up": ((20.0, 0.0, 90.0), 24.18),
    "buoyant": ((70.0, 0.0, -20.0), -5.0),
    "nearly-weightless": ((99.0, 0.0, -3.0), 1e-7),
}


@pytest.mark.parametrize("name", sorted(GEOMETRIES))
def test_exact_elastic_catenary(name: str) -> None:
    """Expected: Irvine's closed form (Cable Structures, 1981, eqs. 2.26-2.27) as coded in
    cablestudy.statics.elastic_catenary, a separate implementation. Both solve to round-off
    (tolerance 1e-12 with a polishing Newton step), so end forces and profile agree to
    1e-10 relative to the largest force / the length."""
    rb, w = GEOMETRIES[name]
    L, EA = 100.0, 6.283e7
    air = Medium(density=1.225, gravity=9.80665)
    prob = StaticProblem(
        line=make_line([L], [w], EA),
        medium=air,
        end_a=fixed(0, 0, 0),
        end_b=fixed(*rb),
        n_nodes=101,
        tolerance=1e-12,
    )
    res = SOLVER.solve(prob)
    assert res.status == 0, res.message
    exact = solve_between(np.zeros(3), np.array(rb), L, w, EA, res.s, tolerance=1e-13)
    assert exact.status == 0
    fscale = max(np.max(np.abs(exact.force_a)), np.max(np.abs(exact.force_b)))
    assert np.max(np.abs(res.force_a - exact.force_a)) <= 1e-10 * fscale
    assert np.max(np.abs(res.force_b - exact.force_b)) <= 1e-10 * fscale
    assert np.max(np.abs(res.position - exact.position)) <= 1e-10 * L
    assert np.max(np.abs(res.tension - exact.tension)) <= 1e-10 * fscale
    assert res.drag_iterations == 0  # still water pays for no drag loop


def test_segmented_line_with_attachments_against_ode_integration() -> None:
    """Expected: the same end forces reproduce end B when dr/ds = T (1/EA + 1/|T|) with
    T(s) = T_A - int q - sum F is integrated by an adaptive Runge-Kutta method (scipy
    DOP853, rtol 1e-12) across each segment: an independent integration of the seed's
    eqs. (16)-(18). Error budget: the integrator's ~1e-10 L."""
    lengths, weights, EA = [40.0, 30.0, 50.0], [30.0, 5.0, -8.0], [1e8, 2e6, 5e6]
    atts = [(25.0, (0.0, 0.0, -400.0)), (70.0, (50.0, 20.0, 300.0))]
    line = make_line(lengths, weights, EA, attachments=atts)
    prob = StaticProblem(
        line=line,
        medium=Medium(density=1025.0, gravity=9.80665),
        end_a=fixed(0, 0, 0),
        end_b=fixed(80.0, 30.0, -25.0),
        tolerance=1e-12,
    )
    res = SOLVER.solve(prob)
    assert res.status == 0, res.message
    bounds = np.concatenate(([0.0], np.cumsum(lengths)))
    r = np.zeros(3)
    T = res.force_a.copy()
    for i in range(3):
        q = np.array([0.0, 0.0, -weights[i]])
        stops = sorted(
            {bounds[i], bounds[i + 1], *[a[0] for a in atts if bounds[i] < a[0] < bounds[i + 1]]}
        )
        for lo, hi in zip(stops[:-1], stops[1:], strict=True):
            T_lo = T.copy()

            def rhs(s: float, y: np.ndarray, T_lo=T_lo, lo=lo, q=q, i=i) -> np.ndarray:  # noqa: ANN001
                Ts = T_lo - q * (s - lo)
                return Ts * (1.0 / EA[i] + 1.0 / np.linalg.norm(Ts))

            sol = solve_ivp(rhs, (lo, hi), r, method="DOP853", rtol=1e-12, atol=1e-12 * 120)
            r = sol.y[:, -1]
            T = T_lo - q * (hi - lo)
            for s_att, f in atts:
                if s_att == hi:
                    T = T - np.array(f)
    assert np.max(np.abs(r - np.array([80.0, 30.0, -25.0]))) <= 1e-9 * 120.0
    # global balance: force on both attachments = total applied load
    total = sum(np.array(f) for _, f in atts) + np.array([0, 0, -np.dot(lengths, weights)])
    assert np.max(np.abs(res.force_a + res.force_b - total)) <= 1e-9 * np.abs(total).max()
    assert np.linalg.norm(-res.force_b) == pytest.approx(res.tension[-1], rel=1e-14)


# ---------------------------------------------------------------- two-bar truss


def test_weightless_line_with_point_load_is_a_two_bar_truss() -> None:
    """Expected: a weightless line of lengths l1, l2 loaded by F at the joint is two
    elastic bars; the joint position P solves EA (|P - A| / l1 - 1) e1 + EA (|P - B| / l2 -
    1) e2 + F = 0, found here with scipy's fsolve to 1e-14."""
    A, B = np.zeros(3), np.array([10.0, 2.0, 0.0])
    l1, l2, EA = 6.0, 7.0, 1e5
    F = np.array([30.0, -200.0, -1000.0])

    def balance(P: np.ndarray) -> np.ndarray:
        d1, d2 = A - P, B - P
        n1, n2 = np.linalg.norm(d1), np.linalg.norm(d2)
        return EA * (n1 / l1 - 1) * d1 / n1 + EA * (n2 / l2 - 1) * d2 / n2 + F

    P = fsolve(balance, np.array([5.0, 0.0, -5.0]), xtol=1e-13)
    line = make_line([l1 + l2], [0.0], EA, attachments=[(l1, F)])
    prob = StaticProblem(
        line=line,
        medium=Medium(density=0.0, gravity=9.80665),
        end_a=fixed(*A),
        end_b=fixed(*B),
        n_nodes=14,
        tolerance=1e-12,
    )
    res = SOLVER.solve(prob)
    assert res.status == 0, res.message
    assert np.max(np.abs(res.position[6] - P)) <= 1e-10 * (l1 + l2)
    T1 = EA * (np.linalg.norm(P - A) / l1 - 1)
    assert np.allclose(res.force_a, T1 * (P - A) / np.linalg.norm(P - A), rtol=0, atol=1e-9 * 1000)
    # each bar is straight: interior nodes on the chords
    for k in range(1, 6):
        assert np.allclose(res.position[k], A + (P - A) * k / 6, atol=1e-10)


# ---------------------------------------------------------------- inextensible limit


def test_inextensible_limit() -> None:
    """Expected: the inextensible catenary between points at equal height,
    L = (2H/w) sinh(w l / 2H) (Irvine 1981, eq. 1.14 with h = 0), solved by brentq; the
    elastic solution with EA = 1e14 N differs by O(T/EA) ~ 1e-11 relative."""
    L, w, l = 100.0, 20.0, 80.0
    H = brentq(
        lambda H: 2 * H / w * math.sinh(w * l / (2 * H)) - L, 50.0, 1e6, xtol=1e-14, rtol=1e-15
    )
    prob = StaticProblem(
        line=make_line([L], [w], 1e14),
        medium=Medium(density=0.0, gravity=9.8),
        end_a=fixed(0, 0, 0),
        end_b=fixed(l, 0, 0),
        tolerance=1e-12,
    )
    res = SOLVER.solve(prob)
    assert res.status == 0, res.message
    assert res.force_a[0] == pytest.approx(H, rel=1e-9)
    assert res.force_a[2] == pytest.approx(-w * L / 2, rel=1e-9)
    sag = H / w * (math.cosh(w * l / (2 * H)) - 1)
    assert res.position[50, 2] == pytest.approx(-sag, rel=1e-9)


# ---------------------------------------------------------------- Pode's critical angle


def test_pode_critical_angle_of_a_towed_cable() -> None:
    """Expected: Pode (1951, DTMB report 687): a heavy cable with normal drag only in a
    uniform stream, free lower end, lies straight at the critical angle phi_c to the
    stream where w cos(phi_c) = 1/2 rho d C_N U^2 sin^2(phi_c). With EA = 1e13 N the
    elastic correction (drag per stretched length) is ~1e-10; the drag loop converges to
    1e-10, so the chord angles agree to 1e-8 rad."""
    w, d, cn, U = 10.0, 0.05, 1.2, 1.0
    R = 0.5 * 1025.0 * d * cn * U * U
    c = (-1 + math.sqrt(1 + 4 * (R / w) ** 2)) / (2 * R / w)
    phi_c = math.acos(c)
    med = Medium(
        density=1025.0,
        gravity=9.80665,
        current_z=np.array([0.0]),
        current_velocity=np.array([[U, 0.0, 0.0]]),
    )
    prob = StaticProblem(
        line=make_line([100.0], [w], 1e13, diameter=d, cn=cn, ct=0.0),
        medium=med,
        end_a=fixed(0, 0, 0),
        end_b=EndCondition(kind="force", force=np.zeros(3)),
        n_nodes=41,
        tolerance=1e-10,
    )
    res = SOLVER.solve(prob)
    assert res.status == 0, res.message
    assert res.drag_iterations > 0
    chord = np.diff(res.position, axis=0)
    angles = np.arctan2(-chord[:, 2], chord[:, 0])
    assert np.max(np.abs(angles - phi_c)) <= 1e-8
    # tension grows linearly from the free end: T = w sin(phi_c) (L - s)
    assert res.tension[0] == pytest.approx(w * math.sin(phi_c) * 100.0, rel=1e-8)


# ---------------------------------------------------------------- seabed


def _seabed_reference(
    L: float, w: float, EA: float, h: float, X: float, mu: float
) -> tuple[float, float]:
    """Independent derivation (nested root finds) for a uniform elastic line anchored on
    a flat seabed, top end at horizontal distance X and height h above the anchor
    (Faltinsen 1990, ch. 8, with elasticity): unknown H and suspended length Ls,

        x_s = Ls H/EA + (H/w) asinh(w Ls / H),
        z_s = w Ls^2/(2 EA) + (H/w)(sqrt(1 + (w Ls/H)^2) - 1),

    laid part Lb = L - Ls with tension max(0, H - mu w (Lb - s)), so its stretch is
    Lb (H - mu w Lb / 2) / EA, or H^2 / (2 mu w EA) when friction exhausts it."""

    def z_s(Ls: float, H: float) -> float:
        return w * Ls**2 / (2 * EA) + H / w * (math.sqrt(1 + (w * Ls / H) ** 2) - 1)

    def x_error(H: float) -> float:
        Ls = brentq(lambda Ls: z_s(Ls, H) - h, 0.0, 10 * L, xtol=1e-15, rtol=1e-15)
        Lb = L - Ls
        xs = Ls * H / EA + H / w * math.asinh(w * Ls / H)
        if mu * w * Lb <= H:
            stretch = Lb * (H - 0.5 * mu * w * Lb) / EA
        else:
            stretch = H * H / (2 * mu * w) / EA
        return Lb + stretch + xs - X

    # x_error grows with H (a longer suspended part reaches further): bisect between a
    # nearly vertical hang and the inextensible fully suspended line, H = w (L^2 - h^2) / 2h
    H = brentq(x_error, 1e-3 * w, w * (L * L - h * h) / (2 * h), xtol=1e-12, rtol=1e-15)
    Ls = brentq(lambda Ls: z_s(Ls, H) - h, 0.0, 10 * L, xtol=1e-15, rtol=1e-15)
    return float(H), float(Ls)


@pytest.mark.parametrize("mu", [0.0, 0.5, 5.0])
@pytest.mark.parametrize("X", [205.0, 230.0, 260.0])
def test_seabed_contact_against_independent_derivation(X: float, mu: float) -> None:
    L, w, EA, depth = 300.0, 500.0, 5e8, 100.0
    H, Ls = _seabed_reference(L, w, EA, depth, X, mu)
    med = Medium(density=1025.0, gravity=9.80665, depth=depth, friction=mu)
    prob = StaticProblem(
        line=make_line([L], [w], EA),
        medium=med,
        end_a=fixed(0, 0, -depth),
        end_b=fixed(X, 0, 0),
        tolerance=1e-11,
    )
    res = SOLVER.solve(prob)
    assert res.status == 0, res.message
    # fsolve and the solver both reach ~1e-12; the comparison is at 1e-9
    assert res.laid_length == pytest.approx(L - Ls, rel=1e-9)
    assert -res.force_b[0] == pytest.approx(H, rel=1e-9)
    assert -res.force_b[2] == pytest.approx(w * Ls, rel=1e-9)
    anchor = max(0.0, H - mu * w * (L - Ls))
    assert res.force_a[0] == pytest.approx(anchor, rel=1e-9, abs=1e-9 * H)
    assert np.all(res.position[:, 2] >= -depth - 1e-9 * L)
    laid = res.s <= res.laid_length
    assert np.allclose(res.position[laid, 2], -depth, atol=1e-9 * L)


def test_seabed_lift_off_and_slack_line() -> None:
    """A line whose top end is far enough lifts off entirely (laid length 0, anchor
    force pointing up); one longer than the straight path along the seabed and up is
    reported as a failure with a message (its laid shape is not determined)."""
    med = Medium(density=1025.0, gravity=9.80665, depth=100.0)
    line = make_line([300.0], [500.0], 5e8)
    lifted = SOLVER.solve(
        StaticProblem(line=line, medium=med, end_a=fixed(0, 0, -100), end_b=fixed(280, 0, 0))
    )
    assert lifted.status == 0 and lifted.laid_length == 0.0 and lifted.force_a[2] > 0.0
    exact = solve_between(
        np.array([0, 0, -100.0]), np.array([280, 0, 0.0]), 300.0, 500.0, 5e8, lifted.s
    )
    assert np.allclose(lifted.force_a, exact.force_a, rtol=1e-8)
    slack = SOLVER.solve(
        StaticProblem(line=line, medium=med, end_a=fixed(0, 0, -100), end_b=fixed(150, 0, 0))
    )
    assert slack.status != 0 and "slack on the seabed" in slack.message
    assert np.all(np.isnan(slack.position))


@pytest.mark.parametrize("X", [160.0, 180.0, 195.0])
def test_u_shaped_line_resting_on_the_seabed_between_its_ends(X: float) -> None:
    """Expected: a uniform line with both ends h above a flat, frictionless seabed and
    span X rests on it symmetrically; each suspended half is the elastic catenary from a
    touchdown point with zero vertical tension (as in the anchored reference above):
    2 x_s(H, Ls) + (L - 2 Ls)(1 + H/EA) = X and z_s(H, Ls) = h, solved by nested root
    finds. The solver (frictionless laid part between two suspended parts) must agree to
    the 1e-9 of both solutions."""
    L, w, EA, h = 250.0, 500.0, 5e8, 50.0

    def z_s(Ls: float, H: float) -> float:
        return w * Ls**2 / (2 * EA) + H / w * (math.sqrt(1 + (w * Ls / H) ** 2) - 1)

    def suspended(H: float) -> float:
        return brentq(lambda Ls: z_s(Ls, H) - h, 0.0, 10 * L, xtol=1e-15, rtol=1e-15)

    def x_error(H: float) -> float:
        Ls = suspended(H)
        xs = Ls * H / EA + H / w * math.asinh(w * Ls / H)
        return 2 * xs + (L - 2 * Ls) * (1 + H / EA) - X

    H = brentq(x_error, 1e-3 * w, w * ((L / 2) ** 2 - h * h) / (2 * h), xtol=1e-12, rtol=1e-15)
    Ls = suspended(H)
    med = Medium(density=1025.0, gravity=9.80665, depth=100.0, friction=0.0)
    prob = StaticProblem(
        line=make_line([L], [w], EA),
        medium=med,
        end_a=fixed(0, 0, -50),
        end_b=fixed(X, 0, -50),
        n_nodes=101,
        tolerance=1e-11,
    )
    res = SOLVER.solve(prob)
    assert res.status == 0, res.message
    assert res.laid_length == pytest.approx(L - 2 * Ls, rel=1e-8)
    assert res.force_a[0] == pytest.approx(H, rel=1e-8)
    assert -res.force_a[2] == pytest.approx(w * Ls, rel=1e-9)
    assert np.all(res.position[:, 2] >= -100.0 - 1e-9 * L)
