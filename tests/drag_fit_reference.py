"""The single line's drag fit over sampled phases (``drag_linearisation``): the
reference of the compiled fits (:func:`cablestudy.dynamics.harmonic_kernel.drag_fit_samples`,
:mod:`cablestudy.dynamics.system_fd_fit`), which no run of the package calls: the
mean-square (describing-function) fit of :mod:`cablestudy.dynamics.frequency`, phase by
phase, with the planar and still-water closed forms the kernels share."""

from __future__ import annotations

import numpy as np
from numba import njit

from cablestudy.dynamics.elliptic_fit import still_water_means
from cablestudy.dynamics.frequency_model import (
    FIT_REGULARISATION,
    LinearLine,
    drag_tangent,
    is_planar,
    planar_drag_fit,
    still_water,
)

#: the place of entry (a, b) of a symmetric 3 x 3 matrix in its entries 00, 01, 02, 11,
#: 12, 22
_SYM = ((0, 1, 2), (1, 3, 4), (2, 4, 5))


@njit(cache=True)
def _drag_fit(  # noqa: PLR0913
    velocity_re, velocity_im, current, tangent, c_n, c_t, c_b, tangent_d, samples, exact, out
):  # noqa: ANN001, ANN202
    """Kernel of :func:`drag_linearisation` (loops over nodes and phases); with
    ``exact``, a node whose motion, tangent and current lie in the x-z plane takes
    :func:`planar_drag_fit` instead of the phases, unless it carries a body (``c_b``
    (n,): isotropic drag ``c_b |w| w``, whose plane motion is not two scalar ones), and
    any other node without current the exact period means of the fit
    (:func:`.elliptic_fit.still_water_means`) instead of the phase sums."""
    n = current.shape[0]
    cos = np.empty(samples)
    sin = np.empty(samples)
    for k in range(samples):
        cos[k] = np.cos(2.0 * np.pi * k / samples)
        sin[k] = np.sin(2.0 * np.pi * k / samples)
    Gi = np.empty((3, 3))
    w = np.empty((samples, 3))
    f = np.empty((samples, 3))
    G = np.empty((3, 3))
    H = np.empty((3, 3))
    for i in range(n):
        if exact and c_b[i] == 0.0 and is_planar(velocity_re, velocity_im, tangent, current, i):
            planar_drag_fit(velocity_re, velocity_im, tangent, current, c_n, c_t, tangent_d, i, out)
            continue
        if exact and still_water(current, i):
            g, h, _ = still_water_means(
                velocity_re[i, 0],
                velocity_re[i, 1],
                velocity_re[i, 2],
                velocity_im[i, 0],
                velocity_im[i, 1],
                velocity_im[i, 2],
                tangent[i, 0],
                tangent[i, 1],
                tangent[i, 2],
                c_n[i],
                c_t[i],
                c_b[i],
            )
            for a in range(3):
                for b in range(3):
                    G[a, b] = g[_SYM[a][b]]
                    H[a, b] = h[3 * a + b]
            _regularised_fit(G, H, 1, tangent_d, i, Gi, out)
            continue
        fm0 = fm1 = fm2 = 0.0
        for k in range(samples):
            c, s = cos[k], sin[k]
            # Re((a + i b) e^{i th}) = a cos - b sin; the relative velocity is -v
            for a in range(3):
                w[k, a] = -(velocity_re[i, a] * c - velocity_im[i, a] * s)
            r0 = current[i, 0] + w[k, 0]
            r1 = current[i, 1] + w[k, 1]
            r2 = current[i, 2] + w[k, 2]
            t0, t1, t2 = tangent[i, 0], tangent[i, 1], tangent[i, 2]
            wt = r0 * t0 + r1 * t1 + r2 * t2
            n0, n1, n2 = r0 - wt * t0, r1 - wt * t1, r2 - wt * t2
            sn = np.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
            st = abs(wt) * wt * c_t[i]
            sr = c_b[i] * np.sqrt(r0 * r0 + r1 * r1 + r2 * r2)
            f[k, 0] = c_n[i] * sn * n0 + st * t0 + sr * r0
            f[k, 1] = c_n[i] * sn * n1 + st * t1 + sr * r1
            f[k, 2] = c_n[i] * sn * n2 + st * t2 + sr * r2
            fm0 += f[k, 0]
            fm1 += f[k, 1]
            fm2 += f[k, 2]
        fm0 /= samples
        fm1 /= samples
        fm2 /= samples
        for a in range(3):
            for b in range(3):
                G[a, b] = 0.0
                H[a, b] = 0.0
        for k in range(samples):
            f[k, 0] -= fm0
            f[k, 1] -= fm1
            f[k, 2] -= fm2
            for a in range(3):
                for b in range(3):
                    G[a, b] += w[k, a] * w[k, b]
                    H[a, b] += f[k, a] * w[k, b]
        _regularised_fit(G, H, samples, tangent_d, i, Gi, out)


@njit(cache=True, inline="always")
def _regularised_fit(G, H, count, tangent_d, i, Gi, out):  # noqa: ANN001, ANN202, PLR0913
    """``out[i] = (H + eps D_0)(G + eps I)^-1`` of :func:`_drag_fit` from the sums ``G``
    of ``w w^T`` and ``H`` of ``(f - f_mean) w^T`` (3, 3) over ``count`` phases (1: the
    means themselves), ``D_0 = tangent_d[i]``, ``eps`` :data:`FIT_REGULARISATION` times
    the trace of the mean of ``G``; ``D_0`` for a node at rest. ``G`` and ``H`` are
    overwritten, ``Gi`` (3, 3) is work."""
    trace = (G[0, 0] + G[1, 1] + G[2, 2]) / count
    if not trace > 0.0:  # a node at rest: the small-motion tangent
        for a in range(3):
            for b in range(3):
                out[i, a, b] = tangent_d[i, a, b]
        return
    eps = FIT_REGULARISATION * trace
    for a in range(3):
        for b in range(3):
            G[a, b] = G[a, b] / count
            H[a, b] = H[a, b] / count + eps * tangent_d[i, a, b]
        G[a, a] += eps
    # D G = H  ->  D = H G^-1 (G symmetric positive definite; cofactors)
    Gi[0, 0] = G[1, 1] * G[2, 2] - G[1, 2] * G[2, 1]
    Gi[0, 1] = G[0, 2] * G[2, 1] - G[0, 1] * G[2, 2]
    Gi[0, 2] = G[0, 1] * G[1, 2] - G[0, 2] * G[1, 1]
    Gi[1, 0] = G[1, 2] * G[2, 0] - G[1, 0] * G[2, 2]
    Gi[1, 1] = G[0, 0] * G[2, 2] - G[0, 2] * G[2, 0]
    Gi[1, 2] = G[0, 2] * G[1, 0] - G[0, 0] * G[1, 2]
    Gi[2, 0] = G[1, 0] * G[2, 1] - G[1, 1] * G[2, 0]
    Gi[2, 1] = G[0, 1] * G[2, 0] - G[0, 0] * G[2, 1]
    Gi[2, 2] = G[0, 0] * G[1, 1] - G[0, 1] * G[1, 0]
    det = G[0, 0] * Gi[0, 0] + G[0, 1] * Gi[1, 0] + G[0, 2] * Gi[2, 0]
    for a in range(3):
        for b in range(3):
            Gi[a, b] /= det
    for a in range(3):
        for b in range(3):
            acc = 0.0
            for c2 in range(3):
                acc += H[a, c2] * Gi[c2, b]
            out[i, a, b] = acc


def drag_linearisation(
    line: LinearLine,
    velocity: np.ndarray,
    samples: int = 32,
    tangent: np.ndarray | None = None,
    exact: bool = False,
) -> np.ndarray:
    """Equivalent drag damping [N s/m] (n, 3, 3) for nodal velocity amplitudes
    ``velocity`` [m/s] (n, 3) complex: the mean-square (describing-function) fit of the
    module docstring, over ``samples`` phases (with ``exact``, a node moving in the x-z
    plane in closed form, :func:`planar_drag_fit`, and any other node without current
    by its exact period means, :func:`.elliptic_fit.still_water_means`); ``tangent`` is
    :func:`drag_tangent` (computed when not given)."""
    D0 = drag_tangent(line) if tangent is None else tangent
    out = np.empty((line.n_nodes, 3, 3))
    _drag_fit(
        np.ascontiguousarray(velocity.real),
        np.ascontiguousarray(velocity.imag),
        line.current,
        line.tangent,
        line.drag_normal,
        line.drag_tangential,
        line.body_drag,
        D0,
        samples,
        exact,
        out,
    )
    return out
