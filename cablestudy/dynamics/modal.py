"""Natural frequencies and mode shapes of a line about its static shape.

The line is cut at the sample points of a :class:`~cablestudy.statics.StaticResult`
into straight two-node bar elements (nodes at the static positions). Small motions
``u`` of the nodes about that shape obey ``M u'' + K u = 0``; the modes solve the
generalized symmetric eigenproblem ``K phi = omega^2 M phi``.

Model. Mass, stiffness and structural damping are those of the shared line model
(:mod:`cablestudy.dynamics.model`, the one the time-domain solver integrates), taken at
rest in the static shape by :func:`tangents`: the time-domain Jacobian's own blocks.

* Mass (lumped, block-diagonal 3 x 3 per node): structural mass, added mass normal to
  the line (and along it where ``added_mass_tangential`` is nonzero) about the node
  tangent, attachment masses and their added mass.
* Stiffness: a bar of tension T and chord length l gives ``(EA / l0) t t^T +
  (T / l) (I - t t^T)`` on the difference of its end displacements; the element rest
  lengths are set so that T is the static tension at the element (mean of its end
  samples), so the geometric stiffness is the static tension however stiff the line is.
* Bending (tensioned-beam terms, EI [N m^2]): the discrete curvature at an interior
  node, ``(t_i - t_{i-1}) / h_i``, in its Gauss-Newton linearisation (exact for a
  straight line); a pinned end is moment-free, a clamped end holds its static direction.
* Seabed: nodes resting on it sit on the contact spring (normal stiffness per length,
  ``environment.seabed.stiffness``), and with friction on the stick spring of the
  friction law (for small vibrations static friction does not let the laid line slide):
  the seabed is a linear spring, as in the time domain.

Boundary conditions. A ``fixed`` end node has no degree of freedom. A ``force`` end
(towing) is free in all three directions: the applied force is a dead load (fixed
magnitude and direction) and adds no stiffness; the node keeps its half-element
mass. A ``mooring`` end is free horizontally and held at its height (z fixed).

Solution. The constraints keep one orthonormal basis of free directions per node, so
the reduced mass stays block-diagonal; with its block Cholesky factor L the problem
becomes the standard banded symmetric eigenproblem ``L^-1 K L^-T y = omega^2 y``
(half-bandwidth at most 8 degrees of freedom), solved for the lowest modes only: by
ARPACK in shift-invert mode about 0 (:func:`scipy.sparse.linalg.eigsh` on a sparse
LU of the banded matrix) from a fixed start vector, or for small models and when half
or more of the modes are wanted by LAPACK's banded solver
(:func:`scipy.linalg.eig_banded`). Both are repeatable: the same model gives the same
bits, and each mode shape's sign is fixed by :func:`normalise_modes`.

Accuracy. Lumped masses and linear elements make the frequencies converge as h^2:
for a taut string the discrete frequencies are exactly
``omega_n = 2 sqrt(T / (m h^2)) sin(n pi h / (2 L))``, i.e. a relative error of about
-(n pi h / L)^2 / 24. Where the tension varies by orders of magnitude along the line
(a riser whose bottom tension is small against its weight), elements of equal length
miss the short waves at the low-tension end; :func:`graded_arc_lengths` places the
nodes at equal transverse-wave travel time instead (the caller samples the static
solution there, see :func:`cablestudy.analyses.modal.solve_modal`). The grading uses the
tension only; with EI the low-tension end is over-resolved, which costs accuracy
elsewhere but not convergence.
"""

from __future__ import annotations

import copy
import functools
import math
import time
from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp
from scipy.linalg import eig_banded
from scipy.sparse.linalg import ArpackError, eigsh

from ..physics.contact import default_seabed_stiffness
from ..statics.base import (
    STATUS_NUMERICAL,
    STATUS_OK,
    STATUS_TIME_LIMIT,
    EndCondition,
    LineModel,
    Medium,
    StaticResult,
)
from .assembly import evaluate
from .discrete_line import DiscreteLine, DynamicExtras, discretise_nodes

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
    extras : DynamicExtras or None
        Clamped ends, bodies' added mass, seabed contact stiffness and friction (the
        time-domain model's; None: :func:`default_extras`).
    """

    line: LineModel
    medium: Medium
    end_a: EndCondition
    end_b: EndCondition
    static: StaticResult
    n_modes: int = 10
    include_added_mass: bool = True
    include_bending: bool = True
    extras: DynamicExtras | None = None


@dataclass(kw_only=True)
class ModalResult:
    """Lowest natural frequencies and mode shapes.

    frequency [Hz] (n_modes,), increasing; mode_shape [m] (n_modes, n_nodes, 3): nodal
    displacements scaled so that the largest nodal displacement is 1 m, signed so that
    the largest component of the largest displacement is positive (the first node, from
    end A, and the first component, x, y, z, of those tied: :func:`normalise_modes`);
    s [m] (n_nodes,) the nodes; n_dof the number of degrees of freedom; status, message
    as for static results. The same model gives the same bits run after run
    (:func:`start_vector`).
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
    for node, end in ((0, problem.end_a), (n - 1, problem.end_b)):
        if end.kind == "fixed":
            constraints[node] = [np.eye(3)[:, j] for j in range(3)]
        elif end.kind == "mooring":
            constraints[node].append(np.array([0.0, 0.0, 1.0]))
    return [_free_basis(np.array(c).T if c else np.zeros((3, 0))) for c in constraints]


def shared_model(problem: ModalProblem) -> tuple[DiscreteLine, np.ndarray]:
    """The shared line model (:mod:`cablestudy.dynamics.model`) with nodes at the static
    samples, and the positions at which its tangents are taken.

    The element rest lengths are set to ``l / (1 + T / EA)``, with ``l`` the chord and
    ``T`` the static tension at the element (mean of its end samples): the model's
    chord tensions are then the static tensions of the continuous solution, so the
    geometric stiffness is the static tension however stiff the line is (a chord strain
    of the sampled curve would miss it by EA times the chord's O(h^2 kappa^2) shortening).
    Masses are lumped over the true unstretched lengths. Nodes on the seabed are put
    a nanometre inside it, so that the contact spring (and, with friction, the sticking
    friction spring) acts on them: the seabed is a linear spring, as in the time domain.
    """
    line, st = problem.line, problem.static
    s, pos = np.asarray(st.s, dtype=float), np.asarray(st.position, dtype=float)
    extras = problem.extras or default_extras(line, problem.medium)
    disc = discretise_nodes(line, problem.medium, s, extras)
    chord = np.linalg.norm(np.diff(pos, axis=0), axis=1)
    T_e = 0.5 * (st.tension[:-1] + st.tension[1:])
    changes: dict = {"rest_length": chord / (1.0 + element_strain(line, s, T_e)), "has_drag": False}
    if not problem.include_added_mass:
        zero = np.zeros(disc.n_nodes)
        changes.update(added_mass_normal=zero, added_mass_tangential=zero, body_added_mass=zero)
    if not problem.include_bending:
        changes["bending"] = np.zeros(disc.n_nodes)
    disc = replace(disc, **changes)
    x = pos.copy()
    if disc.has_seabed:
        gap = x @ disc.seabed_normal - disc.seabed_offset
        laid = gap <= 1e-6 * max(float(s[-1]), 1.0)
        x[laid] -= np.outer(gap[laid] + 1e-9, disc.seabed_normal)
    return disc, x


def element_strain(
    line: LineModel, s: np.ndarray, tension: np.ndarray, seg: np.ndarray | None = None
) -> np.ndarray:
    """Strain [-] of the elements between nodes ``s`` [m] carrying ``tension`` [N] (n,),
    by the inverse of each segment's axial law (T / EA where it is linear); ``seg``
    the elements' segments when known (:func:`_segment_index` of their midpoints)."""
    if seg is None:
        seg = _segment_index(line, 0.5 * (s[:-1] + s[1:]))
    out = np.asarray(tension, dtype=float) / line.axial_stiffness[seg]
    for i in range(line.length.size):
        law = line.law_of(i)
        if law is not None:
            on = seg == i
            out[on] = law.strain(np.asarray(tension, dtype=float)[on])
    return out


def element_tangent(
    line: LineModel,
    s: np.ndarray,
    tension: np.ndarray,
    seg: np.ndarray | None = None,
    strain: np.ndarray | None = None,
) -> np.ndarray:
    """Tangent axial stiffness dT/d(strain) [N] of the elements at ``tension`` [N];
    ``seg`` and ``strain`` (:func:`element_strain`) when known."""
    if seg is None:
        seg = _segment_index(line, 0.5 * (s[:-1] + s[1:]))
    out = line.axial_stiffness[seg].astype(float)
    if strain is None:
        strain = element_strain(line, s, tension, seg)
    for i in range(line.length.size):
        law = line.law_of(i)
        if law is not None:
            on = seg == i
            out[on] = law.tangent_stiffness(strain[on])
    return out


def default_extras(line: LineModel, medium: Medium) -> DynamicExtras:
    """Dynamic line properties of a bare :class:`LineModel`: pinned ends, no bodies or
    transverse damping, the default seabed stiffness and the medium's friction."""
    stiffness = default_seabed_stiffness(line.weight) if medium.depth is not None else 0.0
    return DynamicExtras(
        seabed_stiffness=stiffness, friction_axial=medium.friction, friction_lateral=medium.friction
    )


def tangents(problem: ModalProblem) -> tuple[np.ndarray, sp.csr_matrix, sp.csr_matrix]:
    """Nodal mass blocks (n_nodes, 3, 3) [kg], tangent stiffness and structural damping
    (3 n_nodes, 3 n_nodes) [N/m], [N s/m] of all nodes before constraints: the shared
    line model's own tangents (:func:`cablestudy.dynamics.assembly.assemble`) at rest in
    the static shape, without drag (the frequency domain linearises drag itself)."""
    return tangents_of(*shared_model(problem))


def tangents_of(
    disc: DiscreteLine, x: np.ndarray
) -> tuple[np.ndarray, sp.csr_matrix, sp.csr_matrix]:
    """:func:`tangents` of the shared model ``disc`` at positions ``x`` (as
    :func:`shared_model` returns them)."""
    work = evaluate(disc, x, np.zeros_like(x), anchor=x)
    n = disc.n_nodes
    return (
        work.M_d.copy(),
        _block_matrix(n, work.K_d, work.K_o, work.K_o2),
        _block_matrix(n, work.C_d, work.C_o, work.K_o2[:0]),
    )


def _block_matrix(n: int, diag: np.ndarray, off1: np.ndarray, off2: np.ndarray) -> sp.csr_matrix:
    """Sparse (3n, 3n) matrix of diagonal blocks and upper blocks one and two nodes off
    the diagonal (the lower ones their transposes), every entry of a block stored (zeros
    too), in canonical CSR form (columns sorted in each row): the arrays scipy makes of
    the same entries given as coordinates, built row by row from the blocks."""
    m1, m2 = off1.shape[0], off2.shape[0]
    reach = 2 if m2 else (1 if m1 else 0)
    take, template = _block_structure(n, m1, m2)
    # rows[i, k, a, b]: entry (3 i + a, 3 (i + k - reach) + b)
    rows = np.zeros((n, 2 * reach + 1, 3, 3))
    rows[:, reach] = diag
    for k, blocks in ((1, off1), (2, off2)):
        m = blocks.shape[0]
        if m:
            rows[:m, reach + k] = blocks
            rows[k : m + k, reach - k] = np.transpose(blocks, (0, 2, 1))
    return filled_csr(
        template, np.ascontiguousarray(np.transpose(rows, (0, 2, 1, 3))).ravel()[take]
    )


def filled_csr(template: sp.csr_matrix, data: np.ndarray) -> sp.csr_matrix:
    """A CSR matrix of ``template``'s structure (built, and checked, by scipy once)
    holding ``data`` (its stored values, in order), with index arrays of its own: a
    shallow copy of the template, the same arrays scipy's constructor makes of
    ``(data, indices, indptr)`` without its checks of a structure it has already checked
    (10-40 us a matrix, a third of :func:`~.linear_model.linear_lines`)."""
    out = copy.copy(template)
    out.data, out.indices, out.indptr = data, template.indices.copy(), template.indptr.copy()
    return out


@functools.lru_cache(maxsize=32)
def _block_structure(n: int, m1: int, m2: int) -> tuple[np.ndarray, sp.csr_matrix]:
    """Of :func:`_block_matrix` with ``m1`` and ``m2`` blocks one and two nodes off the
    diagonal: which entries of its (n, 3, 2 reach + 1, 3) row blocks are stored (flat,
    read-only), and its structure as a matrix of zeros (:func:`filled_csr`'s template;
    int32 indices, as scipy picks for these sizes)."""
    reach = 2 if m2 else (1 if m1 else 0)
    width = 2 * reach + 1
    present = np.zeros((n, width), dtype=bool)
    present[:, reach] = True
    for k, m in ((1, m1), (2, m2)):
        if m:
            present[:m, reach + k] = True
            present[k : m + k, reach - k] = True
    shape = (n, 3, width, 3)
    take = np.empty(shape, dtype=bool)
    take[...] = present[:, None, :, None]
    cols = np.empty(shape, dtype=np.int32)
    cols[...] = (3 * (np.arange(n)[:, None] + np.arange(width) - reach))[:, None, :, None]
    cols += np.arange(3, dtype=np.int32)
    indptr = np.zeros(3 * n + 1, dtype=np.int32)
    np.cumsum(np.repeat(3 * np.count_nonzero(present, axis=1), 3), out=indptr[1:])
    take = take.ravel()
    take.flags.writeable = False
    template = sp.csr_matrix(
        (np.zeros(int(indptr[-1])), cols.ravel()[take], indptr), shape=(3 * n, 3 * n)
    )
    return take, template


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
    return np.unique(np.concatenate(([0], idx, [len(s_fine) - 1])))


#: largest model (degrees of freedom) solved by LAPACK's banded eigensolver. Its
#: eigenvector back-transformation holds a dense n x n matrix (O(n^2) memory, ~O(n^3)
#: time) and its eigenvalues are accurate to eps * (largest eigenvalue) only, i.e.
#: relative 1e-9 for the lowest modes of a stiff line; larger models (and any model
#: asked for fewer than half its modes) use ARPACK in shift-invert mode about 0 on a
#: sparse LU of the banded matrix, which resolves the lowest modes to relative round-off
BANDED_LIMIT = 60


#: seed of the Lanczos start vector (:func:`start_vector`)
START_SEED = 20_260_101


def start_vector(n: int) -> np.ndarray:
    """The start vector of the Lanczos iteration for ``n`` unknowns: fixed (the same for
    the same ``n``, run after run, in any process), and with Gaussian pseudo-random
    entries so that it has a part along every eigenvector (a constant or a smooth vector
    would be orthogonal to every antisymmetric mode of a symmetric line)."""
    return np.random.default_rng(START_SEED).standard_normal(n)


#: two nodal displacements (or components) whose magnitudes differ by less than this
#: fraction of the largest are ties for the sign convention (:func:`normalise_modes`):
#: far above the eigenvectors' round-off (ARPACK's tolerance 1e-13, LAPACK's ~1e-15 over
#: the spectral gap), so that a symmetric mode's two equal extremes never swap roles
#: from one run or platform to the next
SIGN_TIE = 1e-6


def normalise_modes(U: np.ndarray) -> np.ndarray:
    """Mode shapes ``U`` (modes, nodes, 3) scaled so that the largest nodal displacement
    is 1 m, with the sign convention: the first node (smallest s) whose displacement is
    within :data:`SIGN_TIE` of the largest, and of its components the first (x, y, z
    order) within :data:`SIGN_TIE` of its largest, is positive. A new array."""
    U = np.array(U, dtype=float)
    mag = np.linalg.norm(U, axis=2)
    for j in range(U.shape[0]):
        top = float(np.max(mag[j]))
        if not top > 0.0:
            continue
        node = int(np.flatnonzero(mag[j] >= (1.0 - SIGN_TIE) * top)[0])
        size = np.abs(U[j, node])
        comp = int(np.flatnonzero(size >= (1.0 - SIGN_TIE) * np.max(size))[0])
        U[j] *= (1.0 if U[j, node, comp] > 0.0 else -1.0) / top
    return U


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
    # eigenvalues nearest 0 are the lowest (and any negative ones, which are reported);
    # from a fixed start vector: ARPACK's own is random, drawn from a generator whose state
    # carries over between calls, so the same model gave frequencies that differ in the
    # 13th digit and mode shapes mixed differently within (near-)repeated frequencies
    lam, Y = eigsh(A.tocsc(), k=k, sigma=0.0, which="LM", tol=1e-13, v0=start_vector(n))
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
    # a stretch laid on the seabed that friction has emptied of tension is held by the
    # seabed, not a slack span: only a suspended element must be taut
    ground = problem.medium.seabed_z(st.position[:, 0], st.position[:, 1])
    on_bed = st.position[:, 2] - ground <= 1e-6 * max(float(s[-1] - s[0]), 1.0)
    slack = (T_e <= 0.0) & ~(on_bed[:-1] & on_bed[1:])
    if np.any(slack):
        i = int(np.flatnonzero(slack)[np.argmin(T_e[slack])])
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

    M, K, _ = tangents(problem)
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
    U = normalise_modes((B @ (Linv.T @ Y)).T.reshape(k, n, 3))
    return ModalResult(s=s, frequency=freq, mode_shape=U, n_dof=n_dof, status=STATUS_OK, message="")
