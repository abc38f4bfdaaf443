"""Static equilibrium of the discrete line in positions and element tensions (mixed).

The line model (:mod:`cablestudy.dynamics.model`) computes an element's tension from
its nodes, ``T = EA (l / l0 - 1)``. With node coordinates of size ``R`` rounded to
``eps R``, that tension carries a rounding of ``EA eps R / l0``: 20 N on a 100 m line
of EA 1e15 at 1 m elements, more than the load on a node. Newton on positions alone
then stops at rounding with a wrong tension, or never converges (a stiff line on a
seabed). Here the element tensions are unknowns of their own:

    node i:     sum_e (+-T_e u_e) + f_i(x) = 0            (equilibrium, [N])
    element e:  c_e T_e = max(g_e, 0)

with ``g_e = l_e / l0_e - 1`` the geometric strain, ``c_e = 1 / EA_e`` the compliance
and ``f_i`` every other nodal force of the model (weight and buoyancy, attachments,
bending, seabed contact and friction, drag), taken from the compiled model with the
axial force switched off. The element row is the tension-only law, its branch chosen
as the complementarity ``min(K c T, c T - g) = 0`` (taut: ``c T = g``; slack:
``T = 0``), each row in units of its tolerance so that every residual is judged
against its own: the
force tolerance ``tol_F`` (set by the nodal loads) and the strain tolerance ``tol_g``
(the relative tolerance of the line's strain, or the rounding of the geometry). The
equations hold as EA grows without bound (``c`` -> 0: the inextensible line), so one
Newton covers EA from 1 N to 1e15 N; the tension comes from equilibrium, accurate to
the loads, never from a difference of rounded positions.

Newton uses the exact tangent of the axial part (``T / l (I - u u)`` and the element
directions) and the model's own tangent of the other forces, a backtracking line
search on the scaled residual, and, where it still fails from its start, a
continuation in stiffness: the same line with its compliance raised so that the
largest strain is 1e-2, then lowered by factors of ten to the true one, each solve
starting from the last.

Everything here is pure: arrays in, arrays out, SI units.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from .assembly import Workspace, _trial_states, evaluate, states_changed, update_anchors
from .discrete_line import DiscreteLine

EPS = float(np.finfo(float).eps)
#: K of the slack branch of the element law (see _System.residual)
SLACK_WEIGHT = 1e3


@dataclass(frozen=True, kw_only=True)
class MixedResult:
    """Outcome of :func:`mixed_equilibrium`.

    position [m] (n + 1, 3); tension [N] (n,) element tensions; iterations (Newton,
    summed over the continuation); force_residual [N] the largest out-of-balance force
    of a free node; converged: the forces and the taut elements' strain misfits
    ``|c T - g|`` within their tolerances; anchor [m] (n + 1, 3) the
    seabed friction anchors that hold the friction forces of that state; stages: the
    continuation's stiffness stages used (0: Newton converged from the start);
    timed_out: stopped by its deadline.
    """

    position: np.ndarray
    tension: np.ndarray
    iterations: int
    force_residual: float
    converged: bool
    anchor: np.ndarray
    stages: int = 0
    timed_out: bool = False


def other_forces_line(line: DiscreteLine) -> DiscreteLine:
    """The line with its axial force switched off (zero EA, linear law, no internal
    damping): the model then gives every nodal force but the element tensions'."""
    m = line.n_elements
    return replace(
        line,
        axial_stiffness=np.zeros(m),
        internal_damping=np.zeros(m),
        law_code=np.zeros(m, dtype=np.int64),
    )


def geometry_rounding(line: DiscreteLine, x: np.ndarray) -> float:
    """Relative rounding [-] of an element's length from node coordinates: 64 ulp of
    the coordinates' reach (largest coordinate plus the line length) over the shortest
    element (64 for the few ulp of each coordinate and of the length's sum)."""
    reach = float(np.max(np.abs(x))) + float(np.sum(line.rest_length))
    return 64.0 * EPS * reach / float(np.min(line.rest_length))


def axial_forces(x: np.ndarray, tension: np.ndarray) -> tuple[np.ndarray, ...]:
    """Nodal forces [N] (n + 1, 3) of element ``tension`` [N] in the model's sign (the
    element pulls node e towards e + 1), with the element directions and lengths [m]."""
    d = np.diff(x, axis=0)
    length = np.linalg.norm(d, axis=1)
    u = d / length[:, None]
    f = np.zeros_like(x)
    tu = tension[:, None] * u
    f[1:] += tu
    f[:-1] -= tu
    return f, u, length


def block_triplets(rows: np.ndarray, cols: np.ndarray, blocks: np.ndarray) -> tuple:
    """COO triplets of 3 x 3 ``blocks`` (k, 3, 3) at node rows and columns (k,)."""
    a = np.arange(3)
    r = 3 * rows[:, None, None] + a[None, :, None]
    c = 3 * cols[:, None, None] + a[None, None, :]
    r, c = np.broadcast_arrays(r, c)
    return r.ravel(), c.ravel(), blocks.ravel()


def band_triplets(work: Workspace, n: int, bending: bool) -> list[tuple]:
    """The model's block-band tangent (diagonal, first and, with bending, second
    off-diagonal blocks, symmetric in position) as COO triplets (here the tangent of
    the other forces; :func:`cablestudy.statics.line_state.discrete_jacobian` the whole
    line's)."""
    i, j = np.arange(n), np.arange(n - 1)
    out = [
        block_triplets(i, i, work.K_d),
        block_triplets(j, j + 1, work.K_o),
        block_triplets(j + 1, j, np.transpose(work.K_o, (0, 2, 1))),
    ]
    if bending and n > 2:
        k = np.arange(n - 2)
        out.append(block_triplets(k, k + 2, work.K_o2))
        out.append(block_triplets(k + 2, k, np.transpose(work.K_o2, (0, 2, 1))))
    return out


def mixed_triplets(
    t: np.ndarray,
    u: np.ndarray,
    length: np.ndarray,
    per_length: np.ndarray,
    taut: np.ndarray,
    n: int,
) -> list[tuple]:
    """The mixed form's coupling of positions and tensions as COO triplets (``n``
    nodes; element e's tension in column 3 n + e): in the node rows the tension's
    geometric stiffness T / l (I - u u) on each element's four node blocks and d(node
    force) / d T_e (+u at node e + 1, -u at node e, the model's sign); in the rows of
    the ``taut`` elements' laws d g / d x = (-u, +u) / l0, divided by ``per_length``
    (the rest lengths in the rows' scaling). Element tensions ``t`` [N], unit vectors
    ``u`` and lengths [m] (m,)."""
    e = np.arange(t.size)
    geo = (t / length)[:, None, None] * (np.eye(3)[None] - u[:, :, None] * u[:, None, :])
    pairs = ((e, e, 1.0), (e + 1, e + 1, 1.0), (e, e + 1, -1.0), (e + 1, e, -1.0))
    parts = [block_triplets(r, c, sign * geo) for r, c, sign in pairs]
    a = np.arange(3)
    col_t = 3 * n + e
    for node, sign in ((e + 1, 1.0), (e, -1.0)):
        parts.append(((3 * node[:, None] + a).ravel(), np.repeat(col_t, 3), (sign * u).ravel()))
    for node, sign in ((e + 1, -1.0), (e, 1.0)):
        rows = np.repeat(col_t[taut], 3)
        cols = (3 * node[taut][:, None] + a).ravel()
        parts.append((rows, cols, (sign * u[taut] / per_length[taut][:, None]).ravel()))
    return parts


class _System:
    """Residuals and tangent of the mixed equations for one compliance."""

    def __init__(
        self,
        line: DiscreteLine,
        anchor: np.ndarray,
        work: Workspace,
        compliance: np.ndarray,
        tol_force: float,
        tol_strain: float,
    ) -> None:
        self.line = line
        self.other = other_forces_line(line)
        self.anchor = anchor
        self.work = work
        self.c = compliance
        self.tol_f = tol_force
        self.tol_g = tol_strain
        self.free = ~np.asarray(line.held, dtype=bool)
        self.n = line.n_nodes
        self.m = line.n_elements
        self.broken = np.asarray(line.broken, dtype=bool)
        self.weight = np.full(self.m, SLACK_WEIGHT)

    def weigh_slack(self, x: np.ndarray, tension: np.ndarray) -> None:
        """K of each element: 1e3, or 1e3 times the start's chord shortening over the
        element's stretch where that is more, so that a loaded element starts taut."""
        _, _, length = axial_forces(x, tension)
        misfit = self.c * tension - (length / self.line.rest_length - 1.0)
        stretch = self.c * tension
        ratio = np.divide(misfit, stretch, out=np.zeros_like(misfit), where=stretch > 0.0)
        self.weight = SLACK_WEIGHT * np.maximum(1.0, ratio)

    def forces(self, x: np.ndarray, tension: np.ndarray) -> np.ndarray:
        """Nodal out-of-balance forces [N] (held nodes: their reactions)."""
        evaluate(self.other, x, np.zeros_like(x), self.work, anchor=self.anchor)
        f, self.u, self.length = axial_forces(x, tension)
        return self.work.F + f

    def residual(self, x: np.ndarray, tension: np.ndarray) -> tuple[np.ndarray, ...]:
        """Scaled residual vector, nodal forces [N], strain misfit [-], taut mask."""
        F = self.forces(x, tension)
        g = self.length / self.line.rest_length - 1.0
        misfit = self.c * tension - g
        # c T = max(g, 0) as the complementarity min(K c T, c T - g) = 0 (continuous,
        # so the line search compares like with like): slack where K c T < c T - g,
        # the chord shorter than K times the element's elastic stretch. K is 1e3, and
        # more where the start's chord is short by more than that (a stiff line's
        # chords of a smooth curve are shorter than its arcs by O(h^2 kappa^2), far
        # more than its stretch): every element the start loads starts taut
        slack_value = self.weight * self.c * tension
        taut = (misfit <= slack_value) & ~self.broken
        phi = np.where(taut, misfit, slack_value) / self.tol_g
        vec = np.concatenate([(F[self.free] / self.tol_f).ravel(), phi])
        return vec, F, misfit, taut

    def step(self, x: np.ndarray, tension: np.ndarray, taut: np.ndarray, reg: float) -> tuple:
        """Newton correction (dx [m], dT [N]) of the scaled residual at (x, tension)."""
        n, m = self.n, self.m
        parts = band_triplets(self.work, n, self.line.has_bending)
        # element rows: taut (c T - g) / tol_g, slack K c T / tol_g
        l0 = self.line.rest_length * self.tol_g
        parts += mixed_triplets(tension, self.u, self.length, l0, taut, n)
        nx = 3 * n
        col_t = nx + np.arange(m)
        parts.append((col_t, col_t, np.where(taut, 1.0, self.weight) * self.c / self.tol_g))
        R = np.concatenate([p[0] for p in parts])
        C = np.concatenate([p[1] for p in parts])
        V = np.concatenate([p[2] for p in parts])
        # node rows in units of tol_F; held nodes keep their place (identity rows)
        held_dof = np.repeat(~self.free, 3)
        node_row = R < nx
        scale = np.where(node_row, 1.0 / self.tol_f, 1.0)
        keep = ~(node_row & held_dof[np.minimum(R, nx - 1)])
        R, C, V = R[keep], C[keep], (V * scale)[keep]
        diag = np.where(held_dof, 1.0, reg / self.tol_f)
        R = np.concatenate([R, np.arange(nx)])
        C = np.concatenate([C, np.arange(nx)])
        V = np.concatenate([V, diag])
        J = sp.csc_matrix((V, (R, C)), shape=(nx + m, nx + m))
        vec, *_ = self.last
        rhs = np.zeros(nx + m)
        n_free = 3 * int(self.free.sum())
        rhs[:nx][np.repeat(self.free, 3)] = -vec[:n_free]
        rhs[nx:] = -vec[n_free:]
        sol = splu(J).solve(rhs)
        dx = sol[:nx].reshape(n, 3)
        dx[~self.free] = 0.0  # held exactly (the pivoting LU leaves rounding there)
        return dx, sol[nx:]


def _newton(
    system: _System,
    x: np.ndarray,
    tension: np.ndarray,
    max_iterations: int,
    deadline: float | None = None,
) -> tuple[np.ndarray, np.ndarray, int, bool]:
    """Newton with a backtracking line search; returns positions, tensions, iterations
    and whether the scaled residual fell to 1 (every residual within its tolerance).
    Stops (not converged) when the :func:`time.monotonic` ``deadline`` passes."""
    line = system.line
    lmin = float(np.min(line.rest_length))
    has_friction = bool(
        np.any(line.friction > 0.0) and line.has_seabed and np.all(np.isfinite(line.friction))
    )
    work = system.work
    work.slip_state[:] = 0
    system.last = system.residual(x, tension)
    if has_friction:
        _trial_states(work.slip_state, work.trial, work.contact, line.friction)
        system.last = system.residual(x, tension)
    checks = 0
    restarts = 0
    for it in range(max_iterations + 1):
        vec, F, misfit, taut = system.last
        if np.max(np.abs(vec), initial=0.0) <= 1.0:
            if (
                has_friction
                and checks < 20
                and states_changed(work.slip_state, work.trial, work.contact, line.friction)
            ):
                checks += 1
                system.last = system.residual(x, tension)
                continue
            return x, tension, it, True
        if it == max_iterations or (deadline is not None and time.monotonic() > deadline):
            return x, tension, it, False
        tmax = max(float(np.max(tension)), 0.0)
        reg = 1e-10 * max(tmax, system.tol_f) / lmin
        try:
            dx, dt = system.step(x, tension, taut, reg)
        except RuntimeError:  # a singular tangent
            return x, tension, it, False
        if not (np.all(np.isfinite(dx)) and np.all(np.isfinite(dt))):
            return x, tension, it, False
        merit = float(vec @ vec)
        alpha = 1.0
        for _ in range(30):
            xt, tt = x + alpha * dx, tension + alpha * dt
            trial = system.residual(xt, tt)
            value = float(trial[0] @ trial[0])
            if np.isfinite(value) and value <= (1.0 - 1e-4 * alpha) * merit:
                break
            alpha *= 0.5
        else:
            system.last = system.residual(x, tension)
            if has_friction and restarts < 20:
                # the stick/slip states Newton holds are no longer those of this
                # state (a node met the seabed): set them afresh and go on
                restarts += 1
                _trial_states(work.slip_state, work.trial, work.contact, line.friction)
                system.last = system.residual(x, tension)
                continue
            return x, tension, it, False
        x, tension = xt, tt
        system.last = trial
        if has_friction:
            # a node that has met the seabed takes a stick/slip state from its trial
            # force, the others keep theirs (the friction Newton sees stays smooth)
            _trial_states(work.slip_state, work.trial, work.contact, line.friction, True)
            system.last = system.residual(x, tension)
    return x, tension, max_iterations, False


def mixed_equilibrium(
    line: DiscreteLine,
    x0: np.ndarray,
    tension0: np.ndarray,
    anchor: np.ndarray,
    *,
    tol_force: float,
    relative: float,
    max_iterations: int = 200,
    deadline: float | None = None,
) -> MixedResult:
    """Equilibrium of ``line`` in positions and element tensions.

    Parameters
    ----------
    line : the discrete line (held nodes stay where ``x0`` puts them)
    x0 : [m] (n + 1, 3) start positions (the cable solution at the nodes)
    tension0 : [N] (n,) start element tensions
    anchor : [m] (n + 1, 3) seabed friction anchors
    tol_force : [N] the largest out-of-balance force allowed on a free node
    relative : [-] the relative tolerance of the strain (the study's tolerance)
    max_iterations : Newton iterations per continuation stage
    deadline : a :func:`time.monotonic` time after which Newton stops (not converged;
        ``timed_out`` in the result)
    """
    if np.any(line.law_code != 0):
        raise ValueError("mixed_equilibrium: the element law is written for T = EA strain")
    ea = np.asarray(line.axial_stiffness, dtype=float)
    compliance = 1.0 / ea
    x = np.array(x0, dtype=float, copy=True)
    tension = np.maximum(np.asarray(tension0, dtype=float), 0.0)
    tmax = max(float(np.max(tension)), tol_force)
    floor = geometry_rounding(line, x)
    tol_strain = max(relative * tmax / float(np.min(ea)), floor)
    work = Workspace(line.n_elements)
    system = _System(line, anchor, work, compliance, tol_force, tol_strain)
    system.weigh_slack(x, tension)
    xs, ts, its, ok = _newton(system, x, tension, max_iterations, deadline)
    total = its
    used = 0
    # continuation in stiffness: soften so that the largest strain is 1e-2, then
    # stiffen tenfold at a time to the line's own compliance (a line already that soft
    # has none)
    stages = []
    level = 1e-2 / tmax
    while level > float(np.max(compliance)) * 10.0:
        stages.append(level)
        level *= 0.1
    late = deadline is not None and time.monotonic() > deadline
    if not ok and stages and not late:
        xs, ts = x, tension
        for level in [*stages, None]:
            c = compliance if level is None else np.maximum(compliance, level)
            tol_g = tol_strain if level is None else max(tol_strain, relative * tmax * level)
            system = _System(line, anchor, work, c, tol_force, tol_g)
            system.weigh_slack(xs, ts)
            xs, ts, its, ok = _newton(system, xs, ts, max_iterations, deadline)
            total += its
            used += 1
            if not ok:
                break
        late = deadline is not None and time.monotonic() > deadline
    F = system.last[1]
    free = ~np.asarray(line.held, dtype=bool)
    held_anchor = np.array(anchor, dtype=float, copy=True)
    update_anchors(xs, work.friction, line.seabed_stiffness, work.contact, held_anchor)
    return MixedResult(
        anchor=held_anchor,
        position=xs,
        tension=ts,
        iterations=int(total),
        force_residual=float(np.max(np.abs(F[free]), initial=0.0)),
        converged=bool(ok),
        stages=used,
        timed_out=bool(late and not ok),
    )


def node_forces(
    line: DiscreteLine, x: np.ndarray, tension: np.ndarray, anchor: np.ndarray
) -> tuple[np.ndarray, Workspace]:
    """Out-of-balance nodal forces [N] (n + 1, 3) of positions ``x`` [m] and element
    ``tension`` [N] (held nodes: the reactions the supports give), and the model's
    workspace at that state (contact and friction forces)."""
    work = Workspace(line.n_elements)
    evaluate(other_forces_line(line), x, np.zeros_like(x), work, anchor=anchor)
    f, _, _ = axial_forces(x, tension)
    return work.F + f, work


def is_finite_line(line: DiscreteLine) -> bool:
    """Whether the mixed form applies: every element T = EA strain with EA > 0."""
    return bool(np.all(line.law_code == 0) and np.all(line.axial_stiffness > 0.0)) and bool(
        math.isfinite(float(np.max(line.axial_stiffness)))
    )
