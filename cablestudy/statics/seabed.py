"""Seabed contact of a line anchored on a plane seabed: the laid part.

Quasi-static convention (e.g. Faltinsen, *Sea Loads on Ships and Offshore
Structures*, 1990, ch. 8): the part of the line between the anchor and the touchdown
point (TDP) lies straight on the seabed along the direction ``e`` of the tension at the
TDP; the seabed carries the normal component of its weight; Coulomb friction is fully
mobilised towards the anchor, so that the tension falls from the TDP towards the anchor
at the rate

    k = w sqrt((mu n_z)^2 - c^2) + w (e . z)     [N/m]

and never below zero: where it reaches zero the rest of the laid line towards the anchor
is slack (w > 0 the submerged weight per length, n the upward seabed normal). Friction
first holds the weight's part down the slope across the line, w c with
c = |n_x e_y - n_y e_x| (zero on a flat seabed or along the fall line); Coulomb's cone,
|friction| <= mu w n_z at every point, leaves sqrt((mu n_z)^2 - c^2) per unit weight to
act along the line (:func:`along_friction`). Where c > mu n_z no friction holds the
straight laid line: it would slide sideways, and the solver refuses the state. Drag on
the laid part is neglected.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..physics.axial import gauss_legendre


@dataclass(frozen=True)
class Plane:
    """Seabed plane through (0, 0, -depth) rising at ``slope`` [rad] towards
    ``heading`` [rad from +x]; ``normal`` is its upward unit normal, ``e1``, ``e2`` an
    orthonormal basis of the plane."""

    depth: float
    slope: float
    heading: float
    friction: float

    @property
    def normal(self) -> np.ndarray:
        ch, sh = math.cos(self.heading), math.sin(self.heading)
        ts = math.tan(self.slope)
        n = np.array([-ts * ch, -ts * sh, 1.0])
        return n / np.linalg.norm(n)

    @property
    def basis(self) -> tuple[np.ndarray, np.ndarray]:
        n = self.normal
        ch, sh = math.cos(self.heading), math.sin(self.heading)
        e2 = np.array([-sh, ch, 0.0])  # level line of the plane
        e1 = np.cross(e2, n)
        return e1 / np.linalg.norm(e1), e2

    def height_above(self, r: np.ndarray) -> np.ndarray:
        """Distance above the plane measured along its normal [m] (negative below)."""
        r = np.asarray(r, dtype=float)
        return (r - np.array([0.0, 0.0, -self.depth])) @ self.normal


def along_friction(mu: float, normal: np.ndarray, e: np.ndarray) -> float:
    """Friction per unit weight [-] that a line laid along the unit vector ``e`` on the
    seabed of upward unit ``normal`` and friction coefficient ``mu`` mobilises along
    itself: sqrt((mu n_z)^2 - c^2), c = |n_x e_y - n_y e_x| the weight's part down the
    slope across the line per unit weight, which friction holds first (mu n_z exactly
    where c = 0; 0 where c > mu n_z). Plain Python: :mod:`._fast_contact` compiles it."""
    a = mu * normal[2]
    c = normal[0] * e[1] - normal[1] * e[0]
    return math.sqrt(max(a * a - c * c, 0.0)) if c != 0.0 else a


def seabed_of(medium: Any) -> Plane | None:
    """The seabed plane of a medium (:class:`.base.Medium`: its depth, slope, heading and
    friction; None without a seabed)."""
    if medium.depth is None:
        return None
    return Plane(medium.depth, medium.seabed_slope, medium.seabed_heading, medium.friction)


def _law_stretch(law: Any, t_lo: float, t_hi: float, length: float) -> tuple[float, float]:
    """(int e(T) ds, int de/dT ds) [m], [m/N] over ``length`` [m] of a laid piece whose
    tension runs linearly from t_lo to t_hi [N]: exact through the law's complementary
    energy where the tension changes, by 16-point Gauss-Legendre where it hardly does
    (the difference would cancel)."""
    if length <= 0.0 or t_hi <= 0.0:
        return 0.0, 0.0
    if t_hi - t_lo > 1e-3 * t_hi:
        k = (t_hi - t_lo) / length
        phi = law.complementary_energy(np.array([t_lo, t_hi]))
        e = law.strain(np.array([t_lo, t_hi]))
        return float(phi[1] - phi[0]) / k, float(e[1] - e[0]) / k
    x, w = gauss_legendre(16)
    T = t_lo + (t_hi - t_lo) * x
    e = law.strain(T)
    return float(length * np.sum(w * e)), float(length * np.sum(w / law.tangent_stiffness(e)))


@dataclass
class LaidPart:
    """The laid part from the anchor (s = 0) to the TDP s_td [m].

    ``s`` [m] piece boundaries from 0 to s_td; ``tension`` [N] at them (on the TDP side
    of any point load there); ``tension_lo``, ``tension_hi`` [N] per piece at its anchor
    and TDP ends, ``rate`` [N/m] per piece; ``stretched``
    [m] the stretched laid length; ``positive_flex`` [m/N] = sum over the length with
    positive tension of dl / EA (d stretched / d tension at the TDP); ``rate_td`` [N/m]
    the rate k at the TDP."""

    s: np.ndarray
    tension: np.ndarray
    tension_lo: np.ndarray
    tension_hi: np.ndarray
    rate: np.ndarray
    stretched: float
    positive_flex: float
    rate_td: float


def laid_part(
    s_td: float,
    tension_td: float,
    direction: np.ndarray,
    bounds: np.ndarray,
    weight: np.ndarray,
    EA: np.ndarray,
    point_s: np.ndarray,
    point_force: np.ndarray,
    plane: Plane,
    laws: Sequence[Any] | None = None,
) -> LaidPart:
    """Tension along the laid part, marching from the TDP to the anchor.

    Parameters
    ----------
    s_td : float
        [m] arc length of the touchdown point.
    tension_td : float
        [N] tension at the TDP (>= 0).
    direction : np.ndarray
        [-] (3,) unit vector along the laid line from the anchor towards the TDP.
    bounds : np.ndarray
        [m] (P + 1,) piece boundaries of the whole line.
    weight, EA : np.ndarray
        [N/m], [N] (P,) per piece.
    point_s, point_force : np.ndarray
        [m] (k,), [N] (k, 3): point loads (applied to the line) on the laid part.
    plane : Plane
        The seabed.
    laws : sequence of AxialLaw or None, optional
        [-] (P,) each piece's non-linear axial law (None: T = EA e): its stretch is then
        int e(T) ds = (Phi(T_hi) - Phi(T_lo)) / k exactly (Phi the complementary energy,
        k the tension rate), and its flexibility (e(T_hi) - e(T_lo)) / k.
    """
    n = plane.normal
    mu = plane.friction
    ez = float(direction[2])
    cut = bounds[(bounds > 0.0) & (bounds < s_td)]
    pts = np.concatenate(([0.0], cut, [s_td]))
    tension = np.empty(len(pts))
    tension[-1] = max(tension_td, 0.0)
    stretched = 0.0
    flex = 0.0
    piece = np.clip(
        np.searchsorted(bounds, 0.5 * (pts[:-1] + pts[1:]), side="right") - 1, 0, len(weight) - 1
    )
    rates = weight[piece] * (along_friction(mu, n, direction) + ez)
    order = np.argsort(point_s)
    t_los = np.zeros(len(pts) - 1)
    t_his = np.zeros(len(pts) - 1)
    for j in range(len(pts) - 2, -1, -1):
        lo, hi = pts[j], pts[j + 1]
        ell = hi - lo
        t_hi = tension[j + 1]
        # point loads inside (lo, hi]: friction and along-line jumps
        for i in order:
            if lo < point_s[i] <= hi and point_s[i] < s_td:
                f = point_force[i]
                t_hi = max(t_hi - (mu * max(0.0, -float(f @ n)) - float(f @ direction)), 0.0)
        k = rates[j]
        ea = EA[piece[j]]
        t_lo = t_hi - k * ell
        if t_lo >= 0.0:
            positive = ell
            area = 0.5 * ell * (t_hi + t_lo)
        else:
            positive = t_hi / k if k > 0.0 else ell
            area = 0.5 * t_hi * positive
            t_lo = 0.0
        if t_hi <= 0.0:
            positive, area = 0.0, 0.0
        tension[j] = max(t_lo, 0.0)
        t_los[j], t_his[j] = tension[j], max(t_hi, 0.0)
        law = laws[piece[j]] if laws is not None else None
        if law is None:
            stretched += ell + area / ea
            flex += positive / ea
        else:
            s_, f_ = _law_stretch(law, tension[j], max(t_hi, 0.0), positive)
            stretched += ell + s_
            flex += f_
    rate_td = float(rates[-1]) if len(rates) else 0.0
    return LaidPart(
        s=pts,
        tension=tension,
        tension_lo=t_los,
        tension_hi=t_his,
        rate=rates,
        stretched=stretched,
        positive_flex=flex,
        rate_td=rate_td,
    )
