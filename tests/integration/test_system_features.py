"""System features from YAML to netCDF through `cablestudy run`: lines with bending
stiffness by method discrete, and current drag on the lines and on free points."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cases import expand_cases
from cablestudy.cli import main
from cablestudy.config import parse_study_text
from cablestudy.statics import STATIC_SOLVERS
from cablestudy.statics.system_methods import solve_system_by
from cablestudy.system_cases import system_model
from tests.integration.test_system_study import SYSTEM

RHO, G = 1025.0, 9.80665

#: the integration system (legs on the seabed, a clump, a bridle, a body) with EI on
#: every line, by method discrete, and the body offset by -1 cm, 0, +1 cm in surge
BENDING = (
    SYSTEM.replace("axial_stiffness: 5.0e8}", "axial_stiffness: 5.0e8, bending_stiffness: 2.0e5}")
    .replace("static: {nodes: 11", "static: {method: discrete, nodes: 41")
    .replace("{start: -2.0, stop: 2.0, num: 9, name: surge}", "{values: [-0.01, 0.0, 0.01]}")
)


def run(tmp: Path, text: str, name: str) -> xr.Dataset:
    cfg = tmp / f"{name}.yaml"
    cfg.write_text(text.replace("name: sys", f"name: {name}", 1))
    args = ["run", str(cfg), "--out", str(tmp), "--no-cache", "--no-progress"]
    assert main([*args, "--scheduler", "synchronous"]) == 0
    return xr.load_dataset(tmp / f"{name}.nc")


@pytest.fixture(scope="module")
def bending(tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    return run(tmp_path_factory.mktemp("bending"), BENDING, "bending")


def test_bending_system_runs_end_to_end_as_the_solver_gives_it(bending: xr.Dataset) -> None:
    ds = bending
    assert np.all(ds["status"] == 0), ds["message"].values
    assert "method: discrete" in ds.attrs["study_yaml"]
    assert ds.sizes["s"] == 41
    _, cases = expand_cases(parse_study_text(BENDING, "bending.yaml"))
    res = solve_system_by(system_model(cases[1].study), "discrete", STATIC_SOLVERS)
    here = ds.isel({ds["body_force"].dims[0]: 1})
    np.testing.assert_array_equal(here["body_force"].values[0], res.body_force[0])
    np.testing.assert_array_equal(here["body_stiffness"].values[0], res.body_stiffness[0])
    # the clump is in equilibrium under the lines' pull, its weight and its buoyancy
    f = here["force_b"].sel(line=["leg1", "leg2"]).sum("line") + here["force_a"].sel(line="bridle")
    load = np.array([0.0, 0.0, -(3000.0 - RHO * 0.2) * G])
    scale = float(here["tension_a"].max())
    # the system's tolerance 1e-11 of the largest tension, the lines' own to 1e-11
    np.testing.assert_allclose(f.values + load, 0.0, atol=1e-9 * scale)


def test_bending_system_stiffness_is_the_derivative_of_its_force(bending: xr.Dataset) -> None:
    """The central difference of body_force over the +-1 cm surge offsets against the
    analytic body_stiffness at 0: the difference errs by d^2 F''' / 6 ~ K (d / l)^2 with
    l >= 10 m the shortest length over which the lines' stiffness changes (the fairlead
    depth; the mesh's 7 m elements on the seabed): 1e-6 of the column; 1e-5 asked."""
    F = bending["body_force"].sel(body="buoy").values
    K = bending["body_stiffness"].sel(body="buoy").values[1]
    central = -(F[2] - F[0]) / 0.02
    scale = float(np.max(np.abs(K[:, 0])))
    assert np.max(np.abs(central - K[:, 0])) <= 1e-5 * scale
