"""The external checker of mooring systems in dynamics (issue 24;
tests/integration/test_contract_external_system_dynamics.py): small system studies
written as a MoorDyn/OrcaFlex user writes them from DESIGN.md and docs/guide/systems.md,
edited as YAML mappings, run through ``cablestudy run`` and read back from the netCDF
file. The dataset conventions and the output names are checked by
:func:`tests.system_contract.contract_problems`."""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr
import yaml

from cablestudy.cli import main
from tests.system_contract import BRIDLE, run_study

#: the bridle of tests/system_contract.py (a clump with added mass and drag area at a
#: bridle's junction, a buoy at a riser's), as a mapping without analysis.dynamic
BRIDLE_STUDY: dict[str, Any] = yaml.safe_load(BRIDLE % "")

#: a 9-node single leg from an anchor on the seabed to a fairlead 10 m off the hull's
#: reference point (the line touches the seabed: 320 m on a 296 m chord)
ONE_LEG = """\
name: oneleg
environment: {fluid: water, depth: 100.0}
points:
  a1: {kind: fixed, position: [300.0, 0.0, -100.0]}
  f1: {kind: body, body: hull, offset: [10.0, 0.0, -10.0]}
bodies:
  hull: {kind: prescribed, position: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]}
lines:
  l1: {a: a1, b: f1, segments: [{length: 320.0, diameter: 0.1, mass_per_length: 50.0,
      axial_stiffness: 5.0e8}]}
analysis:
  static: {nodes: 9}
"""


def bridle(name: str, *, depth: float = 200.0) -> dict[str, Any]:
    """The bridle study named ``name`` in water ``depth`` deep (its anchors stay at
    z = -200 m: deeper water leaves every line clear of the seabed)."""
    study = copy.deepcopy(BRIDLE_STUDY)
    study["name"] = name
    study["environment"]["depth"] = depth
    return study


def one_leg(name: str) -> dict[str, Any]:
    study = yaml.safe_load(ONE_LEG)
    study["name"] = name
    return study


def time_domain(
    excitation: Any, *, elements: int = 8, steps: int = 32, periods: int = 12, **more: Any
) -> dict[str, Any]:
    """An ``analysis.dynamic`` block of the time domain (few elements and steps)."""
    return {
        "excitation": excitation,
        "method": "time",
        "elements": elements,
        "points_per_period": steps,
        "max_periods": periods,
        **more,
    }


def run(tmp_path: Path, study: dict[str, Any]) -> xr.Dataset:
    """``cablestudy run`` on the study mapping; the dataset it wrote."""
    return run_study(tmp_path, yaml.safe_dump(study, sort_keys=False))


def run_failing(tmp_path: Path, text: str) -> tuple[int, xr.Dataset]:
    """``cablestudy run`` on a study whose cases may all fail: its exit status and the
    dataset it wrote (docs/guide/cli.md: written even then)."""
    name = yaml.safe_load(text)["name"]
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    args = ["run", str(cfg), "--out", str(tmp_path), "--no-cache", "--no-progress"]
    code = main([*args, "--scheduler", "synchronous"])
    return code, xr.load_dataset(tmp_path / f"{name}.nc")


def periodic_table(period: float, values: np.ndarray) -> list[list[float]]:
    """Rows [t, value] of a periodic table over one ``period`` (the last row closes
    it: its value is the first's)."""
    t = np.linspace(0.0, period, len(values))
    vals = np.array(values, dtype=float)
    vals[-1] = vals[0]
    return [[float(a), float(b)] for a, b in zip(t, vals, strict=True)]


def pitched_offset(offset: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Displacement (n, 3) of a body point at ``offset`` (body frame) when the body
    pitches by ``angle`` (n,) rad: R_y(angle) p - p, exact (R_y: x' = x cos + z sin,
    z' = -x sin + z cos)."""
    x, _, z = offset
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([x * c + z * s - x, np.zeros_like(angle), -x * s + z * c - z], axis=-1)
