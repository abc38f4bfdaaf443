"""The still-water drag fit in closed form (cablestudy/dynamics/elliptic_fit.py, issue
24): the period means of the describing-function fit of a node without current, for
motion in any direction, against

* the elliptic integrals they stand for, at 40 digits (mpmath);
* the phase sums they are the limit of, at 32 to 4096 phases: the trapezoid rule on a
  period converges geometrically for an analytic integrand, as ``exp(-N sigma)`` with
  ``sigma`` the half-width of its strip of analyticity (``atanh(q / p)`` for the
  ellipse's ``sqrt(p^2 cos^2 + q^2 sin^2)``), and as ``N^-2`` / ``N^-3`` where a kink
  is left (``|w_T|``, or ``|w_N|`` on a line);
* the planar closed form (``planar_drag_fit``) on motion in the x-z plane;
* the amplitude scaling of the drag (``G ~ a^2``, ``H ~ a^3``, ``J ~ a``) at 1e-100 and
  1e100 m/s;

and a single line's fit with ``samples`` unset against 4096 phases (case8 from the study
file to the dataset: tests/integration/test_still_water_fit.py)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import mpmath
import numpy as np
import pytest
from numba import njit

from cablestudy.dynamics.elliptic_fit import ellipse_means, still_water_means
from cablestudy.dynamics.frequency_model import FIT_REGULARISATION, planar_drag_fit
from tests.drag_fit_reference import drag_linearisation


@njit(cache=True)
def _closed(vr, vi, tan, c_n, c_t, c_b):  # noqa: ANN001, ANN202
    """(n, 3, 3, 3): per node ``G``, ``H``, ``J`` of :func:`still_water_means`."""
    out = np.empty((vr.shape[0], 3, 3, 3))
    sym = ((0, 1, 2), (1, 3, 4), (2, 4, 5))
    for i in range(vr.shape[0]):
        g, h, j = still_water_means(
            vr[i, 0], vr[i, 1], vr[i, 2], vi[i, 0], vi[i, 1], vi[i, 2],
            tan[i, 0], tan[i, 1], tan[i, 2], c_n[i], c_t[i], c_b[i],
        )  # fmt: skip
        for a in range(3):
            for b in range(3):
                out[i, 0, a, b] = g[sym[a][b]]
                out[i, 1, a, b] = h[3 * a + b]
                out[i, 2, a, b] = j[sym[a][b]]
    return out


@njit(cache=True)
def _planar(vr, vi, tan, cur, c_n, c_t, lean):  # noqa: ANN001, ANN202
    out = np.empty((vr.shape[0], 3, 3))
    for i in range(vr.shape[0]):
        planar_drag_fit(vr, vi, tan, cur, c_n, c_t, lean, i, out)
    return out


def _phase_sums(node: SimpleNamespace, samples: int) -> np.ndarray:
    """The same means over ``samples`` phases, directly from their definitions."""
    th = 2.0 * np.pi * np.arange(samples) / samples
    w = -(
        node.vr[:, None, :] * np.cos(th)[None, :, None]
        - node.vi[:, None, :] * np.sin(th)[None, :, None]
    )
    t = node.tan
    wt = np.einsum("nka,na->nk", w, t)
    wn = w - wt[..., None] * t[:, None, :]
    sn = np.linalg.norm(wn, axis=2)
    sr = np.linalg.norm(w, axis=2)
    cn, ct, cb = (c[:, None, None] for c in (node.c_n, node.c_t, node.c_b))
    f = cn * sn[..., None] * wn + ct * (np.abs(wt) * wt)[..., None] * t[:, None, :]
    f = f + cb * sr[..., None] * w
    f = f - f.mean(axis=1, keepdims=True)
    G = np.einsum("nka,nkb->nab", w, w) / samples
    H = np.einsum("nka,nkb->nab", f, w) / samples
    inv_n = np.where(sn > 0.0, 1.0 / np.where(sn > 0.0, sn, 1.0), 0.0)
    inv_r = np.where(sr > 0.0, 1.0 / np.where(sr > 0.0, sr, 1.0), 0.0)
    P = np.eye(3) - t[:, :, None] * t[:, None, :]
    J = cn * (sn.mean(1)[:, None, None] * P + np.einsum("nka,nkb,nk->nab", wn, wn, inv_n) / samples)
    J = J + 2.0 * ct * np.abs(wt).mean(1)[:, None, None] * (t[:, :, None] * t[:, None, :])
    J = J + cb * (
        sr.mean(1)[:, None, None] * np.eye(3) + np.einsum("nka,nkb,nk->nab", w, w, inv_r) / samples
    )
    return np.stack([G, H, J], axis=1)


def _nodes(rng: np.random.Generator, n: int, **kw: object) -> SimpleNamespace:
    t = rng.normal(size=(n, 3))
    t /= np.linalg.norm(t, axis=1)[:, None]
    node = SimpleNamespace(
        vr=rng.normal(size=(n, 3)),
        vi=rng.normal(size=(n, 3)),
        tan=t,
        c_n=rng.uniform(0.5, 2.0, n),
        c_t=rng.uniform(0.01, 0.1, n),
        c_b=np.where(rng.random(n) < 0.3, rng.uniform(0.5, 2.0, n), 0.0),
    )
    for k, v in kw.items():
        setattr(node, k, v)
    return node


def _closed_of(node: SimpleNamespace) -> np.ndarray:
    return _closed(node.vr, node.vi, node.tan, node.c_n, node.c_t, node.c_b)


def _axis_ratio(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``q / p`` of the ellipses ``a cos - b sin`` (n, 3): from the eigenvalues of
    ``a a^T + b b^T`` (``p^2``, ``q^2``, 0)."""
    ev = np.linalg.eigvalsh(a[:, :, None] * a[:, None, :] + b[:, :, None] * b[:, None, :])
    return np.sqrt(np.maximum(ev[:, 1], 0.0) / ev[:, 2])


@pytest.mark.parametrize("k", [1.0, 1.0 - 1e-9, 0.9, 0.5, 0.2, 1e-2, 1e-4, 1e-8, 1e-20, 1e-40])
def test_ellipse_means_are_the_elliptic_integrals(k: float) -> None:
    """``(<r cos^2>, <r sin^2>, <cos^2 / r>, <sin^2 / r>)`` of ``r = sqrt(1 - m
    sin^2)``, ``m = 1 - k^2``, by mpmath's ``K``, ``E`` at 100 digits (``m`` within
    ``1e-80`` of one needs 80 of them). The bar: rounding times the ``ln(4 / k)`` digits
    the sums lose near a line (module docstring of elliptic_fit), 1e-15 each."""
    with mpmath.workdps(100):
        kk = mpmath.mpf(k)
        m = 1 - kk**2
        K, E = mpmath.ellipk(m), mpmath.ellipe(m)
        if m == 0:
            L = J = mpmath.pi / 4
        else:
            L = (K - E) / m
            J = ((2 * m - 1) * E + (1 - m) * K) / (3 * m)
        want = [float(x * 2 / mpmath.pi) for x in (E - J, J, K - L, L)]
    got = ellipse_means(k)
    bar = 4e-16 * (4.0 + math.log(4.0 / k))
    np.testing.assert_allclose(got, want, rtol=bar, atol=0.0)


def test_ellipse_means_at_a_line_and_a_circle() -> None:
    """A line (``k = 0``): ``<|cos|^3> = 4 / (3 pi)``, ``<|cos| sin^2> = 2 / (3 pi)``,
    ``<|cos|> = 2 / pi``, which ``k -> 0`` approaches (as ``k^2 ln(1 / k)``: below
    1e-15 at ``k = 1e-9``), and 0 for ``<sin^2 / r>``, whose weight ``k^2`` in the fit
    takes it to zero (``(2 / pi) k^2 (ln(4 / k) - 1)`` near the line); a circle: one
    half each."""
    line = (4.0 / (3.0 * math.pi), 2.0 / (3.0 * math.pi), 2.0 / math.pi, 0.0)
    assert ellipse_means(0.0) == pytest.approx(line, rel=1e-15, abs=0.0)
    k = 1e-9
    near = ellipse_means(k)
    np.testing.assert_allclose(near[:3], line[:3], rtol=1e-14)
    want = 2.0 / math.pi * (math.log(4.0 / k) - 1.0)
    assert near[3] == pytest.approx(want, rel=1e-15)
    np.testing.assert_allclose(ellipse_means(1.0), [0.5] * 4, rtol=1e-15)


def test_smooth_means_are_the_geometric_limit_of_the_phase_sums() -> None:
    """Normal and body drag only (``c_T = 0``), ellipses of axis ratio ``k >= 0.05``:
    the integrands are analytic in a strip of half-width ``atanh(k)``; with half of it
    (where they stay within a few times their size) the trapezoid error is below ``2 M
    exp(-N atanh(k) / 2) / (1 - ...)``: bar ``4 exp(-N atanh(k_min) / 2)`` of the
    largest entry, floored at 1e-13 (the rounding of 4096 terms of one size)."""
    rng = np.random.default_rng(11)
    n = 60
    node = _nodes(rng, n, c_t=np.zeros(n))
    # some near-circles in the normal plane: b turned a quarter period from a
    node.vi[:10] = np.cross(
        node.tan[:10], node.vr[:10] - (node.vr[:10] * node.tan[:10]).sum(1)[:, None] * node.tan[:10]
    )
    P = np.eye(3) - node.tan[:, :, None] * node.tan[:, None, :]
    k_n = _axis_ratio(np.einsum("nab,nb->na", P, node.vr), np.einsum("nab,nb->na", P, node.vi))
    k_b = np.where(node.c_b > 0.0, _axis_ratio(node.vr, node.vi), 1.0)
    k = np.minimum(k_n, k_b)
    keep = k >= 0.05
    assert keep.sum() > 40
    node = SimpleNamespace(**{a: v[keep] for a, v in vars(node).items()})
    k = k[keep]
    exact = _closed_of(node)
    scale = np.abs(exact).max(axis=(2, 3))
    for samples in (32, 128, 512, 4096):
        err = np.abs(_phase_sums(node, samples) - exact).max(axis=(2, 3))
        bar = np.maximum(4.0 * np.exp(-samples * np.arctanh(np.minimum(k, 0.99)) / 2.0), 1e-13)[
            :, None
        ]
        assert np.all(err <= bar * scale), (samples, np.max(err / scale / bar))


@pytest.mark.parametrize("shape", ["tangential", "line", "thin"])
def test_kinked_means_converge_at_the_kink_rate(shape: str) -> None:
    """With tangential drag (the kink of ``|w_T|`` at its zeros), or on a line (``|w_N|``)
    or an ellipse thinner than the phase step (``k = 1e-5``: a line to the phases), the
    phase sums still converge to the closed form, at the rate of the kink: the aliased
    Fourier coefficients of ``|cos|`` fall as ``4 / (pi n^2)``, of ``|cos| cos`` as
    ``n^-3``: over the multiples ``jN`` of the phases at most ``(4 / pi) zeta(2) N^-2 ~
    2.1 N^-2`` of the amplitude in ``J`` and ``2.1 N^-3`` in ``H``, for each of two
    kinks a period: bars ``5 N^-2`` and ``5 N^-3`` of the largest entry."""
    rng = np.random.default_rng(12)
    n = 40
    node = _nodes(rng, n)
    if shape == "line":
        node.vi = 0.3 * node.vr
    elif shape == "thin":
        node.vi = 0.3 * node.vr + 1e-5 * np.cross(node.vr, node.tan)
        node.c_b[:] = 0.0
    else:
        node.c_b[:] = 0.0
    exact = _closed_of(node)
    scale = np.abs(exact).max(axis=(2, 3))
    for samples in (32, 128, 512, 4096):
        err = np.abs(_phase_sums(node, samples) - exact).max(axis=(2, 3)) / scale
        assert np.max(err[:, 0]) <= 1e-13
        assert np.max(err[:, 1]) <= 5.0 / samples**3 + 1e-13, (samples, err[:, 1].max())
        assert np.max(err[:, 2]) <= 5.0 / samples**2 + 1e-13, (samples, err[:, 2].max())


def test_planar_means_give_the_planar_closed_form() -> None:
    """Motion, tangent in the x-z plane, no current: the exact means' fit ``H G^-1`` (in
    the plane, where ``G`` is invertible) is ``planar_drag_fit``'s, each a closed form of
    the same first harmonic, to rounding (1e-14) amplified by ``G``'s condition number
    (``(p / q)^2``) of the largest entry."""
    rng = np.random.default_rng(13)
    n = 30
    node = _nodes(rng, n, c_b=np.zeros(n))
    for a in (node.vr, node.vi, node.tan):
        a[:, 1] = 0.0
    node.tan /= np.linalg.norm(node.tan, axis=1)[:, None]
    node.vi[0] = 0.0  # a line
    node.vr[1] = 0.4 * node.tan[1]  # along the tangent only
    node.vi[1] = -0.1 * node.tan[1]
    exact = _closed_of(node)
    xz = np.ix_([0, 2], [0, 2])
    zero = np.zeros((n, 3))
    got = _planar(node.vr, node.vi, node.tan, zero, node.c_n, node.c_t, exact[:, 2])
    for i in range(n):
        G, H = exact[i, 0][xz], exact[i, 1][xz]
        D = H @ np.linalg.pinv(G, rcond=1e-10)
        want = got[i][xz]
        bar = 1e-14 * (np.linalg.cond(G) if i >= 2 else 1.0)
        # on the degenerate two, D only along the motion is determined
        if i < 2:
            u = node.vr[i][[0, 2]] / np.linalg.norm(node.vr[i])
            D, want = D @ u, want @ u
        np.testing.assert_allclose(D, want, rtol=0, atol=bar * np.abs(want).max())
        # the out-of-plane column is the lean's, its row zero
        np.testing.assert_array_equal(got[i][:, 1], exact[i, 2][:, 1])


def test_means_scale_with_the_amplitude_as_the_drag() -> None:
    """``G`` is quadratic, ``H`` cubic and ``J`` linear in the velocity (the drag is
    quadratic); the closed form depends on the axis ratio only, so the scaled means are
    the scaled ones to rounding (5e-14 of the largest entry: some fifty operations an
    entry), from 1e-100 to 1e100 m/s (within the range of
    the cubes); a node at rest has none."""
    rng = np.random.default_rng(14)
    node = _nodes(rng, 20)
    node.vi[3] = 0.3 * node.vr[3]
    base = _closed_of(node)
    for lam in (1e-100, 1e-8, 1e8, 1e100):
        scaled = SimpleNamespace(**vars(node))
        scaled.vr, scaled.vi = lam * node.vr, lam * node.vi
        got = _closed_of(scaled)
        for j, power in enumerate((2, 3, 1)):
            want = base[:, j] * lam**power
            big = np.abs(want).max(axis=(1, 2))[:, None, None]
            assert np.all(np.abs(got[:, j] - want) <= 5e-14 * big)
    rest = SimpleNamespace(**vars(node))
    rest.vr, rest.vi = np.zeros((20, 3)), np.zeros((20, 3))
    assert np.all(_closed_of(rest) == 0.0)


def test_single_line_fit_is_the_limit_of_the_sampled_fit() -> None:
    """``drag_linearisation`` with ``exact`` (``samples`` unset) on nodes moving out of
    every coordinate plane without current, against the sampled fit at 4096 phases:
    they differ by the error of ``H`` (``5 N^-3``, 7e-11 of the largest entry, previous
    test) times the amplification by ``G^-1`` (``G`` exact in both)."""
    rng = np.random.default_rng(15)
    n = 25
    node = _nodes(rng, n)
    line = SimpleNamespace(
        n_nodes=n,
        current=np.zeros((n, 3)),
        tangent=node.tan,
        drag_normal=node.c_n,
        drag_tangential=node.c_t,
        body_drag=node.c_b,
    )
    v = node.vr + 1j * node.vi
    lean = np.zeros((n, 3, 3))
    got = drag_linearisation(line, v, 32, lean, True)
    want = drag_linearisation(line, v, 4096, lean, False)
    coarse = drag_linearisation(line, v, 32, lean, False)
    # G^-1 amplifies the error of H by the ratio of G's two eigenvalues, (p / q)^2;
    # compared on the plane of the motion (D a, D b): across it the sampled fit is
    # H n / eps, the rounding of w . n = 0 (1e-16 |w|) over 1e-6 (the regularisation)
    ev = np.linalg.eigvalsh(_closed_of(node)[:, 0])
    bar = 5.0 / 4096**3 * (ev[:, 2] / ev[:, 1]) + 1e-14
    V = np.stack([node.vr, node.vi], axis=2)
    big = np.abs(want @ V).max(axis=(1, 2))
    assert np.all(np.abs((got - want) @ V).max(axis=(1, 2)) <= bar * big)
    # the 32 phases it replaces were off by far more
    assert np.abs((coarse - want) @ V).max() > 1e-6 * big.max()


def test_free_points_fit_is_the_limit_of_the_sampled_fit() -> None:
    """The system's free points (isotropic drag ``c |w| w``) without current, with
    ``samples`` unset: the fit of the exact means against the oracle's sampled fit at
    4096 phases, on the plane of the motion (bar as for the lines' nodes above), and
    on a line exactly the describing function ``c 8 a / (3 pi)`` along it (to rounding;
    with the regularisation's ``1 + 1e-6``)."""
    from cablestudy.dynamics.system_fd_fit import fit_points
    from tests.system_drag_reference import point_drag_fit

    rng = np.random.default_rng(16)
    P = 12
    c = rng.uniform(50.0, 300.0, P)
    u = rng.normal(size=(P, 3)) + 1j * rng.normal(size=(P, 3))
    u[0] = [0.8j, 0.0, 0.0]  # velocity i omega u = -0.8 omega along x: a line
    cur = np.zeros((P, 3))
    omega = 0.7
    cs = np.cos(2.0 * np.pi * np.arange(32) / 32)
    sn = np.sin(2.0 * np.pi * np.arange(32) / 32)
    got = np.empty((P, 3, 3))
    fit_points(c, cur, u, omega, cs, sn, True, got)
    want = point_drag_fit(c, cur, 1j * omega * u, 4096)
    v = 1j * omega * u
    V = np.stack([v.real, v.imag], axis=2)
    G = 0.5 * (V @ np.swapaxes(V, 1, 2))
    ev = np.linalg.eigvalsh(G)
    bar = 5.0 / 4096**3 * (ev[:, 2] / np.maximum(ev[:, 1], 1e-300 * ev[:, 2])) + 1e-14
    bar[0] = 5.0 / 4096**3 + 1e-14
    big = np.abs(want @ V).max(axis=(1, 2))
    assert np.all(np.abs((got - want) @ V).max(axis=(1, 2)) <= bar * big)
    # G + eps I along the motion: G (1 + FIT_REGULARISATION), H = gain G
    gain = c[0] * 8.0 * 0.8 * omega / (3.0 * np.pi) / (1.0 + FIT_REGULARISATION)
    assert got[0, 0, 0] == pytest.approx(gain, rel=1e-14)
