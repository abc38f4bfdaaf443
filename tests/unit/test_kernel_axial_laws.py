"""The compiled kernels' axial laws are the laws of :mod:`cablestudy.physics.axial`:
same tension and tangent at any strain, and the line model's tangent stiffness with a
non-linear law matches finite differences of its forces."""

from __future__ import annotations

import numpy as np
import pytest

from cablestudy.dynamics.assembly import axial_law, evaluate
from cablestudy.dynamics.discrete_line import discretise, law_arrays
from cablestudy.physics.axial import LinearLaw, PolynomialLaw, SteelWireLaw, TableLaw
from cablestudy.statics.base import LineModel, Medium

LAWS = [
    LinearLaw(2.0e7),
    PolynomialLaw((4.0e6, 2.0e7, 5.0e7)),
    PolynomialLaw((1.0e6, 0.0, 3.0e8, 0.0, 1.0e10)),
    SteelWireLaw(1.0e7, 0.002),
    TableLaw((0.0, 0.005, 0.01, 0.02, 0.04), (0.0, 1.0e4, 3.0e4, 9.0e4, 2.5e5)),
]


@pytest.mark.parametrize("law", LAWS, ids=lambda law: law.name)
def test_kernel_law_is_the_physics_law(law) -> None:  # noqa: ANN001
    """Tension and tangent at strains from 1e-6 to 0.1 (inside and beyond a table):
    the kernel re-implements each law for the compiled loop, so they must agree to
    rounding (1e-12 relative: a few operations of double precision)."""
    code, params, knots, start, count = law_arrays([law], np.zeros(1, dtype=np.int64))
    for eps in np.geomspace(1e-6, 0.1, 37):
        t, dt = axial_law(code[0], params[0], knots, start[0], count[0], 2.0e7, eps)
        assert t == pytest.approx(float(law.tension(eps)), rel=1e-12, abs=1e-9)
        assert dt == pytest.approx(float(law.tangent_stiffness(eps)), rel=1e-12, abs=1e-9)


@pytest.mark.parametrize("law", LAWS[1:], ids=lambda law: law.name)
def test_tangent_with_a_nonlinear_law_matches_finite_differences(law) -> None:  # noqa: ANN001
    """dF/dx of a stretched 3D line (strain about 1e-2) against central differences:
    truncation O(h^2) with h = 1e-7 m, rounding 1e-16 |F| / h; 1e-5 of the largest
    entry."""
    line = LineModel(
        length=np.array([10.0]),
        weight=np.array([50.0]),
        mass=np.array([6.0]),
        axial_stiffness=np.array([2.0e7]),
        diameter=np.array([0.05]),
        drag_normal=np.zeros(1),
        drag_tangential=np.zeros(1),
        added_mass_normal=np.zeros(1),
        added_mass_tangential=np.zeros(1),
        bending_stiffness=np.zeros(1),
        damping_ratio=np.zeros(1),
        attachment_s=np.zeros(0),
        attachment_force=np.zeros((0, 3)),
        attachment_mass=np.zeros(0),
        attachment_volume=np.zeros(0),
        axial_law=(law,),
    )
    disc = discretise(line, Medium(density=0.0, gravity=9.80665), 6)
    rng = np.random.default_rng(2)
    steps = disc.rest_length[:, None] * (1.01 + 1e-3 * rng.normal(size=(6, 1)))
    dirs = rng.normal(size=(6, 3)) * 0.1 + np.array([1.0, 0.0, -0.3])
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    x = np.vstack([np.zeros(3), np.cumsum(steps * dirs, axis=0)])
    v = np.zeros_like(x)
    w = evaluate(disc, x, v)
    K_d, K_o = w.K_d.copy(), w.K_o.copy()
    np.testing.assert_allclose(
        w.tension, law.tension(np.linalg.norm(np.diff(x, axis=0), axis=1) / 10.0 * 6 - 1.0)
    )
    scale = np.abs(K_d).max()
    h = 1e-7
    for i in (1, 3):
        for c in range(3):
            xp, xm = x.copy(), x.copy()
            xp[i, c] += h
            xm[i, c] -= h
            col = (evaluate(disc, xp, v).F - evaluate(disc, xm, v).F) / (2 * h)
            np.testing.assert_allclose(col[i], K_d[i][:, c], atol=1e-5 * scale)
            np.testing.assert_allclose(col[i + 1], K_o[i][c, :], atol=1e-5 * scale)
