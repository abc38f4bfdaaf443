"""Natural frequencies and mode shapes of a line about its static shape.

The line is cut at the sample points of a :class:`~cablestudy.statics.StaticResult`
into straight two-node bar elements (nodes at the static positions). Small motions
``u`` of the nodes about that shape obey ``M u'' + K u = 0``; the modes solve the
generalized symmetric eigenproblem ``K phi = omega^2 M phi``.

Mass (lumped, block-diagonal 3 x 3 per node). Element e between nodes e and e+1, with
unstretched length l0, unit chord vector t and projector P = I - t t^T, gives each of
its nodes half of::

    l0 [ (m + m_an) P + (m + m_at) t t^T ],   m_an = rho C_an pi d^2 / 4,
                                             m_at = rho C_at pi d^2 / 4,

so the fluid's added mass acts in the directions normal to the line only (and along
it where ``added_mass_tangential`` is nonzero). Attachment masses are split between
the two nodes of the element holding them (linear interpolation), without added mass.

Stiffness (tangent of the bar forces). A bar of tension T = EA (l / l0 - 1) and
current chord length l gives ``K_e = (EA / l0) t t^T + (T / l) P`` acting on the
difference of its end displacements: the elastic term along the chord and the
geometric (string) term across it. T is the static tension at the element midpoint
(mean of the nodal tensions), not the chord strain, so the geometric stiffness is
the static tension however stiff the line is.

Bending (tensioned-beam terms, Euler-Bernoulli, EI [N m^2]). The discrete curvature
at an interior node i is kappa_i = (t_i - t_{i-1}) / h_i with h_i the mean unstretched
length of its two elements; the bending energy sum EI_i |t_i - t_{i-1}|^2 / (2 h_i) is
linearised about the static shape (its Gauss-Newton part J^T J, which is exact for a
straight line and drops terms of order EI times static curvature). No curvature is
kept at the end nodes: both ends are moment-free (pinned).

Boundary conditions. A ``fixed`` end node has no degree of freedom. A ``force`` end
(towing) is free in all three directions: the applied force is a dead load (fixed
magnitude and direction) and adds no stiffness; the node keeps its half-element
mass. A ``mooring`` end is free horizontally and held at its height (z fixed).
Nodes resting on the seabed (static ``laid_length`` > 0 and the node on the seabed
plane) are held in the direction normal to the seabed (a bilateral, rigid seabed). On a
frictionless seabed they are free along it; with friction they stick (held in all
directions): for small vibrations static friction does not let the laid line slide,
and where friction has taken all the tension out of the laid part a free node there
would have no lateral stiffness at all (a singular eigenproblem).

Solution. The constraints keep one orthonormal basis of free directions per node, so
the reduced mass stays block-diagonal; with its block Cholesky factor L the problem
becomes the standard banded symmetric eigenproblem ``L^-1 K L^-T y = omega^2 y``
(half-bandwidth at most 8 degrees of freedom), solved for the lowest modes only: by
ARPACK in shift-invert mode about 0 (:func:`scipy.sparse.linalg.eigsh` on a sparse
LU of the banded matrix), or for small models and when half or more of the modes are
wanted by LAPACK's banded solver (:func:`scipy.linalg.eig_banded`).

Accuracy. Lumped masses and linear elements make the frequencies converge as h^2:
for a taut string the discrete frequencies are exactly
``omega_n = 2 sqrt(T / (m h^2)) sin(n pi h / (2 L))``, i.e. a relative error of about
-(n pi h / L)^2 / 24. Where the tension varies by orders of magnitude along the line
(a riser whose bottom tension is small against its weight), elements of equal length
miss the short waves at the low-tension end; :func:`graded_arc_lengths` places the
nodes at equal transverse-wave travel time instead (the caller samples the static
solution there, see :func:`cablestudy.analyses.solve_modal`). The grading uses the
tension only; with EI the low-tension end is over-resolved, which costs accuracy
elsewhere but not convergence.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.linalg import eig_banded
from scipy.sparse.linalg import ArpackError, eigsh

from ..statics.base import (
    STATUS_NUMERICAL,
    STATUS_OK,
    STATUS_TIME_LIMIT,
    EndCondition,
    LineModel,
    Medium,
    StaticResult,
)

#: status of a modal analysis about a static solution that failed
STATUS_STATIC_FAILED = 5
#: status of a static shape with a slack or compressed element (no stable modes)
STATUS_SLACK = 6


@dataclass(frozen=True, kw_only=True)
class ModalProblem:
    """Inputs of a modal analysis.

    Parameters
    ----------
    line : LineModel
        Segments (mass [kg/m], diameter [m], EA [N], EI [N m^2], added-mass
        coefficients [-]) and attachments (mass [kg]).
    medium : Medium
        Fluid density [kg/m^3] (added mass) and seabed.
    end_a, end_b : EndCondition
        End kinds ``fixed``, ``force`` or ``mooring``.
    static : StaticResult
        Static shape sampled at the nodes of the model: ``s`` [m] increasing from 0 to
        the line length, ``position`` [m] (n, 3), ``tension`` [N] (n,).
    n_modes : int
        Number of lowest modes wanted.
    include_added_mass : bool
        Add the fluid's added mass (``added_mass_normal`` normal to the line,
        ``added_mass_tangential`` along it).
    include_bending : bool
        Add the bending stiffness EI of the segments.
    """

    line: LineModel
    medium: Medium
    end_a: EndCondition
    end_b: EndCondition
    static: StaticResult
    n_modes: int = 10
    include_added_mass: bool = True
    include_bending: bool = True


@dataclass(kw_only=True)
class ModalResult:
    """Lowest natural frequencies and mode shapes.

    frequency [Hz] (n_modes,), increasing; mode_shape [m] (n_modes, n_nodes, 3): nodal
    displacements scaled so that the largest nodal displacement is 1 m and its largest
    component is positive; s [m] (n_nodes,) the nodes; n_dof the number of degrees of
    freedom; status, message as for static results.
    """

    s: np.ndarray
    frequency: np.ndarray
    mode_shape: np.ndarray
    n_dof: int = 0
    status: int = STATUS_OK
    message: str = ""

    @property
    def success(self) -> bool:
        return self.status == STATUS_OK

    @classmethod
    def failed(
        cls, s: np.ndarray, n_modes: int, status: int, message: str, n_dof: int = 0
    ) -> ModalResult:
        return cls(
            s=s,
            frequency=np.full(n_modes, np.nan),
            mode_shape=np.full((n_modes, len(s), 3), np.nan),
            n_dof=n_dof,
            status=status,
            message=message,
        )

    def shape_at(self, s: np.ndarray) -> np.ndarray:
        """Mode shapes interpolated linearly (the elements' own shape functions) to the
        arc lengths ``s`` [m]; shape (n_modes, len(s), 3) [m]."""
        s = np.asarray(s, dtype=float)
        out = np.empty((self.mode_shape.shape[0], len(s), 3))
        for k in range(self.mode_shape.shape[0]):
            for c in range(3):
                out[k, :, c] = np.interp(s, self.s, self.mode_shape[k, :, c])
        return out


def _segment_index(line: LineModel, s_mid: np.ndarray) -> np.ndarray:
    """Segment holding each arc length (elements straddling a joint take the segment
    of their midpoint)."""
    ends = line.segment_ends
    idx = np.searchsorted(ends, s_mid, side="right") - 1
    return np.clip(idx, 0, len(line.length) - 1)


def _free_basis(constrained: np.ndarray) -> np.ndarray:
    """Orthonormal basis (3, k) of the directions orthogonal to the columns of
    ``constrained`` (3, c)."""
    if constrained.shape[1] == 0:
        return np.eye(3)
    u, sv, _ = np.linalg.svd(constrained, full_matrices=True)
    rank = int(np.sum(sv > 1e-12 * max(sv[0], 1.0)))
    return u[:, rank:]


def node_bases(problem: ModalProblem) -> list[np.ndarray]:
    """Per node, an orthonormal basis (3, k) of its free directions (k = 0..3)."""
    pos = problem.static.position
    n = len(pos)
    constraints: list[list[np.ndarray]] = [[] for _ in range(n)]
    med = problem.medium
    if med.depth is not None and problem.static.laid_length > 0.0:
        ground = med.seabed_z(pos[:, 0], pos[:, 1])
        tol = 1e-6 * max(float(problem.static.s[-1]), 1.0)
        rise = math.tan(med.seabed_slope)
        normal = np.array(
            [-rise * math.cos(med.seabed_heading), -rise * math.sin(med.seabed_heading), 1.0]
        )
        normal /= np.linalg.norm(normal)
        stick = med.friction > 0.0
        for i in np.flatnonzero(np.abs(pos[:, 2] - ground) <= tol):
            if stick:
                constraints[i] = [np.eye(3)[:, j] for j in range(3)]
            else:
                constraints[i].append(normal)
    for node, end in ((0, problem.end_a), (n - 1, problem.end_b)):
        if end.kind == "fixed":
            constraints[node] = [np.eye(3)[:, j] for j in range(3)]
        elif end.kind == "mooring":
            constraints[node].append(np.array([0.0, 0.0, 1.0]))
    return [_free_basis(np.array(c).T if c else np.zeros((3, 0))) for c in constraints]


def mass_blocks(problem: ModalProblem) -> np.ndarray:
    """Lumped nodal mass blocks (n_nodes, 3, 3) [kg], see the module docstring."""
    line, st = problem.line, problem.static
    s, pos = st.s, st.position
    l0 = np.diff(s)
    chord = np.diff(pos, axis=0)
    t = chord / np.linalg.norm(chord, axis=1)[:, None]
    seg = _segment_index(line, 0.5 * (s[:-1] + s[1:]))
    area = math.pi * line.diameter[seg] ** 2 / 4.0
    rho = problem.medium.density if problem.include_added_mass else 0.0
    m = line.mass[seg]
    m_n = m + rho * line.added_mass_normal[seg] * area
    m_t = m + rho * line.added_mass_tangential[seg] * area
    tt = t[:, :, None] * t[:, None, :]
    blocks_e = (
        0.5 * l0[:, None, None] * (m_n[:, None, None] * (np.eye(3) - tt) + m_t[:, None, None] * tt)
    )
    M = np.zeros((len(s), 3, 3))
    M[:-1] += blocks_e
    M[1:] += blocks_e
    for s_att, mass in zip(line.attachment_s, line.attachment_mass, strict=True):
        if mass == 0.0:
            continue
        e = int(np.clip(np.searchsorted(s, s_att, side="right") - 1, 0, len(l0) - 1))
        xi = (s_att - s[e]) / l0[e]
        M[e] += (1.0 - xi) * mass * np.eye(3)
        M[e + 1] += xi * mass * np.eye(3)
    return M


def stiffness_matrix(problem: ModalProblem) -> sp.csr_matrix:
    """Tangent stiffness (3 n_nodes, 3 n_nodes) [N/m] of all nodes, before constraints."""
    line, st = problem.line, problem.static
    s, pos, T = st.s, st.position, st.tension
    n = len(s)
    l0 = np.diff(s)
    chord = np.diff(pos, axis=0)
    l = np.linalg.norm(chord, axis=1)
    t = chord / l[:, None]
    seg = _segment_index(line, 0.5 * (s[:-1] + s[1:]))
    T_e = 0.5 * (T[:-1] + T[1:])
    tt = t[:, :, None] * t[:, None, :]
    P = np.eye(3) - tt
    K_e = (line.axial_stiffness[seg] / l0)[:, None, None] * tt + (T_e / l)[:, None, None] * P

    rows: list[np.ndarray] = []
    cols: list[np.ndarray] = []
    vals: list[np.ndarray] = []
    ii, jj = np.meshgrid(np.arange(3), np.arange(3), indexing="ij")

    def add(node_i: np.ndarray, node_j: np.ndarray, blocks: np.ndarray) -> None:
        rows.append((3 * node_i[:, None, None] + ii).ravel())
        cols.append((3 * node_j[:, None, None] + jj).ravel())
        vals.append(blocks.ravel())

    a, b = np.arange(n - 1), np.arange(1, n)
    add(a, a, K_e)
    add(b, b, K_e)
    add(a, b, -K_e)
    add(b, a, -K_e)

    if problem.include_bending and n >= 3:
        seg_node = _segment_index(line, s[1:-1])
        EI = line.bending_stiffness[seg_node]
        if np.any(EI > 0.0):
            h = 0.5 * (l0[:-1] + l0[1:])
            G = P / l[:, None, None]  # d t_e / d x_{e+1} = G_e, d t_e / d x_e = -G_e
            # d(t_i - t_{i-1}) / d(x_{i-1}, x_i, x_{i+1}) for interior nodes i = 1..n-2
            J = [G[:-1], -G[:-1] - G[1:], G[1:]]
            c = (EI / h)[:, None, None]
            mid = np.arange(1, n - 1)
            for p in range(3):
                for q in range(3):
                    blk = c * np.einsum("kji,kjl->kil", J[p], J[q])
                    add(mid - 1 + p, mid - 1 + q, blk)
    return sp.csr_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
        shape=(3 * n, 3 * n),
    )


def transverse_mass(
    line: LineModel, medium: Medium, s: np.ndarray, *, include_added_mass: bool = True
) -> np.ndarray:
    """Mass per length moving with transverse motion at arc lengths ``s`` [kg/m]:
    m + rho C_an pi d^2 / 4."""
    seg = _segment_index(line, np.asarray(s, dtype=float))
    rho = medium.density if include_added_mass else 0.0
    area = math.pi * line.diameter[seg] ** 2 / 4
    return line.mass[seg] + rho * line.added_mass_normal[seg] * area


def graded_arc_lengths(
    s: np.ndarray,
    tension: np.ndarray,
    mass: np.ndarray,
    n_elements: int,
    joints: np.ndarray | None = None,
) -> np.ndarray:
    """Node positions [m] that cut the line into ``n_elements`` pieces of equal
    transverse-wave travel time tau = int sqrt(m / T) ds, so that every element holds
    the same share of each mode's phase however much the tension varies (a vertical
    riser whose bottom tension is small against its weight needs elements far shorter
    near the bottom than at the top).

    ``s`` [m], ``tension`` [N] and ``mass`` [kg/m] sample the static line; T is taken
    linear between samples, for which tau and its inverse are exact: on a piece
    starting at (s_i, T_i) with slope g and a = sqrt(m), tau - tau_i = 2 a (sqrt(T) -
    sqrt(T_i)) / g, and s = s_i + D sqrt(T_i) / a + g D^2 / (4 a^2) for D = tau - tau_i.
    Tension below 1e-9 of its largest value is raised to that floor. ``joints`` [m]
    (segment ends) are added to the result.
    """
    s = np.asarray(s, dtype=float)
    T = np.maximum(np.asarray(tension, dtype=float), 1e-9 * float(np.max(tension)))
    m_mid = 0.5 * (mass[:-1] + mass[1:])
    a = np.sqrt(m_mid)
    ds = np.diff(s)
    rt = np.sqrt(T)
    dtau = 2.0 * a * ds / (rt[:-1] + rt[1:])
    tau = np.concatenate(([0.0], np.cumsum(dtau)))
    targets = np.linspace(0.0, tau[-1], n_elements + 1)[1:-1]
    i = np.clip(np.searchsorted(tau, targets, side="right") - 1, 0, len(ds) - 1)
    D = targets - tau[i]
    g = np.diff(T)[i] / ds[i]
    inner = s[i] + D * rt[i] / a[i] + g * D * D / (4.0 * a[i] ** 2)
    out = np.concatenate(([s[0]], np.clip(inner, s[0], s[-1]), [s[-1]]))
    if joints is not None and len(joints):
        out = np.union1d(out, np.asarray(joints, dtype=float))
    return np.unique(out)


def subset_static(static: StaticResult, index: np.ndarray) -> StaticResult:
    """The static result at the sample points ``index`` only."""
    return StaticResult(
        s=static.s[index],
        position=static.position[index],
        tension=static.tension[index],
        force_a=static.force_a,
        force_b=static.force_b,
        laid_length=static.laid_length,
        status=static.status,
        message=static.message,
        iterations=static.iterations,
        residual=static.residual,
    )


def snap_to_samples(s_fine: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """Indices of the samples ``s_fine`` nearest to ``targets`` (increasing, unique,
    first and last sample included)."""
    j = np.clip(np.searchsorted(s_fine, targets), 1, len(s_fine) - 1)
    nearer_left = (targets - s_fine[j - 1]) <= (s_fine[j] - targets)
    idx = np.where(nearer_left, j - 1, j)
    idx = np.unique(np.concatenate(([0], idx, [len(s_fine) - 1])))
    return idx


#: largest model (degrees of freedom) solved by LAPACK's banded eigensolver. Its
#: eigenvector back-transformation holds a dense n x n matrix (O(n^2) memory, ~O(n^3)
#: time) and its eigenvalues are accurate to eps * (largest eigenvalue) only, i.e.
#: relative 1e-9 for the lowest modes of a stiff line; larger models (and any model
#: asked for fewer than half its modes) use ARPACK in shift-invert mode about 0 on a
#: sparse LU of the banded matrix, which resolves the lowest modes to relative round-off
BANDED_LIMIT = 60


def lowest_eigenpairs(A: sp.coo_matrix, k: int) -> tuple[np.ndarray, np.ndarray]:
    """The ``k`` lowest eigenvalues (increasing) and eigenvectors (columns) of the
    symmetric banded matrix ``A``."""
    n = A.shape[0]
    if n <= BANDED_LIMIT or 2 * k >= n:
        upper = A.col >= A.row
        bw = int(np.max(A.col[upper] - A.row[upper])) if np.any(upper) else 0
        ab = np.zeros((bw + 1, n))
        ab[bw + A.row[upper] - A.col[upper], A.col[upper]] = A.data[upper]
        return eig_banded(ab, lower=False, select="i", select_range=(0, k - 1))
    # eigenvalues nearest 0 are the lowest (and any negative ones, which are reported)
    lam, Y = eigsh(A.tocsc(), k=k, sigma=0.0, which="LM", tol=1e-13)
    order = np.argsort(lam)
    return lam[order], Y[:, order]


def modal_analysis(problem: ModalProblem, *, deadline: float | None = None) -> ModalResult:
    """Lowest ``problem.n_modes`` natural frequencies [Hz] and mode shapes about the
    static shape. Never raises for a numerical failure: returns a failed result."""
    st = problem.static
    s = np.asarray(st.s, dtype=float)
    k = problem.n_modes
    if not st.success:
        return ModalResult.failed(
            s, k, STATUS_STATIC_FAILED, f"no static shape to linearise about: {st.message}"
        )
    n = len(s)
    if not (
        np.all(np.isfinite(s))
        and np.all(np.isfinite(st.position))
        and np.all(np.isfinite(st.tension))
    ):
        return ModalResult.failed(
            s, k, STATUS_NUMERICAL, "the static shape holds non-finite values"
        )
    if n < 2 or np.any(np.diff(s) <= 0.0):
        return ModalResult.failed(
            s, k, STATUS_NUMERICAL, "static nodes must have strictly increasing arc length"
        )
    chord = np.linalg.norm(np.diff(st.position, axis=0), axis=1)
    if np.any(chord <= 0.0):
        return ModalResult.failed(
            s, k, STATUS_NUMERICAL, "two static nodes coincide; the element direction is undefined"
        )
    T_e = 0.5 * (st.tension[:-1] + st.tension[1:])
    if np.any(T_e <= 0.0):
        i = int(np.argmin(T_e))
        return ModalResult.failed(
            s,
            k,
            STATUS_SLACK,
            f"the static line is slack or compressed near s = {0.5 * (s[i] + s[i + 1]):.6g} m "
            f"(element tension {T_e[i]:.4g} N); a cable has no small-motion modes there",
        )

    bases = node_bases(problem)
    dims = np.array([b.shape[1] for b in bases])
    n_dof = int(dims.sum())
    if n_dof < k:
        return ModalResult.failed(
            s,
            k,
            STATUS_NUMERICAL,
            f"{k} modes asked for but the model has only {n_dof} degrees of freedom "
            f"({n - 1} elements); use more elements",
            n_dof=n_dof,
        )
    if deadline is not None and time.monotonic() > deadline:
        return ModalResult.failed(
            s, k, STATUS_TIME_LIMIT, "time limit reached before the modal eigenproblem", n_dof=n_dof
        )

    M = mass_blocks(problem)
    K = stiffness_matrix(problem)
    # B: (3n, n_dof) block-diagonal free bases; Linv: inverse Cholesky factors of the
    # reduced nodal mass blocks (n_dof, n_dof), block-diagonal
    offsets = np.concatenate(([0], np.cumsum(dims)))
    b_rows, b_cols, b_vals, l_rows, l_cols, l_vals = [], [], [], [], [], []
    for i, basis in enumerate(bases):
        kd = basis.shape[1]
        if kd == 0:
            continue
        try:
            Lc = np.linalg.cholesky(basis.T @ M[i] @ basis)
        except np.linalg.LinAlgError:
            return ModalResult.failed(
                s,
                k,
                STATUS_NUMERICAL,
                f"node at s = {s[i]:.6g} m has no positive mass in a free direction",
                n_dof=n_dof,
            )
        r3, ck = np.meshgrid(np.arange(3), np.arange(kd), indexing="ij")
        b_rows.append(3 * i + r3.ravel())
        b_cols.append(offsets[i] + ck.ravel())
        b_vals.append(basis.ravel())
        rk, ck2 = np.meshgrid(np.arange(kd), np.arange(kd), indexing="ij")
        l_rows.append(offsets[i] + rk.ravel())
        l_cols.append(offsets[i] + ck2.ravel())
        l_vals.append(np.linalg.inv(Lc).ravel())
    B = sp.csr_matrix(
        (np.concatenate(b_vals), (np.concatenate(b_rows), np.concatenate(b_cols))),
        shape=(3 * n, n_dof),
    )
    Linv = sp.csr_matrix(
        (np.concatenate(l_vals), (np.concatenate(l_rows), np.concatenate(l_cols))),
        shape=(n_dof, n_dof),
    )
    A = (Linv @ (B.T @ K @ B) @ Linv.T).tocoo()
    try:
        lam, Y = lowest_eigenpairs(A, k)
    except (np.linalg.LinAlgError, ValueError, RuntimeError, ArpackError) as exc:
        return ModalResult.failed(
            s, k, STATUS_NUMERICAL, f"eigenproblem failed: {exc}", n_dof=n_dof
        )
    scale = max(float(np.max(np.abs(lam))), 1e-300)
    if lam[0] < -1e-8 * scale:
        return ModalResult.failed(
            s,
            k,
            STATUS_NUMERICAL,
            f"negative stiffness about the static shape (omega^2 = {lam[0]:.4g} 1/s^2): the "
            "static shape is not a stable equilibrium",
            n_dof=n_dof,
        )
    freq = np.sqrt(np.clip(lam, 0.0, None)) / (2.0 * math.pi)
    U = (B @ (Linv.T @ Y)).T.reshape(k, n, 3)
    mag = np.linalg.norm(U, axis=2)
    for j in range(k):
        node = int(np.argmax(mag[j]))
        U[j] /= mag[j, node]
        comp = int(np.argmax(np.abs(U[j, node])))
        if U[j, node, comp] < 0.0:
            U[j] *= -1.0
    return ModalResult(s=s, frequency=freq, mode_shape=U, n_dof=n_dof, status=STATUS_OK, message="")
