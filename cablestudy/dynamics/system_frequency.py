"""Frequency-domain response of a mooring system: every line and free point linearised
together about the static state, driven by harmonic motion of the bodies.

Each line is the single-line frequency domain's linear model
(:class:`~cablestudy.dynamics.frequency.LinearLine`, both end nodes prescribed; its
matrices projected once on the inner nodes, :class:`~.frequency.ReducedLine`). Lines
meet at points: fixed (at rest), on a prescribed body (moved rigidly with it) or free
(junctions, clumps, buoys: unknown). Every quantity is ``Re(Q exp(i w t))``.

The model. With ``A = K - w^2 M + i w (C + D)`` a line's dynamic matrix (``D`` its
linearised drag, below), split into the inner nodes ``I`` and its two end nodes ``E``,
the inner nodes carry no external load and the end rows give the force the line needs
at its end nodes (minus the force of the line on the point):

    A_II u_I + A_IE u_E = 0,        f_E = A_EI u_I + A_EE u_E.

Per line, one band factorisation of ``A_II`` (the line's band) solves ``A_II X =
-A_IE`` for the six end unit motions, so ``u_I = X u_E`` and ``f_E = S u_E`` with the
condensed end dynamic stiffness ``S = A_EE + A_EI X`` (6 x 6, the Schur complement).
A free point ``p`` of mass ``m_p`` (added mass included; 3 x 3) and linearised drag
``D_p`` balances the forces it applies to the lines' end nodes:

    (-w^2 m_p + i w D_p) u_p + sum over line ends at p of (S u_E)_end = 0,

a dense system of three unknowns per free point (the junction system), whose right
side carries the prescribed motion of the other line ends. No matrix over all nodes
is ever formed: per line a banded solve with six right sides, and one small dense solve.

Body motion. A body's complex amplitudes ``(X, Theta)`` (surge, sway, heave [m], roll,
pitch, yaw [rad]) move its point at global offset ``a = R p`` from the reference point
by ``X + Theta x a`` (small rotation: the rotation matrices' first order, whatever
their order).

Drag. Each line's nodal Morison drag is linearised as in the single-line frequency
domain (``drag_linearisation`` of tests/drag_fit_reference.py: the mean-square,
describing-function fit of ``c_N |w_N| w_N + c_T |w_T| w_T``, closed form for motion in
the x-z plane and for any node without current, :mod:`.elliptic_fit`); a free point's
isotropic drag ``c |w| w`` (``c = rho C_d A / 2``) is fitted the same way (over
``samples`` phases; in closed form without current when ``samples`` is unset). Since
``D`` depends on the motion the solve is iterated from the quasi-static motion (``w =
0``: the stiffness alone, the velocity then ``i w u``), with Anderson mixing (depth 4,
the step damped by 0.8: :data:`.system_fd_fit.MIXING`; after a change that grew, the
mean of the last two with the history dropped, as the single line's iteration), until
the velocity amplitudes of every node change by less than ``tolerance`` of the largest.

Output per line: end tension variations at A and B (``F_hat . dF``, ``F_hat`` the unit
static force of the line on the point, as in the single-line frequency domain), the
element tension variations (the envelope ``T_static +- |dT|``) and the displacements;
per point its displacement. Status 0 only when the assembled equations hold: every
line's inner rows and every free point's balance are checked on the solution (the
residual against the largest end force amplitude, :data:`RESIDUAL_BAR`).

Measured (issue 24; case8 imported whole, 40 elements a line): against MoorDyn at
0.1 m, 0.1 Hz every end tension amplitude within 1.7e-3 (surge) and 3.6e-4 (heave) of
the largest (tests/validation/test_system_frequency_moordyn.py); at the references'
2 m surge the linear answer is 1.6e-2 of T_max off MoorDyn's extremes, at 1 m heave
5.6e-4. Where lines lie on the seabed the contact is linearised as the time domain's
spring held closed, at the single line's nodes: a node at each touchdown point
besides the equally spaced ones (:mod:`.touchdown_mesh`), so that a system of one
line is the one-line study's model byte for byte. Measured before that node (on
MoorDyn's lines.txt, chains, 135 m laid; surge at 0.05 Hz): the quasi-static body
stiffness the exact catenary's within 3e-3, the amplitudes 8-15 % above the time
domains' at 0.2 m (ours and MoorDyn's agree within 4 %), and those not linear there
themselves (per metre of motion, 0.05 m and 0.2 m differ by 4 % on leg 1 and 15 % on
legs 2 and 3): ``method: auto`` should send such cases to the time domain. With it,
one 320 m line, 130 m laid, surged 0.15 m at 0.1 Hz: the end B tension amplitude
106.0 N (10 elements) and 92.3 N (40) against the time domain's 94.5 N at 40
elements; without it 148.2 N and 126.9 N.

The iteration of a case runs in one compiled call for all lines
(:mod:`.system_fd_kernel`, the model packed once in flat arrays: :mod:`.system_fd_pack`;
per line only the junction's right sides are solved, four on a line from a junction
to a body); the NumPy/LAPACK iteration line by line (tests/system_frequency_reference.py,
``solve_reference``) is the oracle it is tested against: the same iteration counts
and answers within 1e-7 of the largest (tests/unit/test_system_fd_kernel.py). At two
elements a line (one inner node) the band is widened to a node's drag block. Cases
that share a model go to the kernel together as a sweep
(:mod:`.system_frequency_sweep`, :mod:`.system_fd_sweep`): one work space, each case
from the quasi-static start, its answer the case's alone bit for bit. A warm start from
the neighbours' converged drag was measured (6.4 drag iterations a case instead of
10.1 on case8 surged 2 m over 0.02-0.5 Hz, every answer within the tolerance of the
same fixed point) and removed: it made a case's record depend on the cases solved
beside it.

Building the model is cheap next to a time-domain case (``method: auto`` builds it
before it judges a case): the lines re-solved at the model's nodes in one call of the
compiled static kernels per group (``solve_many``; each answer verified as the
solver's own); their linear lines with alike lines sharing their discretisation
(:func:`~.linear_model.linear_lines`); every line, held at both ends, reduced and its
end couplings picked from its matrices entry by entry over all lines at once
(:func:`~.system_fd_build.held_lines`; :meth:`ReducedLine.of` and
:func:`_coordinate_coupling` or the sparse products line by line for other bases).
All give the plain construction's model byte for byte
(tests/unit/test_system_fd_build.py). On the case8 benchmark at 3 elements a line
(tests' machine, shared): the model 7.2 -> 4.6 ms, of which the re-solve 2.2 ms (the
contact legs verified one by one: 1.1 ms), the linear lines 1.5 ms, the reduction
0.4 ms; packing 0.55 -> 0.24 ms.

Pure: arrays and frozen dataclasses in, a :class:`SystemFrequencyResult` out.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from ..physics.current import current_velocity
from ..statics.base import STATUS_NUMERICAL, STATUS_OK, EndCondition, StaticProblem, StaticResult
from ..statics.system_model import BODY, FREE, MooringSystem, SystemResult
from .frequency_model import (
    STATUS_NOT_CONVERGED,
    DragSettings,
    LinearLine,
    ReducedLine,
    block_entries,
    csr_entries,
    selected_rows,
)
from .linear_model import linear_lines
from .modal import ModalProblem
from .system_fd_kernel import NOT_CONVERGED, SINGULAR_JUNCTION, SINGULAR_LINE
from .system_fd_pack import PackedSystem, pack_system
from .system_fd_sweep import INFO, solve_sweep
from .touchdown_mesh import touchdown_states

#: largest residual of the assembled equations on the solution (inner rows of every
#: line, balance of every free point), relative to the largest end-force amplitude and
#: the largest inertial/stiffness force scale: LAPACK's band and dense solves leave
#: about the condition number times 1e-16; 1e-8 allows condition numbers to 1e8
RESIDUAL_BAR = 1e-8


@dataclass(frozen=True, kw_only=True, eq=False)
class SystemLinear:
    """A mooring system linearised about its static state.

    Parameters
    ----------
    names : line names, (L,)
    lines : each line's reduced linear model (both end nodes prescribed), (L,)
    ends : (L, 2) int, the point at end A and at end B of each line
    point_kind : (P,) int, FIXED, FREE or BODY (:mod:`cablestudy.statics.system`)
    point_body : (P,) int, body index of BODY points (-1 otherwise)
    point_arm : [m] (P, 3) global offset ``R p`` of a BODY point from its body's
        reference point in the static state (zeros otherwise)
    point_mass : [kg] (P, 3, 3) mass and added mass of the free points
    point_drag : [kg/m] (P,) isotropic drag coefficient ``rho C_d A / 2`` of free points
    point_current : [m/s] (P, 3) current at the points
    n_bodies : number of bodies
    """

    names: tuple[str, ...]
    lines: tuple[ReducedLine, ...]
    ends: np.ndarray
    point_kind: np.ndarray
    point_body: np.ndarray
    point_arm: np.ndarray
    point_mass: np.ndarray
    point_drag: np.ndarray
    point_current: np.ndarray
    n_bodies: int

    @property
    def free_points(self) -> np.ndarray:
        return np.flatnonzero(self.point_kind == FREE)

    @functools.cached_property
    def couplings(self) -> tuple[EndCoupling, ...]:
        """Per line the blocks that couple its end nodes (built once)."""
        return tuple(EndCoupling.of(r) for r in self.lines)

    @functools.cached_property
    def packed(self) -> PackedSystem:
        """The model in the compiled iteration's flat arrays (built once)."""
        return pack_system(self)

    @functools.cached_property
    def post(self) -> _Post:
        """What turns a solution into outputs, per line and element (built once)."""
        return _Post.of(self)

    @property
    def has_drag(self) -> bool:
        return bool(np.any(self.point_drag > 0.0)) or any(r.line.has_drag for r in self.lines)


@dataclass(frozen=True, eq=False)
class _Post:
    """A model's constants of the outputs: ``unit`` (L, 2, 3) the static end forces'
    directions; per line end on a body (``body_line``, ``body_end``) its ``body``, the
    ``body_arm`` (k, 3) and the static end force ``body_static`` (k, 3); per element
    of all lines (node ``element`` to the next, flat over the lines' nodes) its
    ``direction``, ``axial_stiffness`` and ``axial_damping`` over its rest length, and
    where the lines' elements split (``element_split``); the static end tensions
    ``static`` (L, 2) and, flat over the lines' nodes, the static tension of the
    envelope ``node_static``, the inner nodes ``inner`` and the flat elements ``left``
    and ``right`` of each, each line's ``first`` and ``last`` node and where they
    split."""

    unit: np.ndarray
    body_line: np.ndarray
    body_end: np.ndarray
    body: np.ndarray
    body_arm: np.ndarray
    body_static: np.ndarray
    element: np.ndarray
    direction: np.ndarray
    axial_stiffness: np.ndarray
    axial_damping: np.ndarray
    element_split: np.ndarray
    static: np.ndarray
    node_static: np.ndarray
    inner: np.ndarray
    left: np.ndarray
    right: np.ndarray
    first: np.ndarray
    last: np.ndarray
    node_split: np.ndarray

    @classmethod
    def of(cls, model: SystemLinear) -> _Post:
        lines = [r.line for r in model.lines]
        L = len(lines)
        static = np.array([np.linalg.norm(ln.end_force, axis=1) for ln in lines]).reshape(L, 2)
        unit = (
            np.array([ln.end_force for ln in lines]).reshape(L, 2, 3)
            / np.where(static > 0.0, static, 1.0)[:, :, None]
        )
        on = [
            (i, k) for i in range(L) for k in range(2) if model.point_kind[model.ends[i, k]] == BODY
        ]
        li = np.array([i for i, _ in on], dtype=int)
        ki = np.array([k for _, k in on], dtype=int)
        pts = model.ends[li, ki]
        start = np.cumsum([0] + [ln.n_nodes for ln in lines])[:-1]
        inner = np.concatenate(
            [s + np.arange(1, ln.n_nodes - 1) for s, ln in zip(start, lines, strict=True)]
        ).astype(int)
        line_of = np.repeat(np.arange(L), [ln.n_nodes - 2 for ln in lines])
        return cls(
            unit=unit,
            body_line=li,
            body_end=ki,
            body=model.point_body[pts],
            body_arm=model.point_arm[pts].reshape(-1, 3),
            body_static=np.array([lines[i].end_force[k] for i, k in on]).reshape(-1, 3),
            element=np.concatenate(
                [s + np.arange(ln.n_nodes - 1) for s, ln in zip(start, lines, strict=True)]
            ),
            direction=np.concatenate([ln.direction for ln in lines]),
            axial_stiffness=np.concatenate([ln.axial_stiffness / ln.rest_length for ln in lines]),
            axial_damping=np.concatenate([ln.axial_damping / ln.rest_length for ln in lines]),
            element_split=np.cumsum([ln.n_nodes - 1 for ln in lines])[:-1],
            static=static,
            node_static=np.concatenate(
                [
                    np.concatenate(([static[i, 0]], 0.5 * (t[:-1] + t[1:]), [static[i, 1]]))
                    for i, t in enumerate(ln.tension for ln in lines)
                ]
            ),
            inner=inner,
            left=inner - line_of - 1,
            right=inner - line_of,
            first=start.astype(int),
            last=(start + [ln.n_nodes - 1 for ln in lines]).astype(int),
            node_split=np.cumsum([ln.n_nodes for ln in lines])[:-1],
        )


#: the end nodes' six coordinates in a line's 3n (A x, y, z; B x, y, z)
def _end_index(n: int) -> np.ndarray:
    return np.array([0, 1, 2, 3 * n - 3, 3 * n - 2, 3 * n - 1])


@dataclass(frozen=True, eq=False)
class EndCoupling:
    """The stiffness, mass and damping blocks of a line between its inner free
    directions ``I`` and its end nodes' coordinates ``E`` (dense: ``IE`` (k, 6), ``EI``
    (6, k), ``EE`` (6, 6)), so that a frequency's condensation needs no product with the
    line's sparse matrices. The drag is per node, so it couples no inner node to an
    end: only its end blocks enter ``EE``."""

    K: tuple[np.ndarray, np.ndarray, np.ndarray]
    M: tuple[np.ndarray, np.ndarray, np.ndarray]
    C: tuple[np.ndarray, np.ndarray, np.ndarray]

    @classmethod
    def of(cls, red: ReducedLine) -> EndCoupling:
        fast = _coordinate_coupling(red.line)
        return cls(*(fast if fast is not None else _sparse_coupling(red.line)))


def _sparse_coupling(line: LinearLine) -> tuple:
    """:class:`EndCoupling`'s (K, M, C) blocks by sparse products with the free basis
    (any basis)."""
    B = line.free_basis.tocsc()
    e = _end_index(line.n_nodes)

    def blocks(Q: object) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        Q = Q.tocsr()  # type: ignore[attr-defined]
        cols = Q[:, e]
        rows = Q[e, :]
        return (
            np.asarray((B.T @ cols).todense()),
            np.asarray((rows @ B).todense()),
            np.asarray(rows[:, e].todense()),
        )

    return blocks(line.stiffness), blocks(line.mass_matrix()), blocks(line.damping)


def _coordinate_coupling(line: LinearLine) -> tuple | None:
    """:class:`EndCoupling`'s (K, M, C) blocks picked entry by entry, without sparse
    products, when the free basis is made of coordinate directions
    (:func:`~.frequency_model.selected_rows`) and the matrices' entries are at hand
    (:func:`~.frequency_model.csr_entries`, :func:`~.frequency_model.block_entries`):
    ``B^T Q[:, E]`` is then ``Q`` at the free rows and the end columns, each entry a
    single product by 1, as scipy's products give it (None: not such a basis)."""
    B = line.free_basis
    rows = selected_rows(B)
    if rows is None:
        return None
    parts = (csr_entries(line.stiffness), block_entries(line.mass), csr_entries(line.damping))
    if any(p is None for p in parts):
        return None
    n3, k = B.shape
    column_of = np.full(n3, -1, dtype=np.int64)
    column_of[rows] = np.arange(k)
    end_of = np.full(n3, -1, dtype=np.int64)
    end_of[_end_index(line.n_nodes)] = np.arange(6)
    out = []
    for row, col, val in parts:  # type: ignore[misc]
        r_in, c_in, r_end, c_end = column_of[row], column_of[col], end_of[row], end_of[col]
        ie, ei, ee = np.zeros((k, 6)), np.zeros((6, k)), np.zeros((6, 6))
        m = (r_in >= 0) & (c_end >= 0)
        ie[r_in[m], c_end[m]] = val[m]
        m = (r_end >= 0) & (c_in >= 0)
        ei[r_end[m], c_in[m]] = val[m]
        m = (r_end >= 0) & (c_end >= 0)
        ee[r_end[m], c_end[m]] = val[m]
        out.append((ie, ei, ee))
    return tuple(out)


@dataclass(kw_only=True)
class SystemFrequencyResult:
    """Harmonic response of a system (complex amplitudes of ``Re(Q e^{i w t})``).

    end_tension [N] (L, 2) variation of each line's end tensions at A and B;
    tension_static [N] (L, 2); element_tension [N] per line (n_l - 1,) complex;
    displacement [m] per line (n_l, 3) complex; point_displacement [m] (P, 3) complex;
    end_force [N] (L, 2, 3) variation of the force of each line on its points at A and
    B; body_force [N, N m] (B, 6) variation of the force and moment of the lines on each
    body about its reference point, ``sum dF`` and ``sum (a x dF + (Theta x a) x F)``
    (the static force ``F`` turning with the arm);
    iterations, converged, change (drag iteration); residual (relative, see
    :data:`RESIDUAL_BAR`); status, message.
    """

    end_tension: np.ndarray
    tension_static: np.ndarray
    element_tension: list[np.ndarray]
    displacement: list[np.ndarray]
    point_displacement: np.ndarray
    end_force: np.ndarray
    body_force: np.ndarray
    iterations: int = 0
    converged: bool = True
    change: float = 0.0
    residual: float = 0.0
    status: int = STATUS_OK
    message: str = ""
    element_tension_static: list[np.ndarray] = field(default_factory=list)
    #: per line the linear tension envelope at its nodes [N] (n_l,), (max, min): static
    #: plus and minus the amplitude of the variation; at the ends the end tensions,
    #: inside the mean of the two elements a node joins (static and complex variation)
    envelope_lines: tuple[list[np.ndarray], list[np.ndarray]] | None = None


# ------------------------------------------------------------------------ building


def system_linear(
    system: MooringSystem,
    static: SystemResult,
    *,
    point_mass: np.ndarray | None = None,
    point_added_mass: np.ndarray | None = None,
    point_drag: np.ndarray | None = None,
    extras: list | None = None,
    nodes: int | None = None,
    solve: Callable[[StaticProblem], StaticResult] | None = None,
    solve_many: Callable[[list[StaticProblem]], list[StaticResult]] | None = None,
) -> tuple[SystemLinear | None, str]:
    """The system linearised about its solved static state ``static``, or None and why
    not. ``point_mass`` and ``point_added_mass`` [kg] (P,) (isotropic) and
    ``point_drag`` [kg/m] (P,) (``rho C_d A / 2``) of the free points (zeros when not
    given); ``extras`` per line the :class:`~cablestudy.dynamics.model.DynamicExtras`
    (None: the line's defaults). The nodes of each line are its static samples, or with
    ``nodes`` that many equally spaced ones: each line solved again by ``solve`` (a
    static solver's ``solve``) between its points where the system put them, or all
    such lines in one call of ``solve_many`` (the same answers as ``solve`` of each)."""
    P = len(system.point_names)
    held = EndCondition(kind="fixed")
    states = list(static.lines)
    if nodes is not None:
        again = [i for i, st in enumerate(states) if len(st.s) != nodes]
        if again and solve is None and solve_many is None:
            raise ValueError("system_linear: nodes needs a static solver (solve)")
        problems = [
            replace(
                system.lines[i].problem,
                end_a=EndCondition(kind="fixed", position=static.point_position[system.lines[i].a]),
                end_b=EndCondition(kind="fixed", position=static.point_position[system.lines[i].b]),
                n_nodes=nodes,
            )
            for i in again
        ]
        if solve_many is not None:
            solved = solve_many(problems)
        else:
            assert solve is not None
            solved = [solve(problem) for problem in problems]
        for i, st in zip(again, solved, strict=True):
            if not st.success:
                return None, f"line {system.lines[i].name!r} at {nodes} nodes: {st.message}"
            states[i] = st
        touchdown_states(system, static, states, nodes, solve, solve_many)
    problems = []
    for i, (sl, st) in enumerate(zip(system.lines, states, strict=True)):
        T_e = 0.5 * (st.tension[:-1] + st.tension[1:])
        med = sl.problem.medium
        if med.depth is not None:
            ground = med.seabed_z(st.position[:, 0], st.position[:, 1])
            on_bed = st.position[:, 2] - ground <= 1e-6 * max(float(st.s[-1]), 1.0)
        else:
            on_bed = np.zeros(len(st.s), dtype=bool)
        slack = (T_e <= 0.0) & ~(on_bed[:-1] & on_bed[1:])
        if np.any(slack):
            return None, (
                f"line {sl.name!r} is slack in the static state (element tension "
                f"{float(T_e[slack].min()):.4g} N); the frequency domain needs taut lines"
            )
        # the linear line's nodes are the state's samples
        ends = static.point_position[[sl.a, sl.b]]
        gap = float(np.max(np.abs(np.asarray(st.position, dtype=float)[[0, -1]] - ends)))
        if gap > 1e-6 * max(float(st.s[-1]), 1.0):
            return None, f"line {sl.name!r} does not end at its points (gap {gap:.3g} m)"
        problems.append(
            ModalProblem(
                line=sl.problem.line,
                medium=med,
                end_a=held,
                end_b=held,
                static=st,
                extras=None if extras is None else extras[i],
            )
        )
    from .system_fd_build import held_lines

    linear = linear_lines(problems)  # linear_line of each, alike lines sharing work
    # every line held at both ends: reduced and coupled in one pass over all lines
    fast = held_lines(linear)
    reduced = fast[0] if fast is not None else [ReducedLine.of(line) for line in linear]
    arm = np.zeros((P, 3))
    on_body = system.point_kind == BODY
    if np.any(on_body):
        bodies = static.body_position if static.body_position is not None else system.body_position
        arm[on_body] = static.point_position[on_body] - bodies[system.point_body[on_body], :3]
    m = np.zeros(P) if point_mass is None else np.asarray(point_mass, dtype=float)
    ma = np.zeros(P) if point_added_mass is None else np.asarray(point_added_mass, dtype=float)
    mass = (m + ma)[:, None, None] * np.eye(3)[None]
    medium = system.lines[0].problem.medium
    current = (
        current_velocity(static.point_position[:, 2], medium.current_z, medium.current_velocity)
        if medium.current_velocity.size
        else np.zeros((P, 3))
    )
    model = SystemLinear(
        names=tuple(sl.name for sl in system.lines),
        lines=tuple(reduced),
        ends=np.array([[sl.a, sl.b] for sl in system.lines], dtype=int).reshape(-1, 2),
        point_kind=np.asarray(system.point_kind, dtype=int),
        point_body=np.asarray(system.point_body, dtype=int),
        point_arm=arm,
        point_mass=mass,
        point_drag=np.zeros(P) if point_drag is None else np.asarray(point_drag, dtype=float),
        point_current=np.asarray(current, dtype=float).reshape(P, 3),
        n_bodies=len(system.body_names),
    )
    if fast is not None:  # the couplings came with the reduced lines (cached property)
        model.__dict__["couplings"] = tuple(EndCoupling(*b) for b in fast[1])
    return model, ""


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``np.cross(a, b)`` of (..., 3) arrays, the same products and differences (so the
    same values) without its reshaping of axes (most of its cost on small arrays)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack((a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0), axis=-1)


def point_motion(model: SystemLinear, body_motion: np.ndarray) -> np.ndarray:
    """Complex displacements [m] (P, 3) of the points for the bodies' complex motion
    amplitudes ``body_motion`` (B, 6) [m, rad]: ``X + Theta x a`` on a body, zero
    elsewhere (free points are unknowns: zero here)."""
    u = np.zeros((model.point_kind.size, 3), dtype=complex)
    on = np.flatnonzero(model.point_kind == BODY)
    if on.size:
        q = np.asarray(body_motion, dtype=complex).reshape(model.n_bodies, 6)[model.point_body[on]]
        u[on] = q[:, :3] + cross(q[:, 3:], model.point_arm[on])
    return u


# ------------------------------------------------------------------------ solving


def sweep_compiled(
    model: SystemLinear, w: np.ndarray, prescribed: np.ndarray, settings: DragSettings
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`.system_fd_sweep.solve_sweep` of the cases ``w`` (n,) [rad/s], points'
    motion ``prescribed`` (n, P, 3) [m]: its disp, u_pts, forces, info, finfo."""
    packed = model.packed
    n = w.size
    N, L, P = int(packed.node_offset[-1]), len(model.lines), model.point_kind.size
    disp = np.empty((n, N, 3), dtype=complex)
    u_pts = np.empty((n, P, 3), dtype=complex)
    forces = np.empty((n, L, 6), dtype=complex)
    info = np.zeros((n, INFO), dtype=np.int64)
    finfo = np.zeros((n, 2))
    solve_sweep(
        np.ascontiguousarray(w),
        np.ascontiguousarray(prescribed, dtype=complex).reshape(n, P, 3),
        float(settings.tolerance),
        int(settings.max_iterations),
        int(settings.samples),
        bool(settings.exact),
        packed.arrays,
        packed.bw,
        disp,
        u_pts,
        forces,
        info,
        finfo,
    )
    return disp, u_pts, forces, info, finfo


def prescribed_motion(
    model: SystemLinear, body_motion: np.ndarray, point_excitation: np.ndarray | None = None
) -> np.ndarray:
    """Complex displacements [m] (P, 3) of the points the motion prescribes: the
    bodies' (:func:`point_motion`) plus the points' own ``point_excitation``."""
    prescribed = point_motion(model, body_motion)
    if point_excitation is not None:
        own = np.asarray(point_excitation, dtype=complex).reshape(prescribed.shape)
        if np.any(own[model.point_kind == FREE] != 0.0):
            raise ValueError("a free point cannot be moved on its own: it is an unknown")
        prescribed = prescribed + own
    return prescribed


def harmonic_result(
    model: SystemLinear,
    omega: float,
    body_motion: np.ndarray,
    settings: DragSettings,
    prescribed: np.ndarray,
    outcome: tuple,
) -> SystemFrequencyResult:
    """The :class:`SystemFrequencyResult` of an iteration's ``outcome`` (kind, message,
    iterations, converged, change, point motion, per line displacements, end forces,
    residual: the NumPy reference's form, tests/system_frequency_reference.py) for the
    motion ``body_motion`` and ``prescribed`` at ``omega``."""
    L = len(model.lines)
    static = model.post.static

    def failed(status: int, message: str, iterations: int = 0) -> SystemFrequencyResult:
        return SystemFrequencyResult(
            end_tension=np.full((L, 2), np.nan + 0j),
            tension_static=static,
            element_tension=[np.full(r.line.n_nodes - 1, np.nan + 0j) for r in model.lines],
            displacement=[np.full((r.line.n_nodes, 3), np.nan + 0j) for r in model.lines],
            point_displacement=np.full(prescribed.shape, np.nan + 0j),
            end_force=np.full((L, 2, 3), np.nan + 0j),
            body_force=np.full((model.n_bodies, 6), np.nan + 0j),
            iterations=iterations,
            converged=False,
            status=status,
            message=message,
            element_tension_static=[r.line.tension.copy() for r in model.lines],
        )

    kind, message, iterations, converged, change, u_pts, disp, forces, residual = outcome
    if kind == "numerical":
        return failed(STATUS_NUMERICAL, message, iterations)
    if kind == "not converged":
        return failed(
            STATUS_NOT_CONVERGED,
            f"drag linearisation did not converge in {settings.max_iterations} iterations "
            f"(last change {change:.3g}, tolerance {settings.tolerance:.3g})",
            iterations,
        )
    if not residual <= RESIDUAL_BAR:
        return failed(
            STATUS_NUMERICAL,
            f"the solution leaves a residual of {residual:.3g} of the force scale "
            f"(bar {RESIDUAL_BAR:g}): ill-conditioned at {omega / (2 * math.pi):.6g} Hz",
            iterations,
        )
    post = model.post
    support = -np.asarray(forces).reshape(L, 2, 3)  # change of the force on the points
    end_tension = np.sum(post.unit * support, axis=2)
    body_force = np.zeros((model.n_bodies, 6), dtype=complex)
    if post.body_line.size:
        theta = np.asarray(body_motion, dtype=complex).reshape(model.n_bodies, 6)[:, 3:]
        sup = support[post.body_line, post.body_end]
        arm = post.body_arm
        moment = cross(arm, sup) + cross(cross(theta[post.body], arm), post.body_static)
        np.add.at(body_force, (post.body, slice(0, 3)), sup)
        np.add.at(body_force, (post.body, slice(3, 6)), moment)
    flat = np.concatenate(disp) if isinstance(disp, list) else disp
    du = flat[post.element + 1] - flat[post.element]
    axial = post.axial_stiffness + 1j * omega * post.axial_damping
    tension = axial * np.sum(post.direction * du, axis=1)
    element = np.split(tension, post.element_split)
    var = np.empty(post.node_static.size, dtype=complex)
    var[post.inner] = 0.5 * (tension[post.left] + tension[post.right])
    var[post.first] = end_tension[:, 0]
    var[post.last] = end_tension[:, 1]
    amp = np.abs(var)
    envelope = (
        np.split(post.node_static + amp, post.node_split),
        np.split(post.node_static - amp, post.node_split),
    )
    return SystemFrequencyResult(
        end_tension=end_tension,
        tension_static=static,
        element_tension=element,
        displacement=disp,
        point_displacement=u_pts,
        end_force=support,
        body_force=body_force,
        iterations=iterations,
        converged=converged,
        change=change,
        residual=residual,
        element_tension_static=[r.line.tension.copy() for r in model.lines],
        envelope_lines=envelope,
    )


def compiled_outcome(
    model: SystemLinear,
    omega: float,
    info: np.ndarray,
    finfo: np.ndarray,
    disp: np.ndarray,
    u_pts: np.ndarray,
    forces: np.ndarray,
) -> tuple:
    """The compiled iteration's ``info``, ``finfo`` and arrays (:func:`.system_fd_sweep.
    iterate`) as the NumPy reference's outcome (tests/system_frequency_reference.py)."""
    code, iterations, bad, at_start = (int(v) for v in info[:4])
    change, residual = float(finfo[0]), float(finfo[1])
    hz = omega / (2 * math.pi)
    if code in (SINGULAR_LINE, SINGULAR_JUNCTION):
        why = (
            f"singular dynamic matrix of line {model.names[bad]!r} at {hz:.6g} Hz"
            if code == SINGULAR_LINE
            else f"singular junction system at {hz:.6g} Hz"
        )
        message = f"quasi-static start: {why}" if at_start else why
        return "numerical", message, iterations, False, change, None, None, None, math.nan
    if code == NOT_CONVERGED:
        return "not converged", "", iterations, False, change, None, None, None, math.nan
    noff = model.packed.node_offset
    parts = [disp[noff[i] : noff[i + 1]] for i in range(len(model.lines))]
    return "", "", iterations, True, change, u_pts, parts, forces, residual


__all__ = [
    "RESIDUAL_BAR",
    "SystemFrequencyResult",
    "SystemLinear",
    "point_motion",
    "system_linear",
]
