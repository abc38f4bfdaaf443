"""Many harmonic responses of one linearised line in one compiled call.

A sweep over excitation frequency, amplitude or phase of one line shares its
:class:`~cablestudy.dynamics.frequency_model.ReducedLine`; per case only the excitation
changes. :func:`solve_harmonic_cases` runs the drag iteration of every case (start
from the quasi-static motion, fit the drag, solve, Anderson-accelerated; see
:mod:`cablestudy.dynamics.frequency`) inside one numba kernel, and
:func:`~cablestudy.dynamics.frequency.solve_harmonic` runs one case through the same
kernel, so a case gives the same numbers alone or in a sweep. The kernel has:

* a band solve on row-major storage that follows the reach of each row (the columns
  that row exchanges actually filled), with threshold pivoting (a row exchange only
  where the diagonal is under a tenth of the column's largest entry), so that an
  elimination step skips columns that are still zero;
* the drag blocks of nodes whose free basis picks coordinate directions added
  directly (the projection ``b^T D b`` then picks entries of ``D``);
* the drag fit in closed form for nodes moving in the x-z plane
  (:func:`~cablestudy.dynamics.frequency_model.planar_drag_fit`) and for any node without
  current (:func:`~cablestudy.dynamics.elliptic_fit.still_water_means`), and over the
  phases laid out so that the compiler vectorises it for the others
  (:func:`drag_fit_samples`);
* the right side and the end reactions from the sparse rows themselves;
* for a line in the x-z plane moved in that plane, the system without its y unknowns,
  which stay zero (:func:`in_plane`).

A line without drag (one linear solve per case, nothing to iterate) goes case by case
through :func:`~cablestudy.dynamics.frequency.solve_harmonic` (LAPACK's band solve).
Pure: arrays in, a :class:`HarmonicCases` out.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp

from .frequency_model import (
    DragSettings,
    LinearLine,
    ReducedLine,
    csr_entries,
    drag_tangent,
    selected_rows,
    solve_undamped,
    sum_components,
)
from .harmonic_kernel import _cases_kernel


@dataclass(kw_only=True)
class HarmonicCases:
    """Harmonic responses of K cases (complex amplitudes of ``Re(Q e^{i w t})``).

    displacement [m] (K, n, 3); element_tension [N] (K, n - 1) tension variation;
    end_tension [N] (K, 2) variation of the end tensions at A and B; tension_static [N]
    (2,) static end tensions; iterations (K,) drag iterations; converged (K,) bool;
    change (K,) last relative change of the drag iteration; ok (K,) bool, False where
    the dynamic matrix was singular (the case's arrays are then NaN); end_force [N]
    (K, 2, 3) the variation of the force of the line on its supports at A and B (whose
    projection on the static end force's direction is ``end_tension``; the force a
    system's body takes from the line).
    """

    displacement: np.ndarray
    element_tension: np.ndarray
    end_tension: np.ndarray
    tension_static: np.ndarray
    iterations: np.ndarray
    converged: np.ndarray
    change: np.ndarray
    ok: np.ndarray
    end_force: np.ndarray


@dataclass(frozen=True, eq=False)
class _Prepared:
    """Arrays of a :class:`ReducedLine` in the form the kernel takes (built once)."""

    k_ptr: np.ndarray
    k_idx: np.ndarray
    k_val: np.ndarray
    c_ptr: np.ndarray
    c_idx: np.ndarray
    c_val: np.ndarray
    bt_ptr: np.ndarray
    bt_idx: np.ndarray
    bt_val: np.ndarray
    rows_k: np.ndarray  # (N, 3 bw + 1) row-major bands of K, M, C
    rows_m: np.ndarray
    rows_c: np.ndarray
    selected: np.ndarray  # (n,) bool: the node's free basis columns are unit vectors
    sel: np.ndarray  # (n, 3) int: the axis of each such column (-1 past the node's)
    pos: np.ndarray  # (n, 3) int: the column of each axis (-1: held along it)
    frac: np.ndarray  # (n,) s / s_end
    d_small: np.ndarray  # (n, 3, 3) drag tangent
    has_drag: bool


_PREPARED: weakref.WeakKeyDictionary[ReducedLine, _Prepared] = weakref.WeakKeyDictionary()


def _rows(band: np.ndarray, bw: int) -> np.ndarray:
    """LAPACK band storage (2 bw + 1, N) as rows: A[i, j] at out[i, j - i + bw] of
    (N, 3 bw + 1) (room for the fill-in of row exchanges on the right)."""
    N = band.shape[1]
    out = np.zeros((N, 3 * bw + 1), dtype=band.dtype)
    i = np.arange(N)[:, None]
    d = np.arange(-bw, bw + 1)[None, :]  # d = j - i
    inside = (i + d >= 0) & (i + d < N)
    i, d = np.broadcast_arrays(i, d)
    out[i[inside], d[inside] + bw] = band[bw - d[inside], (i + d)[inside]]
    return out


def _transposed(B: sp.spmatrix) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(indptr, indices, data) of ``B.T.tocsr()`` (stored zeros kept), by a stable sort
    of the entries of a canonical CSR ``B`` on their column."""
    if not (sp.issparse(B) and B.format == "csr" and B.has_canonical_format):
        BT = B.T.tocsr()
        return BT.indptr, BT.indices, BT.data
    order = np.argsort(B.indices, kind="stable")
    row = np.repeat(np.arange(B.shape[0]), np.diff(B.indptr))
    ptr = np.concatenate(([0], np.cumsum(np.bincount(B.indices, minlength=B.shape[1]))))
    return ptr, row[order], B.data[order]


#: per reduced line its x-z system, or None where it has none (see :func:`in_plane`)
_IN_PLANE: weakref.WeakKeyDictionary[ReducedLine, ReducedLine | None] = weakref.WeakKeyDictionary()


def in_plane(red: ReducedLine) -> ReducedLine:
    """``red`` without its y unknowns where they are decoupled: when the line's tangents
    and current have no y component, every free direction is either y or in the x-z
    plane, and the stiffness, damping and mass couple no y direction with an x-z one,
    then for end motion in the x-z plane the y unknowns stay zero (their right side is
    zero, and the drag fit of motion in the plane couples nothing to y), and the
    elimination of the full system performs, on the non-zero entries, exactly the
    operations of the x-z system alone (a decoupled row is never a pivot for the other
    set, and its updates are zeros). So the same numbers come out of a smaller system.
    Otherwise ``red`` itself."""
    if red in _IN_PLANE:
        return _IN_PLANE[red] or red
    line = red.line
    out = None
    if line.has_drag and not np.any(line.tangent[:, 1]) and not np.any(line.current[:, 1]):
        basis = _plane_basis(line)
        if basis is not None:
            out = ReducedLine.of(replace(line, free_basis=basis))
    _IN_PLANE[red] = out
    return out or red


def _plane_basis(line: LinearLine) -> sp.csr_matrix | None:
    """The free basis of ``line`` without its y columns when every free direction is
    either y or in the x-z plane, some are y, and the stiffness, damping and mass couple
    no y direction with an x-z one (:func:`in_plane`); None otherwise, and None for a
    basis that is not of coordinate directions or matrices with non-finite entries
    (every line :func:`~cablestudy.dynamics.linear_model.linear_line` builds has a
    coordinate basis): the full system then gives the same numbers."""
    B = line.free_basis
    rows = selected_rows(B)
    entries = (csr_entries(line.stiffness), csr_entries(line.damping))
    if rows is None or entries[0] is None or entries[1] is None:
        return None
    # coordinate directions (the free basis of linear_line): a column is y or in-plane
    y_part = rows % 3 == 1
    if not np.any(y_part):
        return None
    for row, col, val in entries:  # type: ignore[misc]
        if np.any(val[(row % 3 == 1) != (col % 3 == 1)] != 0.0):
            return None
    m = line.mass
    if np.any(m[:, 1, 0::2] != 0.0) or np.any(m[:, 0::2, 1] != 0.0):
        return None
    # the stored entries (zeros included) of the kept columns, renumbered, as
    # B[:, ~y_part] keeps them
    new_col = np.cumsum(~y_part) - 1
    keep = ~y_part[B.indices]
    kept_before = np.concatenate(([0], np.cumsum(keep)))
    return sp.csr_matrix(
        (B.data[keep], new_col[B.indices[keep]], kept_before[B.indptr]),
        shape=(B.shape[0], int(np.count_nonzero(~y_part))),
    )


def _prepare(red: ReducedLine) -> _Prepared:
    hit = _PREPARED.get(red)
    if hit is not None:
        return hit
    line = red.line
    bw = red.bandwidth
    K = sp.csr_matrix(line.stiffness)
    C = sp.csr_matrix(line.damping)
    bt_ptr, bt_idx, bt_val = _transposed(line.free_basis)
    n = line.n_nodes
    counts = np.diff(red.offsets)
    nb = red.node_basis  # (n, 3, 3), columns past the node's count are zero
    unit = (np.sum(nb == 1.0, axis=1) == 1) & (np.sum(nb == 0.0, axis=1) == 2)  # (n, 3)
    used = np.arange(3)[None, :] < counts[:, None]  # (n, 3): the node's columns
    selected = np.all(unit | ~used, axis=1)
    sel = np.where(unit, np.argmax(nb == 1.0, axis=1), -1).astype(np.int64)
    pos = np.full((n, 3), -1, dtype=np.int64)
    node, col = np.nonzero(selected[:, None] & used)
    pos[node, sel[node, col]] = col
    out = _Prepared(
        k_ptr=K.indptr.astype(np.int64),
        k_idx=K.indices.astype(np.int64),
        k_val=np.ascontiguousarray(K.data, dtype=float),
        c_ptr=C.indptr.astype(np.int64),
        c_idx=C.indices.astype(np.int64),
        c_val=np.ascontiguousarray(C.data, dtype=float),
        bt_ptr=bt_ptr.astype(np.int64),
        bt_idx=bt_idx.astype(np.int64),
        bt_val=np.ascontiguousarray(bt_val, dtype=float),
        rows_k=_rows(red.K, bw),
        rows_m=_rows(red.M, bw),
        rows_c=_rows(red.C, bw),
        selected=selected,
        sel=sel,
        pos=pos,
        frac=line.s / line.s[-1] if n > 1 else np.zeros(n),
        d_small=drag_tangent(line),
        has_drag=line.has_drag,
    )
    _PREPARED[red] = out
    return out


def solve_harmonic_cases(
    red: ReducedLine,
    omegas: np.ndarray,
    end_motion: np.ndarray,
    settings: DragSettings | None = None,
    *,
    plane: bool = True,
) -> HarmonicCases:
    """Steady harmonic responses of the line at angular frequencies ``omegas`` [rad/s]
    (K,) to end displacements ``end_motion`` [m] (K, 2, 3) complex (A and B), with the
    drag linearised by iteration (module docstring); ``plane`` False keeps the y
    unknowns of a line in the x-z plane (a test's reference). Never raises for a
    numerical failure: a failed case has ``ok`` False and NaN arrays."""
    settings = settings or DragSettings()
    line = red.line
    if not line.has_drag:
        # one linear solve per case: LAPACK's, as solve_harmonic (no iteration to save)
        return _one_by_one(red, omegas, end_motion)
    omegas = np.ascontiguousarray(omegas, dtype=float)
    motion = np.ascontiguousarray(end_motion, dtype=np.complex128)
    if plane and not np.any(motion[:, :, 1]):
        red = in_plane(red)  # the same numbers, a third fewer unknowns (module docstring)
    p = _prepare(red)
    n = line.n_nodes
    K = omegas.size
    u = np.empty((K, n, 3), dtype=np.complex128)
    reaction = np.full((K, 2, 3), np.nan + 0j)
    iterations = np.zeros(K, dtype=np.int64)
    converged = np.zeros(K, dtype=np.bool_)
    change = np.zeros(K)
    ok = np.zeros(K, dtype=np.bool_)
    _cases_kernel(
        omegas,
        motion,
        p.k_ptr,
        p.k_idx,
        p.k_val,
        p.c_ptr,
        p.c_idx,
        p.c_val,
        p.bt_ptr,
        p.bt_idx,
        p.bt_val,
        np.ascontiguousarray(line.mass, dtype=float),
        p.rows_k,
        p.rows_m,
        p.rows_c,
        red.bandwidth,
        red.offsets,
        np.ascontiguousarray(red.node_basis),
        p.selected,
        p.sel,
        p.pos,
        p.frac,
        np.ascontiguousarray(line.current, dtype=float),
        np.ascontiguousarray(line.tangent, dtype=float),
        np.ascontiguousarray(line.drag_normal, dtype=float),
        np.ascontiguousarray(line.drag_tangential, dtype=float),
        line.body_drag,
        p.d_small,
        p.has_drag,
        settings.samples,
        settings.exact,
        settings.tolerance,
        settings.max_iterations,
        u,
        reaction,
        iterations,
        converged,
        change,
        ok,
    )
    du = np.diff(u, axis=1)
    axial = (line.axial_stiffness[None] + 1j * omegas[:, None] * line.axial_damping[None]) / (
        line.rest_length[None]
    )
    element = axial * sum_components(line.direction[None] * du)
    static_mag = np.linalg.norm(line.end_force, axis=1)
    unit = line.end_force / np.where(static_mag > 0.0, static_mag, 1.0)[:, None]
    end_tension = sum_components(unit[None] * -reaction)
    end_tension[~ok] = np.nan + 0j
    support = -reaction
    support[~ok] = np.nan + 0j
    return HarmonicCases(
        displacement=u,
        element_tension=element,
        end_tension=end_tension,
        tension_static=static_mag,
        iterations=iterations,
        converged=converged,
        change=change,
        ok=ok,
        end_force=support,
    )


def _one_by_one(red: ReducedLine, omegas: np.ndarray, end_motion: np.ndarray) -> HarmonicCases:
    """:func:`solve_harmonic_cases` of a line without drag, case by case
    (:func:`~cablestudy.dynamics.frequency_model.solve_undamped`, which
    :func:`~cablestudy.dynamics.frequency.solve_harmonic` gives such a line)."""
    results = [solve_undamped(red, w, X) for w, X in zip(omegas, end_motion, strict=True)]
    # the force on the supports as solve_undamped finds it (the same function of the
    # same displacements: the same numbers)
    support = np.full((len(results), 2, 3), np.nan + 0j)
    for k, (w, r) in enumerate(zip(omegas, results, strict=True)):
        if r.success:
            reaction = red.apply(r.displacement, w, None)
            support[k] = -np.stack([reaction[0], reaction[-1]])
    return HarmonicCases(
        displacement=np.array([r.displacement for r in results]),
        element_tension=np.array([r.element_tension for r in results]),
        end_tension=np.array([r.end_tension for r in results]),
        tension_static=np.linalg.norm(red.line.end_force, axis=1),
        iterations=np.array([r.drag_iterations for r in results], dtype=np.int64),
        converged=np.array([r.drag_converged for r in results], dtype=np.bool_),
        change=np.array([r.drag_change for r in results], dtype=float),
        ok=np.array([r.success for r in results], dtype=np.bool_),
        end_force=support,
    )


def warm_up_line() -> LinearLine:
    """A 3-node taut line with drag (the kernels' warm-up and tests' small case)."""
    n = 3
    eye = sp.identity(3 * n, format="csr")
    basis = sp.csr_matrix(np.eye(3 * n)[:, 3:6])
    z = np.zeros(n)
    return LinearLine(
        s=np.arange(n, dtype=float),
        position=np.zeros((n, 3)),
        mass=np.tile(np.eye(3), (n, 1, 1)),
        stiffness=eye,
        damping=eye * 0.0,
        rest_length=np.ones(n - 1),
        direction=np.tile([1.0, 0.0, 0.0], (n - 1, 1)),
        axial_stiffness=np.ones(n - 1),
        axial_damping=np.zeros(n - 1),
        tension=np.ones(n - 1),
        end_force=np.array([[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]]),
        drag_normal=np.ones(n),
        drag_tangential=z,
        current=np.zeros((n, 3)),
        tangent=np.tile([1.0, 0.0, 0.0], (n, 1)),
        free_basis=basis,
    )


def warm_up() -> None:
    """Load the compiled drag kernel (numba's first call in a process costs about a
    second, mostly loading its own registries); callers do it before timing cases."""
    line = warm_up_line()
    motion = np.zeros((1, 2, 3), dtype=complex)
    motion[0, 1, 2] = 1.0
    solve_harmonic_cases(ReducedLine.of(line), np.array([math.pi]), motion, DragSettings())
