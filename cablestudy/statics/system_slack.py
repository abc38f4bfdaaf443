"""The end forces of a line lying slack on the seabed, for the trial points of a system's
free-point Newton (:func:`.system._solve`).

A line longer than the path from its ends straight down to the seabed and along it has
no determined shape: the cable model's contact Newton stops there ("slack ... not
determined"). Its end forces are determined all the same, wherever the seabed holds the
slack without friction being mobilised: the laid part carries no tension, so each raised
end holds the part of the line hanging straight down from it to the seabed with zero
tension at its foot, and a grounded end holds nothing. This is the limit of the taut
contact state as its touchdown tension goes to zero (the suspended part then hangs
vertically), so the force field the free points see is continuous where a line goes
from taut to slack. MoorPy's catenary takes the same limit for its lines longer than
that path (no horizontal force, the hanging weight at the end).

A free point started where one of its lines is slack (a junction or clump placed by
eye, a MoorDyn file's rough positions) then has defined forces and stiffness, and the
Newton moves it to the equilibrium. These forces are never an answer: the system's
solution is solved again by the verified line solvers (a line slack at the equilibrium
itself still fails there, its shape being undetermined).

The hanging part from an end, with pieces of weight w_i > 0 [N/m] and axial stiffness
EA_i [N] ordered from the end down and downward point loads F_j [N] at the boundaries:
its unstretched length S and top tension W solve

    h = int_0^S (1 + T(u) / EA(u)) du,   T(u) = tension at u above the foot, T(foot) = 0,

h the end's height above the seabed along the vertical. A load exactly at the foot
carries a fraction phi in [0, 1] of its weight (the rest rests on the seabed), so that
h(S, phi) is continuous and increasing. The stiffness: K_zz = dW/dh (w at the foot over
1 + w times the hanging part's flexibility above the foot, or 1 / flexibility while the
foot is at a load), across the vertical none (the slack foot slides). Pure: arrays in,
arrays out (SI units).
"""

from __future__ import annotations

import numpy as np

from .base import StaticProblem, StaticResult
from .seabed import seabed_of
from .semi_analytic_shape import make_layout


def _column(
    ell: np.ndarray, w: np.ndarray, EA: np.ndarray, F: np.ndarray, j: int, ell_j: float,
    phi: float,
) -> tuple[float, float, float]:  # fmt: skip
    """The hanging part whose foot lies ``ell_j`` into piece ``j`` (pieces from the end
    down, ``F[i]`` the load at the top of piece i, F[0] the end's own, not carried),
    the load F[j] carried with fraction ``phi`` when ell_j = 0 (else whole): its height
    [m], top tension [N] and flexibility above the foot sum l/EA [m/N]."""
    T = w[j] * ell_j
    height = ell_j + 0.5 * w[j] * ell_j * ell_j / EA[j]
    flex = ell_j / EA[j]
    for i in range(j - 1, -1, -1):
        T += F[i + 1] * (phi if (i == j - 1 and ell_j == 0.0) else 1.0)
        height += ell[i] + (T * ell[i] + 0.5 * w[i] * ell[i] * ell[i]) / EA[i]
        flex += ell[i] / EA[i]
        T += w[i] * ell[i]
    return height, T, flex


def hanging(
    ell: np.ndarray, w: np.ndarray, EA: np.ndarray, F: np.ndarray, h: float
) -> tuple[float, float, float] | None:
    """The part of a line hanging straight down ``h`` [m] from its end to a zero-tension
    foot: (unstretched length S [m], top tension W [N], dW/dh [N/m]); pieces ``ell``,
    ``w``, ``EA`` from the end down, ``F`` (P + 1,) downward loads at their tops (F[0]
    the end's, not carried). None if the whole line hangs short of the seabed."""
    if h <= 0.0:
        return 0.0, 0.0, 0.0
    top = 0.0
    for j in range(len(ell)):
        if j > 0 and F[j] > 0.0:  # the foot at the load: phi from 0 to 1
            h0, T0, flex = _column(ell, w, EA, F, j, 0.0, 0.0)
            h1, _, _ = _column(ell, w, EA, F, j, 0.0, 1.0)
            if h <= h1:
                phi = (h - h0) / (h1 - h0) if h1 > h0 else 1.0
                return top, T0 + phi * F[j], 1.0 / max(flex, 1e-300)
        h_end, _, _ = _column(ell, w, EA, F, j, float(ell[j]), 1.0)
        if h <= h_end:
            # the height is increasing and quadratic in the foot's depth ell_j: bisect,
            # then the exact root of that quadratic by one Newton-polished pass
            lo, hi = 0.0, float(ell[j])
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if _column(ell, w, EA, F, j, mid, 1.0)[0] < h:
                    lo = mid
                else:
                    hi = mid
                if hi - lo <= 1e-15 * max(float(ell[j]), 1.0):
                    break
            x = 0.5 * (lo + hi)
            _, W, flex = _column(ell, w, EA, F, j, x, 1.0)
            dh = 1.0 + w[j] * flex
            return top + x, W, float(w[j]) / dh
        top += float(ell[j])
    return None


def slack_forces(problem: StaticProblem) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """A line between its fixed end positions lying slack on the seabed: the forces it
    exerts on its ends A and B [N] (3,) and its end stiffness (2, 2, 3, 3) [N/m]
    (K[i, j] = -d f_i / d r_j, as :func:`.line_stiffness.line_end_stiffness`). None where the
    line is not slack there, or where the slack state is not the one above: no seabed,
    a current, a non-linear axial law, a piece lighter than the fluid or a point load
    that is not straight down."""
    plane = seabed_of(problem.medium)
    line = problem.line
    if (
        plane is None
        or problem.medium.has_current
        or line.is_nonlinear
        or getattr(line, "is_spring", False)
        or problem.end_a.position is None
        or problem.end_b.position is None
    ):
        return None
    lay = make_layout(line)
    if not np.all(lay.weight > 0.0):
        return None
    if np.any(np.abs(lay.point[:, :2]) > 0.0) or np.any(lay.point[:, 2] > 0.0):
        return None
    n = plane.normal
    L = float(lay.bounds[-1])
    ends = (np.asarray(problem.end_a.position, float), np.asarray(problem.end_b.position, float))
    down = -lay.point[:, 2]
    orders = (
        (lay.ell, lay.weight, lay.EA, down),  # from A
        (lay.ell[::-1], lay.weight[::-1], lay.EA[::-1], down[::-1]),  # from B
    )
    S, W, k, feet = [0.0, 0.0], [0.0, 0.0], [0.0, 0.0], []
    for i, r in enumerate(ends):
        above = float(plane.height_above(r))
        if above < -1e-6 * L:
            return None  # below the seabed
        h = max(above, 0.0) / float(n[2])  # straight down to the plane
        feet.append(r - np.array([0.0, 0.0, h]))
        if above <= 1e-6 * L:
            continue
        out = hanging(*orders[i], h)
        if out is None:
            return None
        S[i], W[i], k[i] = out
    laid = L - S[0] - S[1]
    if laid < float(np.linalg.norm(feet[1] - feet[0])):
        return None  # taut: the contact solvers' state
    forces = []
    K = np.zeros((2, 2, 3, 3))
    for i in range(2):
        f = np.array([0.0, 0.0, -W[i]])
        if S[i] > 0.0:
            f += lay.point[0 if i == 0 else -1]
            K[i, i, 2, :] = k[i] * n / float(n[2])  # dW/dh dh/dr
        forces.append(f)
    return forces[0], forces[1], K


def slack_result(
    problem: StaticProblem, force_a: np.ndarray, force_b: np.ndarray, K: np.ndarray
) -> StaticResult:
    """A stand-in result for a slack line in a Newton trial: its end forces, its end
    tensions as the tension samples (the Newton's force scale), no shape (NaN
    positions: never an output, the system's solution is solved again and verified)."""
    L = problem.line.total_length
    ta, tb = float(np.linalg.norm(force_a)), float(np.linalg.norm(force_b))
    return StaticResult(
        s=np.array([0.0, L]),
        position=np.full((2, 3), np.nan),
        tension=np.array([ta, tb]),
        force_a=np.asarray(force_a, dtype=float),
        force_b=np.asarray(force_b, dtype=float),
        laid_length=np.nan,
        message="slack on the seabed (a Newton trial's stand-in)",
    )
