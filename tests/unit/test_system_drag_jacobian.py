"""The mean drag Jacobian kernel of the system frequency domain
(tests/system_drag_reference.py: the NumPy oracle of the compiled fit's lean) against the
per-phase Jacobians summed directly: its phase sums are regrouped for speed, so the
two agree to rounding (1e-13 of the largest entry: a few dozen additions of terms
of one size, 1e-16 each)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from tests.system_drag_reference import mean_drag_jacobian


def _direct(line: SimpleNamespace, v: np.ndarray, samples: int) -> np.ndarray:
    out = np.zeros((line.n_nodes, 3, 3))
    eye = np.eye(3)
    for i in range(line.n_nodes):
        t = line.tangent[i]
        P = eye - np.outer(t, t)
        for k in range(samples):
            th = 2.0 * np.pi * k / samples
            w = line.current[i] - (v[i].real * np.cos(th) - v[i].imag * np.sin(th))
            wn = P @ w
            sn, sr = np.linalg.norm(wn), np.linalg.norm(w)
            jn = sn * P + (np.outer(wn, wn) / sn if sn > 0 else 0.0)
            jb = sr * eye + (np.outer(w, w) / sr if sr > 0 else 0.0)
            jt = 2.0 * abs(w @ t) * np.outer(t, t)
            out[i] += line.drag_normal[i] * jn + line.body_drag[i] * jb
            out[i] += line.drag_tangential[i] * jt
        out[i] /= samples
    return out


def test_kernel_is_the_phase_mean_of_the_drag_jacobian() -> None:
    rng = np.random.default_rng(3)
    n = 13
    t = rng.normal(size=(n, 3))
    t /= np.linalg.norm(t, axis=1)[:, None]
    line = SimpleNamespace(
        n_nodes=n,
        current=0.3 * rng.normal(size=(n, 3)),
        tangent=t,
        drag_normal=rng.random(n),
        drag_tangential=rng.random(n),
        body_drag=np.where(rng.random(n) > 0.5, rng.random(n), 0.0),
    )
    v = rng.normal(size=(n, 3)) + 1j * rng.normal(size=(n, 3))
    v[3] = 0.0  # a node at rest in still water: no drag, no Jacobian
    line.current[3] = 0.0
    v[5] = 0.7 * t[5]  # a node moving along its tangent only (w_N = 0)
    line.current[5] = 0.0
    got = mean_drag_jacobian(line, v, 32)
    want = _direct(line, v, 32)
    np.testing.assert_allclose(got, want, rtol=0.0, atol=1e-13 * np.max(np.abs(want)))
    assert np.all(got[3] == 0.0)
