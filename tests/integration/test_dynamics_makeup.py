"""Dynamics and modal analysis of a composite line end to end (YAML -> netCDF): two
segments of different material, a clump weight with buoyancy at their joint, and a
current that turns and weakens with depth, both ends fixed, end B heaving.

The dynamic model starts from its own discrete equilibrium (80 lumped-mass elements),
seeded by the semi-analytic static solution. The two must agree to the lumping error,
O((h / L)^2) relative with h / L = 1 / 80, i.e. about 1.6e-4 times a curvature factor
of order 1 (measured 2.3e-5); 1e-3 leaves margin while a lost load (the clump's 20 N
or the drag of the current, a few percent of the tension here) would break it.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from cablestudy.cli import main

STUDY = """
name: dyn-composite
environment:
  fluid: water
  current:
    - {z: 0.0, speed: 0.3, heading_deg: 30.0}
    - {z: -20.0, speed: 0.1, heading_deg: 90.0}
line:
  segments:
    - {length: 12.0, diameter: 0.02, mass_per_length: 1.2, axial_stiffness: 2.0e+6}
    - {length: 10.0, diameter: 0.015, mass_per_length: 0.6, axial_stiffness: 1.0e+6}
  attachments:
    - {s: 12.0, mass: 2.0, volume: 0.001}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -15.0]}
  b: {kind: fixed, position: [15.0, 2.0, -5.0]}
analysis:
  static: {nodes: 45}
  modal: {modes: 4}
  dynamic:
    excitation: {end: b, direction: [0.0, 0.0, 1.0], amplitude: 0.2, frequency: 0.3}
sweep:
  analysis.dynamic.excitation.frequency: [0.2, 0.5]
"""


def test_composite_line_with_current_runs_dynamics_and_modes(tmp_path: Path) -> None:
    cfg = tmp_path / "study.yaml"
    cfg.write_text(STUDY)
    assert main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous"]) == 0
    ds = xr.load_dataset(tmp_path / "dyn-composite.nc")
    assert ds.sizes["frequency"] == 2
    assert (ds["status"] == 0).all(), ds["message"].values
    assert (ds["steady_converged"] == 1).all()
    # the dynamic model's discrete statics agree with the semi-analytic solution
    rel = np.abs(ds["tension_static"] - ds["tension_b"]) / ds["tension_b"]
    assert float(rel.max()) < 1e-3
    # the end tension swings around its static value, more at the higher frequency
    assert (ds["tension_min"] < ds["tension_static"]).all()
    assert (ds["tension_max"] > ds["tension_static"]).all()
    swing = ds["tension_max"] - ds["tension_min"]
    assert float(swing.sel(frequency=0.5)) > float(swing.sel(frequency=0.2))
    # natural frequencies about the static shape: positive, ascending, and the same
    # for both excitation frequencies (one static problem; the eigensolver's random
    # start vector leaves differences at its convergence level, ~1e-12 relative)
    f = ds["natural_frequency"].values
    assert np.all(f > 0) and np.all(np.diff(f, axis=-1) >= 0)
    np.testing.assert_allclose(f[0], f[1], rtol=1e-9)
