"""A point load (a clump weight) resting on the seabed at the touchdown point.

The seabed-contact Newton (:func:`.semi_analytic_newton.solve_contact`) solves for the
tension T_td at the touchdown point (TDP) and its arc length s_td. A downward point load
at s_p makes that state set-valued: for a finite range of fairlead positions the TDP
stays at the load while the seabed carries part R of it,

    0 <= R <= R_max = -(f . n)        (f the load on the line, n the seabed normal),

the line is straight on the seabed up to s_p and leaves it there with a kink. R = 0 is
the limit of the TDP just anchor-side of the load (the load hangs, the laid part ends
tangent to the seabed); R = R_max is the limit of the TDP just past it (the load lies on
the seabed, the suspended line leaves tangent to it). The tension across the load,
with Coulomb friction mu R fully mobilised towards the anchor (as on the laid part,
:mod:`.seabed`), jumps by

    T(s_p+) = T(s_p-) - j,    j = f + R n - mu R e     (e the laid direction).

With s_td alone as unknown the residual jumps as the TDP crosses s_p, and Newton's line
search fails there (the clump-near-touchdown failure). :class:`PinMap` replaces s_td by a
coordinate sigma along an extended line in which every such load holds an interval of
length Delta_p = R_max / w_p (w_p the normal weight per length of the line there, so that
moving sigma by one metre changes the force held by the seabed as much as moving the TDP
by one metre does): on it s_td = s_p and R runs linearly from 0 to R_max. The map is
continuous and piecewise linear, the residual continuous in sigma, and Newton crosses the
load without a jump.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass(frozen=True)
class PinMap:
    """Pinning intervals of the downward point loads strictly inside the line: their
    boundary indices ``index``, arc lengths ``s`` [m] (ascending), maximum seabed
    reactions ``r_max`` [N] and interval lengths ``delta`` [m]."""

    index: np.ndarray
    s: np.ndarray
    r_max: np.ndarray
    delta: np.ndarray

    @property
    def extra(self) -> float:
        """[m] the extension of the sigma axis over the line length."""
        return float(np.sum(self.delta))

    def to_line(self, sigma: float) -> tuple[float, int, float, float]:
        """(s_td [m], pinning load's position in this map or -1, R [N], dR/dsigma [N/m]).
        A TDP exactly at a load is always pinned (R = 0 at one end of its interval, R_max
        at the other), so that the load is never left out of both parts."""
        shift = 0.0
        for i in range(len(self.s)):
            lo = self.s[i] + shift
            if sigma < lo:
                break
            if sigma <= lo + self.delta[i]:
                rate = self.r_max[i] / self.delta[i]
                return float(self.s[i]), i, float(rate * (sigma - lo)), float(rate)
            shift += self.delta[i]
        return float(sigma - shift), -1, 0.0, 0.0

    @property
    def kinks(self) -> np.ndarray:
        """[m] the sigma values where the state changes piece (ends of the intervals)."""
        lo = self.s + np.concatenate(([0.0], np.cumsum(self.delta)[:-1]))
        return np.sort(np.concatenate((lo, lo + self.delta)))

    def to_sigma(self, s_td: float) -> float:
        """sigma of a TDP at s_td [m] not pinned (a TDP exactly at a load: the load
        lying on the seabed, R = R_max)."""
        return float(s_td + np.sum(self.delta[self.s <= s_td]))


def pin_map(
    bounds: np.ndarray, point: np.ndarray, weight: np.ndarray, normal: np.ndarray
) -> PinMap:
    """The pinning intervals of a layout: ``bounds`` [m] (P + 1,), ``point`` [N] (P + 1, 3)
    point loads at the boundaries, ``weight`` [N/m] (P,), ``normal`` the seabed's upward
    unit normal. Loads pulling up or along the seabed cannot rest on it: no interval."""
    fn = point @ normal
    idx = np.flatnonzero(fn[1:-1] < 0.0) + 1
    L = float(bounds[-1])
    mean = float(np.sum(np.abs(weight) * np.diff(bounds))) / L
    r_max = -fn[idx]
    delta = np.empty(len(idx))
    for j, k in enumerate(idx):
        # the normal weight per length anchor-side of the load, else the line's mean
        w = float(weight[k - 1]) * float(normal[2])
        if not w > 0.0:
            w = mean * float(normal[2])
        delta[j] = r_max[j] / max(w, 1e-300)
    keep = delta > 1e-12 * L
    return PinMap(idx[keep], bounds[idx[keep]].astype(float), r_max[keep], delta[keep])


def pin_jump(
    force: np.ndarray,
    reaction: float,
    r_max: float,
    T_hat: np.ndarray,
    normal: np.ndarray,
    mu: float,
) -> tuple[np.ndarray, np.ndarray, float, np.ndarray, float]:
    """A pinned load's state from the in-plane unknown T_hat [N] and the reaction R [N]:
    (j [N], dj/dR [-], t_lo [N], dt_lo/dT_hat [-] (3,), dt_lo/dR [-]).

    The tension past the load is T(s_p+) = T_hat - j with j = f + R n - (R / R_max) f_t
    (f_t the load's part in the seabed plane), the laid part ends at s_p- along
    e = T_hat / |T_hat| with tension t_lo = |T_hat| - (R / R_max) (mu R_max - f . e).
    Along e and n this is the load's equilibrium with the seabed reaction R n and the
    friction mu R towards the anchor; T_hat is the tension at the TDP of the neighbouring
    states at both ends (R = 0: the load hangs just past the TDP; R = R_max: it lies just
    before it, where :func:`.seabed.laid_part` takes mu R_max - f . e off the tension),
    so the state is continuous across both ends. The load's part across the line in the
    seabed plane is ignored on the laid side, as :func:`.seabed.laid_part` does."""
    tn = float(np.linalg.norm(T_hat))
    e = T_hat / tn
    ft = force - float(force @ normal) * normal
    a = reaction / r_max
    j = force + reaction * normal - a * ft
    dj_dR = normal - ft / r_max
    fe = float(force @ e)
    t_lo = tn - a * (mu * r_max - fe)
    dt_dT = e + a * (force - fe * e) / tn
    dt_dR = -(mu * r_max - fe) / r_max
    return j, dj_dR, t_lo, dt_dT, dt_dR


def first_lift(bounds: np.ndarray, point: np.ndarray, normal: np.ndarray) -> tuple[float, int]:
    """(arc length [m], boundary index) of the first point load strictly inside the line
    that pulls away from the seabed (a buoyancy module: ``point . normal > 0``), or
    (inf, -1). The seabed-contact state cannot have the touchdown point (TDP) past it:
    the seabed only pushes, so a laid line cannot hold a load lifting it. Short of it
    the state is continuous in s_td up to the load (the load hangs just past the TDP and
    the suspended line leaves there with the kink the load makes as s_td -> s_p-). At
    s_td = s_p exactly the load would fall between the laid and the suspended parts, so
    the contact Newton keeps s_td a little short of it."""
    up = np.flatnonzero(point[1:-1] @ normal > 0.0) + 1
    if not up.size:
        return math.inf, -1
    return float(bounds[up[0]]), int(up[0])


def arch_refusal(
    lay: Any, normal: np.ndarray, laid: tuple[float, float], method: str, flip: float | None = None
) -> str:
    """Why a state with one laid stretch cannot be (empty when it can): its laid stretch
    ``laid`` [m] (from, to: arc lengths of the layout ``lay``,
    :class:`.semi_analytic_shape.Layout`) holds a load lifting the line, a point load
    pulling away from the seabed of upward unit ``normal``, or a piece lighter than the
    fluid. The seabed cannot pull it down: the line arches off the seabed there, between
    two touchdowns. ``flip`` [m]: the line's length where ``lay`` runs from B (the
    message counts s from A)."""
    (lo, hi), b = laid, lay.bounds
    up = np.flatnonzero((b > lo) & (b < hi) & (lay.point @ normal > 0.0))
    light = np.flatnonzero((lay.weight < 0.0) & (b[:-1] < hi) & (b[1:] > lo))
    s = b if flip is None else flip - b
    if up.size:
        what = f"a buoy at s = {s[up[0]]:.6g} m"
    elif light.size:
        k = light[0]
        what = f"a buoyant piece at s = {min(s[k], s[k + 1]):.6g} to {max(s[k], s[k + 1]):.6g} m"
    else:
        return ""
    return (
        f"{what} lifts the line off the seabed between two touchdowns; method '{method}' "
        "models one laid stretch; method 'discrete' models it"
    )
