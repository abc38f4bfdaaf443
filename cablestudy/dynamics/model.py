"""Discretised line model: lumped masses at nodes joined by straight elastic elements.

The line is cut along its unstretched arc length ``s`` into elements (nodes at every
segment boundary, so each element has one material). Element ``e`` joins nodes ``e``
and ``e + 1``; with ``d = x[e+1] - x[e]``, ``l = |d|`` and unit vector ``u = d / l`` its
strain and tension are

    eps = l / l0 - 1                                  (exact for large displacements)
    T   = max(EA eps + c eps_dot, 0)  if eps > 0 else 0   (tension-only)

with ``eps_dot = u . (v[e+1] - v[e]) / l0`` and the internal damping ``c = zeta l0
sqrt(EA m)`` [N s] (``zeta``: fraction of critical damping of the element's axial
mode, the segments' ``damping_ratio``). This is the moustafa seed's nonlinear strain
(its eq. 2 is the same stretch written relative to the static catenary, eqs. 4-6)
without the small-strain truncation, and its tension law eq. (6) with the
compression cut off.

Loads at nodes (tributary length = half of each adjacent element):

* weight in the fluid (weight minus buoyancy) and attachment forces, constant;
* Morison drag on the relative velocity ``U = U_current(z) - v``, split along the node
  tangent ``t``: ``f = 1/2 rho d l (C_N |U_N| U_N + pi C_T |U_T| U_T)``
  (:mod:`cablestudy.physics.hydro`, the dodaran-park seed eqs. 38-39);
* inertia ``M = m l I + C_a rho A l (I - t t) + C_at rho A l t t`` (structural mass
  plus added mass, normal and tangential).

Everything here is pure: arrays in, arrays out, SI units. The kernels are compiled
with numba (cached on disk) because a time step is a few microseconds of arithmetic
on short arrays, where interpreter overhead would dominate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..statics.base import LineModel, Medium


@dataclass(frozen=True, kw_only=True)
class DiscreteLine:
    """A line cut into ``n`` elements (``n + 1`` nodes).

    Parameters
    ----------
    s : [m] (n + 1,) unstretched arc length of the nodes from end A
    rest_length : [m] (n,) unstretched element lengths
    axial_stiffness : [N] (n,) EA of each element
    internal_damping : [N s] (n,) axial damping coefficient c (tension c * strain rate)
    mass : [kg] (n + 1,) lumped structural mass (line and attachments)
    added_mass_normal, added_mass_tangential : [kg] (n + 1,) lumped added mass
    drag_normal, drag_tangential : [kg/m] (n + 1,) 1/2 rho C_N d l and 1/2 rho pi C_T d l
    force : [N] (n + 1, 3) constant nodal force (weight in the fluid, attachments)
    current_z : [m] (m,) heights of the current profile, increasing
    current_velocity : [m/s] (m, 3) current at those heights
    has_drag : whether any drag acts (False in vacuum or with zero coefficients)
    """

    s: np.ndarray
    rest_length: np.ndarray
    axial_stiffness: np.ndarray
    internal_damping: np.ndarray
    mass: np.ndarray
    added_mass_normal: np.ndarray
    added_mass_tangential: np.ndarray
    drag_normal: np.ndarray
    drag_tangential: np.ndarray
    force: np.ndarray
    current_z: np.ndarray
    current_velocity: np.ndarray
    has_drag: bool

    @property
    def n_elements(self) -> int:
        return int(self.rest_length.size)

    @property
    def n_nodes(self) -> int:
        return int(self.s.size)

    def kernel_args(self) -> tuple:
        """The arrays in the order the compiled kernels take them."""
        return (
            self.rest_length,
            self.axial_stiffness,
            self.internal_damping,
            self.force,
            self.drag_normal,
            self.drag_tangential,
            self.added_mass_normal,
            self.added_mass_tangential,
            self.mass,
            self.current_z,
            self.current_velocity,
            self.has_drag,
        )


def element_counts(lengths: np.ndarray, elements: int) -> np.ndarray:
    """Elements per segment, about proportional to segment length, at least one each."""
    lengths = np.asarray(lengths, dtype=float)
    counts = np.maximum(1, np.round(elements * lengths / lengths.sum()).astype(int))
    while counts.sum() > max(elements, len(lengths)):
        excess = np.where(counts > 1, counts - elements * lengths / lengths.sum(), -np.inf)
        counts[int(np.argmax(excess))] -= 1
    while counts.sum() < elements:
        i = int(np.argmax(elements * lengths / lengths.sum() - counts))
        counts[i] += 1
    return counts


def discretise(line: LineModel, medium: Medium, elements: int) -> DiscreteLine:
    """Lumped-mass model of ``line`` in ``medium`` with about ``elements`` elements
    (at least one per segment; nodes on every segment boundary).

    Parameters
    ----------
    line : the segments and attachments (SI units, see :class:`LineModel`)
    medium : fluid density [kg/m^3], gravity [m/s^2] and current
    elements : target number of elements [-]
    """
    counts = element_counts(line.length, elements)
    bounds = line.segment_ends
    s = np.concatenate(
        [np.linspace(bounds[i], bounds[i + 1], counts[i] + 1)[:-1] for i in range(len(counts))]
        + [bounds[-1:]]
    )
    seg = np.repeat(np.arange(len(counts)), counts)
    l0 = np.diff(s)
    rho = medium.density
    area = np.pi * line.diameter**2 / 4.0
    ea = line.axial_stiffness[seg]
    m_el = line.mass[seg]
    c_int = line.damping_ratio[seg] * l0 * np.sqrt(ea * m_el)
    n = s.size

    def lump(per_length: np.ndarray) -> np.ndarray:
        half = 0.5 * per_length[seg] * l0
        out = np.zeros(n)
        out[:-1] += half
        out[1:] += half
        return out

    mass = lump(line.mass)
    added_n = lump(line.added_mass_normal * rho * area)
    added_t = lump(line.added_mass_tangential * rho * area)
    drag_n = lump(0.5 * rho * line.drag_normal * line.diameter)
    drag_t = lump(0.5 * rho * np.pi * line.drag_tangential * line.diameter)
    force = np.zeros((n, 3))
    force[:, 2] = -lump(line.weight)
    for k in range(line.attachment_s.size):
        sa = float(line.attachment_s[k])
        e = int(np.clip(np.searchsorted(s, sa, side="right") - 1, 0, n - 2))
        xi = (sa - s[e]) / l0[e]
        for node, share in ((e, 1.0 - xi), (e + 1, xi)):
            force[node] += share * line.attachment_force[k]
            mass[node] += share * line.attachment_mass[k]
    has_drag = bool(rho > 0.0 and (np.any(drag_n > 0.0) or np.any(drag_t > 0.0)))
    return DiscreteLine(
        s=s,
        rest_length=l0,
        axial_stiffness=ea,
        internal_damping=c_int,
        mass=mass,
        added_mass_normal=added_n,
        added_mass_tangential=added_t,
        drag_normal=drag_n,
        drag_tangential=drag_t,
        force=force,
        current_z=np.ascontiguousarray(medium.current_z, dtype=float),
        current_velocity=np.ascontiguousarray(medium.current_velocity, dtype=float).reshape(-1, 3),
        has_drag=has_drag,
    )


def interpolate_nodes(s_nodes: np.ndarray, s_points: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Linear interpolation along the line of nodal ``values`` (..., n + 1, 3) to arc
    lengths ``s_points`` [m]; returns (..., p, 3)."""
    e = np.clip(np.searchsorted(s_nodes, s_points, side="right") - 1, 0, s_nodes.size - 2)
    w = ((s_points - s_nodes[e]) / (s_nodes[e + 1] - s_nodes[e]))[:, None]
    return (1.0 - w) * values[..., e, :] + w * values[..., e + 1, :]


# ------------------------------------------------------------------ compiled kernels


@njit(cache=True)
def assemble(
    x,
    v,
    rest_length,
    axial_stiffness,
    internal_damping,
    force,
    drag_normal,
    drag_tangential,
    added_mass_normal,
    added_mass_tangential,
    mass,
    current_z,
    current_velocity,
    has_drag,
    F,
    K_d,
    K_o,
    C_d,
    C_o,
    M_d,
    tension,
    strain,
    taut0,
):  # noqa: ANN001, ANN201
    """Nodal out-of-balance force ``F = f_internal - f_external`` [N] (n + 1, 3) at
    positions ``x`` [m] and velocities ``v`` [m/s], so that ``M a + F = 0``; its
    tangents: stiffness ``K = dF/dx`` and damping ``C = dF/dv`` as diagonal blocks
    (n + 1, 3, 3) and the blocks coupling node e to e + 1 (n, 3, 3); the mass blocks
    ``M_d`` (n + 1, 3, 3) [kg]; element tension [N] and strain [-] (n,).

    The derivatives of drag and added mass through the node tangent, and of the
    current through z, are left out of the tangents (quasi-Newton). An element flagged
    in ``taut0`` (taut at the start of the time step) keeps its axial stiffness in
    ``K`` even where this iterate makes it slack: otherwise a predictor a few
    micrometres short would drop the axial stiffness of a taut element, and Newton
    would take a huge step along the line's soft (inextensional) modes."""
    n_el = rest_length.shape[0]
    n = n_el + 1
    for i in range(n):
        for a in range(3):
            F[i, a] = -force[i, a]
            for b in range(3):
                K_d[i, a, b] = 0.0
                C_d[i, a, b] = 0.0
                M_d[i, a, b] = 0.0
    u = np.empty(3)
    for e in range(n_el):
        length2 = 0.0
        for a in range(3):
            u[a] = x[e + 1, a] - x[e, a]
            length2 += u[a] * u[a]
        length = math.sqrt(length2)
        rate = 0.0
        for a in range(3):
            u[a] /= length
            rate += u[a] * (v[e + 1, a] - v[e, a])
        l0 = rest_length[e]
        eps = length / l0 - 1.0
        strain[e] = eps
        t = 0.0
        kax = 0.0
        cax = 0.0
        if eps > 0.0:
            t = axial_stiffness[e] * eps + internal_damping[e] * rate / l0
            if t > 0.0:
                kax = axial_stiffness[e] / l0
                cax = internal_damping[e] / l0
            else:
                t = 0.0
        if taut0[e] and kax == 0.0:
            kax = axial_stiffness[e] / l0
        tension[e] = t
        kg = t / length
        for a in range(3):
            F[e + 1, a] += t * u[a]
            F[e, a] -= t * u[a]
            for b in range(3):
                k = (kax - kg) * u[a] * u[b]
                if a == b:
                    k += kg
                c = cax * u[a] * u[b]
                K_d[e, a, b] += k
                K_d[e + 1, a, b] += k
                K_o[e, a, b] = -k
                C_d[e, a, b] += c
                C_d[e + 1, a, b] += c
                C_o[e, a, b] = -c
    tan = np.empty(3)
    rel = np.empty(3)
    un = np.empty(3)
    for i in range(n):
        lo = i - 1 if i > 0 else 0
        hi = i + 1 if i < n - 1 else n - 1
        norm2 = 0.0
        for a in range(3):
            tan[a] = x[hi, a] - x[lo, a]
            norm2 += tan[a] * tan[a]
        norm = math.sqrt(norm2)
        for a in range(3):
            tan[a] /= norm
        mn = added_mass_normal[i]
        mt = added_mass_tangential[i]
        for a in range(3):
            for b in range(3):
                M_d[i, a, b] = (mt - mn) * tan[a] * tan[b]
            M_d[i, a, a] += mass[i] + mn
        if has_drag:
            for a in range(3):
                if current_z.shape[0] > 0:
                    rel[a] = np.interp(x[i, 2], current_z, current_velocity[:, a]) - v[i, a]
                else:
                    rel[a] = -v[i, a]
            rt = rel[0] * tan[0] + rel[1] * tan[1] + rel[2] * tan[2]
            sn2 = 0.0
            for a in range(3):
                un[a] = rel[a] - rt * tan[a]
                sn2 += un[a] * un[a]
            sn = math.sqrt(sn2)
            cn = drag_normal[i]
            ct = drag_tangential[i]
            st = abs(rt)
            for a in range(3):
                F[i, a] -= cn * sn * un[a] + ct * st * rt * tan[a]
                for b in range(3):
                    c = 2.0 * ct * st * tan[a] * tan[b] - cn * sn * tan[a] * tan[b]
                    if sn > 0.0:
                        c += cn * un[a] * un[b] / sn
                    if a == b:
                        c += cn * sn
                    C_d[i, a, b] += c


@njit(cache=True)
def _inv3(m, out):  # noqa: ANN001, ANN202
    a, b, c = m[0, 0], m[0, 1], m[0, 2]
    d, e, f = m[1, 0], m[1, 1], m[1, 2]
    g, h, k = m[2, 0], m[2, 1], m[2, 2]
    A = e * k - f * h
    B = -(d * k - f * g)
    C = d * h - e * g
    det = a * A + b * B + c * C
    inv = 1.0 / det
    out[0, 0] = A * inv
    out[1, 0] = B * inv
    out[2, 0] = C * inv
    out[0, 1] = -(b * k - c * h) * inv
    out[1, 1] = (a * k - c * g) * inv
    out[2, 1] = -(a * h - b * g) * inv
    out[0, 2] = (b * f - c * e) * inv
    out[1, 2] = -(a * f - c * d) * inv
    out[2, 2] = (a * e - b * d) * inv
    return det


@njit(cache=True)
def solve_block_tridiagonal(D, O, rhs, out, Dinv, y):  # noqa: ANN001, ANN201
    """Solve a symmetric block-tridiagonal system with 3 x 3 blocks: diagonal blocks
    ``D`` (m, 3, 3), upper blocks ``O`` (m - 1, 3, 3) (the lower ones are their
    transposes), right side ``rhs`` (m, 3), into ``out`` (block Thomas algorithm, no
    pivoting across blocks: the systems here are symmetric positive definite).
    Returns False when a pivot block is singular."""
    m = D.shape[0]
    W = np.empty((3, 3))
    P = np.empty((3, 3))
    for a in range(3):
        y[0, a] = rhs[0, a]
        for b in range(3):
            P[a, b] = D[0, a, b]
    det = _inv3(P, Dinv[0])
    if not (abs(det) > 0.0) or not math.isfinite(det):
        return False
    for i in range(1, m):
        # W = O[i-1]^T Dinv[i-1]
        for a in range(3):
            for b in range(3):
                acc = 0.0
                for c in range(3):
                    acc += O[i - 1, c, a] * Dinv[i - 1, c, b]
                W[a, b] = acc
        for a in range(3):
            acc = rhs[i, a]
            for c in range(3):
                acc -= W[a, c] * y[i - 1, c]
            y[i, a] = acc
            for b in range(3):
                acc = D[i, a, b]
                for c in range(3):
                    acc -= W[a, c] * O[i - 1, c, b]
                P[a, b] = acc
        det = _inv3(P, Dinv[i])
        if not (abs(det) > 0.0) or not math.isfinite(det):
            return False
    for a in range(3):
        acc = 0.0
        for c in range(3):
            acc += Dinv[m - 1, a, c] * y[m - 1, c]
        out[m - 1, a] = acc
    tmp = np.empty(3)
    for i in range(m - 2, -1, -1):
        for a in range(3):
            acc = y[i, a]
            for c in range(3):
                acc -= O[i, a, c] * out[i + 1, c]
            tmp[a] = acc
        for a in range(3):
            acc = 0.0
            for c in range(3):
                acc += Dinv[i, a, c] * tmp[c]
            out[i, a] = acc
    return True


class Workspace:
    """Scratch arrays of the kernels for a line of ``n`` elements (allocated once per
    run, reused every step)."""

    def __init__(self, n_elements: int) -> None:
        n = n_elements + 1
        self.F = np.zeros((n, 3))
        self.K_d = np.zeros((n, 3, 3))
        self.K_o = np.zeros((n - 1, 3, 3))
        self.C_d = np.zeros((n, 3, 3))
        self.C_o = np.zeros((n - 1, 3, 3))
        self.M_d = np.zeros((n, 3, 3))
        self.tension = np.zeros(n - 1)
        self.strain = np.zeros(n - 1)
        self.taut0 = np.zeros(n - 1, dtype=np.bool_)
        self.J_d = np.zeros((max(n - 2, 1), 3, 3))
        self.J_o = np.zeros((max(n - 3, 1), 3, 3))
        self.r = np.zeros((max(n - 2, 1), 3))
        self.dx = np.zeros((max(n - 2, 1), 3))
        self.Dinv = np.zeros((max(n - 2, 1), 3, 3))
        self.y = np.zeros((max(n - 2, 1), 3))

    def assemble_args(self) -> tuple:
        return (
            self.F,
            self.K_d,
            self.K_o,
            self.C_d,
            self.C_o,
            self.M_d,
            self.tension,
            self.strain,
            self.taut0,
        )

    def solver_args(self) -> tuple:
        return (self.J_d, self.J_o, self.r, self.dx, self.Dinv, self.y)


def evaluate(
    line: DiscreteLine, x: np.ndarray, v: np.ndarray, work: Workspace | None = None
) -> Workspace:
    """Forces, tangents, masses and tensions at state (``x`` [m], ``v`` [m/s])."""
    work = work or Workspace(line.n_elements)
    assemble(
        np.ascontiguousarray(x, dtype=float),
        np.ascontiguousarray(v, dtype=float),
        *line.kernel_args(),
        *work.assemble_args(),
    )
    return work


@njit(cache=True)
def _static_newton(
    x,
    rest_length,
    axial_stiffness,
    internal_damping,
    force,
    drag_normal,
    drag_tangential,
    added_mass_normal,
    added_mass_tangential,
    mass,
    current_z,
    current_velocity,
    has_drag,
    F,
    K_d,
    K_o,
    C_d,
    C_o,
    M_d,
    tension,
    strain,
    taut0,
    J_d,
    J_o,
    r,
    dx,
    Dinv,
    y,
    tol,
    max_iterations,
):  # noqa: ANN001, ANN201
    n = x.shape[0]
    v = np.zeros_like(x)
    res = np.inf
    lmin = rest_length.min()
    for it in range(max_iterations + 1):
        assemble(
            x,
            v,
            rest_length,
            axial_stiffness,
            internal_damping,
            force,
            drag_normal,
            drag_tangential,
            added_mass_normal,
            added_mass_tangential,
            mass,
            current_z,
            current_velocity,
            has_drag,
            F,
            K_d,
            K_o,
            C_d,
            C_o,
            M_d,
            tension,
            strain,
            taut0,
        )
        res = 0.0
        for i in range(1, n - 1):
            for a in range(3):
                res = max(res, abs(F[i, a]))
        if res <= tol:
            return it, res, True
        if it == max_iterations:
            break
        for i in range(1, n - 1):
            for a in range(3):
                r[i - 1, a] = -F[i, a]
                for b in range(3):
                    J_d[i - 1, a, b] = K_d[i, a, b]
            # a little mass-like regularisation keeps slack nodes solvable
            for a in range(3):
                J_d[i - 1, a, a] += 1e-9 * (axial_stiffness.max() / lmin)
        for i in range(1, n - 2):
            for a in range(3):
                for b in range(3):
                    J_o[i - 1, a, b] = K_o[i, a, b]
        ok = solve_block_tridiagonal(
            J_d[: n - 2], J_o[: max(n - 3, 0)], r[: n - 2], dx[: n - 2], Dinv[: n - 2], y[: n - 2]
        )
        if not ok:
            return it, res, False
        big = 0.0
        for i in range(n - 2):
            for a in range(3):
                big = max(big, abs(dx[i, a]))
        scale = 1.0
        if big > 0.25 * lmin:
            scale = 0.25 * lmin / big
        for i in range(1, n - 1):
            for a in range(3):
                x[i, a] += scale * dx[i - 1, a]
    return max_iterations, res, False


def static_equilibrium(
    line: DiscreteLine, x0: np.ndarray, *, tolerance: float, max_iterations: int = 100
) -> tuple[np.ndarray, int, float, bool]:
    """Equilibrium of the discrete line with both end nodes held where ``x0`` puts them.

    Newton from ``x0`` (the continuous static solution at the nodes), so that the time
    integration starts at rest in the discrete model's own equilibrium.

    Returns positions [m] (n + 1, 3), iterations, the largest nodal out-of-balance
    force [N], and whether it fell below ``tolerance`` [N].
    """
    x = np.array(x0, dtype=float, copy=True)
    work = Workspace(line.n_elements)
    it, res, ok = _static_newton(
        x,
        *line.kernel_args(),
        *work.assemble_args(),
        *work.solver_args(),
        tolerance,
        max_iterations,
    )
    return x, int(it), float(res), bool(ok)


def energies(line: DiscreteLine, x: np.ndarray, v: np.ndarray) -> tuple[float, float, float]:
    """(kinetic, strain, potential of the constant nodal forces) energy [J] of the
    discrete line; the potential is ``-sum(force . x)``."""
    work = evaluate(line, x, v)
    kinetic = 0.5 * float(np.einsum("ia,iab,ib->", v, work.M_d, v))
    eps = np.maximum(work.strain, 0.0)
    strain = 0.5 * float(np.sum(line.axial_stiffness * line.rest_length * eps**2))
    potential = -float(np.sum(line.force * x))
    return kinetic, strain, potential
