"""The shooting solver's initial-value problem (:mod:`.shooting`, whose docstring
gives the formulation): the line's segments and loads (:class:`_Line`), the environment
and its current (:class:`_Env`), the local frame and the equations integrated piece by
piece (:class:`_Integrator`), and the part laid on a (sloped) seabed with friction, in
closed form (:func:`_laid_profile`).
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
    LineModel,
)

#: legs end (and restart in a new frame) where |sin(elevation)| reaches this [-]
_POLE_LIMIT = 0.95


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

    def segment_at(self, s: float) -> int:
        """Index of the segment containing s (the one starting at s when on a
        boundary)."""
        return min(max(bisect.bisect_right(self.ends, s) - 1, 0), len(self.weight) - 1)

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
