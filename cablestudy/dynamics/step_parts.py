"""Compiled pieces of the Newton iterations and time steps shared by the single line
(:mod:`.alpha_step`, :mod:`.integrator`, :mod:`.model`) and the system
(:mod:`.system_march`): the operations each wrote out, in the same order, no float
flags (as every caller), so the answers are the same bit for bit. Pure."""

from __future__ import annotations

from numba import njit


@njit(cache=True)
def largest_correction(dx, n):  # noqa: ANN001, ANN201
    """The largest ``|dx[i, c]|`` of the first ``n`` nodes."""
    big = 0.0
    for i in range(n):
        for c in range(3):
            big = max(big, abs(dx[i, c]))
    return big


@njit(cache=True)
def newmark_correct(x1, v1, a1, dx, held, n, scale, beta, gamma, h):  # noqa: ANN001, ANN201, PLR0913
    """Add ``scale dx`` to the free nodes' positions, and the Newmark acceleration and
    velocity that follow (``d / (beta h^2)``, ``gamma d / (beta h)``)."""
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
    """The statics' regularisation of slack nodes: at most ``reg``, and 1e-6 of the
    geometric stiffness ``max(tension) / lmin`` (not below 1e-6 ``reg``)."""
    tmax = 0.0
    for e in range(tension.shape[0]):
        tmax = max(tmax, tension[e])
    return min(reg, max(1e-6 * tmax / lmin, 1e-6 * reg))


@njit(cache=True)
def quarter_element_scale(big, lmin):  # noqa: ANN001, ANN201
    """The factor that cuts a correction of size ``big`` to ``lmin / 4`` (1 within)."""
    scale = 1.0
    if big > 0.25 * lmin:
        scale = 0.25 * lmin / big
    return scale


@njit(cache=True)
def predict_positions(x0, v0, past_x, past_t, npast, t, tn, x_pred):  # noqa: ANN001, ANN201, PLR0913
    """Newton's start ``x_pred`` at ``tn``: the quadratic through the kept positions
    (``past_x`` at ``past_t``) and ``x0`` at ``t``, a straight step with ``v0`` while
    ``npast`` < 2. Returns the quadratic's weights (zeros for the straight step)."""
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
    """An accepted step: ``x0`` at ``t`` joins the two kept positions (count into
    ``st_i[5]``), the end state becomes the start, ``ext_z`` keeps each highest ``z``."""
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
    """After an accepted step: a ``changed`` one (state switch, steep tension) restarts
    the count of smooth steps ``st_i[1]``; two smooth ones go a level coarser."""
    if changed:
        st_i[1] = 0
    else:
        st_i[1] += 1
        if st_i[1] >= 2 and st_i[0] > 0:
            st_i[0] -= 1
            st_i[1] = 0
