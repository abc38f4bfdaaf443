"""Compiled kernels of the frequency domain against their reference implementations."""

from __future__ import annotations

import numpy as np
from scipy.linalg import solve_banded

from cablestudy.dynamics.frequency import _band_solve


def test_band_solve_matches_lapack_with_row_exchanges() -> None:
    rng = np.random.default_rng(3)
    n, bw = 40, 4
    A = np.zeros((n, n), dtype=complex)
    for i in range(n):
        for j in range(max(0, i - bw), min(n, i + bw + 1)):
            A[i, j] = rng.normal() + 1j * rng.normal()
    A[np.arange(n), np.arange(n)] *= 1e-3  # small pivots: row exchanges needed
    b = rng.normal(size=n) + 1j * rng.normal(size=n)
    ab = np.zeros((2 * bw + 1, n), dtype=complex)
    for i in range(n):
        for j in range(max(0, i - bw), min(n, i + bw + 1)):
            ab[bw + i - j, j] = A[i, j]
    ref = solve_banded((bw, bw), ab, b)
    work = np.zeros((3 * bw + 1, n), dtype=complex)
    work[bw:] = ab
    x = np.empty(n, dtype=complex)
    assert _band_solve(work, bw, b.copy(), x)
    # both are backward stable: the residual is round-off times |A| |x|
    np.testing.assert_allclose(A @ x, b, atol=1e-10 * np.abs(A).max() * np.abs(x).max() * n)
    np.testing.assert_allclose(x, ref, rtol=1e-8, atol=1e-10 * np.abs(ref).max())
