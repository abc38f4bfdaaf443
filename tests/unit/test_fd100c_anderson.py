"""Anderson mixing of the system frequency domain without BLAS or LAPACK (issue 24's speed
work): its sums (:func:`cablestudy.dynamics.system_fd_fit._dot`) and its small solve
(:func:`cablestudy.dynamics.system_fd_fit._small_solve`) within their rounding bounds of
the exact answers, and the whole step the normal equations' solution it replaces."""

from __future__ import annotations

import math

import numpy as np

from cablestudy.dynamics.system_fd_fit import DEPTH, MIXING, _dot, _small_solve, anderson

EPS = np.finfo(float).eps


def test_dot_within_the_bound_of_a_summation() -> None:
    """Against the exactly rounded sum (``math.fsum`` of the products, each exact to
    half an ulp): any order of n - 1 additions errs by at most ``gamma_n sum |a_i b_i|``
    (``gamma_n = n eps / (1 - n eps)``, Higham's bound for recursive summation), here
    with the products' own rounding (one more unit)."""
    rng = np.random.default_rng(100)
    for n in (0, 1, 3, 4, 5, 17, 1809):
        a = rng.standard_normal(n) * 10.0 ** rng.integers(-3, 3, n)
        b = rng.standard_normal(n)
        exact = math.fsum(float(x) * float(y) for x, y in zip(a, b, strict=True))
        bound = (n + 1) * EPS / (1 - (n + 1) * EPS) * float(np.sum(np.abs(a * b)))
        assert abs(_dot(a, b, n) - exact) <= bound, n
        # the same bits whatever the call (a fixed order): a case's mixing is its own
        assert _dot(a, b, n) == _dot(a.copy(), b.copy(), n)


def test_small_solve_is_backward_stable_and_refuses_a_singular_system() -> None:
    """Gaussian elimination with partial pivoting of an m x m system (m <= DEPTH, as the
    mixing's): the residual within ``c m^2 eps |A| |x|`` (backward stability, growth
    factor at most 2^(m-1)), on Gram matrices as the mixing forms them, some nearly
    singular (two histories almost alike) with the mixing's regularisation; a zero
    pivot (an exactly singular matrix) is refused."""
    rng = np.random.default_rng(24)
    for trial in range(300):
        m = 1 + trial % DEPTH
        dR = rng.standard_normal((m, 50))
        if trial % 5 == 0 and m > 1:
            dR[1] = dR[0] + 1e-9 * rng.standard_normal(50)
        A = dR @ dR.T
        A += 1e-12 * np.trace(A) * np.eye(m)
        b = dR @ rng.standard_normal(50)
        x = b.copy()
        assert _small_solve(A.copy(), x, m)
        growth = 2.0 ** (m - 1)
        bound = 4 * m * m * growth * EPS * np.abs(A).max() * np.abs(x).sum() * m
        assert np.max(np.abs(A @ x - b)) <= bound, trial
    singular = np.array([[1.0, 2.0], [2.0, 4.0]])
    assert not _small_solve(singular, np.array([1.0, 1.0]), 2)


def test_a_mixing_step_is_the_normal_equations_solution() -> None:
    """With a history of pairs the mixed iterate is ``gbar - (1 - MIXING) rbar``,
    ``gbar = g - sum_j gam_j (g - G_j)``, ``rbar = r - sum_j gam_j (r - R_j)``, with
    ``gam`` solving ``(dR dR^T + 1e-12 tr I) gam = dR r`` (the NumPy reference's step,
    tests/system_frequency_reference.py); with one pair ``d + MIXING r`` bit for bit.
    Equal to rounding of the small system: its condition number times eps relative to
    the iterate's size, times the cancellation of forming ``(r - R_a) . (r - R_b)``
    from the residuals' Gram matrix (each product is rounded relative to ``|r|^2``,
    ``|R_a|^2``, not to the differences')."""
    rng = np.random.default_rng(7)
    size = 40
    keep = DEPTH + 1
    hist_R = np.empty((keep, size))
    hist_G = np.empty((keep, size))
    gram = np.empty((keep, keep))
    state = np.zeros(2, dtype=np.int64)
    d = rng.standard_normal(size)
    last = math.inf
    change = 1.0
    for _ in range(8):
        g = 0.5 * d + rng.standard_normal(size)  # a contraction plus noise
        count, head = int(state[0]), int(state[1])
        if count == keep:
            head, count = (head + 1) % keep, count - 1
        rows = [(head + j) % keep for j in range(count)]
        old_R = [hist_R[r].copy() for r in rows]
        old_G = [hist_G[r].copy() for r in rows]
        r = g - d
        want = d + MIXING * r
        tol = 0.0
        if old_R:
            dR = np.array([r - q for q in old_R])
            A = dR @ dR.T
            A += 1e-12 * np.trace(A) * np.eye(len(old_R))
            gam = np.linalg.solve(A, dR @ r)
            gbar = g - sum(gj * (g - Gj) for gj, Gj in zip(gam, old_G, strict=True))
            rbar = r - sum(gj * (r - Rj) for gj, Rj in zip(gam, old_R, strict=True))
            want = gbar - (1.0 - MIXING) * rbar
            cancel = max(r @ r, *(q @ q for q in old_R)) / np.abs(A).max()
            scale = np.abs(g).max() + np.abs(old_G).max() + np.abs(old_R).max()
            tol = 100 * np.linalg.cond(A) * EPS * scale * max(1.0, cancel)
        change *= 0.5  # shrinking: no restart
        got = d.copy()
        anderson(got, g, hist_R, hist_G, gram, state, change, last)
        last = change
        assert np.max(np.abs(got - want)) <= tol
        d = got
