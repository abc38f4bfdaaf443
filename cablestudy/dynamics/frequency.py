"""Frequency-domain response of a line linearised about its static shape.

Input is a :class:`LinearLine`: lumped mass blocks (fluid added mass included), the
tangent stiffness (elastic + geometric, and bending), structural damping, per-element
data for the tension output, per-node drag data, and the split of the degrees of
freedom into free directions (columns of ``free_basis``) and prescribed ones (the
end nodes, moved by the excitation or held; other directions that are not free,
e.g. nodes held by the seabed, stay at rest). Any line model that can produce these
arrays can use this solver (today: :func:`cablestudy.dynamics.linear_model.linear_line`).

Harmonic motion. Every quantity is ``q(t) = Re(Q exp(i w t))``. The end motion ``X``
(complex, per end) is given; the free displacements solve

    B^T [K - w^2 M + i w (C + D)] B q = -B^T [K - w^2 M + i w (C + D)] u_p,
    u = B q + u_p,

where ``B`` is the free basis, ``u_p`` holds the prescribed end displacements and
``D`` is the drag damping (below). The element tension varies by

    dT_e = (EA_e / l0_e + i w c_e / l0_e) t_e . (u_{e+1} - u_e),

the first-order change of ``T = EA (l / l0 - 1) + c dl/dt / l0`` (``dl = t . du`` to
first order); the same element law gives the stiffness ``(EA / l0) t t^T + (T / l) P``
used in ``K``, so the tension output and the stiffness are consistent: ``d(T t) =
dT t + T dt`` with ``dt = P du / l``. The force of the line on an end support is
``-(A u)_j`` at the end node ``j`` (``A`` the dynamic stiffness above: the support
reaction balances the element forces, the drag and the inertia of the end node's
mass, as in the time domain), and the end tension varies by ``F_hat . dF``
(``F_hat`` the unit static end force); its second-order part is neglected.

Drag linearisation (equivalent, describing function). The Morison drag on node
``i`` (the law of :mod:`cablestudy.physics.hydro`, lumped over the node's
tributary length)

    f(w) = c_N |w_N| w_N + c_T |w_T| w_T,    w = U_c - v (relative velocity),

is replaced by ``f_bar + D_i (w - U_c)``, with ``D_i`` the 3 x 3 matrix that
minimises the mean square error over a period of the computed motion: with ``w'``
the oscillating part of the relative velocity and ``f'`` that of the drag,
``D = <f' w'^T> <w' w'^T>^-1`` (averages over ``samples`` equally spaced phases). For
harmonic ``w'`` this is the first-harmonic (describing-function) fit, and it
dissipates exactly the mean power of the nonlinear drag, ``<f' . w'> = <(D w') . w'>``
(energy equivalence). In still water and one-dimensional motion of velocity
amplitude ``a`` it is the classical ``c 8 a / (3 pi)``.

With a current ``U`` (component ``U_N`` normal to the line, say, and one-dimensional
oscillation of amplitude ``a`` along it) ``|U + a cos(th)| (U + a cos(th))`` has no
sign change when ``|U| >= a``, so it is the polynomial ``sgn(U)(U^2 + 2 U a cos(th) +
a^2 cos^2(th))``: its first harmonic is exactly ``2 |U| a cos(th)``, i.e. ``D = 2 c |U|``,
the tangent at the mean flow (the linear term); the quadratic term only adds a mean
force ``c a^2 / 2`` (a second-order drift, which the linear model leaves out, as it
leaves out the mean drift of any nonlinearity) and the second harmonic. For ``|U| <
a`` the fit falls between ``2 c |U|`` and ``c 8 a / (3 pi)``; for motion across a
current in 2 or 3 dimensions the same fit gives the matrix ``c (|U| I + U U^T / |U|)``
on the normal plane in the limit ``a << |U|``. Directions in which a node does not
move (``<w' w'^T>`` singular there) take the drag's Jacobian averaged over the node's
motion (the damping a small motion across it feels; the small-motion tangent at rest),
and directions in which it hardly moves lean towards it (:data:`FIT_REGULARISATION`,
:mod:`.drag_lean`).

A node whose motion, tangent and current lie in the x-z plane (every node of a line
hanging in that plane and moved in it) has scalar normal and tangential relative
velocities, each a mean plus one harmonic, and the fit is then done in closed form
(:func:`harmonic_gain`, :func:`planar_drag_fit`): exact, where 32 phases alias the
odd harmonics of ``|x| x`` into the fit at about 1e-4 of it, and cheaper. Any other
node without current is fitted by the exact period means of the sums, in closed form
for motion in any direction (:mod:`.elliptic_fit`: complete elliptic integrals of the
normal velocity's ellipse). The phases serve the nodes in a current, and every node
when a study sets ``samples``.

Since ``D`` depends on the motion, the solve is iterated: start from the quasi-static
motion (the end motion spread linearly along the line), compute ``D``, solve, and
repeat (compiled, in :mod:`cablestudy.dynamics.harmonic_cases`), with Anderson
acceleration of depth one on the fixed point ``D = G(D)`` (near a resonance the plain
map behaves like ``a -> c / a`` and oscillates; the secant step removes that), until
the nodal velocities change by less than ``tolerance`` of their largest amplitude.

Pure: arrays in, a :class:`FrequencyResult` out (status, message, counters).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import solve_banded

from ..statics.base import STATUS_NUMERICAL, STATUS_OK
from .frequency_model import (
    DragSettings,
    FrequencyResult,
    LinearLine,
    ReducedLine,
    drag_force,
    drag_tangent,
    singular_result,
    solve_undamped,
)


def solve_harmonic(
    red: ReducedLine,
    omega: float,
    end_motion: np.ndarray,
    settings: DragSettings | None = None,
) -> FrequencyResult:
    """Steady harmonic response at angular frequency ``omega`` [rad/s] to the end
    displacements ``end_motion`` [m] (2, 3) complex (A and B), with the drag
    linearised by iteration (module docstring). Never raises for a numerical failure."""
    settings = settings or DragSettings()
    line = red.line
    n = line.n_nodes
    static_mag = np.linalg.norm(line.end_force, axis=1)
    failed = singular_result(n, static_mag, omega)
    if line.has_drag:
        # the drag iteration is that of a sweep's cases (one compiled kernel), so a
        # case gives the same numbers alone or in a sweep
        from .harmonic_cases import solve_harmonic_cases

        one = solve_harmonic_cases(
            red, np.array([float(omega)]), np.asarray(end_motion, dtype=complex)[None], settings
        )
        if not one.ok[0]:
            return failed
        return FrequencyResult(
            displacement=one.displacement[0],
            element_tension=one.element_tension[0],
            end_tension=one.end_tension[0],
            tension_static=static_mag,
            drag_iterations=int(one.iterations[0]),
            drag_converged=bool(one.converged[0]),
            drag_change=float(one.change[0]),
            status=STATUS_OK,
            message="",
        )
    return solve_undamped(red, omega, end_motion)


# ------------------------------------------------------------------ irregular motion


def _gauss_hermite(m: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes (m^3, 3) and weights (m^3,) of the tensor Gauss-Hermite rule for the
    standard normal distribution in three dimensions."""
    x, w = np.polynomial.hermite_e.hermegauss(m)
    w = w / w.sum()
    X = np.stack(np.meshgrid(x, x, x, indexing="ij"), -1).reshape(-1, 3)
    W = np.prod(np.stack(np.meshgrid(w, w, w, indexing="ij"), -1).reshape(-1, 3), axis=1)
    return X, W


def drag_stochastic(
    line: LinearLine, covariance: np.ndarray, tangent: np.ndarray, points: int = 6
) -> np.ndarray:
    """Statistically linearised drag damping [N s/m] (n, 3, 3) for a Gaussian relative
    velocity of mean the current and covariance ``covariance`` [m^2/s^2] (n, 3, 3):
    ``D = E[df/dw] = E[f (w - U) ^T] C^-1`` (Stein's lemma: the mean-square optimal
    linear fit, as the harmonic fit is for a sine), by tensor Gauss-Hermite quadrature
    with ``points`` nodes per direction. Directions without motion take the
    small-motion tangent ``tangent`` (:func:`drag_tangent`)."""
    X, W = _gauss_hermite(points)
    lam, Q = np.linalg.eigh(covariance)
    L = Q * np.sqrt(np.clip(lam, 0.0, None))[:, None, :]  # (n, 3, 3): C = L L^T
    dev = np.einsum("iab,kb->kia", L, X)  # (m^3, n, 3)
    f = drag_force(line, line.current[None] + dev)
    H = np.einsum("k,kia,kib->iab", W, f, dev)
    trace = np.trace(covariance, axis1=1, axis2=2)
    eps = np.where(trace > 0.0, 1e-10 * trace, 1.0)[:, None, None]
    lhs = covariance + eps * np.eye(3)
    rhs = np.where((trace > 0.0)[:, None, None], H + eps * tangent, tangent)
    return np.swapaxes(np.linalg.solve(lhs, np.swapaxes(rhs, 1, 2)), 1, 2)


@dataclass(kw_only=True)
class SpectrumResult:
    """Response to an end-motion spectrum: per spectral line (K,) the complex
    amplitudes of the end tensions (K, 2) [N] and element tensions (K, n - 1) [N], and
    of the nodes' displacements (K, n, 3) [m] (NaN on failure); tension_static (2,) [N];
    iterations, converged, change; status, message."""

    end_tension: np.ndarray
    element_tension: np.ndarray
    tension_static: np.ndarray
    displacement: np.ndarray
    iterations: int = 0
    converged: bool = True
    change: float = 0.0
    status: int = STATUS_OK
    message: str = ""


def solve_spectrum(
    red: ReducedLine,
    omegas: np.ndarray,
    end_motion: np.ndarray,
    settings: DragSettings | None = None,
) -> SpectrumResult:
    """Linear response to end motion given as spectral lines: angular frequencies
    ``omegas`` [rad/s] (K,), end displacement amplitudes ``end_motion`` [m] (K, 2, 3)
    (the lines are independent, random-phase: variances add). The drag is linearised
    statistically on the covariance of the relative velocity summed over the lines,
    ``C = sum_k Re(v_k v_k^H) / 2``, and iterated to consistency as in
    :func:`solve_harmonic`."""
    settings = settings or DragSettings()
    line = red.line
    n = line.n_nodes
    B = line.free_basis
    BT = B.T.tocsr()
    bw = red.bandwidth
    K = omegas.size
    static_mag = np.linalg.norm(line.end_force, axis=1)

    def solve_all(D: np.ndarray | None) -> np.ndarray | None:
        U = np.empty((K, n, 3), dtype=complex)
        band = None if D is None else red.drag_band(D)
        for k, w in enumerate(omegas):
            up = np.zeros((n, 3), dtype=complex)
            up[0], up[-1] = end_motion[k, 0], end_motion[k, 1]
            ab = red.K - w**2 * red.M + 1j * w * red.C
            if band is not None:
                ab = ab + 1j * w * band
            rhs = -(BT @ red.apply(up, w, D).ravel())
            if rhs.size == 0:
                U[k] = up
                continue
            try:
                q = solve_banded((bw, bw), ab, rhs, check_finite=False)
            except (np.linalg.LinAlgError, ValueError):
                return None
            if not np.all(np.isfinite(q)):
                return None
            U[k] = (B @ q).reshape(n, 3) + up
        return U

    def covariance(U: np.ndarray) -> np.ndarray:
        V = 1j * omegas[:, None, None] * U
        return 0.5 * np.real(np.einsum("kia,kib->iab", V, V.conj()))

    D: np.ndarray | None = None
    iterations, converged, change = 0, True, 0.0
    if line.has_drag:
        frac = (line.s / line.s[-1])[None, :, None]
        U = (1.0 - frac) * end_motion[:, 0:1, :] + frac * end_motion[:, 1:2, :]
        D_small = drag_tangent(line)
        D = drag_stochastic(line, covariance(U), D_small)
        sigma = np.sqrt(np.einsum("iaa->i", covariance(U)))
        converged = False
        last = math.inf
        for iterations in range(1, settings.max_iterations + 1):  # noqa: B007
            U_new = solve_all(D)
            if U_new is None:
                break
            C = covariance(U_new)
            sigma_new = np.sqrt(np.einsum("iaa->i", C))
            change = float(np.max(np.abs(sigma_new - sigma)) / max(np.max(sigma_new), 1e-300))
            U, sigma = U_new, sigma_new
            if change <= settings.tolerance:
                converged = True
                break
            relax = 0.5 if change >= 0.5 * last else 1.0
            last = change
            D = (1.0 - relax) * D + relax * drag_stochastic(line, C, D_small)
    else:
        U = solve_all(None)  # type: ignore[assignment]
    if U is None or (line.has_drag and iterations and not np.all(np.isfinite(U))):
        return SpectrumResult(
            end_tension=np.full((K, 2), np.nan + 0j),
            element_tension=np.full((K, n - 1), np.nan + 0j),
            tension_static=static_mag,
            displacement=np.full((K, n, 3), np.nan + 0j),
            status=STATUS_NUMERICAL,
            message="singular dynamic matrix at a spectral line",
        )
    du = np.diff(U, axis=1)
    axial = (line.axial_stiffness[None] + 1j * omegas[:, None] * line.axial_damping[None]) / (
        line.rest_length[None]
    )
    element = axial * np.einsum("ea,kea->ke", line.direction, du)
    unit = line.end_force / np.where(static_mag > 0.0, static_mag, 1.0)[:, None]
    ends = np.empty((K, 2), dtype=complex)
    for k, w in enumerate(omegas):
        r = red.apply(U[k], w, D)
        ends[k, 0] = -unit[0] @ r[0]
        ends[k, 1] = -unit[1] @ r[-1]
    return SpectrumResult(
        end_tension=ends,
        element_tension=element,
        tension_static=static_mag,
        displacement=U,
        iterations=iterations,
        converged=converged,
        change=change,
    )
