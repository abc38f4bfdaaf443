"""Modal analysis end to end: YAML study -> `cablestudy run` -> netCDF -> xarray."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import xarray as xr

from cablestudy.cli import main

STUDY = """\
name: modal-e2e
description: Shallow level cable in water, natural frequencies about the static shape
environment:
  fluid: water
  gravity: 9.80665
line:
  segments:
    - length: 100.2
      diameter: 0.05
      mass_per_length: 8.0
      axial_stiffness: 1.0e8
      added_mass_normal: 1.0
ends:
  a: {kind: fixed, position: [0.0, 0.0, -10.0]}
  b: {kind: fixed, position: [100.0, 0.0, -10.0]}
analysis:
  static: {method: analytic, nodes: 51}
  modal: {modes: 10}
sweep:
  line.segments.0.added_mass_normal: [0.0, 1.0]
"""


def test_modal_yaml_to_netcdf(tmp_path: Path) -> None:
    cfg = tmp_path / "study.yaml"
    cfg.write_text(STUDY)
    assert main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous"]) == 0
    ds = xr.load_dataset(tmp_path / "modal-e2e.nc")
    assert (ds["status"] == 0).all()
    f = ds["natural_frequency"]
    assert f.dims == ("added_mass_normal", "mode")
    assert f.attrs["units"] == "Hz"
    np.testing.assert_array_equal(ds["mode"].values, np.arange(1, 11))
    assert np.all(np.diff(f.values, axis=1) >= 0.0)
    assert ds["mode_shape"].dims == ("added_mass_normal", "mode", "s", "component")
    np.testing.assert_allclose(
        np.linalg.norm(ds["mode_shape"].values, axis=-1).max(axis=-1), 1.0, rtol=0.05
    )

    # first mode: out of plane, Irvine's pi sqrt(H / m) / l, m the mass per hanging
    # length plus rho C_a pi d^2 / 4 (the sag here is ~1/90 of the span, so Irvine's
    # O((d/l)^2) error ~ 0.52 (d/l)^2 < 1e-4; discretisation with 200 elements ~ 1e-5)
    rho, d = 1025.0, 0.05
    for ca in (0.0, 1.0):
        case = ds.sel(added_mass_normal=ca)
        H = float(case["force_a"].sel(component="x"))
        arc = float(np.sum(np.hypot(np.diff(case["x"].values), np.diff(case["z"].values))))
        m = 8.0 * 100.2 / arc + rho * ca * math.pi * d**2 / 4
        f1 = math.sqrt(H / m) / (2 * 100.0)
        np.testing.assert_allclose(float(case["natural_frequency"].sel(mode=1)), f1, rtol=5e-4)


def test_modal_config_error_names_field(tmp_path: Path, capsys) -> None:  # noqa: ANN001
    cfg = tmp_path / "bad.yaml"
    cfg.write_text(STUDY.replace("modal: {modes: 10}", "modal: {modes: 10, elements: 2}"))
    assert main(["run", str(cfg), "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "analysis.modal" in err and "elements = 2" in err


RISER = """\
name: riser-modal
description: Vertical riser, bottom tension 1 kN under 36 kN at the top
environment: {fluid: water, gravity: 9.80665}
line:
  segments:
    - {length: LENGTH, diameter: 0.15, mass_per_length: 30.0, axial_stiffness: 1.0e9}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -300.0]}
  b: {kind: fixed, position: [0.0, 0.0, 0.0]}
analysis:
  static: {method: analytic, nodes: 31}
  modal: {modes: 8, elements: 200}
"""


def test_graded_modal_mesh_end_to_end(tmp_path: Path) -> None:
    """The default graded mesh through the whole pipeline: lateral modes of a vertical
    riser against the Bessel roots of the string with linear tension (dataset
    bottom tension). Budget: graded-mesh error (pi n / 200)^2 / 24 times a coefficient
    up to ~30 for a strongly varying tension (measured in the validation tests), i.e.
    < 4e-4, plus the stretch the string equation ignores, T / (2 EA) < 2e-5."""
    from scipy.optimize import brentq

    from cablestudy.dynamics.strings import linear_tension_string

    w = (30.0 - 1025.0 * math.pi * 0.15**2 / 4) * 9.80665
    # unstretched length for T0 = 1 kN: L + (T0 L + w L^2 / 2) / EA = 300 m
    length = brentq(
        lambda L: L + (1000.0 * L + w * L * L / 2) / 1.0e9 - 300.0, 290.0, 300.0, xtol=1e-13
    )
    cfg = tmp_path / "riser.yaml"
    cfg.write_text(RISER.replace("LENGTH", repr(length)))
    assert main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous"]) == 0
    ds = xr.load_dataset(tmp_path / "riser-modal.nc")
    assert int(ds["status"]) == 0
    T0 = float(ds["tension_a"])
    assert abs(T0 - 1000.0) < 1.0
    exact = linear_tension_string(
        length=length,
        bottom_tension=T0,
        weight=w,
        mass=30.0 + 1025.0 * math.pi * 0.15**2 / 4,
        count=4,
    )
    f = ds["natural_frequency"].values
    np.testing.assert_allclose(f[0::2], exact, rtol=5e-4)
    np.testing.assert_allclose(f[1::2], exact, rtol=5e-4)


def test_irvine_study_config_reproduces_irvine(tmp_path: Path) -> None:
    """configs/irvine-modal-lambda.yaml (23 cases, lambda^2 from 1 to 1000 at sag/span
    1/40) run through the CLI: every mode of every case within 1 % of Irvine's
    frequency of its family (measured worst 0.34 %, the O((d/l)^2) term), and lambda^2
    recomputed from the results spans 1 ... 1000."""
    from cablestudy.dynamics import irvine
    from cablestudy.figures.modal_figures import classify

    cfg = Path(__file__).resolve().parents[2] / "configs" / "irvine-modal-lambda.yaml"
    assert main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous"]) == 0
    ds = xr.load_dataset(tmp_path / "irvine-modal-lambda.nc")
    assert (ds["status"] == 0).all()
    lambdas = []
    for i in range(ds.sizes["lambda_squared"]):
        case = ds.isel(lambda_squared=i)
        EA = float(case["lambda_squared_axial_stiffness"])
        L0 = float(case["lambda_squared_length"])
        H = float(case["force_a"].sel(component="x"))
        T, s = case["tension"].values, case["arc_length"].values
        effective_length = float(np.trapezoid((T / H) ** 2 * (1 + T / EA), s))
        lam2 = irvine.cable_parameter(
            span=100.0,
            weight=9.80665,
            horizontal_tension=H,
            axial_stiffness=EA,
            effective_length=effective_length,
        )
        lambdas.append(lam2)
        arc = float(np.sum(np.hypot(np.diff(case["x"].values), np.diff(case["z"].values))))
        f_unit = math.sqrt(H / (L0 / arc)) / (2 * math.pi * 100.0)  # omega_bar = 1
        expected = irvine.frequencies(lam2, 8)
        found: dict[str, list[float]] = {}
        shapes = case["mode_shape"].values
        for f, shape in zip(case["natural_frequency"].values, shapes, strict=True):
            found.setdefault(classify(shape), []).append(float(f))
        assert "longitudinal" not in found
        for family, f in found.items():
            ref = expected[family][: len(f)] * f_unit
            np.testing.assert_allclose(f, ref, rtol=0.01, err_msg=f"{family} at {lam2}")
    assert min(lambdas) < 1.01 and max(lambdas) > 990.0


def test_modal_needs_positive_mass(tmp_path: Path, capsys) -> None:  # noqa: ANN001
    cfg = tmp_path / "massless.yaml"
    cfg.write_text(STUDY.replace("mass_per_length: 8.0", "mass_per_length: 0.0"))
    assert main(["run", str(cfg), "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "line.segments.0.mass_per_length" in err and "analysis.modal" in err
