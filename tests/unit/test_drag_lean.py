"""The lean of the single line's drag fit (cablestudy/dynamics/drag_lean.py): where a
node hardly moves the fit takes the drag's Jacobian averaged over the node's motion
(the system's lean), not the small-motion tangent at the mean flow (zero in still
water), against

* the closed form of a node swinging along a straight line in still water: across its
  motion the fit is ``c_N <|v_N|> = c_N 2 a / pi`` (was zero), along it the
  describing-function gain ``8 c_N a / (3 pi)``;
* the NumPy reference of the system's lean (tests/system_drag_reference.py,
  ``mean_drag_jacobian``) and the fit given that lean (``drag_linearisation``), on
  nodes in a current (the same phases) and without (the exact means, against 4096
  phases).
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from cablestudy.dynamics.frequency_model import FIT_REGULARISATION
from cablestudy.dynamics.harmonic_kernel import drag_fit_samples
from tests.drag_fit_reference import drag_linearisation
from tests.system_drag_reference import mean_drag_jacobian


def _fit(line: SimpleNamespace, v: np.ndarray, samples: int, exact: bool) -> tuple:
    """(fit, lean) (n, 3, 3) of the single line's kernel fit at velocities ``v``."""
    n = line.n_nodes
    th = 2.0 * np.pi * np.arange(samples) / samples
    work = [np.empty((n, samples)) for _ in range(6)]
    out, lean = np.empty((n, 3, 3)), np.empty((n, 3, 3))
    tangent_d = np.zeros((n, 3, 3))  # still water: the small-motion tangent is zero
    drag_fit_samples(
        np.ascontiguousarray(v.real), np.ascontiguousarray(v.imag), line.current,
        line.tangent, line.drag_normal, line.drag_tangential, line.body_drag, tangent_d,
        np.cos(th), np.sin(th), exact, *work, np.empty(n, dtype=np.int64), lean, out,
    )  # fmt: skip
    return out, lean


def _line(rng: np.random.Generator, n: int, current: np.ndarray) -> SimpleNamespace:
    t = rng.normal(size=(n, 3))
    t /= np.linalg.norm(t, axis=1)[:, None]
    return SimpleNamespace(
        n_nodes=n,
        current=current,
        tangent=t,
        drag_normal=rng.uniform(0.5, 2.0, n),
        drag_tangential=rng.uniform(0.01, 0.1, n),
        body_drag=np.where(rng.random(n) < 0.3, rng.uniform(0.5, 2.0, n), 0.0),
    )


def test_across_a_straight_swing_the_fit_is_the_mean_normal_speed() -> None:
    """A node swinging along ``e1`` (normal to its tangent ``t``) with amplitude ``a``
    in still water, normal drag only: the velocity covariance is singular across the
    motion (along ``e2``), where the fit is its lean whole, ``c_N <|v_N|> = c_N 2 a /
    pi`` (exact means; with phases, their mean of ``|cos|``), along ``e1`` the gain ``8
    c_N a / (3 pi)`` within the regularisation: ``(h + e j) / (g + e)`` against ``h /
    g`` with ``e = 1e-6 g`` and ``j / h * g = 3 / 2``, 5e-7 relative; along
    ``t`` zero. The directions out of every coordinate plane (not the planar closed
    form) with exact binary components: ``v . e2`` and ``v . t`` are exactly zero.
    Across, the fit is ``(H + e J)(G + e I)^-1`` solved by cofactors (``G + e I`` of
    eigenvalues ``g``, ``e``, ``e``): each cofactor has a rounding of ``u g^2`` against
    its size ``g e`` and the determinant, a sum of them times ``g``, cancels down to ``g
    e^2``, so every entry (over that determinant) carries up to ``u (g / e)^2`` ~ 1e-4
    relative (measured 2.3e-6 across, 1.5e-6 along; the system's fit shares that
    arithmetic); bound 1e-4."""
    e1, e2 = np.array([1.0, 2.0, 2.0]) / 3.0, np.array([2.0, 1.0, -2.0]) / 3.0
    t = np.array([2.0, -2.0, 1.0]) / 3.0
    n, a, c = 4, 0.75, 1.3
    line = SimpleNamespace(
        n_nodes=n,
        current=np.zeros((n, 3)),
        tangent=np.tile(t, (n, 1)),
        drag_normal=np.full(n, c),
        drag_tangential=np.zeros(n),
        body_drag=np.zeros(n),
    )
    v = np.array([0.25, 0.5, 0.5])[None, :] * np.array([1.0, 1j, -1.0, -1j])[:, None]
    assert np.all(v.real @ e2 == 0.0) and np.all(v.real @ t == 0.0)
    for exact in (True, False):
        fit, _ = _fit(line, v, 32, exact)
        mean_abs = 2.0 / math.pi
        if not exact:  # the 32 phases' mean of |cos|
            mean_abs = float(np.mean(np.abs(np.cos(2.0 * np.pi * np.arange(32) / 32))))
        across = np.einsum("a,nab,b->n", e2, fit, e2)
        assert np.allclose(across, c * mean_abs * a, rtol=1e-4, atol=0.0), exact
        along = np.einsum("a,nab,b->n", e1, fit, e1) / (8.0 * c * a / (3.0 * math.pi))
        if exact:  # the regularisation's 5e-7 plus the determinant's rounding (below)
            assert np.all(np.abs(along - 1.0) <= 0.5 * FIT_REGULARISATION + 1e-4)
        assert np.all(np.abs(fit @ t) <= 1e-4 * c * a)
        assert np.all(np.abs(np.einsum("a,nab,b->n", e1, fit, e2)) <= 1e-4 * c * a)


def test_the_lean_is_the_system_s_mean_jacobian_and_the_fit_leans_on_it() -> None:
    """Random nodes moving out of every plane, half in a current: their lean is the
    reference mean Jacobian, over the same 32 phases in a current (the same sums in
    another order: 1e-13), exact without (4096 phases of the reference: the kinks of
    ``|w_T|`` and of ``|w_N|`` leave errors falling as ``N^-2``, ``(2 pi / N)^2 / 6``
    ~ 4e-7 of ``J``; bound 1e-6); and the fit is ``drag_linearisation`` given that
    lean (1e-10: two orders of the same arithmetic, amplified by ``G^-1``'s
    conditioning, at most 1e3 on these random motions)."""
    rng = np.random.default_rng(24)
    n = 40
    current = rng.normal(scale=0.5, size=(n, 3)) * (np.arange(n) % 2 == 0)[:, None]
    line = _line(rng, n, current)
    v = rng.normal(size=(n, 3)) + 1j * rng.normal(size=(n, 3))
    fit, lean = _fit(line, v, 32, True)
    scale = np.abs(lean).max(axis=(1, 2))[:, None, None]
    moving = current.any(axis=1)
    ref32 = mean_drag_jacobian(line, v, 32)
    assert np.all(np.abs(lean - ref32)[moving] <= 1e-13 * scale[moving])
    ref = mean_drag_jacobian(line, v, 4096)
    assert np.all(np.abs(lean - ref)[~moving] <= 1e-6 * scale[~moving])
    want = drag_linearisation(line, v, 32, lean, True)
    big = np.abs(want).max(axis=(1, 2))[:, None, None]
    assert np.all(np.abs(fit - want) <= 1e-10 * big)
