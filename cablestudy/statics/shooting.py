"""Shooting solver (``analysis.static.method: shooting``): the 3D static line written in
tension, elevation and azimuth angles and Cartesian coordinates, integrated as an
initial-value problem from one end, with Newton's method on the unknown start values.

Formulation (vaz-patel seed, section 2 and eqs. 2, 4a-4c and A1 without the installation
terms V_po, V_0): along the unstretched arc length s of a segment of weight w [N/m] per
unstretched length and axial stiffness EA [N], the line force F = T t (T tension, t the
unit tangent towards increasing s) obeys dF/ds = -f, with f the external load per
unstretched length. Writing t through an elevation angle phi and an azimuth angle psi
about a reference frame (e1, e2, e3),

    t = cos(phi) cos(psi) e1 + cos(phi) sin(psi) e2 + sin(phi) e3,
    n = dt/dphi,   b = (dt/dpsi) / cos(phi),

the equilibrium equations resolved on (t, n, b) and the compatibility relations are

    dT/ds   = -f . t
    dphi/ds = -f . n / T
    dpsi/ds = -f . b / (T cos(phi))
    dr/ds   = (1 + T / EA) t                   (elastic stretch, Hooke's law)

with f = (0, 0, -w) + (1 + T / EA) f_drag(t, z). The drag per unit *stretched* length is
Morison's split into normal and tangential parts of the current velocity relative to the
tangent (dodaran-park seed eqs. 38-39, :func:`cablestudy.physics.hydro.drag_per_length`;
there, as here, the drag of an element is proportional to its stretched length and the
unstretched diameter; with ``stretched_drag_diameter`` (study key
``analysis.static.drag_diameter: stretched``) the diameter thins as d (1 + e)^(-1/2), as
in the vaz-patel seed, a change of relative size T / 2EA). The current is the
piecewise-linear profile in z of the study, so it may turn with depth; drag depends on
the local tangent and height and so sits inside the ODE (no outer iteration).

Azimuth singularity: psi is undefined where t is parallel to e3. The reference frame is
chosen afresh at the start of every integration leg with e1 = t and e3 perpendicular to t
(the binormal of the local load plane when it exists, so a plane catenary stays on phi =
0), and a leg ends by an event when |sin(phi)| reaches 0.95; the integration then
restarts at that point with a new frame. The angle form is therefore used everywhere and
|cos(phi)| >= 0.31 in every leg.

Legs also end at segment boundaries and at attachments (point forces, clump weights,
buoys: F(s+) = F(s-) - P for a force P applied to the line), where the angles are
recomputed from the force after the jump. The ODE is integrated with scipy's DOP853
(Dormand-Prince 8(5,3)), relative tolerance 1e-12 by default.

Shooting: the line is mirrored internally so that the integration starts at end A' and
runs to B'. The start end is, in this order of preference, a fixed end on the seabed
(see below), a `force` or `mooring` end (integration from its known force towards the
fixed end, the stable direction from low to high tension: the unknowns are its position,
or its horizontal position and vertical force), or a fixed end (unknowns: the three
components of the force there). Newton's method meets the three conditions at the other
end: its position (fixed), the force on the line there (force), or the horizontal force
and height (mooring). The Jacobian is by central differences, updated by Broyden's
formula between refreshes; the line search uses the 2-norm of the scaled residual.
Strong currents are reached by continuation in current speed from the still-water
solution, with a secant predictor. A free end (zero force) starts along its own load
(so a cable with a free end in a uniform current starts at Pode's critical angle).

Seabed (vaz-patel: the integration starts at the touchdown point): when the start end is
fixed on the seabed, the unknowns become the tension T_0 at the touchdown point, the
direction of the laid part in the seabed plane and the laid length. The laid part is
straight, in the seabed plane, and the line leaves the seabed tangentially at the
touchdown point; a negative third unknown instead lifts the line off at the anchor at an
angle, so grounded and lifted anchors are one smooth family of shots. Friction follows the
usual quasi-static convention: fully mobilised along the laid length towards the anchor,

    T(s) = max(0, T_0 - sum over the laid length beyond s of (mu w cos(a) + w e_z)),

(e_z the rise of the laid direction, a the seabed slope), so friction reduces the anchor
tension but never below zero and does not change the suspended shape. An end counts as
on the seabed within 1e-6 of the line length; contact elsewhere (a line sagging onto the
seabed between raised ends) is reported as a failure, never ignored.

Installation (vaz-patel seed, eqs. 3b-4c, ``analysis.static.installation``): in the
frame of a laying ship moving at the constant horizontal velocity V_0 with the cable
paid out from end B towards end A at speed V_po, the flow relative to the cable is the
current minus V_0 plus V_po along the tangent, and the cable flowing round its own
curvature replaces T by T - mu V_po^2 in the normal and binormal equations (mu: mass
per stretched length plus the normal added mass Cm rho pi d^2 / 4). The continuation
then ramps the frame flow and pay-out before the current.

Convergence: Newton stops when the scaled end residual (positions / line length,
forces / total weight and applied loads) is below max(tolerance, 100 rtol) and then
polishes for up to four more steps towards the integration floor.
"""

from __future__ import annotations

import bisect
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..physics.axial import gauss_legendre
from .base import (
    STATUS_NO_SOLUTION,
    STATUS_NOT_CONVERGED,
    STATUS_NUMERICAL,
    STATUS_OK,
    STATUS_TIME_LIMIT,
    EndCondition,
    LineModel,
    StaticProblem,
    StaticResult,
)
from .elastic_catenary import CatenarySolution, profile, solve_between

#: an end is on the seabed when within this fraction of the line length of it [-]
_GROUND_TOL = 1e-6
#: legs end (and restart in a new frame) where |sin(elevation)| reaches this [-]
_POLE_LIMIT = 0.95
#: Newton iterations allowed per current-continuation step before it is shortened
_CONTINUATION_ITERATIONS = 15
#: Newton iterations allowed from each alternative starting point
_ALTERNATIVE_ITERATIONS = 30
#: finite-difference step of the Newton Jacobian, in the scaled unknowns [-]
_FD_STEP = 1e-7


class _ShotFailed(Exception):
    """An integration that cannot be completed (tension vanishing, solver failure)."""


class _TimeUp(Exception):
    """The deadline passed."""


# ----------------------------------------------------------------------------------
# line data from the start end


@dataclass(frozen=True)
class _Line:
    """Segments and attachments seen from the start end (s from the start end) [SI]."""

    ends: tuple[float, ...]  # segment boundaries, len n_seg + 1
    weight: tuple[float, ...]
    axial_stiffness: tuple[float, ...]
    diameter: tuple[float, ...]
    drag_normal: tuple[float, ...]
    drag_tangential: tuple[float, ...]
    mass: tuple[float, ...]
    added_mass_normal: tuple[float, ...]
    att_s: tuple[float, ...]  # sorted, merged positions of attachments
    att_force: tuple[tuple[float, float, float], ...]
    #: per segment its non-linear axial law (None: T = EA e); () when all linear
    laws: tuple = ()

    def strain(self, k: int, T: float) -> float:
        """Strain [-] of segment k at tension T [N] (its axial law; tension-only)."""
        law = self.laws[k] if self.laws else None
        if law is None:
            return T / self.axial_stiffness[k]
        return law.strain_scalar(T)

    @property
    def length(self) -> float:
        return self.ends[-1]

    def segment_at(self, s: float, *, right: bool = True) -> int:
        """Index of the segment containing s (the one starting at s when on a
        boundary and ``right``)."""
        k = bisect.bisect_right(self.ends, s) - 1 if right else bisect.bisect_left(self.ends, s) - 1
        return min(max(k, 0), len(self.weight) - 1)

    def total_load(self) -> np.ndarray:
        """Weight and attachment forces on the line [N] (3,)."""
        lengths = np.diff(self.ends)
        load = np.array([0.0, 0.0, -float(np.dot(self.weight, lengths))])
        for p in self.att_force:
            load += np.asarray(p)
        return load

    def mean_weight(self) -> float:
        return float(np.dot(self.weight, np.diff(self.ends)) / self.length)

    def compliance(self) -> float:
        """Sum of L_k / EA_k [m/N]."""
        return float(np.sum(np.diff(self.ends) / np.asarray(self.axial_stiffness)))


def _make_line(model: LineModel, reverse: bool) -> _Line:
    lengths = np.asarray(model.length, dtype=float)
    order = slice(None, None, -1) if reverse else slice(None)
    L = float(np.sum(lengths))
    ends = tuple(float(v) for v in np.concatenate(([0.0], np.cumsum(lengths[order]))))
    ends = ends[:-1] + (L,)
    merged: dict[float, np.ndarray] = {}
    for s, p in zip(model.attachment_s, model.attachment_force, strict=True):
        key = float(L - s) if reverse else float(s)
        key = min(max(key, 0.0), L)
        merged[key] = merged.get(key, np.zeros(3)) + np.asarray(p, dtype=float)
    keys = sorted(merged)

    def col(a: np.ndarray) -> tuple[float, ...]:
        return tuple(float(v) for v in np.asarray(a, dtype=float)[order])

    return _Line(
        ends=ends,
        weight=col(model.weight),
        axial_stiffness=col(model.axial_stiffness),
        diameter=col(model.diameter),
        drag_normal=col(model.drag_normal),
        drag_tangential=col(model.drag_tangential),
        mass=col(model.mass),
        added_mass_normal=col(model.added_mass_normal),
        att_s=tuple(keys),
        att_force=tuple(tuple(float(c) for c in merged[k]) for k in keys),  # type: ignore[misc]
        laws=tuple(model.axial_law[order]) if model.axial_law else (),
    )


# ----------------------------------------------------------------------------------
# environment


@dataclass(frozen=True)
class _Env:
    """Fluid density [kg/m^3], current profile (z [m], velocity [m/s]), laying-frame
    velocity [m/s] and pay-out [m/s] (cable speed along -t relative to the frame), with
    continuation factors on the current (``c_current``) and on the frame velocity and
    pay-out (``c_frame``)."""

    density: float
    current_z: tuple[float, ...]
    current_u: tuple[tuple[float, float, float], ...]
    frame: tuple[float, float, float] = (0.0, 0.0, 0.0)
    payout: float = 0.0
    c_current: float = 1.0
    c_frame: float = 1.0
    #: drag on the stretched diameter d (1 + e)^(-1/2) (vaz-patel seed, eqs. 4a-4c)
    stretched: bool = False

    @property
    def installation(self) -> bool:
        return self.payout != 0.0 or any(c != 0.0 for c in self.frame)

    @property
    def has_current(self) -> bool:
        """Any flow relative to the line (current, frame velocity or pay-out)."""
        current = self.c_current != 0.0 and any(any(c != 0.0 for c in u) for u in self.current_u)
        return current or (self.c_frame != 0.0 and self.installation)

    def scaled(self, t: float) -> _Env:
        """The flow at continuation parameter t in [0, 1]: for an installation in a
        current the frame velocity and pay-out ramp up first (t <= 1/2), then the
        current, so a laying configuration is followed into the current; otherwise
        everything scales with t."""
        if self.installation and any(any(c != 0.0 for c in u) for u in self.current_u):
            c_frame, c_current = min(1.0, 2.0 * t), max(0.0, 2.0 * t - 1.0)
        else:
            c_frame = c_current = t
        return _Env(
            self.density,
            self.current_z,
            self.current_u,
            self.frame,
            self.payout,
            c_current,
            c_frame,
            self.stretched,
        )

    @property
    def payout_speed(self) -> float:
        return self.c_frame * self.payout

    def velocity(self, z: float) -> tuple[float, float, float]:
        """Current minus the frame velocity at height z [m/s]; the current profile is
        piecewise linear, constant beyond its ends."""
        zs, us, c = self.current_z, self.current_u, self.c_current
        if len(zs) == 1 or z <= zs[0]:
            u = us[0]
        elif z >= zs[-1]:
            u = us[-1]
        else:
            i = bisect.bisect_right(zs, z) - 1
            a = (z - zs[i]) / (zs[i + 1] - zs[i])
            u0, u1 = us[i], us[i + 1]
            u = (
                u0[0] + a * (u1[0] - u0[0]),
                u0[1] + a * (u1[1] - u0[1]),
                u0[2] + a * (u1[2] - u0[2]),
            )
        f, v = self.c_frame, self.frame
        return (c * u[0] - f * v[0], c * u[1] - f * v[1], c * u[2] - f * v[2])


def _load(
    env: _Env, line: _Line, k: int, t: tuple[float, float, float], z: float, T: float
) -> tuple[float, float, float]:
    """External load per unstretched length on segment k with tangent t at height z
    with tension T [N/m]: weight plus drag per stretched length times the stretch. The
    flow relative to the line is the current in the laying frame plus the pay-out
    speed along the tangent (vaz-patel seed, Appendix B: V_rt, V_rn, V_rb)."""
    w = line.weight[k]
    fx, fy, fz = 0.0, 0.0, -w
    if env.has_current and env.density > 0.0:
        ux, uy, uz = env.velocity(z)
        ut = ux * t[0] + uy * t[1] + uz * t[2]
        nx, ny, nz = ux - ut * t[0], uy - ut * t[1], uz - ut * t[2]
        ut += env.payout_speed
        un = math.sqrt(nx * nx + ny * ny + nz * nz)
        stretch = 1.0 + line.strain(k, T)
        # drag per stretched length times the stretch; the stretched diameter thins as
        # (1 + e)^(-1/2), so its drag per unstretched length grows as (1 + e)^(1/2)
        kk = (
            0.5
            * env.density
            * line.diameter[k]
            * (math.sqrt(stretch) if env.stretched else stretch)
        )
        cn = kk * line.drag_normal[k] * un
        ct = kk * math.pi * line.drag_tangential[k] * abs(ut) * ut
        fx += cn * nx + ct * t[0]
        fy += cn * ny + ct * t[1]
        fz += cn * nz + ct * t[2]
    return fx, fy, fz


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def _frame(t0: np.ndarray, f0: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Reference frame (e1, e2, e3) with e1 = t0 and e3 perpendicular to t0: the binormal
    of the load plane where the load is not along the tangent."""
    fn = float(np.linalg.norm(f0))
    candidates = []
    if fn > 0.0:
        candidates.append(np.cross(t0, f0 / fn))
    candidates += [
        np.cross(t0, [0.0, 0.0, 1.0]),
        np.cross(t0, [1.0, 0.0, 0.0]),
        np.cross(t0, [0.0, 1.0, 0.0]),
    ]
    for c in candidates:
        if np.linalg.norm(c) > 1e-3:
            e3 = _unit(c)
            break
    e2 = np.cross(e3, t0)
    return t0, _unit(e2), e3


# ----------------------------------------------------------------------------------
# one shot


@dataclass
class _Piece:
    """One integration leg: dense solution of (T, phi, psi, x, y, z) on [s0, s1]."""

    s0: float
    s1: float
    sol: Callable[[np.ndarray], np.ndarray]


@dataclass
class _Shot:
    force_end: np.ndarray  # F(L+): force applied to the line at the far end [N]
    position_end: np.ndarray  # [m]
    pieces: list[_Piece]
    legs: int


class _Integrator:
    def __init__(
        self,
        line: _Line,
        env: _Env,
        *,
        rtol: float,
        force_scale: float,
        deadline: float | None,
        max_legs: int = 2000,
    ) -> None:
        self.line, self.env, self.rtol = line, env, rtol
        self.force_scale, self.deadline, self.max_legs = force_scale, deadline, max_legs
        L = line.length
        self.atol = np.array([rtol * force_scale, rtol, rtol, rtol * L, rtol * L, rtol * L])
        self.t_min = 1e-10 * force_scale

    def tighten(self) -> bool:
        """Divide the integration tolerances by 100 (down to 2.5e-14); False when already
        there."""
        if self.rtol <= 3e-14:
            return False
        self.rtol = max(self.rtol / 100.0, 2.5e-14)
        self.atol = self.atol / 100.0
        return True

    def _rhs_factory(
        self, k: int, e1: np.ndarray, e2: np.ndarray, e3: np.ndarray
    ) -> Callable[[float, np.ndarray], list[float]]:
        e1x, e1y, e1z = (float(v) for v in e1)
        e2x, e2y, e2z = (float(v) for v in e2)
        e3x, e3y, e3z = (float(v) for v in e3)
        line, env = self.line, self.env
        EA = line.axial_stiffness[k]
        law = line.laws[k] if line.laws else None
        cos, sin = math.cos, math.sin
        m_flow, m_add = self._flow_mass(k)

        def rhs(s: float, y: np.ndarray) -> list[float]:
            T, ph, ps, _, _, z = y
            cph, sph, cps, sps = cos(ph), sin(ph), cos(ps), sin(ps)
            a, b = cph * cps, cph * sps
            t = (
                a * e1x + b * e2x + sph * e3x,
                a * e1y + b * e2y + sph * e3y,
                a * e1z + b * e2z + sph * e3z,
            )
            a, b = -sph * cps, -sph * sps
            n = (
                a * e1x + b * e2x + cph * e3x,
                a * e1y + b * e2y + cph * e3y,
                a * e1z + b * e2z + cph * e3z,
            )
            bn = (-sps * e1x + cps * e2x, -sps * e1y + cps * e2y, -sps * e1z + cps * e2z)
            f = _load(env, line, k, t, z, T)
            st = 1.0 + (T / EA if law is None else law.strain_scalar(T))
            # pay-out: the cable flowing round its own curvature needs T - mu V^2 in the
            # normal equations (seed eqs. 4b-4c), mu the mass and added mass per
            # stretched length
            Te = T - (m_flow / st + m_add) if m_flow or m_add else T
            return [
                -(f[0] * t[0] + f[1] * t[1] + f[2] * t[2]),
                -(f[0] * n[0] + f[1] * n[1] + f[2] * n[2]) / Te,
                -(f[0] * bn[0] + f[1] * bn[1] + f[2] * bn[2]) / (Te * cph),
                st * t[0],
                st * t[1],
                st * t[2],
            ]

        return rhs

    def _flow_mass(self, k: int) -> tuple[float, float]:
        """(m V^2, m_a V^2) [N] of segment k for the pay-out speed V at this
        continuation scale: structural mass per unstretched length (divided by the
        stretch where used) and normal added mass per length."""
        v = self.env.payout_speed
        if v == 0.0:
            return 0.0, 0.0
        line = self.line
        area = math.pi * line.diameter[k] ** 2 / 4.0
        return (line.mass[k] * v * v, line.added_mass_normal[k] * self.env.density * area * v * v)

    def effective_tension(self, k: int, T: float) -> float:
        """T - mu V^2 [N]: the tension that resists curvature under pay-out."""
        m_flow, m_add = self._flow_mass(k)
        return T - m_flow / (1.0 + self.line.strain(k, T)) - m_add

    def run(self, s0: float, force: np.ndarray, position: np.ndarray, *, dense: bool) -> _Shot:
        """Integrate from s0 (force F(s0-) and position given) to the far end."""
        from scipy.integrate import solve_ivp  # here, not at import: validation needs none

        line = self.line
        L = line.length
        F = np.array(force, dtype=float)
        r = np.array(position, dtype=float)
        # an attachment at s0 acts at the start; those beyond s0, and segment boundaries
        # beyond s0, are knots
        at_start = s0 + 1e-14 * L
        knots = sorted(
            {x for x in line.ends[1:-1] if x > s0} | {x for x in line.att_s if x > at_start} | {L}
        )
        for s_att, p in zip(line.att_s, line.att_force, strict=True):
            if s0 - 1e-14 * L <= s_att <= at_start:
                F = F - np.asarray(p)
        pieces: list[_Piece] = []
        legs = 0
        s = s0
        for knot in knots:
            k = line.segment_at(0.5 * (s + knot))
            while s < knot:
                legs += 1
                if legs > self.max_legs:
                    raise _ShotFailed(f"more than {self.max_legs} integration legs")
                if self.deadline is not None and time.monotonic() > self.deadline:
                    raise _TimeUp
                T = float(np.linalg.norm(F))
                if not math.isfinite(T) or T <= self.t_min:
                    raise _ShotFailed(f"tension vanishes at s = {s:.6g} m")
                if self.effective_tension(k, T) <= self.t_min:
                    raise _ShotFailed(
                        f"the tension at s = {s:.6g} m does not exceed mu V^2 "
                        "of the pay-out (the cable cannot hold a curve)"
                    )
                t0 = F / T
                f0 = np.asarray(_load(self.env, line, k, tuple(t0), float(r[2]), T))
                e1, e2, e3 = _frame(t0, f0)
                rhs = self._rhs_factory(k, e1, e2, e3)

                def pole(_s: float, y: np.ndarray) -> float:
                    return _POLE_LIMIT - abs(math.sin(y[1]))

                def slack(_s: float, y: np.ndarray, k: int = k) -> float:
                    return self.effective_tension(k, y[0]) - self.t_min

                pole.terminal = True  # type: ignore[attr-defined]
                slack.terminal = True  # type: ignore[attr-defined]
                y0 = np.array([T, 0.0, 0.0, r[0], r[1], r[2]])
                sol = solve_ivp(
                    rhs,
                    (s, knot),
                    y0,
                    method="DOP853",
                    rtol=self.rtol,
                    atol=self.atol,
                    events=(pole, slack),
                    dense_output=dense,
                )
                if sol.status == -1:
                    raise _ShotFailed(f"integration failed at s = {s:.6g} m: {sol.message}")
                y = sol.y[:, -1]
                if not np.all(np.isfinite(y)):
                    raise _ShotFailed(f"non-finite state after s = {s:.6g} m")
                s_new = float(sol.t[-1])
                if sol.status == 1 and sol.t_events[1].size:
                    raise _ShotFailed(f"tension vanishes at s = {s_new:.6g} m")
                if sol.status == 1 and s_new <= s:
                    raise _ShotFailed(f"no progress at s = {s:.6g} m")
                if dense:
                    pieces.append(_Piece(s, s_new, sol.sol))
                T, ph, ps = float(y[0]), float(y[1]), float(y[2])
                t = (
                    math.cos(ph) * math.cos(ps) * e1
                    + math.cos(ph) * math.sin(ps) * e2
                    + math.sin(ph) * e3
                )
                F = T * t
                r = y[3:6].copy()
                s = s_new if sol.status == 1 else knot
            # jump at an attachment on this knot
            i = bisect.bisect_left(line.att_s, knot)
            if i < len(line.att_s) and line.att_s[i] == knot:
                F = F - np.asarray(line.att_force[i])
        return _Shot(force_end=F, position_end=r, pieces=pieces, legs=legs)


# ----------------------------------------------------------------------------------
# the laid part on the seabed


@dataclass(frozen=True)
class _Seabed:
    depth: float
    normal: np.ndarray  # unit upward normal
    upslope: np.ndarray  # unit in-plane vector rising towards the slope heading
    across: np.ndarray  # unit in-plane horizontal vector
    friction: float

    def z(self, x: float, y: float) -> float:
        # plane through (0, 0, -depth) with normal n: n . (r - r0) = 0
        n = self.normal
        return -self.depth - (n[0] * x + n[1] * y) / n[2]

    def direction(self, beta: float) -> np.ndarray:
        return math.cos(beta) * self.upslope + math.sin(beta) * self.across

    def beta_of(self, v: np.ndarray) -> float:
        return math.atan2(float(np.dot(v, self.across)), float(np.dot(v, self.upslope)))


def _seabed(medium_depth: float, slope: float, heading: float, friction: float) -> _Seabed:
    tan_a = math.tan(slope)
    ch, sh = math.cos(heading), math.sin(heading)
    normal = _unit(np.array([-tan_a * ch, -tan_a * sh, 1.0]))
    upslope = _unit(np.array([ch, sh, tan_a]))
    across = np.array([-sh, ch, 0.0])
    return _Seabed(medium_depth, normal, upslope, across, friction)


def _laid_tension(
    line: _Line, bed: _Seabed, e: np.ndarray, q: float, t_tdp: float
) -> tuple[list[tuple[float, float, float, float]], float]:
    """Pieces (s_a, s_b, T_lin(s_a), dT/ds) of the tension along the laid part [0, q],
    marching from the touchdown point towards the anchor, and the tension just after the
    anchor [N]. In a piece the tension is max(0, T_lin); a piece starts (at its touchdown
    side) from the clipped tension of the one before, so a slack stretch stays slack up
    to the next attachment that pulls."""
    pts = sorted(
        {0.0, q} | {x for x in line.ends if 0.0 < x < q} | {x for x in line.att_s if 0.0 < x < q}
    )
    mu, m_z, e_z = bed.friction, float(bed.normal[2]), float(e[2])
    # march backwards from the touchdown point
    pieces = []
    T_right = t_tdp
    for a, b in zip(pts[-2::-1], pts[:0:-1], strict=True):
        i = bisect.bisect_left(line.att_s, b)
        if b < q and i < len(line.att_s) and line.att_s[i] == b:
            p = np.asarray(line.att_force[i])
            normal_load = max(0.0, -float(np.dot(p, bed.normal)))
            T_right = T_right + float(np.dot(p, e)) - mu * normal_load
        k = line.segment_at(0.5 * (a + b))
        w = line.weight[k]
        g = w * e_z + mu * w * m_z  # dT/ds
        T_left = T_right - g * (b - a)
        pieces.append((a, b, T_left, g))
        T_right = max(0.0, T_left)  # a slack stretch stays slack (never below zero)
    pieces.reverse()
    return pieces, T_right


def _clipped_integral(T_a: float, g: float, length: float) -> float:
    """Integral over [0, length] of max(0, T_a + g x) dx."""
    T_b = T_a + g * length
    if T_a >= 0.0 and T_b >= 0.0:
        return 0.5 * (T_a + T_b) * length
    if T_a <= 0.0 and T_b <= 0.0:
        return 0.0
    x0 = -T_a / g
    return 0.5 * T_a * x0 if T_a > 0.0 else 0.5 * T_b * (length - x0)


def _laid_stretch(law: Any, EA: float, T_a: float, g: float, length: float) -> float:
    """Stretch [m] of a straight laid piece over [0, length] whose tension is
    max(0, T_a + g x) [N]: int e(T) dx, i.e. the clipped tension integral / EA for a
    linear law, else (Phi(T_b) - Phi(T_a)) / g with Phi the law's complementary energy
    (exact), or 16-point Gauss-Legendre where the tension hardly changes (|g| length
    below 1e-3 of the tension, where that difference would cancel)."""
    if law is None:
        return _clipped_integral(T_a, g, length) / EA
    T_b = T_a + g * length
    if length <= 0.0 or (T_a <= 0.0 and T_b <= 0.0):
        return 0.0
    big = max(abs(T_a), abs(T_b))
    if abs(T_b - T_a) > 1e-3 * big:
        phi = law.complementary_energy(np.array([max(T_a, 0.0), max(T_b, 0.0)]))
        return float(phi[1] - phi[0]) / g
    x, w = gauss_legendre(16)
    return float(length * np.sum(w * law.strain(np.maximum(T_a + g * length * x, 0.0))))


def _laid_profile(
    line: _Line, bed: _Seabed, e: np.ndarray, q: float, t_tdp: float, s: np.ndarray
) -> tuple[np.ndarray, np.ndarray, float]:
    """Stretched distance from the anchor [m] and clipped tension [N] at s (inside
    [0, q]), and the total stretched laid length [m]."""
    pieces, _ = _laid_tension(line, bed, e, q, t_tdp)
    dist = np.zeros(len(s))
    tens = np.zeros(len(s))
    total = 0.0
    for a, b, T_a, g in pieces:
        k = line.segment_at(0.5 * (a + b))
        EA = line.axial_stiffness[k]
        law = line.laws[k] if line.laws else None
        inside = (s >= a) & (s <= b)
        for j in np.nonzero(inside)[0]:
            x = float(s[j]) - a
            dist[j] = total + x + _laid_stretch(law, EA, T_a, g, x)
            tens[j] = max(0.0, T_a + g * x)
        total += (b - a) + _laid_stretch(law, EA, T_a, g, b - a)
    return dist, tens, total


# ----------------------------------------------------------------------------------
# the solver


@dataclass
class _Setup:
    line: _Line
    env: _Env
    start: EndCondition
    far: EndCondition
    reverse: bool
    bed: _Seabed | None
    mode: str  # 'fixed', 'grounded', 'force' or 'mooring': the kind of the start end
    force_scale: float


@dataclass
class _Start:
    """Where a shot starts: at s0 with force F(s0-) and position r(s0); ``laid`` is the
    laid direction (grounded start with a laid part), ``t_tdp`` the touchdown tension;
    ``force_start`` is the force of the line on the start fixture [N]; ``origin`` the
    position at s = 0 [m]."""

    s0: float
    force: np.ndarray
    position: np.ndarray
    laid: np.ndarray | None
    t_tdp: float
    force_start: np.ndarray
    origin: np.ndarray


class ShootingSolver:
    """Registry entry ``shooting``: angle-form ODE shooting (vaz-patel seed), see the
    module docstring.

    Parameters
    ----------
    rtol : float
        relative tolerance of the DOP853 integration [-]
    """

    name = "shooting"

    def __init__(self, *, rtol: float = 1e-12) -> None:
        self.rtol = rtol

    # -- contract ------------------------------------------------------------------
    def unsupported(self, problem: StaticProblem) -> list[str]:
        out = []
        kinds = (problem.end_a.kind, problem.end_b.kind)
        if "fixed" not in kinds:
            out.append(
                f"end kinds a={kinds[0]!r}, b={kinds[1]!r} (at least one end must be "
                "'fixed': a line held only by forces has no unique position)"
            )
        med = problem.medium
        if med.depth is not None:
            L = problem.line.total_length
            for label, end in (("a", problem.end_a), ("b", problem.end_b)):
                if end.kind == "fixed" and end.position is not None:
                    ground = float(med.seabed_z(end.position[0], end.position[1]))
                    if end.position[2] < ground - _GROUND_TOL * L:
                        out.append(
                            f"end {label} at z = {end.position[2]:.6g} m below the "
                            f"seabed (z = {ground:.6g} m there)"
                        )
                if (
                    end.kind == "mooring"
                    and end.z is not None
                    and end.z < -med.depth - (_GROUND_TOL * L)
                    and med.seabed_slope == 0.0
                ):
                    out.append(f"end {label} mooring height z = {end.z:.6g} m below the seabed")
        return out

    def solve(self, problem: StaticProblem, *, deadline: float | None = None) -> StaticResult:
        s_out = np.linspace(0.0, problem.line.total_length, problem.n_nodes)
        missing = self.unsupported(problem)
        if missing:
            return StaticResult.failed(s_out, STATUS_NO_SOLUTION, "; ".join(missing))
        try:
            return self._solve(problem, s_out, deadline).check_finite()
        except _TimeUp:
            return StaticResult.failed(
                s_out, STATUS_TIME_LIMIT, "time limit reached in the shooting solver"
            )
        except Exception as exc:  # noqa: BLE001 - a numerical fault is data, not a crash
            return StaticResult.failed(
                s_out, STATUS_NUMERICAL, f"shooting solver: {type(exc).__name__}: {exc}"
            )

    # -- set-up ---------------------------------------------------------------------
    def _setup(self, problem: StaticProblem) -> _Setup:
        """Choose the start end: a fixed end on the seabed (touchdown integration), else
        a force or mooring end (integration from its known force towards the fixed end,
        the stable direction from low to high tension), else end A."""
        a, b = problem.end_a, problem.end_b
        med = problem.medium
        model = problem.line
        L = model.total_length
        bed = None
        if med.depth is not None:
            bed = _seabed(med.depth, med.seabed_slope, med.seabed_heading, med.friction)

        def on_ground(end: EndCondition, weight: float) -> bool:
            if bed is None or end.kind != "fixed" or end.position is None or weight <= 0.0:
                return False
            return abs(end.position[2] - bed.z(end.position[0], end.position[1])) <= (
                _GROUND_TOL * L
            )

        if on_ground(a, float(model.weight[0])):
            reverse, mode = False, "grounded"
        elif on_ground(b, float(model.weight[-1])):
            reverse, mode = True, "grounded"
        elif a.kind != "fixed":
            reverse, mode = False, a.kind
        elif b.kind != "fixed":
            reverse, mode = True, b.kind
        else:
            reverse, mode = False, "fixed"
        start, far = (b, a) if reverse else (a, b)
        line = _make_line(model, reverse)
        # installation: the flow seen in the laying frame is the current minus the
        # frame velocity; the cable moves along itself from B to A at the pay-out speed
        if med.current_velocity.size:
            cz, cu = med.current_z, med.current_velocity
        else:
            cz, cu = np.zeros(1), np.zeros((1, 3))
        env = _Env(
            density=med.density,
            current_z=tuple(float(z) for z in cz),
            current_u=tuple(tuple(float(c) for c in u) for u in cu),  # type: ignore[misc]
            frame=tuple(float(c) for c in problem.touchdown_velocity),  # type: ignore[arg-type]
            payout=-problem.payout_speed if reverse else problem.payout_speed,
            stretched=problem.stretched_drag_diameter,
        )
        scale = float(np.sum(np.abs(model.weight) * model.length))
        if model.attachment_force.size:
            scale += float(np.sum(np.linalg.norm(model.attachment_force, axis=1)))
        for end in (a, b):
            if end.force is not None:
                scale = max(scale, float(np.linalg.norm(end.force)))
        if scale <= 0.0:
            scale = 1e-6 * float(np.min(model.axial_stiffness))
        return _Setup(line, env, start, far, reverse, bed, mode, scale)

    # -- residual -------------------------------------------------------------------
    def _start_state(self, st: _Setup, env: _Env, u: np.ndarray) -> _Start:
        """The start of a shot from the scaled unknowns ``u``."""
        L = st.line.length
        if st.mode == "fixed":
            assert st.start.position is not None
            p0 = np.asarray(st.start.position, dtype=float)
            return _Start(0.0, u * st.force_scale, p0, None, 0.0, u * st.force_scale, p0)
        if st.mode == "grounded":
            assert st.bed is not None and st.start.position is not None
            p0 = np.asarray(st.start.position, dtype=float)
            T0 = float(u[0]) * st.force_scale
            if T0 <= 0.0:
                raise _ShotFailed("non-positive tension at the touchdown point")
            e = st.bed.direction(float(u[1]))
            q = float(u[2]) * L
            if q >= 0.0:
                if q >= L:
                    raise _ShotFailed("laid length would exceed the line length")
                _, T_anchor = _laid_tension(st.line, st.bed, e, q, T0)
                _, _, total = _laid_profile(st.line, st.bed, e, q, T0, np.zeros(0))
                return _Start(q, T0 * e, p0 + total * e, e, T0, max(0.0, T_anchor) * e, p0)
            gamma = -float(u[2])
            t0 = math.cos(gamma) * e + math.sin(gamma) * st.bed.normal
            return _Start(0.0, T0 * t0, p0, None, T0, T0 * t0, p0)
        assert st.start.force is not None
        R = np.asarray(st.start.force, dtype=float)
        if st.mode == "force":
            p0 = u * L
            F0 = -R
        else:  # mooring: unknown vertical force and horizontal position
            assert st.start.z is not None
            p0 = np.array([u[1] * L, u[2] * L, st.start.z])
            F0 = np.array([-R[0], -R[1], u[0] * st.force_scale])
        # attachments at the start end act on the line there
        F_plus = F0.copy()
        if st.line.att_s and st.line.att_s[0] == 0.0:
            F_plus = F_plus - np.asarray(st.line.att_force[0])
        if float(np.linalg.norm(F_plus)) > 1e-9 * st.force_scale:
            return _Start(0.0, F0, p0, None, 0.0, F0, p0)
        # a free end: the line leaves it along its load, F(s) = -f s for small s
        return self._free_end_start(st, env, p0, F0)

    def _free_end_start(self, st: _Setup, env: _Env, p0: np.ndarray, F0: np.ndarray) -> _Start:
        line = st.line
        k = line.segment_at(0.0)
        f = np.asarray(_load(env, line, k, (0.0, 0.0, 1.0), float(p0[2]), 0.0))
        if not np.any(f):
            raise _ShotFailed("a free end with no load on the line next to it")
        t0 = -f / np.linalg.norm(f)
        for _ in range(200):  # tangent along minus the load it produces (fixed point)
            f = np.asarray(_load(env, line, k, tuple(t0), float(p0[2]), 0.0))
            t_new = -f / np.linalg.norm(f)
            if np.linalg.norm(t_new - t0) < 1e-15:
                break
            t0 = _unit(0.5 * (t0 + t_new))
        delta = 1e-9 * line.length
        fmag = float(np.linalg.norm(f))
        return _Start(delta, fmag * delta * t0, p0 + delta * t0, None, 0.0, F0, p0)

    def _residual(
        self, st: _Setup, integ: _Integrator, u: np.ndarray, dense: bool = False
    ) -> tuple[np.ndarray, _Shot, _Start]:
        start = self._start_state(st, integ.env, u)
        shot = integ.run(start.s0, start.force, start.position, dense=dense)
        L = st.line.length
        far = st.far
        if far.kind == "fixed":
            assert far.position is not None
            r = (shot.position_end - far.position) / L
        elif far.kind == "force":
            assert far.force is not None
            r = (shot.force_end - far.force) / st.force_scale
        else:
            assert far.force is not None and far.z is not None
            r = np.array(
                [
                    (shot.force_end[0] - far.force[0]) / st.force_scale,
                    (shot.force_end[1] - far.force[1]) / st.force_scale,
                    (shot.position_end[2] - far.z) / L,
                ]
            )
        return r, shot, start

    # -- initial guesses --------------------------------------------------------------
    def _guess(self, st: _Setup) -> np.ndarray:
        if st.mode in ("force", "mooring"):
            return self._guess_from_free_end(st)
        line, far = st.line, st.far
        L = line.length
        w = line.mean_weight()
        EA = L / line.compliance()
        assert st.start.position is not None
        p0 = np.asarray(st.start.position, dtype=float)
        loads = line.total_load()
        F0: np.ndarray | None = None
        if far.kind == "force":
            assert far.force is not None
            F0 = np.asarray(far.force, dtype=float) - loads
        elif far.kind == "fixed":
            assert far.position is not None
            res = solve_between(p0, far.position, L, w, EA, np.array([0.0, L]), tolerance=1e-10)
            if res.success:
                F0 = res.force_a.copy()
            else:
                d = np.asarray(far.position) - p0
                chord = float(np.linalg.norm(d))
                F0 = (d / chord if chord > 0 else np.array([0.0, 0.0, 1.0])) * st.force_scale
            for s_k, p in zip(line.att_s, line.att_force, strict=True):
                F0 = F0 + np.asarray(p) * (1.0 - s_k / L)
        else:  # mooring
            assert far.force is not None and far.z is not None
            Hv = np.array([far.force[0], far.force[1]])
            H = float(np.linalg.norm(Hv))
            h = far.z - p0[2]
            VA = self._mooring_va(H, h, L, w, EA)
            F0 = np.array([Hv[0] - loads[0], Hv[1] - loads[1], VA])
        if st.mode == "fixed":
            return F0 / st.force_scale
        return self._grounded_guess(st, F0, w)

    def _guess_from_free_end(self, st: _Setup) -> np.ndarray:
        """Start at a force or mooring end: one still-water shot from a trial position
        gives the offset to the fixed far end (exact without current)."""
        line, far = st.line, st.far
        L = line.length
        assert far.position is not None and st.start.force is not None
        p_far = np.asarray(far.position, dtype=float)
        if st.mode == "force":
            u = p_far / L
        else:
            assert st.start.z is not None
            R = np.asarray(st.start.force, dtype=float)
            H = float(np.linalg.norm(R[:2]))
            w = line.mean_weight()
            EA = L / line.compliance()
            # catenary from the far (fixed) end to the mooring end: tension there is
            # (H e, V_A + w L) along the line towards the mooring end
            VA = self._mooring_va(H, st.start.z - p_far[2], L, w, EA)
            vz = -(VA + w * L)
            u = np.array([vz / st.force_scale, p_far[0] / L, p_far[1] / L])
        integ = _Integrator(
            line, st.env.scaled(0.0), rtol=1e-8, force_scale=st.force_scale, deadline=None
        )
        try:
            shot = integ.run(*self._shot_args(st, integ, u), dense=False)
        except _ShotFailed:
            return u
        shift = p_far - shot.position_end
        if st.mode == "force":
            return u + shift / L
        return np.array([u[0], u[1] + shift[0] / L, u[2] + shift[1] / L])

    def _shot_args(
        self, st: _Setup, integ: _Integrator, u: np.ndarray
    ) -> tuple[float, np.ndarray, np.ndarray]:
        start = self._start_state(st, integ.env, u)
        return start.s0, start.force, start.position

    @staticmethod
    def _other_guesses(st: _Setup, u0: np.ndarray) -> list[np.ndarray]:
        """Further starting points, tried in turn when Newton fails from the first."""
        if st.mode == "grounded":
            return [
                np.array([u0[0] * f, u0[1], q])
                for f in (1.0, 0.3)
                for q in (0.5, 0.2, 0.05, -0.2)
                if q != u0[2]
            ]
        if st.mode == "fixed":
            return [u0 * f for f in (0.3, 3.0, 10.0)]
        return []

    @staticmethod
    def _mooring_va(H: float, h: float, L: float, w: float, EA: float) -> float:
        """Vertical component V_A of the tension vector at A of a uniform catenary with
        horizontal tension H whose far end is h above A [N]."""
        from scipy.optimize import brentq

        if w == 0.0:
            return H * h / max(math.sqrt(max(L * L - h * h, 1e-12 * L * L)), 1e-12)

        def f(VA: float) -> float:
            sol = CatenarySolution(H, VA, np.array([1.0, 0.0]), L, w, EA, 0, 0.0)
            return float(profile(sol, np.array([L]))[1][0]) - h

        lo, hi = -abs(w) * L - H - 1.0, abs(w) * L + H + 1.0
        for _ in range(200):
            if f(lo) < 0.0:
                break
            lo = 2.0 * lo
        for _ in range(200):
            if f(hi) > 0.0:
                break
            hi = 2.0 * hi
        try:
            return float(brentq(f, lo, hi, xtol=1e-12 * (abs(w) * L + H)))
        except ValueError:
            return 0.5 * w * L

    def _grounded_guess(self, st: _Setup, F0: np.ndarray, w: float) -> np.ndarray:
        """Start unknowns (T_0, beta, q / L) for a start end on the seabed, from a free
        start-force guess and, where the line should rest on the seabed, the inextensible
        catenary with touchdown."""
        from scipy.optimize import brentq

        assert st.bed is not None and st.start.position is not None
        bed, line, far = st.bed, st.line, st.far
        L = line.length
        p0 = np.asarray(st.start.position, dtype=float)
        horiz = np.array([F0[0], F0[1], 0.0])
        if far.kind == "fixed":
            assert far.position is not None
            d = np.asarray(far.position, dtype=float) - p0
            horiz = np.array([d[0], d[1], 0.0])
        if np.linalg.norm(horiz) == 0.0:
            horiz = bed.upslope.copy()
        beta = bed.beta_of(horiz)
        suspended: float | None = None
        H = float(np.linalg.norm(F0[:2]))
        if far.kind == "fixed":
            assert far.position is not None
            d = np.asarray(far.position, dtype=float) - p0
            h = float(np.dot(d, bed.normal))
            X = float(np.linalg.norm(d - h * bed.normal))
            if h > 0.0 and X > 0.0:

                def gap(Ls: float) -> float:
                    a = (Ls * Ls - h * h) / (2.0 * h)
                    return (L - Ls) + a * math.asinh(Ls / a) - X

                # the largest suspended length with a sign change of the gap on a grid
                grid = np.linspace(h * (1.0 + 1e-6), L, 65) if h < L else np.zeros(0)
                gaps = [gap(float(g)) for g in grid]
                for g0, g1, v0, v1 in zip(
                    grid[-2::-1], grid[:0:-1], gaps[-2::-1], gaps[:0:-1], strict=True
                ):
                    if v0 * v1 <= 0.0:
                        suspended = float(brentq(gap, g0, g1, xtol=1e-9 * L))
                        a = (suspended**2 - h * h) / (2.0 * h)
                        H = a * w
                        break
        elif far.kind == "mooring":
            assert far.z is not None
            h = far.z - bed.z(p0[0], p0[1])
            if h > 0.0 and w > 0.0:
                suspended = math.sqrt(h * h + 2.0 * h * H / w)
        else:
            assert far.force is not None
            if w > 0.0 and far.force[2] > 0.0:
                suspended = float(far.force[2]) / w
        if suspended is not None and 0.0 < suspended < L and H > 0.0:
            return np.array([H / st.force_scale, beta, (L - suspended) / L])
        # lifted anchor: the start force as it is
        T = float(np.linalg.norm(F0))
        if T == 0.0:
            return np.array([1.0, beta, 0.0])
        t0 = F0 / T
        gamma = math.asin(max(-1.0, min(1.0, float(np.dot(t0, bed.normal)))))
        beta = bed.beta_of(t0 - np.dot(t0, bed.normal) * bed.normal) if gamma < 1.5 else beta
        return np.array([T / st.force_scale, beta, -max(gamma, 0.0)])

    # -- Newton ---------------------------------------------------------------------
    def _newton(
        self,
        st: _Setup,
        integ: _Integrator,
        u0: np.ndarray,
        tol: float,
        max_iterations: int,
        deadline: float | None,
    ) -> tuple[np.ndarray, float, int, int, str]:
        """Damped Newton on the scaled end residual. The Jacobian is a central-difference
        one, refreshed when a step does not reduce the residual well and otherwise
        updated by Broyden's rank-one formula (each refresh costs six shots). Returns
        (u, residual norm, iterations, status, message)."""

        failures: list[str] = []

        def resid(u: np.ndarray) -> np.ndarray | None:
            try:
                return self._residual(st, integ, u)[0]
            except _ShotFailed as exc:
                failures.append(str(exc))
                return None

        u = np.array(u0, dtype=float)
        r = resid(u)
        if r is None:
            return u, math.inf, 0, STATUS_NOT_CONVERGED, f"the first shot failed: {failures[-1]}"
        norm = float(np.max(np.abs(r)))
        it = 0
        polish = 0
        J: np.ndarray | None = None
        fresh = False
        while True:
            if norm <= tol:
                # a few more steps towards the round-off floor of the integration
                polish += 1
                if polish > 4 or norm <= 10.0 * integ.rtol:
                    return u, norm, it, STATUS_OK, ""
            if it >= max_iterations:
                if norm <= tol:
                    return u, norm, it, STATUS_OK, ""
                return (
                    u,
                    norm,
                    it,
                    STATUS_NOT_CONVERGED,
                    (
                        f"shooting Newton did not converge in {max_iterations} iterations "
                        f"(residual {norm:.3g}, tolerance {tol:.3g})"
                    ),
                )
            if deadline is not None and time.monotonic() > deadline:
                raise _TimeUp
            it += 1
            if J is None:
                J = self._jacobian(resid, u, r)
                fresh = True
                if J is None:
                    return (
                        u,
                        norm,
                        it,
                        STATUS_NOT_CONVERGED,
                        ("shots next to the current iterate fail (tension vanishes)"),
                    )
            step = np.linalg.lstsq(J, -r, rcond=None)[0]
            if not np.all(np.isfinite(step)):
                return u, norm, it, STATUS_NUMERICAL, "non-finite Newton step"
            lam = 1.0
            accepted = False
            merit = float(np.linalg.norm(r))  # the step is a descent direction of |r|_2
            while lam >= 1.0 / 4096.0:
                un = u + lam * step
                rn = resid(un)
                if rn is not None:
                    nn = float(np.max(np.abs(rn)))
                    if float(np.linalg.norm(rn)) < (1.0 - 1e-4 * lam) * merit:
                        accepted = True
                        break
                lam *= 0.5
                if not fresh and lam < 0.2:
                    break  # a stale Jacobian: refresh it before searching further
            if not accepted:
                if not fresh:
                    J = None
                    continue
                if norm <= tol:
                    return u, norm, it, STATUS_OK, ""
                if norm < 1e-5 and integ.tighten():
                    # stalled near the solution: the integration error of an
                    # ill-conditioned shot is the floor; integrate more tightly
                    r = resid(u)
                    if r is None:
                        return u, norm, it, STATUS_NOT_CONVERGED, "a tighter shot failed"
                    norm = float(np.max(np.abs(r)))
                    J = None
                    continue
                return (
                    u,
                    norm,
                    it,
                    STATUS_NOT_CONVERGED,
                    (
                        f"shooting Newton line search failed (residual {norm:.3g}, "
                        f"tolerance {tol:.3g})"
                    ),
                )
            slow = float(np.linalg.norm(rn)) > 0.5 * merit
            if slow and fresh:
                if norm <= tol:
                    return un, nn, it, STATUS_OK, ""
                if nn < 1e-5:
                    integ.tighten()
                    rn = resid(un)
                    if rn is None:
                        return u, norm, it, STATUS_NOT_CONVERGED, "a tighter shot failed"
                    nn = float(np.max(np.abs(rn)))
            # Broyden's update of the Jacobian along the step taken; a slow step with
            # an updated Jacobian asks for a fresh one
            du = un - u
            J = J + np.outer(rn - r - J @ du, du) / float(du @ du)
            fresh = False
            if slow:
                J = None
            u, r, norm = un, rn, nn

    @staticmethod
    def _jacobian(
        resid: Callable[[np.ndarray], np.ndarray | None], u: np.ndarray, r: np.ndarray
    ) -> np.ndarray | None:
        """Central-difference Jacobian (one-sided where a shot fails): the shooting map
        of a drag-loaded line is strongly nonlinear, and central differences keep
        Newton quadratic down to the integration round-off."""
        J = np.empty((len(r), len(u)))
        for j in range(len(u)):
            h = _FD_STEP * max(1.0, abs(u[j]))
            du = np.zeros_like(u)
            du[j] = h
            rp, rm = resid(u + du), resid(u - du)
            if rp is not None and rm is not None:
                J[:, j] = (rp - rm) / (2.0 * h)
            elif rp is not None:
                J[:, j] = (rp - r) / h
            elif rm is not None:
                J[:, j] = (r - rm) / h
            else:
                return None
        return J

    # -- driver ---------------------------------------------------------------------
    def _solve(
        self, problem: StaticProblem, s_out: np.ndarray, deadline: float | None
    ) -> StaticResult:
        st = self._setup(problem)
        tol = max(problem.tolerance, 100.0 * self.rtol)
        u = self._guess(st)
        total_it = 0

        def newton(factor: float, u0: np.ndarray, cap: int) -> tuple[np.ndarray, float, int, str]:
            nonlocal total_it
            integ = _Integrator(
                st.line,
                st.env.scaled(factor),
                rtol=self.rtol,
                force_scale=st.force_scale,
                deadline=deadline,
            )
            u1, norm1, it, status1, msg1 = self._newton(st, integ, u0, tol, cap, deadline)
            total_it += it
            return u1, norm1, status1, msg1

        u0 = u
        u, norm, status, msg = newton(0.0, u0, problem.max_iterations)
        for alt in self._other_guesses(st, u0):
            if status == STATUS_OK or (st.mode == "grounded" and u[0] < 1e-4):
                break  # converged, or heading for a slack line (diagnosed below)
            u, norm, status, msg = newton(
                0.0, alt, min(problem.max_iterations, _ALTERNATIVE_ITERATIONS)
            )
        unloaded = not any(st.line.weight) and not st.line.att_force
        if status != STATUS_OK and st.env.has_current and unloaded:
            # no still-water shape (a slack weightless line): go straight to the full
            # current
            for start in [u0, *self._other_guesses(st, u0)]:
                u, norm, status, msg = newton(
                    1.0, start, min(problem.max_iterations, _ALTERNATIVE_ITERATIONS)
                )
                if status == STATUS_OK:
                    return self._finish(st, s_out, u, norm, total_it, deadline)
        if status != STATUS_OK and st.mode == "grounded" and u[0] < 1e-4:
            return StaticResult.failed(
                s_out,
                STATUS_NO_SOLUTION,
                "slack line: the touchdown tension tends to zero (the line is longer than a "
                "straight laid part and a vertical hanging part can take, so it would pile "
                "on the seabed; there is no taut static shape)",
                iterations=total_it,
                residual=norm,
            )
        if status != STATUS_OK and st.mode == "grounded" and st.far.kind == "force":
            assert st.far.force is not None
            lift = float(st.far.force[2]) + sum(max(0.0, p[2]) for p in st.line.att_force)
            if lift <= 0.0:
                return StaticResult.failed(
                    s_out,
                    STATUS_NO_SOLUTION,
                    f"the force at the free end (vertical component {st.far.force[2]:.6g} N) "
                    "and the attachments do not lift the line off the seabed: it would be "
                    "pulled into the seabed",
                    iterations=total_it,
                    residual=norm,
                )
        if status != STATUS_OK and st.mode == "grounded" and u[2] > 0.0:
            L = st.line.length
            near = [x for x in st.line.att_s if abs(x - u[2] * L) < 0.02 * L]
            if near:
                return StaticResult.failed(
                    s_out,
                    status,
                    f"the touchdown point runs into the attachment at s = {near[0]:.6g} m "
                    "(from the seabed end): a point load resting on the seabed at the "
                    "touchdown point, with a kink in the line there, is not modelled; "
                    f"{msg}",
                    iterations=total_it,
                    residual=norm,
                )
        if status != STATUS_OK:
            hint = (
                "; no equilibrium above the seabed may exist for these end conditions"
                if st.mode == "grounded"
                else ""
            )
            return StaticResult.failed(
                s_out, status, f"still water: {msg}{hint}", iterations=total_it, residual=norm
            )
        if st.env.has_current:
            # continuation in current speed from the still-water solution, with a secant
            # predictor from the last two converged steps
            done, step, n_steps = 0.0, 1.0, 0
            prev: tuple[float, np.ndarray] | None = None
            while done < 1.0:
                n_steps += 1
                trial = min(1.0, done + step)
                if n_steps > 80:
                    return StaticResult.failed(
                        s_out,
                        STATUS_NOT_CONVERGED,
                        f"current-speed continuation stalled at {done:.3g} of the current",
                        iterations=total_it,
                        residual=norm,
                    )
                u_pred = u
                if prev is not None:
                    u_pred = u + (trial - done) * (u - prev[1]) / (done - prev[0])
                # a continuation step that needs many iterations is retried shorter
                cap = (
                    problem.max_iterations
                    if step < 2e-3
                    else min(problem.max_iterations, _CONTINUATION_ITERATIONS)
                )
                u_try, norm_t, status_t, msg_t = newton(trial, u_pred, cap)
                if status_t == STATUS_OK:
                    prev = (done, u)
                    done, u, norm = trial, u_try, norm_t
                    step = min(1.0 - done, 2.0 * step) if done < 1.0 else step
                    continue
                step *= 0.25
                if step < 1e-3:
                    return StaticResult.failed(
                        s_out,
                        status_t,
                        f"current-speed continuation failed at {trial:.3g} of the current: {msg_t}",
                        iterations=total_it,
                        residual=norm_t,
                    )
        return self._finish(st, s_out, u, norm, total_it, deadline)

    def _finish(
        self,
        st: _Setup,
        s_out: np.ndarray,
        u: np.ndarray,
        norm: float,
        total_it: int,
        deadline: float | None,
    ) -> StaticResult:
        """The converged shot again, with dense output, sampled at the output nodes."""
        integ = _Integrator(
            st.line, st.env, rtol=self.rtol, force_scale=st.force_scale, deadline=deadline
        )
        try:
            r, shot, start = self._residual(st, integ, u, dense=True)
        except _ShotFailed as exc:
            return StaticResult.failed(
                s_out,
                STATUS_NUMERICAL,
                f"final shot failed: {exc}",
                iterations=total_it,
                residual=norm,
            )
        return self._result(st, s_out, shot, start, total_it, float(np.max(np.abs(r))))

    def _result(
        self,
        st: _Setup,
        s_out: np.ndarray,
        shot: _Shot,
        start: _Start,
        iterations: int,
        residual: float,
    ) -> StaticResult:
        L = st.line.length
        s_loc = (L - s_out) if st.reverse else s_out.copy()
        position = np.full((len(s_out), 3), np.nan)
        tension = np.full(len(s_out), np.nan)
        laid = 0.0
        before = s_loc < start.s0
        if start.laid is not None:
            assert st.bed is not None
            laid = start.s0
            dist, tens, _ = _laid_profile(st.line, st.bed, start.laid, start.s0, start.t_tdp, s_loc)
            position[before] = start.origin + dist[before, None] * start.laid
            tension[before] = tens[before]
        elif np.any(before):  # the short straight piece next to a free end
            frac = s_loc[before] / start.s0
            position[before] = start.origin + frac[:, None] * (start.position - start.origin)
            tension[before] = frac * float(np.linalg.norm(start.force))
        for piece in shot.pieces:
            inside = (s_loc >= piece.s0) & (s_loc <= piece.s1) & np.isnan(tension)
            if np.any(inside):
                y = piece.sol(s_loc[inside])
                tension[inside] = y[0]
                position[inside] = y[3:6].T
        # a node exactly at an attachment reports the tension on its B side (s+)
        for j in np.nonzero(np.isin(s_loc, st.line.att_s))[0]:
            for piece in shot.pieces:
                if (piece.s1 if st.reverse else piece.s0) == s_loc[j]:
                    tension[j] = float(piece.sol(np.array([s_loc[j]]))[0, 0])
                    break
        force_start = start.force_start
        force_far = -shot.force_end
        force_a, force_b = (force_far, force_start) if st.reverse else (force_start, force_far)
        if st.bed is not None:
            ground = np.array([st.bed.z(x, y) for x, y in position[:, :2]])
            below = float(np.max(ground - position[:, 2]))
            if below > 1e-6 * L:
                return StaticResult.failed(
                    s_out,
                    STATUS_NO_SOLUTION,
                    f"the line passes {below:.4g} m below the seabed; the shooting solver "
                    "models seabed contact only from a fixed end on the seabed (within "
                    "1e-6 of the line length; touchdown integration)",
                    iterations=iterations,
                    residual=residual,
                )
        return StaticResult(
            s=s_out,
            position=position,
            tension=tension,
            force_a=force_a,
            force_b=force_b,
            laid_length=float(laid),
            status=STATUS_OK,
            message="",
            iterations=iterations,
            residual=residual,
        )
