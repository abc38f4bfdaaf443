"""The flat arrays of a linearised mooring system for the compiled drag iteration
(:mod:`.system_fd_kernel`): per line its nodes, inner free directions (dofs) and band
rows of the reduced stiffness, mass and damping (``A[i, j]`` at ``R[i, j - i + bw]``,
one ``bw`` for all lines, wide enough for a node's whole drag block), its coupling
blocks to the end nodes and the dofs they touch, the drag and mass data of its nodes,
its full stiffness and damping (CSR, for the residual); the points' data.

Pure: a linear model in, arrays out.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from .system_fd_block import block_lines


@dataclass(frozen=True, eq=False)
class PackedSystem:
    """A :class:`~.system_frequency.SystemLinear` in flat arrays (module docstring);
    built once per model (:func:`pack_system`)."""

    arrays: tuple
    bw: int
    node_offset: np.ndarray
    dof_offset: np.ndarray


def _rows(ab: np.ndarray, bw_line: int, bw: int) -> np.ndarray:
    """LAPACK band storage ``ab`` (2 bw_line + 1, k) as row storage (k, 2 bw + 1): each
    stored entry copied to its place, zeros elsewhere (one gather, its indices built
    once per shape: :func:`_row_index`)."""
    k = ab.shape[1]
    out = np.zeros((k, 2 * bw + 1))
    to, frm = _row_index(k, bw_line, bw)
    out.ravel()[to] = ab.ravel()[frm]
    return out


@functools.lru_cache(maxsize=64)
def _row_index(k: int, bw_line: int, bw: int) -> tuple[np.ndarray, np.ndarray]:
    """Flat indices into the row storage (k, 2 bw + 1) and the band storage
    (2 bw_line + 1, k) of :func:`_rows`: ``A[i, i + d]`` is ``ab[bw_line - d, i + d]``
    and goes to ``out[i, bw + d]``, for ``|d| <= bw_line`` and ``0 <= i + d < k``."""
    i = np.repeat(np.arange(k), 2 * bw_line + 1)
    d = np.tile(np.arange(-bw_line, bw_line + 1), k)
    on = (i + d >= 0) & (i + d < k)
    i, d = i[on], d[on]
    to = i * (2 * bw + 1) + bw + d
    frm = (bw_line - d) * k + i + d
    for a in (to, frm):
        a.flags.writeable = False
    return to, frm


def pack_system(model) -> PackedSystem:  # noqa: ANN001 - SystemLinear (no import circle)
    """The packed arrays of ``model`` (a :class:`~.system_frequency.SystemLinear`)."""
    lines = model.lines
    n_nodes = np.array([r.line.n_nodes for r in lines], dtype=np.int64)
    n_dofs = np.array([r.K.shape[1] for r in lines], dtype=np.int64)
    noff = np.concatenate(([0], np.cumsum(n_nodes))).astype(np.int64)
    koff = np.concatenate(([0], np.cumsum(n_dofs))).astype(np.int64)
    counts = [np.diff(r.offsets) for r in lines]
    # one band width for all lines, wide enough for a node's full block of drag
    bw = max(
        max(r.bandwidth, int(np.max(c, initial=1)) - 1) for r, c in zip(lines, counts, strict=True)
    )
    bw = max(bw, 0)
    K = (
        np.concatenate([_rows(r.K, r.bandwidth, bw) for r in lines])
        if koff[-1]
        else np.zeros((0, 2 * bw + 1))
    )
    M = (
        np.concatenate([_rows(r.M, r.bandwidth, bw) for r in lines])
        if koff[-1]
        else np.zeros_like(K)
    )
    C = (
        np.concatenate([_rows(r.C, r.bandwidth, bw) for r in lines])
        if koff[-1]
        else np.zeros_like(K)
    )
    cp = model.couplings
    IE = [
        np.concatenate([c.K[0] for c in cp]),
        np.concatenate([c.M[0] for c in cp]),
        np.concatenate([c.C[0] for c in cp]),
    ]
    EI = [
        np.concatenate([c.K[1] for c in cp], axis=1),
        np.concatenate([c.M[1] for c in cp], axis=1),
        np.concatenate([c.C[1] for c in cp], axis=1),
    ]
    EE = [
        np.stack([c.K[2] for c in cp]),
        np.stack([c.M[2] for c in cp]),
        np.stack([c.C[2] for c in cp]),
    ]
    # per line the dofs coupled to its end nodes (non-zero rows of A_IE, columns of A_EI),
    # found over all lines' blocks at once
    nz = np.zeros(int(koff[-1]), dtype=bool)
    for Q in IE:
        nz |= np.any(Q != 0.0, axis=1)
    for Q in EI:
        nz |= np.any(Q != 0.0, axis=0)
    dof = np.flatnonzero(nz)
    of_line = np.searchsorted(koff, dof, side="right") - 1
    couple = (dof - koff[of_line]).astype(np.int64)
    coff = np.concatenate(([0], np.cumsum(np.bincount(of_line, minlength=len(lines))))).astype(
        np.int64
    )
    basis = np.concatenate([r.node_basis for r in lines])
    ncount = np.concatenate(counts).astype(np.int64)
    nfirst = np.concatenate([r.offsets[:-1] for r in lines]).astype(np.int64)

    def cat(name: str) -> np.ndarray:
        return np.ascontiguousarray(
            np.concatenate([getattr(r.line, name) for r in lines]), dtype=float
        )

    body = np.ascontiguousarray(np.concatenate([r.line.body_drag for r in lines]))
    # full (3n, 3n) stiffness and damping of every line in CSR, row pointers global
    csr = []
    for name in ("stiffness", "damping"):
        ptr, idx, val, start = [np.zeros(1, dtype=np.int64)], [], [], 0
        for r in lines:
            A = getattr(r.line, name).tocsr()
            ptr.append(A.indptr[1:].astype(np.int64) + start)
            idx.append(A.indices.astype(np.int64))
            val.append(A.data.astype(float))
            start += A.nnz
        csr += [np.concatenate(ptr), np.concatenate(idx), np.concatenate(val)]
    kind = np.asarray(model.point_kind)
    free = model.free_points
    slot = np.full(kind.size, -1, dtype=np.int64)
    slot[free] = np.arange(free.size)
    has_drag = bool(model.has_drag)
    unit = (ncount == 3) & np.all(basis == np.eye(3), axis=(1, 2))
    arrays = (
        noff,
        koff,
        K,
        M,
        C,
        *IE,
        *EI,
        *EE,
        couple,
        coff,
        basis,
        ncount,
        nfirst,
        cat("current"),
        cat("tangent"),
        cat("drag_normal"),
        cat("drag_tangential"),
        body,
        np.ascontiguousarray(np.concatenate([r.line.mass for r in lines])),
        *csr,
        np.ascontiguousarray(model.ends, dtype=np.int64),
        slot,
        free.astype(np.int64),
        np.ascontiguousarray(model.point_mass, dtype=float),
        np.ascontiguousarray(model.point_drag, dtype=float),
        np.ascontiguousarray(model.point_current, dtype=float),
        has_drag,
        # per node whether its basis is the identity (three free directions, x y z):
        # its drag enters the band as it is (:func:`.system_fd_kernel._solve`)
        unit,
        # per line whether its matrix is block tridiagonal in its nodes' 3 x 3 blocks:
        # factored by :func:`.system_fd_block.block_factor`
        block_lines(noff, koff, K, M, C, ncount, nfirst, unit, bw),
    )
    return PackedSystem(arrays=arrays, bw=bw, node_offset=noff, dof_offset=koff)
