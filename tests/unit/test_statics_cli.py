"""The semi-analytic solver end to end: YAML study -> CLI run -> netCDF dataset."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from cablestudy.cli import main
from cablestudy.statics.elastic_catenary import solve_between

TOWED = """
name: towed-in-current
description: towed cable with a clump weight in a current turning with depth
environment:
  fluid: water
  current:
    - {z: 0.0, speed: 1.0, heading_deg: 0.0}
    - {z: -200.0, speed: 0.5, heading_deg: 90.0}
line:
  segments:
    - {length: 150.0, diameter: 0.03, weight_in_fluid: 5.0, axial_stiffness: 1.0e7}
    - {length: 50.0, diameter: 0.05, weight_in_fluid: 20.0, axial_stiffness: 5.0e7}
  attachments:
    - {s: 100.0, mass: 50.0, volume: 0.01}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: force, force: [0.0, 0.0, -100.0]}
analysis:
  static: {method: catenary, nodes: 41, tolerance: 1.0e-9, drag_elements: 40}
sweep:
  environment.current.0.speed: {values: [0.0, 0.5, 1.5], name: current_speed}
"""

SPAN = """
name: span-sweep
description: still-water catenaries in a batch, and a mooring line on the seabed
environment:
  fluid: water
  depth: 200.0
  seabed: {friction: 0.3}
line:
  segments:
    - {length: 300.0, diameter: 0.1, weight_in_fluid: 500.0, axial_stiffness: 5.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -20.0]}
  b: {kind: fixed, position: [210.0, 0.0, 0.0]}
analysis:
  static: {method: catenary, nodes: 51, tolerance: 1.0e-10}
sweep:
  ends.b.position.0: {values: [130.0, 160.0, 190.0, 240.0], name: span}
  ends.a.position.2: {values: [-20.0, -200.0], name: anchor_z}
"""


def _run(tmp_path: Path, text: str, name: str) -> xr.Dataset:
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    assert (
        main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous", "--no-cache"])
        == 0
    )
    return xr.load_dataset(tmp_path / f"{name}.nc")


def test_towed_cable_in_turning_current(tmp_path: Path) -> None:
    ds = _run(tmp_path, TOWED, "towed-in-current")
    assert (ds["status"] == 0).all()
    assert list(ds["current_speed"].values) == [0.0, 0.5, 1.5]
    assert (ds["drag_iterations"] > 0).all()  # the deep current point is never zero
    assert (ds["static_residual"] <= 1e-9).all()
    # the towing force is applied to the line at B: the line pulls its attachment back
    assert np.allclose(ds["force_b"].values, [0.0, 0.0, 100.0], atol=1e-9)
    # the line hangs from A: the attachment at A is pulled down
    assert np.all(ds["force_a"].sel(component="z").values < 0.0)
    # the current pushes the line along +x near the surface and +y at depth
    fast = ds.sel(current_speed=1.5)
    assert float(fast["x"].isel(s=10)) > 5.0 and float(fast["y"].isel(s=-1)) > 5.0


def test_batched_span_sweep_and_seabed(tmp_path: Path) -> None:
    ds = _run(tmp_path, SPAN, "span-sweep")
    assert (ds["status"] == 0).all(), ds["message"].values
    # anchored on the seabed (z = -200): laid length falls as the span grows
    laid = ds["laid_length"].sel(anchor_z=-200.0).values
    assert laid[0] > laid[1] > 0.0 and laid[-1] == 0.0  # touchdown, then lift-off
    # anchor far above the seabed: free-hanging (batched) cases equal Irvine's catenary
    for span in (130.0, 160.0, 190.0, 240.0):
        case = ds.sel(anchor_z=-20.0, span=span)
        exact = solve_between(
            np.array([0, 0, -20.0]),
            np.array([span, 0, 0.0]),
            300.0,
            500.0,
            5e8,
            ds["s"].values,
            tolerance=1e-13,
        )
        F = np.abs(exact.force_a).max()
        assert np.max(np.abs(case["force_a"].values - exact.force_a)) <= 1e-9 * F
        assert np.max(np.abs(case["z"].values - exact.position[:, 2])) <= 1e-9 * 300.0
