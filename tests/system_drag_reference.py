"""The drag of a system's frequency domain, linearised over the motion: each line node's
normal, tangential and transverse drag Jacobian averaged over the phases of its harmonic
velocity (the fit's fallback where the motion is thin), and a free point's isotropic drag
fitted as its describing function, in NumPy: the test oracle of the compiled fit
(:mod:`cablestudy.dynamics.system_fd_fit`), used by the reference iteration
(:mod:`tests.system_frequency_reference`)."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from cablestudy.dynamics.frequency_model import FIT_REGULARISATION, DragSettings, LinearLine
from tests.drag_fit_reference import drag_linearisation

#: phases of the oracle's still-water means (:func:`node_fits`): the trapezoid rule on
#: a period. The fit's sums are analytic in the phase but for the kinks of ``|w_T| w_T``
#: (and of ``|w_N| w_N`` on a line), whose aliasing falls as ``DENSE^-3`` (1e-11 of the
#: fit here); the mean Jacobian's kinks (``|w_T|``) leave ``DENSE^-2``, which one
#: Richardson step with ``2 DENSE`` phases removes (the aliased coefficients of ``|cos|``
#: are ``4 / (pi (n^2 - 1))``: an expansion in ``1 / N^2``, next term ``N^-4``)
DENSE = 4096


def mean_drag_jacobian(line: LinearLine, velocity: np.ndarray, samples: int) -> np.ndarray:
    """The drag's Jacobian ``d f / d w`` [N s/m] (n, 3, 3) averaged over ``samples``
    phases of the nodes' motion (complex velocity amplitudes ``velocity`` (n, 3)):
    ``c_N (|w_N| P + w_N w_N^T / |w_N|) + 2 c_T |w_T| t t^T + c_B (|w| I + w w^T / |w|)``
    at ``w = U - Re(v e^{i th})``. What the drag fit leans towards in directions in
    which a node hardly moves (:data:`~.frequency.FIT_REGULARISATION`): there it is the
    damping a small motion across the node's own motion feels (``c_N 2 a / pi`` across a
    one-dimensional oscillation of amplitude ``a`` in still water), the limit of the
    fit as the motion in that direction vanishes; at rest it is the tangent at the
    mean flow (:func:`~.frequency.drag_tangent`). Leaning towards the latter instead
    (zero in still water) makes the fit jump between the two as a node's motion turns
    from nearly straight to straight, and the iteration of a system in three
    dimensions then wanders (case8 under surge above 0.2 Hz: no convergence in 100
    iterations; with this lean, 6 to 20)."""
    out = np.empty((line.n_nodes, 3, 3))
    _mean_jacobian(
        np.ascontiguousarray(velocity.real),
        np.ascontiguousarray(velocity.imag),
        line.current,
        line.tangent,
        line.drag_normal,
        line.drag_tangential,
        line.body_drag,
        samples,
        out,
    )
    return out


@njit(cache=True)
def _mean_jacobian(vr, vi, current, tangent, c_n, c_t, c_b, samples, out):  # noqa: ANN001, ANN202, PLR0913
    """Kernel of :func:`mean_drag_jacobian` (loops over nodes and phases). The phase
    sums are taken once per node, ``sum |w_N|``, ``sum w_N w_N^T / |w_N|`` (and the
    same of ``w`` where a lumped body drags), and the projector applied after: the
    same terms as the per-phase Jacobians summed, one product per phase fewer than
    nine, and the phases' cosines and sines computed once per call."""
    n = current.shape[0]
    cs = np.empty(samples)
    sn_ = np.empty(samples)
    for k in range(samples):
        cs[k] = math.cos(2.0 * math.pi * k / samples)
        sn_[k] = math.sin(2.0 * math.pi * k / samples)
    w = np.empty(3)
    wn = np.empty(3)
    Wn = np.empty((3, 3))
    Wb = np.empty((3, 3))
    for i in range(n):
        t0, t1, t2 = tangent[i, 0], tangent[i, 1], tangent[i, 2]
        t = (t0, t1, t2)
        body = c_b[i] != 0.0
        Wn[:, :] = 0.0
        Wb[:, :] = 0.0
        sum_n = 0.0
        sum_r = 0.0
        abs_t = 0.0
        for k in range(samples):
            c = cs[k]
            s = sn_[k]
            for a in range(3):
                w[a] = current[i, a] - (vr[i, a] * c - vi[i, a] * s)
            wt = w[0] * t0 + w[1] * t1 + w[2] * t2
            abs_t += abs(wt)
            for a in range(3):
                wn[a] = w[a] - wt * t[a]
            sn = math.sqrt(wn[0] * wn[0] + wn[1] * wn[1] + wn[2] * wn[2])
            sum_n += sn
            if sn > 0.0:
                for a in range(3):
                    for b in range(a, 3):
                        Wn[a, b] += wn[a] * wn[b] / sn
            if body:
                sr = math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
                sum_r += sr
                if sr > 0.0:
                    for a in range(3):
                        for b in range(a, 3):
                            Wb[a, b] += w[a] * w[b] / sr
        along = c_t[i] * 2.0 * (abs_t / samples)
        for a in range(3):
            for b in range(a, 3):
                eye = 1.0 if a == b else 0.0
                jn = sum_n * (eye - t[a] * t[b]) + Wn[a, b]
                jb = sum_r * eye + Wb[a, b]
                v = (c_n[i] * jn + c_b[i] * jb) / samples + along * t[a] * t[b]
                out[i, a, b] = v
                out[i, b, a] = v


def point_fits(
    c: np.ndarray, current: np.ndarray, velocity: np.ndarray, settings: DragSettings
) -> np.ndarray:
    """:func:`point_drag_fit` as the compiled
    :func:`~cablestudy.dynamics.system_fd_fit.fit_points` defines it: over
    ``settings.samples`` phases, except with ``settings.exact`` at a point without
    current, where the fit is that of the exact period means, here by dense quadrature
    (:data:`DENSE` phases: ``|w| w`` is analytic in the phase but on a line, whose kink
    leaves ``DENSE^-3``)."""
    fit = point_drag_fit(c, current, velocity, settings.samples)
    still = np.all(current == 0.0, axis=1)
    if settings.exact and np.any(still):
        fit[still] = point_drag_fit(c, current, velocity, DENSE)[still]
    return fit


def point_drag_fit(
    c: np.ndarray, current: np.ndarray, velocity: np.ndarray, samples: int
) -> np.ndarray:
    """Equivalent drag damping [N s/m] (P, 3, 3) of isotropic drag ``c |w| w`` at points
    moving with complex velocity amplitudes ``velocity`` (P, 3) in the current
    ``current`` (P, 3): the mean-square fit over ``samples`` phases, ``D = <f' w'^T>
    <w' w'^T>^-1``, leaning towards the small-motion tangent ``c (|U| I + U U^T / |U|)``
    in directions without motion (:data:`~.frequency.FIT_REGULARISATION`)."""
    th = 2.0 * np.pi * np.arange(samples) / samples
    w = -(
        velocity.real[None] * np.cos(th)[:, None, None]
        - velocity.imag[None] * np.sin(th)[:, None, None]
    )
    r = current[None] + w
    f = c[None, :, None] * np.linalg.norm(r, axis=2)[..., None] * r
    f = f - f.mean(axis=0)
    G = np.einsum("kpa,kpb->pab", w, w) / samples
    H = np.einsum("kpa,kpb->pab", f, w) / samples
    su = np.linalg.norm(current, axis=1)
    inv = np.where(su > 0.0, 1.0 / np.where(su > 0.0, su, 1.0), 0.0)
    D0 = c[:, None, None] * (
        su[:, None, None] * np.eye(3)
        + inv[:, None, None] * (current[:, :, None] * current[:, None, :])
    )
    trace = np.trace(G, axis1=1, axis2=2)
    eps = np.where(trace > 0.0, FIT_REGULARISATION * trace, 1.0)[:, None, None]
    lhs = G + eps * np.eye(3)
    rhs = np.where((trace > 0.0)[:, None, None], H + eps * D0, D0)
    # D lhs = rhs -> lhs^T D^T = rhs^T (lhs symmetric)
    return np.swapaxes(np.linalg.solve(lhs, np.swapaxes(rhs, 1, 2)), 1, 2)


def node_fits(
    line: LinearLine, velocity: np.ndarray, settings: DragSettings
) -> tuple[np.ndarray, np.ndarray]:
    """The lean (:func:`mean_drag_jacobian`) and the drag fit leaning on it
    (:func:`~cablestudy.dynamics.frequency_model.drag_linearisation`) of every node of
    ``line`` at the velocity amplitudes ``velocity`` (n, 3), as the compiled
    :func:`~cablestudy.dynamics.system_fd_fit.fit_node` defines them: over
    ``settings.samples`` phases, except with ``settings.exact`` at a node without
    current, where both are the exact period means, here by dense quadrature
    (:data:`DENSE` phases; the lean Richardson-extrapolated from ``DENSE`` and ``2
    DENSE``), independent of the compiled closed form
    (:mod:`cablestudy.dynamics.elliptic_fit`); a node there whose motion and tangent lie
    in the x-z plane (no body) takes the planar closed form with that lean."""
    lean = mean_drag_jacobian(line, velocity, settings.samples)
    still = np.all(line.current == 0.0, axis=1)
    if not (settings.exact and np.any(still)):
        return lean, drag_linearisation(line, velocity, settings.samples, lean, settings.exact)
    coarse = mean_drag_jacobian(line, velocity, DENSE)
    fine = mean_drag_jacobian(line, velocity, 2 * DENSE)
    lean[still] = ((4.0 * fine - coarse) / 3.0)[still]
    planar = (
        (velocity.real[:, 1] == 0.0)
        & (velocity.imag[:, 1] == 0.0)
        & (line.tangent[:, 1] == 0.0)
        & (line.current[:, 1] == 0.0)
        & (line.body_drag == 0.0)
    )
    fit = drag_linearisation(line, velocity, settings.samples, lean, True)
    dense = drag_linearisation(line, velocity, DENSE, lean, False)
    use_dense = still & ~planar
    fit[use_dense] = dense[use_dense]
    return lean, fit
