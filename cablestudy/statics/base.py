"""The static-solver contract: plain inputs (frozen dataclasses of arrays, SI units)
and a result with status, message and counters.

A static solver

1. is a :class:`StaticSolver` registered in :data:`cablestudy.statics.STATIC_SOLVERS`
   under the name a study gives as ``analysis.static.method``;
2. lists in :meth:`StaticSolver.unsupported` every feature of a problem it cannot
   handle (checked for every case before any work starts: a config error);
3. returns from :meth:`StaticSolver.solve` a :class:`StaticResult`; a numerical failure
   is a nonzero ``status`` with a ``message``, never an exception and never NaN with
   status 0; the registry (:data:`cablestudy.statics.STATIC_SOLVERS`) passes every
   result through :func:`.verify.verified`, so status 0 means verified;
4. checks ``deadline`` (a :func:`time.monotonic` value) in its loops and returns
   :data:`STATUS_TIME_LIMIT` when it passes.

Conventions: z up, sea surface z = 0, seabed z = -depth; ``s`` is unstretched arc
length from end A. End forces are the forces the line exerts on the attachment at
that end, so their magnitude is the end tension.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

STATUS_OK = 0
STATUS_NOT_CONVERGED = 1
STATUS_NUMERICAL = 2
STATUS_TIME_LIMIT = 3
STATUS_NO_SOLUTION = 4
#: the solver reported convergence but the result fails the whole-line verification
#: (:mod:`.verify`): its numbers are kept for inspection, the message holds the residuals
STATUS_NOT_VERIFIED = 11
#: the static line's tension exceeds its break limit (line.break): not a solver failure,
#: the static results are kept (see :mod:`.limits`)
STATUS_BROKEN = 10


@dataclass(frozen=True, kw_only=True)
class LineModel:
    """A line of uniform segments from A to B.

    Parameters (arrays of shape (n_segments,) unless said)
    ----------
    length : [m] unstretched segment lengths
    weight : [N/m] weight in the fluid (positive down; negative for buoyant)
    mass : [kg/m] structural mass per length
    axial_stiffness : [N] EA
    diameter : [m] hydrodynamic diameter
    drag_normal, drag_tangential : [-] drag coefficients
    added_mass_normal, added_mass_tangential : [-] added-mass coefficients
    bending_stiffness : [N m^2] EI
    damping_ratio : [-] axial structural damping, fraction of critical
    attachment_s : [m] shape (n_att,), positions along the line
    attachment_force : [N] shape (n_att, 3), constant static force incl. weight/buoyancy
    attachment_mass : [kg] shape (n_att,)
    attachment_volume : [m^3] shape (n_att,)
    axial_law : tuple of :class:`cablestudy.physics.axial.AxialLaw` or None, one per
        segment (empty: all linear); None where the law is T = EA e. ``axial_stiffness``
        is then the law's reference stiffness (guesses and scales only).
    """

    length: np.ndarray
    weight: np.ndarray
    mass: np.ndarray
    axial_stiffness: np.ndarray
    diameter: np.ndarray
    drag_normal: np.ndarray
    drag_tangential: np.ndarray
    added_mass_normal: np.ndarray
    added_mass_tangential: np.ndarray
    bending_stiffness: np.ndarray
    damping_ratio: np.ndarray
    attachment_s: np.ndarray
    attachment_force: np.ndarray
    attachment_mass: np.ndarray
    attachment_volume: np.ndarray
    axial_law: tuple = ()
    #: [m^2] (n_att,) C_D A of the lumped bodies (isotropic drag; empty: none)
    attachment_drag_area: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def is_nonlinear(self) -> bool:
        """True when some segment's axial law is not T = EA e."""
        return any(law is not None for law in self.axial_law)

    def law_of(self, segment: int):  # type: ignore[no-untyped-def]
        """The axial law of ``segment`` (None: linear with ``axial_stiffness``)."""
        return self.axial_law[segment] if self.axial_law else None

    @property
    def total_length(self) -> float:
        return float(np.sum(self.length))

    @property
    def segment_ends(self) -> np.ndarray:
        """Arc length at segment boundaries, shape (n_segments + 1,) [m]."""
        return np.concatenate(([0.0], np.cumsum(self.length)))

    @property
    def is_uniform(self) -> bool:
        return bool(
            np.all(self.weight == self.weight[0])
            and np.all(self.axial_stiffness == self.axial_stiffness[0])
            and len(set(map(id, self.axial_law))) <= 1
        )


#: the arrays of a :class:`LineModel` with one value per segment, but ``length``
SEGMENT_ARRAYS = (
    "weight",
    "mass",
    "axial_stiffness",
    "diameter",
    "drag_normal",
    "drag_tangential",
    "added_mass_normal",
    "added_mass_tangential",
    "bending_stiffness",
    "damping_ratio",
)


@dataclass(frozen=True, kw_only=True)
class Medium:
    """Fluid, gravity, seabed and current.

    density [kg/m^3]; gravity [m/s^2]; depth [m] or None (no seabed);
    seabed_slope [rad] rising towards seabed_heading [rad from +x]; friction [-];
    current_z [m] shape (m,), increasing; current_velocity [m/s] shape (m, 3).
    """

    density: float
    gravity: float
    depth: float | None = None
    seabed_slope: float = 0.0
    seabed_heading: float = 0.0
    friction: float = 0.0
    current_z: np.ndarray = field(default_factory=lambda: np.zeros(0))
    current_velocity: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))

    @property
    def has_current(self) -> bool:
        return bool(self.current_velocity.size) and bool(np.any(self.current_velocity != 0.0))

    def drags(self, line: LineModel) -> bool:
        """Whether a current here loads ``line`` with drag (a current in a fluid with
        density, on a segment with a drag area)."""
        return (
            self.has_current
            and self.density > 0.0
            and bool(np.any(line.diameter * (line.drag_normal + line.drag_tangential) > 0.0))
        )

    def seabed_z(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Height of the seabed under (x, y) [m] (-inf where there is no seabed)."""
        if self.depth is None:
            return np.full(np.shape(x), -np.inf)
        rise = math.tan(self.seabed_slope)
        along = np.asarray(x) * math.cos(self.seabed_heading) + np.asarray(y) * math.sin(
            self.seabed_heading
        )
        return -self.depth + rise * along


@dataclass(frozen=True, kw_only=True)
class EndCondition:
    """kind 'fixed' (position [m]), 'force' (force on the line [N], 3-vector) or
    'mooring' (horizontal force on the line [N] as a 3-vector with z ignored, and z [m])."""

    kind: str
    position: np.ndarray | None = None
    force: np.ndarray | None = None
    z: float | None = None


@dataclass(frozen=True, kw_only=True)
class StaticProblem:
    line: LineModel
    medium: Medium
    end_a: EndCondition
    end_b: EndCondition
    n_nodes: int = 101
    tolerance: float = 1e-9
    max_iterations: int = 100
    #: drag elements along the line for solvers that lump drag (0: solver default)
    drag_elements: int = 0

    #: steady cable laying (vaz-patel seed): speed of the cable along itself from B
    #: towards A [m/s], and the horizontal velocity of the laying frame [m/s] (3,)
    payout_speed: float = 0.0
    touchdown_velocity: np.ndarray = field(default_factory=lambda: np.zeros(3))
    #: drag on the stretched diameter d (1 + e)^(-1/2) (vaz-patel seed) instead of d
    stretched_drag_diameter: bool = False
    #: the seabed's contact stiffness per length [N/m^2] (None: the default) and lateral
    #: friction coefficient (None: ``medium.friction``): used by the methods that model
    #: them (a clamped end holds the static solution's own direction, so the statics of
    #: a clamped end are a pinned one's: the dynamics clamp, docs/guide/line-model.md)
    seabed_stiffness: float | None = None
    friction_lateral: float | None = None

    @property
    def is_installation(self) -> bool:
        return self.payout_speed != 0.0 or bool(np.any(self.touchdown_velocity != 0.0))


@dataclass(kw_only=True)
class StaticResult:
    """Static solution sampled at ``s`` (unstretched arc length from A).

    position [m] (n, 3); tension [N] (n,); force_a, force_b [N] (3,): forces the line
    exerts on the attachments at A and B; laid_length [m] on the seabed.
    """

    s: np.ndarray
    position: np.ndarray
    tension: np.ndarray
    force_a: np.ndarray
    force_b: np.ndarray
    laid_length: float = 0.0
    status: int = STATUS_OK
    message: str = ""
    iterations: int = 0
    residual: float = 0.0
    #: outer iterations of a drag (current) loop, 0 in still water
    drag_iterations: int = 0
    #: why the batched (compiled) kernel, which tried this problem first, left it to the
    #: general solver ('' if it settled it, or did not try: cablestudy.statics.batch)
    fallback: str = ""
    #: the solver's converged state where it gives the line's end stiffness
    #: (:mod:`.line_state`: method discrete, and catenary in a current); None otherwise
    state: Any = None

    @property
    def success(self) -> bool:
        return self.status == STATUS_OK

    @classmethod
    def failed(
        cls,
        s: np.ndarray,
        status: int,
        message: str,
        *,
        iterations: int = 0,
        residual: float = math.nan,
    ) -> StaticResult:
        n = len(s)
        return cls(
            s=s,
            position=np.full((n, 3), np.nan),
            tension=np.full(n, np.nan),
            force_a=np.full(3, np.nan),
            force_b=np.full(3, np.nan),
            laid_length=math.nan,
            status=status,
            message=message,
            iterations=iterations,
            residual=residual,
        )

    def check_finite(self) -> StaticResult:
        """Turn a status-0 result holding NaN or infinity into a failure (never a
        silent NaN)."""
        if self.status == STATUS_OK:
            arrays = (self.position, self.tension, self.force_a, self.force_b)
            if not all(np.all(np.isfinite(a)) for a in arrays):
                return StaticResult.failed(
                    self.s,
                    STATUS_NUMERICAL,
                    "solver returned non-finite values although it reported convergence",
                    iterations=self.iterations,
                    residual=self.residual,
                )
        return self


class StaticSolver(Protocol):
    name: str

    def unsupported(self, problem: StaticProblem) -> list[str]:
        """Features of ``problem`` this solver cannot handle (empty: all supported)."""
        ...

    def solve(self, problem: StaticProblem, *, deadline: float | None = None) -> StaticResult: ...
