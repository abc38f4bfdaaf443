"""The data of a mooring system in statics: points (fixed, free, on a body), bodies and
the lines between points, and the static state a solve returns
(:mod:`.system` solves it; :mod:`.system_fast` is its compiled Newton)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .base import STATUS_OK, StaticProblem, StaticResult

FIXED, FREE, BODY = 0, 1, 2


@dataclass(frozen=True, kw_only=True)
class SystemLine:
    """A line between points ``a`` and ``b`` (indices into the system's points);
    ``problem``'s end conditions are replaced by the points' positions."""

    name: str
    problem: StaticProblem
    a: int
    b: int


@dataclass(frozen=True, kw_only=True)
class MooringSystem:
    """Points, prescribed bodies and lines.

    Parameters
    ----------
    point_names : names of the points, (n,)
    point_kind : (n,) int, FIXED, FREE or BODY
    point_position : [m] (n, 3): position (fixed), starting guess (free), or offset from
        the body's reference point in the body frame (body)
    point_body : (n,) int, body index of BODY points (-1 otherwise)
    point_force : [N] (n, 3) constant net force on free points (weight, buoyancy, force)
    body_names : (m,)
    body_position : [m, rad] (m, 6) surge, sway, heave, roll, pitch, yaw
    lines : the lines
    tolerance : [-] free-point equilibrium: largest net force / force scale
    max_iterations : Newton iterations on the free points
    """

    point_names: tuple[str, ...]
    point_kind: np.ndarray
    point_position: np.ndarray
    point_body: np.ndarray
    point_force: np.ndarray
    body_names: tuple[str, ...] = ()
    body_position: np.ndarray = field(default_factory=lambda: np.zeros((0, 6)))
    lines: tuple[SystemLine, ...] = ()
    tolerance: float = 1e-9
    max_iterations: int = 100
    #: (m,) True where the body is free: its ``body_position`` is then the starting guess
    #: of its equilibrium under the lines, its weight, buoyancy and applied force
    body_free: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=bool))
    #: [N] (m,) weight m g, acting down at ``body_cog``; buoyancy rho V g, up at ``body_cob``
    body_weight: np.ndarray = field(default_factory=lambda: np.zeros(0))
    body_buoyancy: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: [m] (m, 3) centres of gravity and buoyancy in the body frame
    body_cog: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    body_cob: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    #: [N] (m, 3) constant force at the reference point
    body_applied: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    #: [N/m] (m,) rho g A_WP: the waterplane's heave force -rho g A_WP z at the reference
    #: point (z the body's heave); empty: none
    body_waterplane: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: [kg/m] (n,) 1/2 rho C_D A of the free points: drag in the lines' current
    #: (:func:`point_drag`); empty: none
    point_drag: np.ndarray = field(default_factory=lambda: np.zeros(0))


@dataclass(kw_only=True)
class SystemResult:
    """Static state of a system. ``lines``: each line's result (positions, tensions, end
    forces on the attachments); ``point_position`` [m] (n, 3) of every point;
    ``body_force`` [N, N m] (m, 6) of the lines on each body about its reference point;
    ``body_stiffness`` (m, 6, 6) = -d body_force / d body_position, free points
    re-equilibrated."""

    lines: list[StaticResult]
    point_position: np.ndarray
    body_force: np.ndarray
    body_stiffness: np.ndarray
    status: int = STATUS_OK
    message: str = ""
    iterations: int = 0
    residual: float = 0.0
    #: [m, rad] (m, 6) the bodies' positions (free bodies: in equilibrium)
    body_position: np.ndarray | None = None
    #: why the compiled system Newton (:mod:`.system_fast`) left the system to this
    #: general path ('' if it solved it, or was not asked: a method other than catenary)
    fallback: str = ""
    #: the extra body poses asked of the solve (``extra_poses`` of :func:`.system.solve_system`)
    #: solved with it by the compiled path, each verified: ``poses`` (K, m, 6), the lines'
    #: ``position`` (K, M, n, 3) [m], ``laid_length`` (K, M) [m], ``anchored`` (K, M)
    #: (on the seabed at an anchor); None when not asked or not all settled and verified
    extra: dict | None = None
    #: [N] (n, 3) the seabed's force on each point resting on it (free points only; zero
    #: elsewhere); None when no point rests on the seabed
    seabed_force: np.ndarray | None = None
    #: the names of the free points resting on the seabed
    resting: tuple[str, ...] = ()


class SystemFailure(Exception):
    """A numerical failure of a system solve (becomes status and message)."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status
        self.message = message


# --------------------------------------------------------------------------- rotation


def point_drag(system: MooringSystem, pos: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """Current drag on the free points at positions ``pos`` [m] (n, 3): the force
    ``c |U| U`` [N] (n, 3) with ``c = 1/2 rho C_D A`` [kg/m] (``system.point_drag``) and U
    the current at the point's height, and its stiffness ``-d f / d r`` (3n, 3n), exact:
    the force changes with the point's height only, through the profile's slope U'(z)
    (piecewise linear: the slope of the piece the point is in, 0 beyond the profile's
    ends), ``d f / d z = c (|U| I + U U^T / |U|) U'``. None when no point has drag."""
    c = np.asarray(system.point_drag, dtype=float)
    if c.size == 0 or not np.any(c > 0.0) or not system.lines:
        return None
    medium = system.lines[0].problem.medium
    pz, pv = medium.current_z, medium.current_velocity
    n = len(pos)
    force = np.zeros((n, 3))
    K = np.zeros((3 * n, 3 * n))
    if pz.size == 0:
        return force, K
    for i in np.flatnonzero(c > 0.0):
        z = float(pos[i, 2])
        U = np.array([np.interp(z, pz, pv[:, k]) for k in range(3)])
        speed = float(np.linalg.norm(U))
        force[i] = c[i] * speed * U
        k = int(np.searchsorted(pz, z, side="right")) - 1
        if speed == 0.0 or k < 0 or k >= pz.size - 1:
            continue  # beyond the profile's ends the current is constant
        slope = (pv[k + 1] - pv[k]) / (pz[k + 1] - pz[k])
        dfdz = c[i] * (speed * np.eye(3) + np.outer(U, U) / speed) @ slope
        K[3 * i : 3 * i + 3, 3 * i + 2] -= dfdz
    return force, K


def on_seabed_note(
    system: MooringSystem, free_mask: np.ndarray, pressed: np.ndarray, plane: object
) -> str:
    """The part of a failure's message naming the free points the last Newton step
    pressed onto the seabed, or its start put there (``pressed``, per free point)."""
    low = [
        str(n) for n, p in zip(np.asarray(system.point_names)[free_mask], pressed, strict=True) if p
    ]
    return f"; free point {', '.join(low)} is pressed onto or placed on the seabed" if low else ""


def unpulled_note(
    system: MooringSystem, free_mask: np.ndarray, contact: np.ndarray, results: list, scale: float
) -> str:
    """The part of a failure's message naming the free points resting on the seabed that
    no line pulls (each lies slack there): the statics do not fix where they rest."""
    idle = [
        str(system.point_names[i])
        for i, on in zip(np.flatnonzero(free_mask), contact, strict=True)
        if on
        and all(
            np.linalg.norm(r.force_a if ln.a == i else r.force_b) <= 1e-6 * scale
            for ln, r in zip(system.lines, results, strict=True)
            if i in (ln.a, ln.b)
        )
    ]
    if not idle:
        return ""
    return (
        f"; free point {', '.join(idle)} rests on the seabed with every line lying slack "
        "from it: where it rests is not determined by the statics (shorten a line lying "
        "from it, or move its anchor)"
    )
