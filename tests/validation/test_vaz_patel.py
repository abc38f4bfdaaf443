"""The vaz-patel seed's static examples as studies (configs/vaz-patel-*.yaml), run from
YAML to netCDF with the shooting solver, and the one table of numbers the seed copy
prints (Table 1, the HA cable)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from cablestudy.cli import main

CONFIGS = Path(__file__).resolve().parents[2] / "configs"


def test_table1_ha_cable_is_consistent_with_buoyancy() -> None:
    """Seed Table 1: weight in air 26.49 N/m, in sea 17.76 N/m, diameter 0.0332 m. The
    difference is the buoyancy rho g pi d^2 / 4 of sea water (1025 kg/m^3): 8.70 N/m
    against the printed 8.73 N/m, agreeing to the 3 printed digits of the diameter
    (a relative error of 0.15 % in d, i.e. 0.3 % in the area). The study uses the printed
    weights themselves."""
    rho, g, d = 1025.0, 9.80665, 0.0332
    buoyancy = rho * g * math.pi * d * d / 4.0
    assert buoyancy == pytest.approx(26.49 - 17.76, rel=4e-3)
    seg = yaml.safe_load((CONFIGS / "vaz-patel-turning-current.yaml").read_text())
    seg = seg["line"]["segments"][0]
    assert seg["weight_in_fluid"] == 17.76
    assert seg["mass_per_length"] * g == pytest.approx(26.49, rel=1e-4)
    assert seg["diameter"] == d and seg["drag_normal"] == 1.649


@pytest.fixture(scope="module")
def results(tmp_path_factory: pytest.TempPathFactory) -> dict[str, xr.Dataset]:
    out = tmp_path_factory.mktemp("vaz-patel")
    data = {}
    for name in (
        "vaz-patel-segmented-mooring",
        "vaz-patel-turning-current",
        "vaz-patel-cable-installation",
    ):
        assert main(["run", str(CONFIGS / f"{name}.yaml"), "--out", str(out)]) == 0
        data[name] = xr.load_dataset(out / f"{name}.nc")
    return data


def test_segmented_mooring(results: dict[str, xr.Dataset]) -> None:
    """Every heading converges; the fairlead and anchor are where the study puts them;
    the laid length starts at the anchor (z = -depth); friction (mu = 1) exceeds the
    touchdown tension, so the anchor tension is zero (the quasi-static convention); the
    cross current (90 deg) moves the line out of the x-z plane, the in-line ones do not;
    tension is continuous across the chain-polyester joints (no point loads there)."""
    ds = results["vaz-patel-segmented-mooring"]
    assert ds["status"].values.tolist() == [0, 0, 0], ds["message"].values
    assert np.allclose(ds["x"].values[:, -1], 1650.0, atol=1e-6)
    assert np.allclose(ds["z"].values[:, -1], -20.0, atol=1e-6)
    assert np.allclose(ds["z"].values[:, 0], -1000.0, atol=1e-9)
    laid = ds["laid_length"].values
    assert np.all((laid > 100.0) & (laid < 400.0))  # inside the bottom chain
    for i, lb in enumerate(laid):
        on = ds["s"].values <= lb
        assert np.allclose(ds["z"].values[i, on], -1000.0, atol=1e-9)
    assert np.allclose(ds["force_a"].values, 0.0)
    y_max = np.max(np.abs(ds["y"].values), axis=1)
    assert y_max[1] > 10.0 and y_max[0] < 1e-6 and y_max[2] < 1e-6
    s = ds["s"].values
    for joint in (400.0, 1800.0):
        i = int(np.argmin(np.abs(s - joint)))
        jump = np.abs(ds["tension"].values[:, i + 1] - ds["tension"].values[:, i - 1])
        assert np.all(jump < 0.05 * ds["tension"].values[:, i])  # two 5 m steps of chain


def test_turning_current_cable(results: dict[str, xr.Dataset]) -> None:
    """The ship holds 2 kN along +x at the surface (the mooring-end condition holds); with
    the lower current in the same plane the cable stays in the x-z plane; turned to 45
    and 90 deg it leaves it further and further; above 300 m the current is along x,
    so there the cable does not bend sideways (its y is constant to the y-drag of the
    transition layer, checked as a small change over the top 250 m)."""
    ds = results["vaz-patel-turning-current"]
    assert ds["status"].values.tolist() == [0, 0, 0], ds["message"].values
    fb = ds["force_b"].values
    # the solver's force residual is relative to the line's weight, w L = 44.4 kN
    assert np.allclose(fb[:, 0], -2000.0, rtol=0.0, atol=1e-9 * 17.76 * 2500.0)
    assert np.allclose(fb[:, 1], 0.0, atol=1e-9 * 17.76 * 2500.0)
    assert np.allclose(ds["z"].values[:, -1], 0.0, atol=1e-6)
    y_top = ds["y"].values[:, -1]
    assert abs(y_top[0]) < 1e-6 and 100.0 < y_top[1] < y_top[2]
    z = ds["z"].values
    for i in (1, 2):
        upper = z[i] > -250.0
        assert np.ptp(ds["y"].values[i, upper]) < 0.05 * abs(y_top[i])
    # the weight balance: the vertical force at the ship equals the weight of the
    # suspended length (drag of a horizontal current has no vertical part on a
    # horizontal line, but on the inclined suspended part it does, so compare loosely)
    w = 17.76
    suspended = 2500.0 - ds["laid_length"].values
    assert np.allclose(-fb[:, 2], w * suspended, rtol=0.05)


def test_cable_installation(results: dict[str, xr.Dataset]) -> None:
    """Steady laying, seen from the ship: the water flows aft at the ship speed, so
    above the touchdown point the suspended cable turns from the horizontal towards
    Pode's critical angle for that flow, cos(phi)/sin^2(phi) = 1/2 rho Cn d U^2 / w
    (42.9 deg), which attracts it as the tension grows (the deviation decays like a
    power of the tension, slowly here since T grows by only ~30 % over the upper half):
    the angle rises monotonically, stays below phi and ends within 2 deg of it at the
    ship; the ship's horizontal force is held; a transverse current pushes the cable
    sideways, more for a faster current."""
    ds = results["vaz-patel-cable-installation"]
    assert ds["status"].values.tolist() == [0, 0, 0, 0], ds["message"].values
    still = ds.isel(speed=0)
    k = 0.5 * 1025.0 * 1.649 * 0.0332 * 1.0**2 / 17.76
    phi = math.acos((-1.0 + math.sqrt(1.0 + 4.0 * k * k)) / (2.0 * k))
    z = still["z"].values
    upper = z > -500.0
    dx = np.diff(still["x"].values)[upper[1:]]
    dz = np.diff(z)[upper[1:]]
    angle = np.arctan2(dz, dx)
    assert np.all(np.diff(angle) > 0.0) and np.all(angle < phi)
    assert phi - angle[-1] < math.radians(2.0)
    assert np.allclose(ds["force_b"].values[:, 0], -25000.0, rtol=1e-8)
    y_ship = ds["y"].values[:, -1]
    assert abs(y_ship[0]) < 1e-6 and np.all(np.diff(y_ship) > 50.0)


def test_figures_build(results: dict[str, xr.Dataset], tmp_path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    from cablestudy.figures import vaz_patel_figures

    for builder in (
        vaz_patel_figures.mooring,
        vaz_patel_figures.turning_current,
        vaz_patel_figures.cable_installation,
    ):
        path = builder(results, tmp_path)
        assert path.exists() and path.stat().st_size > 10_000
