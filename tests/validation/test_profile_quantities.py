"""Tangent angles, elongation and wall tension along a static line (vaz-patel seed's
outputs), run YAML to netCDF and checked against closed forms."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main
from cablestudy.physics.profile import profile_quantities

CATENARY = """
name: profile-check
environment: {fluid: air, gravity: 9.80665}
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e+5}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {method: analytic, nodes: 201, tolerance: 1.0e-12}
"""

HANGING = """
name: hanging
environment: {fluid: water, gravity: 9.80665}
line:
  segments:
    - {length: 50.0, diameter: 0.1, mass_per_length: 20.0, axial_stiffness: 1.0e+8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: force, force: [0.0, 0.0, 0.0]}
analysis:
  static: {method: shooting, nodes: 51, tolerance: 1.0e-10}
"""


def _run(tmp_path: Path, text: str, name: str) -> xr.Dataset:
    path = tmp_path / f"{name}.yaml"
    path.write_text(text)
    assert main(["run", str(path), "--out", str(tmp_path), "--no-progress"]) == 0
    return xr.load_dataset(tmp_path / f"{name}.nc")


def test_catenary_angles_and_elongation_against_closed_forms(tmp_path: Path) -> None:
    """Equilibrium of the piece from A to s: T t(s) = F_A + w s e_z (F_A the force of the
    line on support A), so sin(elevation) = (F_Az + w s) / T exactly; the elongation is
    the integral of T / EA, with T = sqrt(H^2 + (F_Az + w s)^2) in closed form
    (u sqrt(H^2 + u^2) + H^2 asinh(u / H)) / (2 w EA). Tolerances: second-order
    differences on h = 0.5 m with curvature kappa <= w / H give an angle error about
    h^2 kappa^2 / 6; trapezoids on T / EA an error L h^2 max|T''| / (12 EA)."""
    ds = _run(tmp_path, CATENARY, "profile-check")
    assert int(ds.status) == 0
    w = 2.466 * 9.80665 - 1.225 * 9.80665 * math.pi * 0.02**2 / 4
    fa = ds.force_a.values
    s = ds.s.values
    T = ds.tension.values
    h_force = abs(fa[0])
    exact = np.arcsin((fa[2] + w * s) / T)
    kappa = w / h_force
    assert ds.elevation.attrs["units"] == "rad"
    np.testing.assert_allclose(ds.elevation.values, exact, atol=0.5**2 * kappa**2)
    np.testing.assert_array_equal(ds.azimuth.values, 0.0)  # +x throughout, in plane
    ea = 6.283e5

    def primitive(u: np.ndarray) -> np.ndarray:
        return (u * np.hypot(h_force, u) + h_force**2 * np.arcsinh(u / h_force)) / (2 * w * ea)

    closed = primitive(fa[2] + w * s) - primitive(fa[2])
    bound = 100.0 * 0.5**2 * w**2 / h_force / (12 * ea)  # T'' <= w^2 / H
    np.testing.assert_allclose(ds.elongation.values, closed, atol=bound)
    # the stretched length agrees with the polygon of the positions to its own O(h^2)
    polygon = np.linalg.norm(np.diff(np.stack([ds.x, ds.y, ds.z], 1), axis=0), axis=1).sum()
    assert polygon == pytest.approx(100.0 + closed[-1], abs=100.0 * 0.5**2 * kappa**2 / 24)
    # in air the wall and effective tensions differ by rho_air g z A only
    area = math.pi * 0.02**2 / 4
    np.testing.assert_allclose(
        ds.tension_wall.values, T + 1.225 * 9.80665 * ds.z.values * area, rtol=1e-14
    )


def test_hanging_line_wall_tension_carries_the_end_cap_pressure(tmp_path: Path) -> None:
    """A line hanging from the surface with a free (unloaded) bottom end: the effective
    tension is zero at the bottom, where the wall is compressed by the water pressure
    on its end cap, T_wall = -rho g L A; at the top the wall carries the weight in air
    minus that end-cap force, m g L - rho g L A (Archimedes: the submerged weight)."""
    ds = _run(tmp_path, HANGING, "hanging")
    assert int(ds.status) == 0
    rho, g, area, length = 1025.0, 9.80665, math.pi * 0.1**2 / 4, 50.0
    stretch = 1.0 + 20.0 * g * length / 1.0e8  # bottom depth: stretched length, at most
    bottom = ds.tension_wall.values[-1]
    assert bottom == pytest.approx(-rho * g * area * float(-ds.z.values[-1]), rel=1e-9)
    assert -ds.z.values[-1] == pytest.approx(length, rel=stretch - 1.0)
    top = ds.tension_wall.values[0]
    assert top == pytest.approx((20.0 - rho * area) * g * length, rel=1e-9)
    np.testing.assert_allclose(ds.elevation.values, -math.pi / 2, atol=1e-9)
    assert np.isfinite(ds.azimuth.values).all()


def test_azimuth_follows_a_turning_line() -> None:
    """A horizontal quarter circle of radius R from +x heading to +y heading: azimuth
    psi(s) = s / R (second-order differences: error h^2 / (6 R^2) inside, a few times
    that at the ends)."""
    r, n = 10.0, 201
    s = np.linspace(0.0, 0.5 * math.pi * r, n)
    pos = np.stack([r * np.sin(s / r), r - r * np.cos(s / r), np.zeros(n)], 1)
    out = profile_quantities(
        s,
        pos,
        np.full(n, 1.0),
        axial_stiffness=np.full(n, 1.0),
        area=np.zeros(n),
        density=0.0,
        gravity=9.8,
    )
    h = s[1]
    np.testing.assert_allclose(out["azimuth"], s / r, atol=4 * h**2 / (6 * r**2))
    np.testing.assert_allclose(out["elevation"], 0.0, atol=1e-15)
    np.testing.assert_allclose(out["elongation"], s, rtol=1e-12)  # strain 1
