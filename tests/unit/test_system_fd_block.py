"""The block-tridiagonal factor of the system's frequency domain
(:mod:`cablestudy.dynamics.system_fd_block`) against the band factor it stands in for.

Without a row exchange the LU factors of a matrix are unique, and the block factor does
the band factor's own operations on them in the same order (each entry less its
products by the multipliers in the order of the pivots; the same quotient for a
pivot's inverse): where the band factor exchanges no rows the two give the same bits,
so those tests ask for equality, not a tolerance. Where the band factor would exchange
rows the block factor declines, and the kernel runs the band factor from the start:
the answer is then the band factor's, bit for bit, too.
"""

from __future__ import annotations

import numpy as np
import pytest

from cablestudy.dynamics.frequency_model import DragSettings
from cablestudy.dynamics.system_fd_block import block_factor
from cablestudy.dynamics.system_fd_kernel import _band_factor, _line_rows
from cablestudy.dynamics.system_fd_sweep import solve_sweep
from cablestudy.dynamics.system_frequency import prescribed_motion
from tests.unit.test_system_fd_kernel import _case8_model

BW = 5


def _line(n: int, seed: int, *, weak_first: bool = False):  # noqa: ANN202
    """Band rows (3n, 2 BW + 1) of a random complex block-tridiagonal matrix of n nodes
    (diagonal blocks dominant, as a dynamic stiffness is, unless ``weak_first``: the
    first pivot then 1e-3 of the entries below it), drag blocks D of its n + 2 nodes
    (ends included) and the node layout of :func:`_line_rows`."""
    rng = np.random.default_rng(seed)
    k = 3 * n
    dense = np.zeros((k, k), dtype=complex)
    for s in range(n):
        blk = slice(3 * s, 3 * s + 3)
        dense[blk, blk] = rng.normal(size=(3, 3)) + 1j * rng.normal(size=(3, 3)) + 8.0 * np.eye(3)
        if s + 1 < n:
            nxt = slice(3 * s + 3, 3 * s + 6)
            dense[blk, nxt] = rng.normal(size=(3, 3)) + 1j * rng.normal(size=(3, 3))
            dense[nxt, blk] = rng.normal(size=(3, 3)) + 1j * rng.normal(size=(3, 3))
    if weak_first:
        dense[0, 0] = 1e-3
    rows = np.zeros((k, 2 * BW + 1), dtype=complex)
    for i in range(k):
        for j in range(max(0, i - BW), min(k, i + BW + 1)):
            rows[i, j - i + BW] = dense[i, j]
    D = rng.normal(size=(n + 2, 3, 3))
    ncount = np.array([0] + [3] * n + [0], dtype=np.int64)
    nfirst = np.array([0, *range(0, k, 3), k], dtype=np.int64)
    unit = ncount == 3
    basis = np.broadcast_to(np.eye(3), (n + 2, 3, 3)).copy()
    return rows, D, ncount, nfirst, unit, basis


def _sides(k: int, m: int, seed: int) -> np.ndarray:
    """m right sides: the first non-zero throughout (a prescribed end's motion), the
    others zero down to the last node (a free end's unit motions)."""
    rng = np.random.default_rng(seed)
    B = np.zeros((k, m), dtype=complex)
    B[:, 0] = rng.normal(size=k) + 1j * rng.normal(size=k)
    B[k - 3 :, 1:] = rng.normal(size=(3, m - 1))
    return B


@pytest.mark.parametrize("rev", [False, True])
@pytest.mark.parametrize("drag", [False, True])
def test_block_factor_is_the_band_factors_lu(rev: bool, drag: bool) -> None:
    """The upper factor, the pivots' inverses and the eliminated right sides are the band
    factor's, bit for bit (module docstring), read in either order with or without
    drag; the band factor's upper rows are zero beyond the next node, where the block
    factor's rows end."""
    n, m, w = 7, 3, 0.8
    rows, D, ncount, nfirst, unit, basis = _line(n, 1)
    k = 3 * n
    iw = 1j * w
    R = np.zeros((k, 3 * BW + 1), dtype=complex)
    _line_rows(R, rows, 0, k, rev, BW, drag, 0, n + 1, ncount, nfirst, unit, basis, D, iw)
    B = _sides(k, m, 2)
    reach, pinv = np.zeros(k, dtype=np.int64), np.zeros(k, dtype=complex)
    assert _band_factor(R, BW, k, reach, B, m, pinv)
    Rb = np.zeros_like(R)
    Bb = _sides(k, m, 2)
    reach_b, pinv_b = np.zeros(k, dtype=np.int64), np.zeros(k, dtype=complex)
    g0 = n if rev else 1
    assert block_factor(rows, 0, k, rev, BW, drag, D, g0, iw, Rb, reach_b, Bb, m, pinv_b)
    assert np.array_equal(pinv_b, pinv)
    assert np.array_equal(Bb, B)
    for i in range(k):
        assert reach_b[i] == min(3 * (i // 3) + 5, k - 1)
        span = slice(BW, BW + reach_b[i] - i + 1)
        assert np.array_equal(Rb[i, span], R[i, span])
        assert not np.any(R[i, BW + reach_b[i] - i + 1 : BW + reach[i] - i + 1])


def test_block_factor_declines_where_the_band_factor_exchanges_rows() -> None:
    """A first pivot 1e-3 of the entries below it: the band factor exchanges rows and
    solves the system to rounding; the block factor declines."""
    n, m = 5, 2
    rows, D, ncount, nfirst, unit, basis = _line(n, 3, weak_first=True)
    k = 3 * n
    R = np.zeros((k, 3 * BW + 1), dtype=complex)
    _line_rows(R, rows, 0, k, False, BW, False, 0, n + 1, ncount, nfirst, unit, basis, D, 0j)
    Rb = np.zeros_like(R)
    assert not block_factor(
        rows, 0, k, False, BW, False, D, 1, 0j, Rb, np.zeros(k, dtype=np.int64),
        _sides(k, m, 4), m, np.zeros(k, dtype=complex),
    )  # fmt: skip
    reach, pinv = np.zeros(k, dtype=np.int64), np.zeros(k, dtype=complex)
    B = _sides(k, m, 4)
    assert _band_factor(R, BW, k, reach, B, m, pinv)
    assert reach[0] > 5  # a row exchange widened the first row's reach


def test_kernel_falls_back_to_the_band_factor_bit_for_bit() -> None:
    """case8 with the equations of a node in the middle of one line scaled by 1e4 (its
    multipliers then far above the pivot threshold's bound): the block factor declines
    on that line (checked on its matrix without drag; the drag, 1e-4 of those rows'
    entries, cannot change that) and serves the others.
    The kernel's answers with the block factor allowed are those of the band factor
    alone on every line, bit for bit (the kernel's residual check reads the unchanged
    full matrices, so it is not a check here)."""
    model = _case8_model(9)
    p = model.packed
    arrays = list(p.arrays)
    assert np.all(arrays[39])  # every case8 line is block tridiagonal
    line, bw = 3, p.bw
    k0, k = int(p.dof_offset[line]), int(p.dof_offset[line + 1] - p.dof_offset[line])
    # line 4 runs from a junction to the spar: eliminated from its end B (rev), its right
    # sides already carried through the nodes before the weak one when the block factor
    # declines (so the kernel must build them again)
    ends, slot = arrays[31], arrays[32]
    rev = bool(slot[ends[line, 0]] >= 0 and slot[ends[line, 1]] < 0)
    assert rev
    mid = k0 + 3 * (k // 6)  # a middle node's rows, scaled: its multipliers 1e4 larger
    for idx in (2, 3, 4):  # K, M, C band rows
        rows = arrays[idx].copy()
        rows[mid : mid + 3] *= 1e4
        arrays[idx] = rows
    w = 2 * np.pi * np.array([0.05, 0.2])
    for omega in w:
        A = arrays[2] - omega**2 * arrays[3] + 1j * omega * arrays[4]
        B = np.ones((k, 1), dtype=complex)
        assert not block_factor(
            A.astype(complex), k0, k, rev, bw, False, np.zeros((1, 3, 3)), 0, 0j,
            np.zeros((k, 3 * bw + 1), dtype=complex), np.zeros(k, dtype=np.int64), B, 1,
            np.zeros(k, dtype=complex),
        )  # fmt: skip
    motion = np.array([[-0.5j, 0, 0, 0, 0, 0]])
    pres = np.ascontiguousarray(np.stack([prescribed_motion(model, motion)] * w.size))
    N, P, L = int(p.node_offset[-1]), pres.shape[1], len(model.lines)
    s = DragSettings()
    out = []
    for blocky in (arrays[39], np.zeros_like(arrays[39])):
        packed = (*arrays[:39], blocky)
        res = (
            np.empty((w.size, N, 3), dtype=complex),
            np.empty((w.size, P, 3), dtype=complex),
            np.empty((w.size, L, 6), dtype=complex),
            np.zeros((w.size, 4), dtype=np.int64),
            np.zeros((w.size, 2)),
        )
        solve_sweep(w, pres, s.tolerance, s.max_iterations, s.samples, s.exact, packed, bw, *res)
        out.append(res)
    for a, b in zip(out[0], out[1], strict=True):
        assert np.array_equal(a, b)
    assert np.all(out[0][3][:, 0] == 0)  # converged, no singular line
