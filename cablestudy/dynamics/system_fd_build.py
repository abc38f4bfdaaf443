"""The reduced lines of a system's frequency-domain model built in one pass over all
lines (issue 24: ``method: auto`` builds the model before it judges a case, and the
per-line construction cost a time-domain case's time again).

Every line of :func:`~.system_frequency.system_linear` is held at both end nodes
(:func:`~.linear_model.held_ends_basis`): its free directions are the coordinates of
the inner nodes, in order. Projecting a matrix on that basis is then picking its
entries at the inner rows and columns, and the couplings to the end nodes are its
entries at the inner rows and the end columns (and the transpose), entry by entry.
:func:`held_lines` does that for the stiffness, mass and damping of all lines at once
(one concatenation of their entries, one selection, one scatter into flat arrays whose
slices are each line's band and coupling blocks), instead of
:meth:`.frequency_model.ReducedLine.of` and
:func:`~.system_frequency._coordinate_coupling` line by line (general bases, each
entry found by index arithmetic per line). The arithmetic is the same (each stored
value copied once, into zeros; the reduced matrices keep the non-zero entries, the
couplings every stored entry), so both give the same arrays bit for bit
(tests/unit/test_system_fd_build.py).

Pure: linear lines in, reduced lines and coupling blocks out.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence

import numpy as np
import scipy.sparse as sp

from .frequency_model import LinearLine, ReducedLine, block_band_places
from .linear_model import _held_ends


@functools.lru_cache(maxsize=64)
def _held_layout(n: int, bw: int) -> tuple[np.ndarray, ...]:
    """:class:`ReducedLine`'s ``node_basis``, ``band_index``, ``block_index`` and
    ``offsets`` of a line of ``n`` nodes held at both ends with band ``bw``, as
    :meth:`ReducedLine.of` computes them for that basis (read-only: shared)."""
    rows = np.arange(3, 3 * max(n - 1, 1), dtype=np.int64) if n > 2 else np.zeros(0, np.int64)
    node = rows // 3
    counts = np.bincount(node, minlength=n)
    first = np.concatenate(([0], np.cumsum(counts)[:-1]))
    padded = np.zeros((n, 3, 3))
    padded[node, rows % 3, np.arange(rows.size) - first[node]] = 1.0
    blk_i, blk_r, blk_c, band_r, band_c = block_band_places(counts, bw)
    offsets = np.concatenate(([0], np.cumsum(counts))).astype(np.int64)
    out = (padded, band_r, band_c, blk_i, blk_r, blk_c, offsets, counts)
    for a in out:
        a.flags.writeable = False
    return out


def _held(line: LinearLine) -> bool:
    """Whether the line's free basis is :func:`~.linear_model.held_ends_basis` (its
    stored arrays byte for byte): the basis :func:`held_lines` is exact for."""
    B = line.free_basis
    n = line.n_nodes
    if not (sp.issparse(B) and B.format == "csr" and B.shape == (3 * n, 3 * max(n - 2, 0))):
        return False
    H = _held_ends(n)
    data, indices, indptr = H.data, H.indices, H.indptr
    return (
        B.data.dtype == data.dtype
        and B.indices.dtype == indices.dtype
        and B.indptr.dtype == indptr.dtype
        and B.indptr.tobytes() == indptr.tobytes()
        and B.indices.tobytes() == indices.tobytes()
        and B.data.tobytes() == data.tobytes()
    )


def _entries(
    lines: Sequence[LinearLine],
) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]] | None:
    """Per matrix (stiffness, mass, damping) the stored entries of all lines, flat:
    (line, row, column, value), as :func:`~.frequency_model.csr_entries` and
    :func:`~.frequency_model.block_entries` give each line's; None where a line's are
    not at hand (not canonical CSR, or a value not finite)."""
    L = len(lines)
    n = np.array([ln.n_nodes for ln in lines], dtype=np.int64)
    out = []
    for kind in ("stiffness", "mass", "damping"):
        if kind == "mass":
            blocks = np.concatenate([ln.mass for ln in lines])
            if not np.all(np.isfinite(blocks)):
                return None
            node = np.arange(blocks.shape[0]) - np.repeat(np.cumsum(n) - n, n)
            a = np.arange(3)
            rows = np.broadcast_to(3 * node[:, None, None] + a[None, :, None], blocks.shape)
            cols = np.broadcast_to(3 * node[:, None, None] + a[None, None, :], blocks.shape)
            which = np.repeat(np.arange(L), 9 * n)
            out.append((which, rows.ravel(), cols.ravel(), blocks.ravel().astype(float)))
            continue
        mats = [getattr(ln, kind) for ln in lines]
        if not all(sp.issparse(A) and A.format == "csr" and A.has_canonical_format for A in mats):
            return None
        data = np.concatenate([A.data for A in mats]).astype(float)
        if not np.all(np.isfinite(data)):
            return None
        per_row = np.concatenate([np.diff(A.indptr) for A in mats])
        local_row = np.arange(per_row.size) - np.repeat(np.cumsum(3 * n) - 3 * n, 3 * n)
        which = np.repeat(np.arange(L), [A.data.size for A in mats])
        cols = np.concatenate([A.indices for A in mats]).astype(np.int64)
        out.append((which, np.repeat(local_row, per_row), cols, data))
    return out


def held_lines(
    lines: Sequence[LinearLine],
) -> tuple[list[ReducedLine], list[tuple[tuple[np.ndarray, ...], ...]]] | None:
    """Each line's :class:`ReducedLine` and its end couplings (the (K, M, C) blocks of
    :class:`~.system_frequency.EndCoupling`: ``IE`` (k, 6), ``EI`` (6, k), ``EE``
    (6, 6) each), for lines held at both end nodes, built over all lines at once
    (module docstring); None where a line's basis is not the held ends' or its
    matrices are not at hand (then the plain construction applies)."""
    L = len(lines)
    if L == 0:
        return [], []
    if not all(_held(line) for line in lines):
        return None
    got = _entries(lines)
    if got is None:
        return None
    n = np.array([ln.n_nodes for ln in lines], dtype=np.int64)
    k = 3 * np.maximum(n - 2, 0)
    picked = []
    bw = np.zeros(L, dtype=np.int64)
    for which, row, col, val in got:
        n3 = 3 * n[which]
        r_in = (row >= 3) & (row < n3 - 3)
        c_in = (col >= 3) & (col < n3 - 3)
        r_end = np.where(row < 3, row, row - n3 + 6)
        c_end = np.where(col < 3, col, col - n3 + 6)
        keep = r_in & c_in & (val != 0.0)
        r, c = row - 3, col - 3
        np.maximum.at(bw, which[keep], np.abs(r[keep] - c[keep]))
        picked.append((which, r, c, val, r_in, c_in, r_end, c_end, keep))
    # wide enough for a node's whole block (the drag's), as ReducedLine.of
    bw = np.maximum(bw, np.where(n > 2, 2, 0))
    width = 2 * bw + 1
    band_start = np.concatenate(([0], np.cumsum(width * k)))
    ie_start = np.concatenate(([0], np.cumsum(6 * k)))
    bands, couplings = [], []
    for which, r, c, val, r_in, c_in, r_end, c_end, keep in picked:
        band = np.zeros(int(band_start[-1]))
        w = which[keep]
        band[band_start[w] + (bw[w] + r[keep] - c[keep]) * k[w] + c[keep]] = val[keep]
        ie = np.zeros(int(ie_start[-1]))
        m = r_in & ~c_in
        w = which[m]
        ie[ie_start[w] + r[m] * 6 + c_end[m]] = val[m]
        ei = np.zeros(int(ie_start[-1]))
        m = ~r_in & c_in
        w = which[m]
        ei[ie_start[w] + r_end[m] * k[w] + c[m]] = val[m]
        ee = np.zeros((L, 6, 6))
        m = ~r_in & ~c_in
        ee[which[m], r_end[m], c_end[m]] = val[m]
        bands.append(band)
        couplings.append((ie, ei, ee))
    reduced, blocks = [], []
    for i, line in enumerate(lines):
        b, ki = int(bw[i]), int(k[i])
        padded, band_r, band_c, blk_i, blk_r, blk_c, offsets, _ = _held_layout(int(n[i]), b)
        K, M, C = (band[band_start[i] : band_start[i + 1]].reshape(2 * b + 1, ki) for band in bands)
        reduced.append(
            ReducedLine(
                line=line,
                K=K,
                M=M,
                C=C,
                bandwidth=b,
                node_basis=padded,
                band_index=(band_r, band_c),
                block_index=(blk_i, blk_r, blk_c),
                offsets=offsets,
            )
        )
        blocks.append(
            tuple(
                (
                    ie[ie_start[i] : ie_start[i + 1]].reshape(ki, 6),
                    ei[ie_start[i] : ie_start[i + 1]].reshape(6, ki),
                    ee[i],
                )
                for ie, ei, ee in couplings
            )
        )
    return reduced, blocks


__all__ = ["held_lines"]
