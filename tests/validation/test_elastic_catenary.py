"""Irvine's elastic catenary (cablestudy.statics.elastic_catenary) against independent
checks: a numerical integration of the equilibrium equations, the inextensible catenary,
the hanging vertical line, end swap, mirror/rotation/translation invariance and global
equilibrium, for slack, inclined, near-vertical, buoyant and stretched-taut lines.

Expected numbers come from the equilibrium equations themselves (Irvine, *Cable
Structures*, 1981, ch. 2): with the tension vector (H e, V(s)), V = V_A + w s,

    dx/ds = (H / T) (1 + T / EA),   dz/ds = (V / T) (1 + T / EA),   T = sqrt(H^2 + V^2),

integrated here with scipy's DOP853 at rtol = atol / L = 1e-13. Its global error is a few
times 1e-13 of the line length, so profile checks use 1e-10 L (the issue's 1e-10
relative target) with three orders of margin for the integrator.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from cablestudy.statics import STATUS_OK
from cablestudy.statics.elastic_catenary import solve_between, solve_plane

G = 9.80665
#: the seed's Fig. 4 steel wire in air: 2.466 kg/m less the air it displaces [N/m]
W_STEEL = (2.466 - 1.225 * math.pi * 0.02**2 / 4.0) * G
EA_STEEL = 6.283e7  # E pi d^2 / 4 with E = 2e11 Pa, d = 0.02 m [N]

#: label -> (end A [m], end B [m], unstretched length [m], weight [N/m], EA [N])
CASES: dict[str, tuple[list[float], list[float], float, float, float]] = {
    # the dodaran-park Fig. 4 line: supports at different levels
    "fig4-inclined": ([0.0, 0.0, 0.0], [92.5, 0.0, -8.6], 100.0, W_STEEL, EA_STEEL),
    "slack-level": ([0.0, 0.0, 0.0], [50.0, 0.0, 0.0], 100.0, W_STEEL, EA_STEEL),
    "steep-inclined": ([0.0, 0.0, -50.0], [30.0, 0.0, 40.0], 100.0, W_STEEL, EA_STEEL),
    "near-vertical-slack": ([0.0, 0.0, 0.0], [0.5, 0.0, -95.0], 100.0, W_STEEL, EA_STEEL),
    # 2.5 % stretch of a soft line hanging almost straight down
    "near-vertical-taut": ([0.0, 0.0, 0.0], [1e-3, 0.0, -102.5], 100.0, W_STEEL, 1.0e5),
    # chord 100.87 m > 100 m unstretched: only the elastic stretch makes it reach
    "stretched-taut": ([0.0, 0.0, 0.0], [100.5, 0.0, 8.6], 100.0, W_STEEL, EA_STEEL),
    "skew-3d": ([10.0, -20.0, -5.0], [50.0, 30.0, -40.0], 80.0, W_STEEL, EA_STEEL),
    "buoyant": ([0.0, 0.0, -100.0], [60.0, 0.0, -80.0], 100.0, -5.0, 1.0e6),
    # EA only 10 w L: the stretch is a large part of the shape
    "soft-slack": ([0.0, 0.0, 0.0], [70.0, 0.0, -10.0], 100.0, W_STEEL, 10.0 * W_STEEL * 100),
}


def solved(label: str, n: int = 201):  # noqa: ANN201
    pa, pb, L, w, EA = CASES[label]
    s = np.linspace(0.0, L, n)
    res = solve_between(np.array(pa), np.array(pb), L, w, EA, s, tolerance=1e-12)
    assert res.status == STATUS_OK, res.message
    return res, np.array(pa), np.array(pb), L, w, EA


def integrate(
    pa: np.ndarray, force_a: np.ndarray, L: float, w: float, EA: float, s_eval: np.ndarray
) -> np.ndarray:
    """Positions (n, 3) from integrating the equilibrium equations from end A with the
    tension vector at A equal to ``force_a`` (the force on the support at A)."""
    Hvec = force_a[:2]
    VA = force_a[2]

    def rhs(s: float, y: np.ndarray) -> np.ndarray:
        V = VA + w * s
        T = math.sqrt(Hvec @ Hvec + V * V)
        stretch = 1.0 + T / EA
        return np.array([Hvec[0] / T * stretch, Hvec[1] / T * stretch, V / T * stretch])

    sol = solve_ivp(rhs, (0.0, L), pa, method="DOP853", t_eval=s_eval, rtol=1e-13, atol=1e-13 * L)
    assert sol.success
    return sol.y.T


@pytest.mark.parametrize("label", [k for k in CASES])
def test_profile_matches_integrated_equilibrium(label: str) -> None:
    res, pa, pb, L, w, EA = solved(label)
    ode = integrate(pa, res.force_a, L, w, EA, res.s)
    # the integrated line closes on B and passes through every closed-form point
    np.testing.assert_allclose(ode[-1], pb, rtol=0, atol=1e-10 * L)
    np.testing.assert_allclose(res.position, ode, rtol=0, atol=1e-10 * L)
    # tension along the line: T = |(H, V_A + w s)|, independent of the profile formula
    V = res.force_a[2] + w * res.s
    T = np.hypot(np.linalg.norm(res.force_a[:2]), V)
    np.testing.assert_allclose(res.tension, T, rtol=1e-12)


@pytest.mark.parametrize("label", [k for k in CASES])
def test_end_forces_are_the_shooting_fixed_point(label: str) -> None:
    """One Newton step of an independent shooting method (ODE closure, finite-difference
    Jacobian) from the closed-form end force moves it by < 1e-10 of the end tension: the
    closed-form forces are the integrated equations' solution to that accuracy."""
    res, pa, pb, L, w, EA = solved(label, n=3)
    e = (pb - pa)[:2] / np.linalg.norm((pb - pa)[:2])
    H, VA = float(np.linalg.norm(res.force_a[:2])), float(res.force_a[2])

    def miss(p: np.ndarray) -> np.ndarray:
        f = np.array([p[0] * e[0], p[0] * e[1], p[1]])
        end = integrate(pa, f, L, w, EA, np.array([L]))[-1]
        d = end - pb
        return np.array([d[:2] @ e, d[2]])

    p0 = np.array([H, VA])
    scale = float(np.linalg.norm(res.force_a))
    jac = np.empty((2, 2))
    for j in range(2):
        dp = np.zeros(2)
        dp[j] = 1e-5 * scale
        jac[:, j] = (miss(p0 + dp) - miss(p0 - dp)) / (2 * dp[j])
    step = np.linalg.solve(jac, -miss(p0))
    assert np.max(np.abs(step)) <= 1e-10 * scale, (step, scale)


def test_near_vertical_taut_forces_against_straight_line() -> None:
    """Hanging almost straight down and stretched 2.5 %: a vertical elastic line under its
    own weight, with top tension T_A, stretches to h = L + (T_A L - w L^2 / 2) / EA, so
    T_A = (EA (h - L) + w L^2 / 2) / L. The 1e-3 m horizontal offset changes the vertical
    forces by O((1e-3 / 100)^2) = 1e-10 relative; 1e-8 leaves margin for that term."""
    res, pa, pb, L, w, EA = solved("near-vertical-taut")
    h = pa[2] - pb[2]
    # tension at the top T_A = -V_A: h = L + (T_A L - w L^2 / 2) / EA
    TA = (EA * (h - L) + 0.5 * w * L * L) / L
    assert res.force_a[2] == pytest.approx(-TA, rel=1e-8)
    assert res.force_b[2] == pytest.approx(TA - w * L, rel=1e-8)


def test_vertical_folded_line_has_free_hanging_branches() -> None:
    """Both ends on one vertical, the line longer than their distance: it hangs in two
    vertical branches from a fold where the tension vanishes. Each branch is a vertical
    elastic line of length s_k under its own weight: drop = s_k + w s_k^2 / (2 EA)."""
    L, w, EA = 100.0, W_STEEL, 1.0e6
    pa, pb = np.array([0.0, 0.0, 0.0]), np.array([0.0, 0.0, -30.0])
    s = np.linspace(0.0, L, 11)
    res = solve_between(pa, pb, L, w, EA, s)
    assert res.status == STATUS_OK, res.message
    assert np.linalg.norm(res.force_a[:2]) == 0.0
    s_fold = -res.force_a[2] / w  # where V = V_A + w s = 0
    drop_a = s_fold + w * s_fold**2 / (2 * EA)
    drop_b = (L - s_fold) + w * (L - s_fold) ** 2 / (2 * EA)
    # both branches end at the fold: A - drop_a == B - drop_b (1e-12 L: brentq to 1e-15)
    assert pa[2] - drop_a == pytest.approx(pb[2] - drop_b, abs=1e-12 * L)
    assert res.force_a[2] + res.force_b[2] == pytest.approx(-w * L, rel=1e-14)


def test_inextensible_limit_matches_the_classic_catenary() -> None:
    """EA = 1e20 N makes stretch ~1e-17: level supports must give the classic catenary,
    L = (2 H / w) sinh(w l / (2 H)), solved for H by brentq (independent of the
    Lagrangian formulas); sag (H / w)(cosh(w l / 2H) - 1)."""
    l, L, w = 80.0, 100.0, W_STEEL
    res = solve_between(np.zeros(3), np.array([l, 0.0, 0.0]), L, w, 1e20, np.array([0.0, L / 2, L]))
    H = brentq(
        lambda H: 2 * H / w * math.sinh(w * l / (2 * H)) - L, 50.0, 1e7, xtol=1e-14, rtol=1e-15
    )
    assert res.force_a[0] == pytest.approx(H, rel=1e-10)
    assert res.force_a[2] == pytest.approx(-w * L / 2, rel=1e-12)
    sag = H / w * (math.cosh(w * l / (2 * H)) - 1.0)
    assert res.position[1, 2] == pytest.approx(-sag, rel=1e-10)
    assert res.position[1, 0] == pytest.approx(l / 2, rel=1e-12)


def test_weightless_taut_line_is_a_straight_spring() -> None:
    """w = 0 and chord d > L: a straight spring, T = EA (d / L - 1), uniform stretch."""
    L, EA = 10.0, 1e5
    pa, pb = np.array([1.0, 2.0, 3.0]), np.array([4.0, 10.0, -3.0])
    d = float(np.linalg.norm(pb - pa))
    s = np.linspace(0, L, 5)
    res = solve_between(pa, pb, L, 0.0, EA, s)
    assert res.status == STATUS_OK
    T = EA * (d / L - 1.0)
    np.testing.assert_allclose(res.tension, T, rtol=1e-14)
    np.testing.assert_allclose(res.force_a, T * (pb - pa) / d, rtol=1e-14, atol=1e-12 * T)
    np.testing.assert_allclose(res.position, pa + np.outer(s / L, pb - pa), atol=1e-13 * L)


@pytest.mark.parametrize("label", [k for k in CASES])
def test_end_swap_gives_the_same_line(label: str) -> None:
    """The line from B to A is the same line: forces exchange ends, s runs backwards.
    Both are solved to round-off, so agreement to 1e-10 (end tension, length)."""
    res, pa, pb, L, w, EA = solved(label)
    rev = solve_between(pb, pa, L, w, EA, res.s, tolerance=1e-12)
    assert rev.status == STATUS_OK
    T = max(np.linalg.norm(res.force_a), np.linalg.norm(res.force_b))
    np.testing.assert_allclose(rev.force_a, res.force_b, rtol=0, atol=1e-10 * T)
    np.testing.assert_allclose(rev.force_b, res.force_a, rtol=0, atol=1e-10 * T)
    np.testing.assert_allclose(rev.position, res.position[::-1], rtol=0, atol=1e-10 * L)
    np.testing.assert_allclose(rev.tension, res.tension[::-1], rtol=0, atol=1e-10 * T)


@pytest.mark.parametrize("label", ["fig4-inclined", "skew-3d", "stretched-taut", "buoyant"])
def test_mirror_rotation_and_translation_invariance(label: str) -> None:
    """Mirroring y -> -y, rotating about z by 0.7 rad and translating the supports moves
    the line and its end forces with them."""
    res, pa, pb, L, w, EA = solved(label)
    T = float(np.linalg.norm(res.force_a))
    c, s_ = math.cos(0.7), math.sin(0.7)
    maps = {
        "mirror": np.diag([1.0, -1.0, 1.0]),
        "rotate": np.array([[c, -s_, 0.0], [s_, c, 0.0], [0.0, 0.0, 1.0]]),
    }
    shift = np.array([123.0, -45.0, 6.0])
    for name, R in maps.items():
        out = solve_between(R @ pa + shift, R @ pb + shift, L, w, EA, res.s, tolerance=1e-12)
        assert out.status == STATUS_OK, name
        np.testing.assert_allclose(
            out.position, res.position @ R.T + shift, rtol=0, atol=1e-10 * L, err_msg=name
        )
        np.testing.assert_allclose(
            out.force_a, R @ res.force_a, rtol=0, atol=1e-10 * T, err_msg=name
        )
        np.testing.assert_allclose(
            out.force_b, R @ res.force_b, rtol=0, atol=1e-10 * T, err_msg=name
        )


@pytest.mark.parametrize("label", [k for k in CASES])
def test_end_forces_carry_the_weight(label: str) -> None:
    """Forces on the two supports sum to the line's weight (down) with no horizontal
    resultant; their magnitudes are the end tensions."""
    res, pa, pb, L, w, EA = solved(label)
    total = res.force_a + res.force_b
    scale = max(abs(w) * L, float(np.linalg.norm(res.force_a)))
    np.testing.assert_allclose(total, [0.0, 0.0, -w * L], rtol=0, atol=1e-12 * scale)
    assert np.linalg.norm(res.force_a) == pytest.approx(res.tension[0], rel=1e-14)
    assert np.linalg.norm(res.force_b) == pytest.approx(res.tension[-1], rel=1e-14)


def test_plane_solver_rejects_weightless_slack_line() -> None:
    """A weightless line not stretched between its ends has no unique shape: a failure
    with a message, not an exception or NaN with status 0."""
    sol, status, msg = solve_plane(5.0, 0.0, 10.0, 0.0, 1e5)
    assert sol is None and status != STATUS_OK and "weightless" in msg
