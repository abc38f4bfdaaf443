"""The linearised line of the frequency domain (:mod:`.frequency` gives the
formulation): the line about its static shape (:class:`LinearLine`) reduced to its free
degrees of freedom (:class:`ReducedLine`: banded mass, damping and stiffness), the drag
settings and its linearisation (the planar fit, the gain of a harmonic), the result of
a harmonic solve (:class:`FrequencyResult`), and the response of a line without drag:
one banded linear solve (:func:`solve_undamped`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numba import njit
from scipy.linalg import solve_banded

from ..statics.base import STATUS_NUMERICAL, STATUS_OK

#: status of a case whose drag linearisation did not converge
STATUS_NOT_CONVERGED = 7


@dataclass(frozen=True, kw_only=True, eq=False)
class LinearLine:
    """A line linearised about its static shape (n nodes, n - 1 elements).

    Parameters
    ----------
    s : [m] (n,) unstretched arc length of the nodes from end A
    position : [m] (n, 3) static node positions
    mass : [kg] (n, 3, 3) lumped mass blocks, added mass included
    stiffness : [N/m] (3n, 3n) tangent stiffness (elastic, geometric, bending)
    damping : [N s/m] (3n, 3n) structural damping
    rest_length : [m] (n - 1,) unstretched element lengths l0
    direction : [-] (n - 1, 3) unit element chords t
    axial_stiffness : [N] (n - 1,) EA of each element
    axial_damping : [N s] (n - 1,) c of each element (tension c * strain rate)
    tension : [N] (n - 1,) static element tension
    end_force : [N] (2, 3) static force of the line on the supports at A and B
    drag_normal, drag_tangential : [kg/m] (n,) nodal drag coefficients 1/2 rho C_N d l
        and 1/2 rho pi C_T d l (l: tributary length)
    current : [m/s] (n, 3) current velocity at the nodes
    tangent : [-] (n, 3) unit tangent at the nodes
    free_basis : [-] (3n, k) orthonormal free directions, block per node
    drag_body : [kg/m] (n,) isotropic drag coefficients 1/2 rho C_D A of lumped bodies
        at the nodes (drag ``c |w| w``), or None for none
    """

    s: np.ndarray
    position: np.ndarray
    mass: np.ndarray
    stiffness: sp.csr_matrix
    damping: sp.csr_matrix
    rest_length: np.ndarray
    direction: np.ndarray
    axial_stiffness: np.ndarray
    axial_damping: np.ndarray
    tension: np.ndarray
    end_force: np.ndarray
    drag_normal: np.ndarray
    drag_tangential: np.ndarray
    current: np.ndarray
    tangent: np.ndarray
    free_basis: sp.csr_matrix
    drag_body: np.ndarray | None = None

    @property
    def n_nodes(self) -> int:
        return int(self.s.size)

    @property
    def body_drag(self) -> np.ndarray:
        """[kg/m] (n,) the bodies' drag coefficients (zeros without bodies)."""
        if self.drag_body is None:
            return np.zeros(self.n_nodes)
        return np.ascontiguousarray(self.drag_body, dtype=float)

    @property
    def has_drag(self) -> bool:
        return bool(
            np.any(self.drag_normal > 0.0)
            or np.any(self.drag_tangential > 0.0)
            or np.any(self.body_drag > 0.0)
        )

    def mass_matrix(self) -> sp.csr_matrix:
        """Block-diagonal mass (3n, 3n) [kg]."""
        return block_diagonal(self.mass)


def block_diagonal(blocks: np.ndarray) -> sp.csr_matrix:
    """Sparse block-diagonal matrix of ``blocks`` (n, 3, 3)."""
    n = blocks.shape[0]
    rows = (3 * np.arange(n)[:, None, None] + np.arange(3)[None, :, None]).repeat(3, 2)
    cols = (3 * np.arange(n)[:, None, None] + np.arange(3)[None, None, :]).repeat(3, 1)
    return sp.csr_matrix((blocks.ravel(), (rows.ravel(), cols.ravel())), shape=(3 * n, 3 * n))


#: weight of the lean ``D_0`` in the sampled drag fit, relative to the trace of the
#: velocity covariance: ``D = (H + e D_0)(G + e I)^-1`` with ``e`` this times the trace,
#: so a direction in which the node moves by less than about 1e-3 of its largest
#: amplitude leans towards ``D_0`` (the single line's and the system's kernels: the
#: drag's mean Jacobian, :mod:`.drag_lean`; the reference fit of
#: tests/drag_fit_reference.py: the one given). The fit in such a direction is ill-determined
#: (a thin velocity ellipse: out of plane on a line in a cross current) and fed back
#: into the motion it made the drag iteration stall at 1e-7 to 1e-5; with 1e-10 the
#: cross-current lines of tests/unit/test_harmonic_cases.py took 3 to 47 iterations and
#: did not converge below 1e-8, with 1e-6 they take 3 to 12 and converge to 1e-10, and
#: their end tensions move by at most 1.3e-6 (against 1e-8, converged to 1e-9).
FIT_REGULARISATION = 1e-6


@dataclass(frozen=True, kw_only=True)
class DragSettings:
    """Drag iteration: ``tolerance`` [-] on the relative change of the nodal velocity
    amplitudes, ``max_iterations``, and ``samples`` phases per period in the fit; with
    ``exact`` a node moving in the x-z plane is fitted in closed form
    (:func:`planar_drag_fit`), any other node without current by the exact period
    means (:func:`.elliptic_fit.still_water_means`), and the phases serve the nodes in
    a current."""

    tolerance: float = 1e-6
    max_iterations: int = 100
    samples: int = 32
    exact: bool = True


@dataclass(kw_only=True)
class FrequencyResult:
    """Harmonic response at one frequency (complex amplitudes of ``Re(Q e^{i w t})``).

    displacement [m] (n, 3); element_tension [N] (n - 1,) tension variation;
    end_tension [N] (2,) variation of the end tensions at A and B; tension_static [N]
    (2,) static end tensions; drag_iterations, drag_converged, drag_change (last
    relative change); status, message.
    """

    displacement: np.ndarray
    element_tension: np.ndarray
    end_tension: np.ndarray
    tension_static: np.ndarray
    drag_iterations: int = 0
    drag_converged: bool = True
    drag_change: float = 0.0
    status: int = STATUS_OK
    message: str = ""

    @property
    def success(self) -> bool:
        return self.status == STATUS_OK


def block_band_places(counts: np.ndarray, bw: int) -> tuple[np.ndarray, ...]:
    """Per entry of the nodes' reduced blocks (``counts[i]`` coordinates at node ``i``):
    its node, row and column in the block, and its row and column in band storage."""
    sizes = counts**2
    blk_i = np.repeat(np.arange(counts.size), sizes)
    local = np.arange(int(sizes.sum())) - np.repeat(np.cumsum(sizes) - sizes, sizes)
    k_of = counts[blk_i]
    blk_r = local // np.maximum(k_of, 1)
    blk_c = local % np.maximum(k_of, 1)
    offset = np.concatenate(([0], np.cumsum(counts)[:-1]))
    band_r = bw + blk_r - blk_c
    band_c = offset[blk_i] + blk_c
    return blk_i, blk_r, blk_c, band_r, band_c


def singular_result(n: int, tension_static: np.ndarray, omega: float) -> FrequencyResult:
    """NaN response of ``n`` nodes, singular dynamic matrix at ``omega`` [rad/s]."""
    return FrequencyResult(
        displacement=np.full((n, 3), np.nan + 0j),
        element_tension=np.full(n - 1, np.nan + 0j),
        end_tension=np.full(2, np.nan + 0j),
        tension_static=tension_static,
        status=STATUS_NUMERICAL,
        message=f"singular dynamic matrix at {omega / (2 * math.pi):.6g} Hz",
    )


def sum_components(p: np.ndarray) -> np.ndarray:
    """``np.sum(p, axis=-1)`` of ``p`` (..., 3), bit for bit (numpy adds from a zero:
    ``((0 + x) + y) + z``, which fixes the sign of a sum of zeros and the order), with
    three array additions instead of numpy's reduction over an axis of three (five
    times slower on a sweep's (cases, nodes, 3) arrays)."""
    return 0.0 + p[..., 0] + p[..., 1] + p[..., 2]


def drag_force(line: LinearLine, relative_velocity: np.ndarray) -> np.ndarray:
    """Morison drag [N] (..., n, 3) on the nodes for relative velocities (..., n, 3)."""
    t = line.tangent
    wt = np.einsum("...ia,ia->...i", relative_velocity, t)[..., None]
    wn = relative_velocity - wt * t
    sn = np.sqrt(np.einsum("...a,...a->...", wn, wn))[..., None]
    out = line.drag_normal[:, None] * sn * wn + line.drag_tangential[:, None] * np.abs(wt) * wt * t
    if line.drag_body is not None:
        sr = np.sqrt(np.einsum("...a,...a->...", relative_velocity, relative_velocity))[..., None]
        out = out + line.body_drag[:, None] * sr * relative_velocity
    return out


def drag_tangent(line: LinearLine) -> np.ndarray:
    """d f / d w [N s/m] (n, 3, 3) at the mean flow ``w = U_c`` (small-motion limit)."""
    t = line.tangent
    U = line.current
    ut = np.sum(U * t, axis=1)
    un = U - ut[:, None] * t
    sn = np.linalg.norm(un, axis=1)
    P = np.eye(3) - t[:, :, None] * t[:, None, :]
    safe = np.where(sn > 0.0, sn, 1.0)
    Dn = sn[:, None, None] * P + np.where(sn > 0.0, 1.0 / safe, 0.0)[:, None, None] * (
        un[:, :, None] * un[:, None, :]
    )
    Dt = 2.0 * np.abs(ut)[:, None, None] * (t[:, :, None] * t[:, None, :])
    out = line.drag_normal[:, None, None] * Dn + line.drag_tangential[:, None, None] * Dt
    if line.drag_body is not None:  # c |U| I + c U U^T / |U|
        su = np.linalg.norm(U, axis=1)
        inv = np.where(su > 0.0, 1.0 / np.where(su > 0.0, su, 1.0), 0.0)
        Db = su[:, None, None] * np.eye(3) + inv[:, None, None] * (U[:, :, None] * U[:, None, :])
        out = out + line.body_drag[:, None, None] * Db
    return out


@njit(cache=True, inline="always")
def harmonic_gain(U, c):  # noqa: ANN001, ANN201
    """``b_1 / c`` [m/s] for ``g(x) = |x| x`` of ``x = U + c cos(psi)`` (``c >= 0``), with
    ``b_1`` the first Fourier coefficient of ``g`` in ``psi``: the equivalent (energy)
    gain of the quadratic law about a mean flow ``U`` for a harmonic oscillation of
    amplitude ``c``. Where ``x`` changes sign (``|U| < c``), at ``psi_0 = arccos(-U /
    c)``, integrating ``x^2 cos(psi)`` over ``[0, psi_0]`` and ``[psi_0, pi]`` gives, with
    ``mu = U / c`` and ``s_0 = sin(psi_0) = sqrt(1 - mu^2)``,
    ``b_1 / c = c (2 / pi) (2 mu psi_0 + 2 s_0 (2 + mu^2) / 3 - mu pi)``
    (``8 c / (3 pi)`` in still water); otherwise ``x`` keeps its sign and ``b_1 / c = 2
    |U|`` exactly (the tangent at the mean flow). Both meet at ``|mu| = 1``."""
    if not c > 0.0:
        return 2.0 * abs(U)
    if U == 0.0:  # still water
        return c * (8.0 / (3.0 * math.pi))
    mu = U / c
    if mu >= 1.0 or mu <= -1.0:
        return 2.0 * abs(U)
    psi0 = math.acos(-mu)
    s0 = math.sqrt(1.0 - mu * mu)
    return c * (2.0 / math.pi) * (2.0 * mu * psi0 + 2.0 * s0 * (2.0 + mu * mu) / 3.0 - mu * math.pi)


@njit(cache=True, inline="always")
def is_planar(vr, vi, t, u, i):  # noqa: ANN001, ANN201
    """Node ``i``'s velocity amplitude ``vr + i vi``, tangent ``t`` and current ``u``
    (n, 3) have no y component."""
    return vr[i, 1] == 0.0 and vi[i, 1] == 0.0 and t[i, 1] == 0.0 and u[i, 1] == 0.0


@njit(cache=True, inline="always")
def still_water(u, i):  # noqa: ANN001, ANN201
    """Node ``i`` has no current (``u`` (n, 3)): its drag fit has exact period means in
    closed form (:func:`.elliptic_fit.still_water_means`)."""
    return u[i, 0] == 0.0 and u[i, 1] == 0.0 and u[i, 2] == 0.0


@njit(cache=True, inline="always")
def planar_drag_fit(vr, vi, t, u, c_n, c_t, tangent_d, i, out):  # noqa: ANN001, ANN201, PLR0913
    """The drag fit of node ``i`` whose tangent ``(t0, 0, t2)``, current ``(u0, 0, u2)``
    and velocity amplitude ``(a0 + i b0, 0, a2 + i b2)`` lie in the x-z plane, in closed
    form (the limit of the sampled fit as the phases grow, without its aliasing error,
    which is about 1e-4 of the gain at 32 phases): in the plane the normal and
    tangential relative velocities are scalars ``U_N + c_N cos(th + phi_N)`` and ``U_T +
    c_T cos(th + phi_T)`` along ``nu = (-t2, 0, t0)`` and ``t``, the normal drag
    ``c_N |w_N| w_N nu`` depends on the normal one alone and the tangential on the
    tangential one alone, so the first harmonic of the drag is ``k_N w_N' nu + k_T
    w_T' t`` with ``k = c harmonic_gain(U, c)``: ``D = k_N nu nu^T + k_T t t^T`` in the
    plane. The y row and column are those of the small-motion tangent ``tangent_d``
    (n, 3, 3), as in the sampled fit for a direction in which the node does not move;
    a node at rest takes that tangent whole. ``out`` (n, 3, 3) receives ``D`` at ``i``
    (arrays and an index rather than a node's views: no view is made per node)."""
    a0, a2 = vr[i, 0], vr[i, 2]
    b0, b2 = vi[i, 0], vi[i, 2]
    if a0 == 0.0 and a2 == 0.0 and b0 == 0.0 and b2 == 0.0:
        for a in range(3):
            for b in range(3):
                out[i, a, b] = tangent_d[i, a, b]
        return
    t0, t2 = t[i, 0], t[i, 2]
    vn_re = -t2 * a0 + t0 * a2
    vn_im = -t2 * b0 + t0 * b2
    vt_re = t0 * a0 + t2 * a2
    vt_im = t0 * b0 + t2 * b2
    u0, u2 = u[i, 0], u[i, 2]
    kn = c_n[i] * harmonic_gain(-t2 * u0 + t0 * u2, math.sqrt(vn_re * vn_re + vn_im * vn_im))
    kt = c_t[i] * harmonic_gain(t0 * u0 + t2 * u2, math.sqrt(vt_re * vt_re + vt_im * vt_im))
    out[i, 0, 0] = kn * t2 * t2 + kt * t0 * t0
    out[i, 0, 2] = kt * t0 * t2 - kn * t2 * t0
    out[i, 2, 0] = out[i, 0, 2]
    out[i, 2, 2] = kn * t0 * t0 + kt * t2 * t2
    out[i, 0, 1] = tangent_d[i, 0, 1]
    out[i, 1, 1] = tangent_d[i, 1, 1]
    out[i, 2, 1] = tangent_d[i, 2, 1]
    out[i, 1, 0] = 0.0
    out[i, 1, 2] = 0.0


def _band_of(row: np.ndarray, col: np.ndarray, val: np.ndarray, bw: int, size: int) -> np.ndarray:
    """The (size, size) matrix of the distinct entries ``val`` at (``row``, ``col``) in
    LAPACK band storage with ``bw`` sub- and super-diagonals."""
    ab = np.zeros((2 * bw + 1, size), dtype=val.dtype)
    np.add.at(ab, (bw + row - col, col), val)
    return ab


def selected_rows(B: sp.spmatrix) -> np.ndarray | None:
    """The row of each column of ``B`` when every column is a coordinate direction (a
    single non-zero, 1, besides stored zeros) and the rows increase with the columns
    (the free basis of :func:`~cablestudy.dynamics.linear_model.linear_line`, and that
    basis without its y columns); None otherwise. Then ``B^T A B`` is ``A`` at those
    rows and columns, entry by entry (a sum of one product by 1 and of products by
    zero, for finite ``A``)."""
    if not (sp.issparse(B) and B.format == "csr"):
        return None
    nz = B.data != 0.0
    if not np.all(B.data[nz] == 1.0):
        return None
    rows = np.repeat(np.arange(B.shape[0]), np.diff(B.indptr))[nz]
    if rows.size != B.shape[1] or not np.array_equal(B.indices[nz], np.arange(B.shape[1])):
        return None
    if rows.size > 1 and not np.all(rows[1:] > rows[:-1]):
        return None
    return rows


def csr_entries(A: sp.spmatrix) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """(rows, columns, values) of the stored entries of ``A`` when it is a CSR matrix in
    canonical form (sorted, no duplicates) with finite values; None otherwise."""
    if not (sp.issparse(A) and A.format == "csr" and A.has_canonical_format):
        return None
    if not np.all(np.isfinite(A.data)):
        return None
    return np.repeat(np.arange(A.shape[0]), np.diff(A.indptr)), A.indices, A.data


def block_entries(blocks: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """:func:`csr_entries` of :func:`block_diagonal` of ``blocks`` (n, 3, 3), without
    building it; None where a value is not finite."""
    if not np.all(np.isfinite(blocks)):
        return None
    node = 3 * np.arange(blocks.shape[0])[:, None, None]
    a = np.arange(3)
    rows = np.broadcast_to(node + a[None, :, None], blocks.shape).ravel()
    cols = np.broadcast_to(node + a[None, None, :], blocks.shape).ravel()
    return rows, cols, np.ascontiguousarray(blocks, dtype=float).ravel()


def _selected(
    entries: tuple[np.ndarray, np.ndarray, np.ndarray], column_of: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The non-zero entries (rows, columns, values) of ``B^T A B`` for a coordinate basis
    ``B`` (:func:`selected_rows`), with ``column_of`` the column of ``B`` at each row of
    ``A`` (-1 where none) and ``entries`` those of ``A`` (:func:`csr_entries`): the same
    entries as scipy's products, which drop the zeros they compute."""
    row, col, val = entries
    r, c = column_of[row], column_of[col]
    keep = (r >= 0) & (c >= 0) & (val != 0.0)
    return r[keep], c[keep], val[keep]


@dataclass(frozen=True, eq=False)
class ReducedLine:
    """The matrices of a :class:`LinearLine` projected once on its free basis, in band
    storage (node order keeps them banded), reused by every frequency and amplitude
    of a sweep; per frequency only the drag blocks change."""

    line: LinearLine
    K: np.ndarray
    M: np.ndarray
    C: np.ndarray
    bandwidth: int
    node_basis: np.ndarray
    band_index: tuple[np.ndarray, np.ndarray]
    block_index: tuple[np.ndarray, np.ndarray, np.ndarray]
    offsets: np.ndarray

    @classmethod
    def of(cls, line: LinearLine) -> ReducedLine:
        B = line.free_basis
        n = line.n_nodes
        rows = selected_rows(B)
        parts = (
            None
            if rows is None
            else (csr_entries(line.stiffness), block_entries(line.mass), csr_entries(line.damping))
        )
        if rows is not None and parts is not None and all(p is not None for p in parts):
            # coordinate free directions: the projections pick entries (no products)
            column_of = np.full(B.shape[0], -1, dtype=np.int64)
            column_of[rows] = np.arange(rows.size)
            reduced = [_selected(p, column_of) for p in parts]  # type: ignore[arg-type]
            node = rows // 3
            counts = np.bincount(node, minlength=n)
            first = np.concatenate(([0], np.cumsum(counts)[:-1]))
            padded = np.zeros((n, 3, 3))
            padded[node, rows % 3, np.arange(rows.size) - first[node]] = 1.0
        else:
            reduced = []
            for A in (line.stiffness, line.mass_matrix(), line.damping):
                coo = (B.T @ A @ B).tocoo()
                reduced.append((coo.row, coo.col, coo.data))
            # per node its free basis, padded with zero columns to (3, 3); a node's
            # columns are those with a non-zero in its three rows, in column order
            coo = sp.coo_matrix(B)
            keep = coo.data != 0.0
            row, col, val = coo.row[keep], coo.col[keep], coo.data[keep]
            node = row // 3
            pairs, where = np.unique(node * max(B.shape[1], 1) + col, return_inverse=True)
            pair_node = pairs // max(B.shape[1], 1)
            counts = np.bincount(pair_node, minlength=n)
            first = np.concatenate(([0], np.cumsum(counts)[:-1]))
            rank = np.arange(pairs.size) - first[pair_node]
            padded = np.zeros((n, 3, 3))
            padded[node, row % 3, rank[where]] = val
        bw = max(int(np.max(np.abs(r - c), initial=0)) for r, c, _ in reduced)
        # wide enough for a node's whole block, which the drag fills even where the
        # stiffness leaves zeros (a single inner node of a line in the y-z plane: x
        # uncoupled, band 1 from the entries, a drag block of band 2)
        bw = max(bw, int(np.max(counts, initial=1)) - 1)
        size = B.shape[1]
        blk_i, blk_r, blk_c, band_r, band_c = block_band_places(counts, bw)
        K, M, C = (_band_of(r, c, v, bw, size) for r, c, v in reduced)
        return cls(
            line=line,
            K=K,
            M=M,
            C=C,
            bandwidth=bw,
            node_basis=padded,
            band_index=(band_r, band_c),
            block_index=(blk_i, blk_r, blk_c),
            offsets=np.concatenate(([0], np.cumsum(counts))).astype(np.int64),
        )

    def drag_band(self, D: np.ndarray) -> np.ndarray:
        """The drag blocks ``D`` (n, 3, 3) projected on the free basis, in band storage."""
        b = self.node_basis
        blocks = np.swapaxes(b, 1, 2) @ D @ b
        out = np.zeros(self.K.shape)
        out[self.band_index] = blocks[self.block_index]
        return out

    def apply(self, u: np.ndarray, omega: float, D: np.ndarray | None) -> np.ndarray:
        """``[K - w^2 M + i w (C + D)] u`` [N] (n, 3) for displacements ``u`` (n, 3)."""
        line = self.line
        flat = u.ravel()
        out = line.stiffness @ flat + 1j * omega * (line.damping @ flat)
        out = out.reshape(-1, 3) - omega**2 * np.einsum("iab,ib->ia", line.mass, u)
        if D is not None:
            out = out + 1j * omega * np.einsum("iab,ib->ia", D, u)
        return out


def solve_undamped(red: ReducedLine, omega: float, end_motion: np.ndarray) -> FrequencyResult:
    """Steady harmonic response of a line without drag at angular frequency ``omega``
    [rad/s] to the end displacements ``end_motion`` [m] (2, 3) complex (A and B): one
    linear solve, LAPACK's band solver (:func:`.frequency.solve_harmonic` of such a line).
    Never raises for a numerical failure."""
    line = red.line
    n = line.n_nodes
    static_mag = np.linalg.norm(line.end_force, axis=1)
    failed = singular_result(n, static_mag, omega)
    # no drag: one linear solve, LAPACK's band solver
    B = line.free_basis
    up = np.zeros((n, 3), dtype=complex)
    up[0], up[-1] = end_motion[0], end_motion[-1]
    # right side: the prescribed end motion through the dynamic matrix
    rhs = -(B.T @ red.apply(up, omega, None).ravel())
    u = up.copy()
    if rhs.size:
        ab = red.K - omega**2 * red.M + 1j * omega * red.C
        bw = red.bandwidth
        try:
            q = solve_banded((bw, bw), ab, rhs, check_finite=False)
        except (np.linalg.LinAlgError, ValueError):
            return failed
        if not np.all(np.isfinite(q)):
            return failed
        u = (B @ q).reshape(n, 3) + up
    du = np.diff(u, axis=0)
    axial = (line.axial_stiffness + 1j * omega * line.axial_damping) / line.rest_length
    element_tension = axial * np.sum(line.direction * du, axis=1)
    reaction = red.apply(u, omega, None)
    support = -np.stack([reaction[0], reaction[-1]])  # change of the force on the supports
    unit = line.end_force / np.where(static_mag > 0.0, static_mag, 1.0)[:, None]
    end_tension = np.sum(unit * support, axis=1)
    return FrequencyResult(
        displacement=u,
        element_tension=element_tension,
        end_tension=end_tension,
        tension_static=static_mag,
        status=STATUS_OK,
        message="",
    )
