"""Compiled kernels of the frequency domain against independent references: the band
solve against LAPACK, the closed-form harmonic drag gain against quadrature, the
sampled drag fit against the closed form as the phases grow, and the batched fit
against the per-node reference fit."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import solve_banded

from cablestudy.dynamics.frequency_model import FIT_REGULARISATION, harmonic_gain
from cablestudy.dynamics.harmonic_cases import _rows
from cablestudy.dynamics.harmonic_kernel import band_solve_rows, drag_fit_samples
from tests.drag_fit_reference import _drag_fit, drag_linearisation


def _random_band(n: int, bw: int, diag_scale: float, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    A = np.zeros((n, n), dtype=complex)
    for i in range(n):
        for j in range(max(0, i - bw), min(n, i + bw + 1)):
            A[i, j] = rng.normal() + 1j * rng.normal()
    A[np.arange(n), np.arange(n)] *= diag_scale
    b = rng.normal(size=n) + 1j * rng.normal(size=n)
    return A, b


@pytest.mark.parametrize("diag_scale", [1e-3, 1.0, 30.0], ids=["exchanges", "mixed", "dominant"])
def test_band_solve_matches_lapack(diag_scale: float) -> None:
    """Small diagonals force row exchanges (fill-in beyond the band); a dominant one
    needs none. Both solvers are backward stable, so the residual is round-off times
    |A| |x| n, and the two answers differ by at most the condition number times that
    (rtol 1e-8 leaves a factor 1e5 over the 1e-16 unit round-off for it)."""
    n, bw = 40, 4
    A, b = _random_band(n, bw, diag_scale, seed=3)
    ab = np.zeros((2 * bw + 1, n), dtype=complex)
    for i in range(n):
        for j in range(max(0, i - bw), min(n, i + bw + 1)):
            ab[bw + i - j, j] = A[i, j]
    ref = solve_banded((bw, bw), ab, b)
    R = _rows(ab, bw)
    x = np.empty(n, dtype=complex)
    assert band_solve_rows(R, bw, np.empty(n, dtype=np.int64), b.copy(), x)
    np.testing.assert_allclose(A @ x, b, atol=1e-13 * np.abs(A).max() * np.abs(x).max() * n)
    np.testing.assert_allclose(x, ref, rtol=1e-8, atol=1e-10 * np.abs(ref).max())


def test_band_solve_reports_a_singular_matrix() -> None:
    n, bw = 12, 2
    A, b = _random_band(n, bw, 1.0, seed=4)
    A[:, 5] = 0.0  # a zero column: no pivot at step 5
    ab = np.zeros((2 * bw + 1, n), dtype=complex)
    for i in range(n):
        for j in range(max(0, i - bw), min(n, i + bw + 1)):
            ab[bw + i - j, j] = A[i, j]
    assert not band_solve_rows(
        _rows(ab, bw), bw, np.empty(n, dtype=np.int64), b, np.empty(n, complex)
    )


def _first_harmonic(U: float, c: float, points: int = 200_000) -> float:
    """b_1 / c of |x| x for x = U + c cos(psi), by the trapezoid rule on the period
    (error ~ points^-3 from the kink of the second derivative: 1e-16 here)."""
    psi = 2.0 * np.pi * np.arange(points) / points
    x = U + c * np.cos(psi)
    return float(2.0 * np.mean(np.abs(x) * x * np.cos(psi)) / c)


@pytest.mark.parametrize(
    ("U", "c"),
    [(0.0, 1.0), (0.3, 1.0), (-0.3, 1.0), (0.99, 1.0), (1.0, 1.0), (2.5, 1.0), (-4.0, 0.5)],
)
def test_harmonic_gain_is_the_first_harmonic(U: float, c: float) -> None:
    """The closed form against quadrature, to its round-off (1e-12: the quadrature's
    error is 1e-16 and the formula's a few ulps of terms of size 1)."""
    assert harmonic_gain(U, c) == pytest.approx(_first_harmonic(U, c), rel=1e-12, abs=1e-14)


def test_harmonic_gain_limits() -> None:
    """Still water: the classical 8 c / (3 pi); no sign change (|U| >= c): the tangent
    2 |U|, exactly; no motion: the tangent too."""
    assert harmonic_gain(0.0, 2.0) == pytest.approx(2.0 * 8.0 / (3.0 * math.pi), rel=1e-15)
    assert harmonic_gain(1.5, 1.0) == 3.0
    assert harmonic_gain(-1.5, 1.0) == 3.0
    assert harmonic_gain(0.7, 0.0) == 1.4
    # continuous where the sign change begins
    assert harmonic_gain(1.0 - 1e-9, 1.0) == pytest.approx(2.0, abs=1e-8)


def _fit_one(
    node: tuple[np.ndarray, ...], cn: float, ct: float, samples: int, exact: bool
) -> np.ndarray:
    """_drag_fit of one node ``(t, vr, vi, u)`` without a body (1, 3, 3)."""
    t, vr, vi, u = node
    out = np.empty((1, 3, 3))
    td = _tangent(t, u, cn, ct)
    _drag_fit(vr, vi, u, t, np.array([cn]), np.array([ct]), np.zeros(1), td, samples, exact, out)
    return out


def _planar_node(rng: np.random.Generator) -> tuple[np.ndarray, ...]:
    th = rng.uniform(0.0, np.pi)
    t = np.array([[math.cos(th), 0.0, math.sin(th)]])
    vr = np.array([[rng.normal(), 0.0, rng.normal()]])
    vi = np.array([[rng.normal(), 0.0, rng.normal()]])
    u = np.array([[0.4 * rng.normal(), 0.0, 0.4 * rng.normal()]])
    return t, vr, vi, u


def _tangent(t: np.ndarray, u: np.ndarray, cn: float, ct: float) -> np.ndarray:
    tt = t[0]
    ut = float(u[0] @ tt)
    un = u[0] - ut * tt
    sn = float(np.linalg.norm(un))
    P = np.eye(3) - np.outer(tt, tt)
    Dn = sn * P + (np.outer(un, un) / sn if sn > 0.0 else 0.0)
    return (cn * Dn + ct * 2.0 * abs(ut) * np.outer(tt, tt))[None]


def test_sampled_fit_converges_to_the_closed_form_at_third_order() -> None:
    """For motion in the x-z plane the fit over ``samples`` phases aliases the odd
    harmonics k = samples -+ 1 of |x| x into the first; they fall as k^-3 (the law's
    second derivative jumps where x changes sign), so the sampled fit's distance to its
    limit (the closed form, regularised as the sampled fit is) is bounded by C
    samples^-3. Where the sign changes fall between the phases moves the
    error up and down at a given count, so the test bounds it instead of reading an
    order from two counts: error x samples^3 / |D| stays under 50 (observed 1 to 30)
    from 32 to 1024 phases, and the least-squares slope of log error is between -3.5
    and -2.2 (observed -2.4 to -3.3), on nodes with and without a current."""
    rng = np.random.default_rng(8)
    cn, ct = 1.7, 0.4
    counts = np.array([32, 64, 128, 256, 512, 1024])
    for _ in range(6):
        node = _planar_node(rng)
        t, vr, vi, u = node
        td = _tangent(t, u, cn, ct)
        closed = _fit_one(node, cn, ct, 32, True)
        # the sampled fit is regularised, D = (H + e D_0)(G + e I)^-1 with e =
        # FIT_REGULARISATION tr G; without aliasing H = D_closed G, and G = (a a^T + b
        # b^T) / 2 exactly at any number of phases, so its limit is
        G = 0.5 * (np.outer(vr[0], vr[0]) + np.outer(vi[0], vi[0]))
        e = FIT_REGULARISATION * np.trace(G)
        exact = ((closed[0] @ G + e * td[0]) @ np.linalg.inv(G + e * np.eye(3)))[None]
        errs = []
        for samples in counts:
            got = _fit_one(node, cn, ct, int(samples), False)
            errs.append(np.abs(got - exact)[0][np.ix_([0, 2], [0, 2])].max())
        errs = np.array(errs)
        assert np.all(errs * counts**3 / np.abs(exact).max() < 50.0), errs
        slope = np.polyfit(np.log(counts), np.log(errs), 1)[0]
        assert -3.5 < slope < -2.2, (slope, errs)


def test_closed_form_fit_dissipates_the_mean_drag_power() -> None:
    """Energy equivalence: with the relative velocity w' = -Re(v e^{i th}), the mean
    power of the drag's fluctuation <f' . w'> equals that of the fit <(D w') . w'>,
    both by the trapezoid rule on 200,000 phases (error 1e-16)."""
    rng = np.random.default_rng(9)
    cn, ct = 1.2, 0.3
    th = 2.0 * np.pi * np.arange(200_000) / 200_000
    for _ in range(5):
        node = _planar_node(rng)
        t, vr, vi, u = node
        D = _fit_one(node, cn, ct, 8, True)
        w = -(vr[0][None] * np.cos(th)[:, None] - vi[0][None] * np.sin(th)[:, None])
        r = u[0][None] + w
        rt = r @ t[0]
        rn = r - rt[:, None] * t[0][None]
        f = cn * np.linalg.norm(rn, axis=1)[:, None] * rn + ct * (np.abs(rt) * rt)[:, None] * t[0]
        f = f - f.mean(axis=0)
        power = np.mean(np.sum(f * w, axis=1))
        fitted = np.mean(np.sum((w @ D[0].T) * w, axis=1))
        assert fitted == pytest.approx(power, rel=1e-10)


@pytest.mark.parametrize("exact", [True, False])
def test_batched_fit_is_the_reference_fit(exact: bool) -> None:
    """drag_fit_samples (the batched solver's layout) gives _drag_fit's numbers bit for
    bit, given the lean it takes (the mean Jacobian, dynamics/drag_lean.py, which it
    writes into ``lean``; the small-motion tangent ``td`` where a node takes the planar
    closed form), on nodes in the x-z plane and out of it, moving and at rest, with a
    current, with and without a body's drag."""
    rng = np.random.default_rng(10)
    n, samples = 12, 32
    vr = rng.normal(size=(n, 3))
    vi = rng.normal(size=(n, 3))
    t = rng.normal(size=(n, 3))
    u = 0.3 * rng.normal(size=(n, 3))
    planar = np.arange(n) % 2 == 0
    for a in (vr, vi, t, u):
        a[planar, 1] = 0.0
    vr[4] = vi[4] = 0.0  # at rest, in the plane
    vr[5] = vi[5] = 0.0  # at rest, out of it
    t /= np.linalg.norm(t, axis=1)[:, None]
    td = np.concatenate([_tangent(t[i : i + 1], u[i : i + 1], 1.1, 0.2) for i in range(n)])
    cn, ct = np.full(n, 1.1), np.full(n, 0.2)
    cb = np.where(np.arange(n) % 3 == 1, 0.7, 0.0)  # bodies on some nodes
    got = np.empty((n, 3, 3))
    cos = np.cos(2.0 * np.pi * np.arange(samples) / samples)
    sin = np.sin(2.0 * np.pi * np.arange(samples) / samples)
    work = [np.empty((n, samples)) for _ in range(6)]
    kind, lean = np.empty(n, np.int64), np.empty((n, 3, 3))
    drag_fit_samples(vr, vi, u, t, cn, ct, cb, td, cos, sin, exact, *work, kind, lean, got)
    closed_planar = exact & planar & (cb == 0.0)
    lean[closed_planar] = td[closed_planar]
    ref = np.empty((n, 3, 3))
    _drag_fit(vr, vi, u, t, cn, ct, cb, lean, samples, exact, ref)
    assert got.tobytes() == ref.tobytes()


def test_body_drag_fit_and_tangent() -> None:
    """A lumped body's isotropic drag c |w| w: in still water and motion of velocity
    amplitude a along one direction the fit is the classical 8 c a / (3 pi) along it
    (4096 phases: aliasing below 1e-10; regularised as every sampled fit); its
    small-motion tangent at a current U is c (|U| I + U U^T / |U|), the derivative of
    drag_force (central differences, step 1e-6 of |U|: error ~1e-12 relative)."""
    from dataclasses import replace

    from cablestudy.dynamics.frequency_model import drag_force, drag_tangent
    from cablestudy.dynamics.harmonic_cases import warm_up_line

    line = warm_up_line()
    n = line.n_nodes
    body = replace(
        line,
        drag_normal=np.zeros(n),
        drag_tangential=np.zeros(n),
        drag_body=np.full(n, 0.8),
    )
    v = np.zeros((n, 3), dtype=complex)
    v[:, 2] = 0.3 * np.exp(1j * 0.4)  # a = 0.3 m/s along z
    D = drag_linearisation(body, v, samples=4096)
    # the fit's regularisation scales it by 1 / (1 + FIT_REGULARISATION) here (the
    # small-motion tangent it leans to is zero in still water)
    want = 0.8 * 8.0 * 0.3 / (3.0 * math.pi) / (1.0 + FIT_REGULARISATION)
    assert D[:, 2, 2] == pytest.approx(want, rel=1e-10)
    U = np.array([0.3, -0.2, 0.5])
    current = replace(body, current=np.tile(U, (n, 1)))
    T = drag_tangent(current)[1]
    h = 1e-6 * np.linalg.norm(U)
    fd = np.empty((3, 3))
    for b in range(3):
        dw = np.zeros((n, 3))
        dw[:, b] = h
        fd[:, b] = (drag_force(current, U + dw) - drag_force(current, U - dw))[1] / (2.0 * h)
    np.testing.assert_allclose(T, fd, rtol=1e-8, atol=1e-10)
