"""End to end (YAML -> netCDF) for the slope-slack refusal of a line resting on the
seabed between two raised ends (tests/stress/test_seabed_slope_slack.py has the closed
form): the 120 m line over a flat seabed (shorter than its path down, along and up,
120.7 m: taut, status 0 and verified) and over the 1 deg slope (longer than its taut
shape there, 117.69 m: slack down the slope), recorded failed with its reason and NaN
while the study carries on.

(A line short enough to rest taut on that slope converges in the solver but the
pipeline's whole-line force balance flags it, status 11: the frictionless straight laid
part does not carry the weight's across-slope component, w sin(slope) per metre; a
separate, pre-existing gap.)"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from cablestudy.cli import main

STUDY = """\
name: slope-slack
environment:
  fluid: water
  depth: 100.0
  seabed: {slope_deg: -1.0, slope_heading_deg: -114.59155902616465}
line:
  segments:
    - {length: 120.0, diameter: 0.08, weight_in_fluid: 10.0, mass_per_length: 2.0,
       axial_stiffness: 1.0e6}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -90.0]}
  b: {kind: fixed, position: [-34.33211402, 75.01703771, -71.05872517]}
analysis:
  static: {method: catenary, nodes: 61}
sweep:
  environment.seabed.slope_deg: [0.0, -1.0]
"""


def test_slope_slack_through_the_cli(tmp_path: Path) -> None:
    cfg = tmp_path / "slope-slack.yaml"
    cfg.write_text(STUDY)
    out = tmp_path / "out"
    assert main(["run", str(cfg), "--out", str(out), "--no-cache"]) == 0
    ds = xr.load_dataset(out / "slope-slack.nc")
    status = np.asarray(ds["status"]).ravel()
    assert status[0] == 0
    assert status[1] != 0
    message = str(np.asarray(ds["message"]).ravel()[1])
    assert "slack" in message and "slope" in message, message
    assert np.all(np.isnan(np.asarray(ds["tension_a"])[1]))
    assert float(np.asarray(ds["laid_length"])[0]) > 0.0
