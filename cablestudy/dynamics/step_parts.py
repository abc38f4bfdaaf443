"""Small compiled pieces of the Newton iterations and time steps that the single line
(:mod:`.alpha_step`, :mod:`.integrator`, :mod:`.model`) and the system
(:mod:`.system_march`) share: each the same operations in the same order as both had
written out before, with no floating-point flags (as every caller: none of them takes
fast-math), so that the answers are the same bit for bit.

Pure: arrays in, arrays out.
"""

from __future__ import annotations

from numba import njit


@njit(cache=True)
def largest_correction(dx, n):  # noqa: ANN001, ANN201
    """The largest ``|dx[i, c]|`` of the first ``n`` nodes (0 for none; NaN is passed
    over by ``max``, so a caller tests the correction's finiteness on its own terms)."""
    big = 0.0
    for i in range(n):
        for c in range(3):
            big = max(big, abs(dx[i, c]))
    return big


@njit(cache=True)
def newmark_correct(x1, v1, a1, dx, held, n, scale, beta, gamma, h):  # noqa: ANN001, ANN201, PLR0913
    """Apply the Newton correction ``scale dx`` to the positions of the free nodes of
    the first ``n`` and the Newmark velocity and acceleration that follow from it
    (``da = d / (beta h^2)``, ``dv = gamma d / (beta h)``)."""
    for i in range(n):
        if held[i]:
            continue
        for c in range(3):
            d = scale * dx[i, c]
            x1[i, c] += d
            a1[i, c] += d / (beta * h * h)
            v1[i, c] += gamma * d / (beta * h)


@njit(cache=True)
def slack_regularisation(tension, reg, lmin):  # noqa: ANN001, ANN201
    """The statics' mass-like regularisation of an iteration: ``reg`` at most, kept
    well below the geometric stiffness ``T / l`` of the taut elements (1e-6 of the
    largest ``tension`` over the shortest element ``lmin``, and not below 1e-6 of
    ``reg``), or a light line's soft modes would converge only linearly."""
    tmax = 0.0
    for e in range(tension.shape[0]):
        tmax = max(tmax, tension[e])
    return min(reg, max(1e-6 * tmax / lmin, 1e-6 * reg))


@njit(cache=True)
def quarter_element_scale(big, lmin):  # noqa: ANN001, ANN201
    """The statics' step limit: the factor that cuts a correction of largest component
    ``big`` to a quarter of the shortest element ``lmin`` (1 when it is within)."""
    scale = 1.0
    if big > 0.25 * lmin:
        scale = 0.25 * lmin / big
    return scale


@njit(cache=True)
def predict_positions(x0, v0, past_x, past_t, npast, t, tn, x_pred):  # noqa: ANN001, ANN201, PLR0913
    """Newton's start ``x_pred`` at the step's end ``tn`` from the start ``x0`` at
    ``t``: the quadratic through the two kept positions (``past_x`` at ``past_t``) and
    ``x0``, or a straight step with velocity ``v0`` while fewer than two are kept
    (``npast``). Returns the quadratic's Lagrange weights of the three (zeros for the
    straight step)."""
    n = x0.shape[0]
    la = lb = lc = 0.0
    if npast < 2:
        for i in range(n):
            for c in range(3):
                x_pred[i, c] = x0[i, c] + (tn - t) * v0[i, c]
    else:
        ta, tb, tc = past_t[0], past_t[1], t
        la = (tn - tb) * (tn - tc) / ((ta - tb) * (ta - tc))
        lb = (tn - ta) * (tn - tc) / ((tb - ta) * (tb - tc))
        lc = (tn - ta) * (tn - tb) / ((tc - ta) * (tc - tb))
        for i in range(n):
            for c in range(3):
                x_pred[i, c] = past_x[0, i, c] * la + lb * past_x[1, i, c] + lc * x0[i, c]
    return la, lb, lc


@njit(cache=True)
def accept_state(x0, v0, a0, F0, x1, v1, a1, F, ext_z, t, past_x, past_t, npast, st_i):  # noqa: ANN001, ANN201, PLR0913
    """An accepted step's bookkeeping: the start state ``x0`` at time ``t`` joins the
    last two kept (``past_x``, ``past_t``, ``npast`` of them so far, the count into
    ``st_i[5]``), the end state (``x1, v1, a1``, force ``F``) becomes the next start,
    and ``ext_z`` keeps each node's highest ``z``."""
    n = x0.shape[0]
    if npast < 2:
        for i in range(n):
            for c in range(3):
                past_x[npast, i, c] = x0[i, c]
        past_t[npast] = t
        st_i[5] = npast + 1
    else:
        for i in range(n):
            for c in range(3):
                past_x[0, i, c] = past_x[1, i, c]
                past_x[1, i, c] = x0[i, c]
        past_t[0] = past_t[1]
        past_t[1] = t
    for i in range(n):
        for c in range(3):
            x0[i, c] = x1[i, c]
            v0[i, c] = v1[i, c]
            a0[i, c] = a1[i, c]
            F0[i, c] = F[i, c]
        ext_z[i] = max(ext_z[i], x0[i, 2])


@njit(cache=True)
def relax_level(st_i, changed):  # noqa: ANN001, ANN201
    """The step refinement after an accepted step: a step that changed a contact or
    friction state or a tension steeply keeps the level (``st_i[0]``) and restarts the
    count of smooth steps (``st_i[1]``); two smooth steps in a row go a level coarser."""
    if changed:
        st_i[1] = 0
    else:
        st_i[1] += 1
        if st_i[1] >= 2 and st_i[0] > 0:
            st_i[0] -= 1
            st_i[1] = 0
