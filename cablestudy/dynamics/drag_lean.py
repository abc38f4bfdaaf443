"""The lean of the single line's drag fit (:func:`.harmonic_kernel.drag_fit_samples`):
the drag's Jacobian ``J = <df/dw>`` averaged over the node's motion,

    J = c_N (<|w_N|> (I - t t^T) + <w_N w_N^T / |w_N|>) + 2 c_T <|w_T|> t t^T
        + c_B (<|w|> I + <w w^T / |w|>)

at the relative velocity ``w = U - Re(v e^{i th})`` (normal part ``w_N``, tangential
``w_T``), the damping a small motion across the node's own motion feels. The fit ``D G
= H`` determines ``D`` only in the directions the node moves in; in the others (``G``
singular or nearly so: a node swinging along a line or a thin ellipse, as most nodes of
a line driven by one end do) it takes its lean. The small-motion tangent at the mean
flow (:func:`.frequency_model.drag_tangent`) is zero in still water and ``c |U|`` in a
weak current, far below the damping the moving node gives a motion across it; leaning
on it, the fit of a 3-D line's node jumped between the two as its motion turned from
nearly straight to straight, and the drag iteration circled without settling (one
case in five of a frequency x amplitude x direction sweep of a laid or hanging line
out of the x-z plane, still water or current, at the 100-iteration limit). The mean
Jacobian is what the system's fit leans on (:mod:`.system_fd_fit`,
``tests/system_drag_reference.mean_drag_jacobian``); with it every such case settles.

Pure: arrays in, the lean written into ``lean[i]``; compiled with numba and inlined.
"""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True, inline="always")
def lean_from_entries(j, lean, i):  # noqa: ANN001, ANN201
    """``lean[i]`` (n, 3, 3) the symmetric matrix of the entries ``j`` (00, 01, 02, 11,
    12, 22): the mean Jacobian of :func:`.elliptic_fit.still_water_means`, exact."""
    lean[i, 0, 0] = j[0]
    lean[i, 0, 1] = j[1]
    lean[i, 0, 2] = j[2]
    lean[i, 1, 0] = j[1]
    lean[i, 1, 1] = j[3]
    lean[i, 1, 2] = j[4]
    lean[i, 2, 0] = j[2]
    lean[i, 2, 1] = j[4]
    lean[i, 2, 2] = j[5]


@njit(cache=True, inline="always")
def sampled_lean(W0, W1, W2, planar, current, tangent, c_n, c_t, c_b, i, lean):  # noqa: ANN001, ANN201, PLR0913
    """``lean[i]`` the mean Jacobian (module docstring) of node ``i`` over the phases of
    its relative velocity's motion part ``W0``, ``W1``, ``W2`` (n, samples; ``w = U +
    W``; ``planar``: the node moves in the x-z plane, its ``W1`` unset and taken as
    zero): the sums ``<|w_N|>``, ``<w_N w_N^T / |w_N|>`` (a phase at ``w_N = 0`` adds
    nothing to the second: the limit of a motion that stops there), ``<|w_T|>`` and the
    body's, the projector applied after."""
    samples = W0.shape[1]
    t0, t1, t2 = tangent[i, 0], tangent[i, 1], tangent[i, 2]
    u0, u1, u2 = current[i, 0], current[i, 1], current[i, 2]
    cn, ct, cb = c_n[i], c_t[i], c_b[i]
    sum_n = sum_r = abs_t = 0.0
    n00 = n01 = n02 = n11 = n12 = n22 = 0.0
    q00 = q01 = q02 = q11 = q12 = q22 = 0.0
    for k in range(samples):
        r0, r2 = u0 + W0[i, k], u2 + W2[i, k]
        r1 = u1 if planar else u1 + W1[i, k]
        wt = r0 * t0 + r1 * t1 + r2 * t2
        x0, x1, x2 = r0 - wt * t0, r1 - wt * t1, r2 - wt * t2
        sn = math.sqrt(x0 * x0 + x1 * x1 + x2 * x2)
        abs_t += abs(wt)
        sum_n += sn
        if sn > 0.0:
            inv = 1.0 / sn
            n00 += x0 * x0 * inv
            n01 += x0 * x1 * inv
            n02 += x0 * x2 * inv
            n11 += x1 * x1 * inv
            n12 += x1 * x2 * inv
            n22 += x2 * x2 * inv
        if cb != 0.0:
            rr = math.sqrt(r0 * r0 + r1 * r1 + r2 * r2)
            sum_r += rr
            if rr > 0.0:
                inv = 1.0 / rr
                q00 += r0 * r0 * inv
                q01 += r0 * r1 * inv
                q02 += r0 * r2 * inv
                q11 += r1 * r1 * inv
                q12 += r1 * r2 * inv
                q22 += r2 * r2 * inv
    wn = ((n00, n01, n02), (n01, n11, n12), (n02, n12, n22))
    wb = ((q00, q01, q02), (q01, q11, q12), (q02, q12, q22))
    lean_from_sums(sum_n, sum_r, abs_t, wn, wb, (t0, t1, t2), cn, ct, cb, samples, lean, i)


@njit(cache=True, inline="always")
def lean_from_sums(sum_n, sum_r, abs_t, wn, wb, t, cn, ct, cb, samples, lean, i):  # noqa: ANN001, ANN201, PLR0913
    """``lean[i]`` the mean Jacobian (module docstring) ``c_N (sum |w_N| (I - t t^T) +
    sum w_N w_N^T / |w_N|) + c_B (sum |w| I + sum w w^T / |w|)`` over ``samples`` phases,
    plus ``2 c_T <|w_T|> t t^T``, from the sums ``sum_n`` (of ``|w_N|``), ``sum_r`` (of
    ``|w|``), ``abs_t`` (of ``|w_T|``) and the symmetric 3 x 3 tuples ``wn``, ``wb``
    (of ``w_N w_N^T / |w_N|``, ``w w^T / |w|``); ``t`` the tangent. Shared by
    :func:`sampled_lean` and the system's :func:`.system_fd_fit.fit_node` (inlined: the
    caller's floating-point flags)."""
    along = ct * 2.0 * (abs_t / samples)
    for a in range(3):
        for b in range(a, 3):
            eye = 1.0 if a == b else 0.0
            jn = sum_n * (eye - t[a] * t[b]) + wn[a][b]
            jb = sum_r * eye + wb[a][b]
            v = (cn * jn + cb * jb) / samples + along * t[a] * t[b]
            lean[i, a, b] = v
            lean[i, b, a] = v
