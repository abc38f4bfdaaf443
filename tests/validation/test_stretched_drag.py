"""Drag on the stretched diameter (vaz-patel seed: d (1 + e)^(-1/2), study key
analysis.static.drag_diameter: stretched), shooting solver, YAML to netCDF."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main

# a weightless line in water (weight_in_fluid 0), taut between two fixed points, with no
# tangential drag, across a uniform current: its load is purely normal, so dT/ds = 0 and
# the strain e = T / EA is the same everywhere
STUDY = """
name: {name}
environment:
  fluid: water
  current: [{{z: 0.0, speed: 1.5, heading_deg: 90.0}}]
line:
  segments:
    - {{length: 100.0, diameter: 0.1, weight_in_fluid: 0.0, axial_stiffness: 2.0e+5,
       drag_normal: {cn}, drag_tangential: 0.0}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, -50.0]}}
  b: {{kind: fixed, position: [100.5, 0.0, -50.0]}}
analysis:
  static: {{method: shooting, nodes: 41, tolerance: 1.0e-11, drag_diameter: {how}}}
"""


def _run(tmp_path: Path, name: str, cn: float, how: str) -> xr.Dataset:
    path = tmp_path / f"{name}.yaml"
    path.write_text(STUDY.format(name=name, cn=repr(cn), how=how))
    assert main(["run", str(path), "--out", str(tmp_path), "--no-progress"]) == 0
    ds = xr.load_dataset(tmp_path / f"{name}.nc")
    assert int(ds.status) == 0, str(ds.message.values)
    return ds


def test_stretched_diameter_is_the_unstretched_law_with_scaled_drag(tmp_path: Path) -> None:
    """With e uniform, drag per unstretched length is 1/2 rho C d sqrt(1 + e) |U| U on
    the stretched diameter and 1/2 rho C' d (1 + e) |U| U on the unstretched one: the
    two shapes coincide when C' = C / sqrt(1 + e). Both are solved to 1e-11; the
    positions then agree to the solver's tolerance times the line length."""
    stretched = _run(tmp_path, "stretched", 1.2, "stretched")
    t = stretched.tension.values
    assert np.ptp(t) <= 1e-8 * t.mean()  # uniform tension
    e = float(t.mean()) / 2.0e5
    assert e > 0.02  # a strain large enough for the law to matter
    scaled = _run(tmp_path, "scaled", 1.2 / math.sqrt(1.0 + e), "unstretched")
    plain = _run(tmp_path, "plain", 1.2, "unstretched")
    for var in ("x", "y", "z", "tension"):
        np.testing.assert_allclose(
            stretched[var].values,
            scaled[var].values,
            atol=1e-7 * (100.0 if var != "tension" else t.mean()),
        )
    # and the law matters: the plain unstretched diameter drags more, by about
    # (1 + e)^(1/2) (a little less: the line then deflects more and its normal flow drops)
    drag = {k: float(d.force_a[1] + d.force_b[1]) for k, d in (("s", stretched), ("p", plain))}
    ratio = drag["p"] / drag["s"]
    assert 1.0 + 0.25 * e < ratio < math.sqrt(1.0 + e) * (1.0 + 1e-6), ratio


def test_solvers_without_it_refuse_it(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    path = tmp_path / "s.yaml"
    path.write_text(
        STUDY.format(name="s", cn="1.2", how="stretched").replace(
            "method: shooting", "method: catenary"
        )
    )
    assert main(["validate", str(path)]) == 2
    assert "stretched diameter" in capsys.readouterr().err
