"""A lazy-wave riser in statics, YAML -> netCDF.

Three segments of 250 / 150 / 300 m (diameter 0.3 m, 180 kg/m) from the fairlead (end A,
20 m below the surface) to the anchor on the seabed (end B, 450 m off, 300 m deep), five
buoyancy modules (8 m^3, 1500 kg) at s = 270 ... 390 m. The seabed-contact Newton of
method 'catenary' started from the uniform line's guess, which ignores the modules' lift
and put the touchdown point (TDP) among the modules; a module cannot lie on the seabed,
the residual jumps where the TDP crosses one, and the line search failed there ("line
search failed in the seabed-contact Newton iteration (residual 0.076)"; 'discrete',
which starts from it, failed too). Now the TDP is kept short of the first module
(:func:`cablestudy.statics.contact_pin.first_lift`).

Checks: status 0 with 'catenary' and 'shooting' (independent methods: closed-form
segment increments with Newton on the end forces, against an ODE integrated from the
TDP) and their agreement; the modules hang above the seabed; the whole-line vertical
balance; and with 4 m^3 modules (the line between them lies on the seabed, each module
lifting an arch: one laid part from the anchor cannot represent it) 'catenary' does
not claim status 0 while 'discrete', started from its state, still solves it.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main

G = 9.80665
RHO = 1025.0
L = 700.0
MODULES = [270.0, 300.0, 330.0, 360.0, 390.0]
EA = 1.0e9

STUDY = """\
name: {name}
description: lazy-wave riser, five buoyancy modules
environment:
  fluid: water
  depth: 300.0
line:
  segments:
    - {{length: 250.0, diameter: 0.3, mass_per_length: 180.0, axial_stiffness: {ea}}}
    - {{length: 150.0, diameter: 0.3, mass_per_length: 180.0, axial_stiffness: {ea}}}
    - {{length: 300.0, diameter: 0.3, mass_per_length: 180.0, axial_stiffness: {ea}}}
  attachments:
{modules}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, -20.0]}}
  b: {{kind: fixed, position: [450.0, 0.0, -300.0]}}
analysis:
  static: {{nodes: 71}}
sweep:
  analysis.static.method: {methods}
"""


def _run(tmp_path: Path, name: str, volume: float, methods: list[str]) -> xr.Dataset:
    modules = "\n".join(
        f"    - {{s: {s}, mass: 1500.0, volume: {volume}, name: m{i}}}"
        for i, s in enumerate(MODULES)
    )
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(
        STUDY.format(name=name, ea=EA, modules=modules, methods="[" + ", ".join(methods) + "]")
    )
    out = tmp_path / name
    assert main(["run", str(cfg), "--out", str(out), "--no-cache"]) == 0
    return xr.load_dataset(out / f"{name}.nc")


def _by_method(ds: xr.Dataset, method: str) -> xr.Dataset:
    dim = next(d for d in ds["status"].dims)
    values = [str(v) for v in ds[dim].values]
    return ds.isel({dim: values.index(method)})


def test_lazy_wave_solves_with_catenary_and_agrees_with_shooting(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    ds = _run(tmp_path, "lazywave", 8.0, ["catenary", "shooting"])
    capsys.readouterr()
    assert np.all(ds["status"] == 0), ds["message"].values
    cat, sho = _by_method(ds, "catenary"), _by_method(ds, "shooting")

    # weight in water per metre and the modules' net lift
    w = (180.0 - RHO * np.pi / 4.0 * 0.3**2) * G
    lift = (RHO * 8.0 - 1500.0) * G * len(MODULES)
    for r in (cat, sho):
        laid = float(r["laid_length"])
        # the laid stretch ends before the modules (counted from the anchor, s = 700)
        assert 0.0 < laid < L - max(MODULES)
        # the modules hang clear of the seabed (z = -300)
        z_mod = r["z"].sel(s=MODULES).values
        assert np.all(z_mod > -300.0 + 1.0), z_mod
        # whole-line vertical balance: the ends hold up (-force) and the seabed carries
        # the laid line's weight w * laid (flat seabed, unstretched length); together
        # they carry the line's weight in water less the modules' lift. Exact for both
        # methods up to round-off of sums of ~1e6 N (1e-8 relative is far above it)
        held = -float(r["force_a"].sel(component="z") + r["force_b"].sel(component="z"))
        np.testing.assert_allclose(held + w * laid, w * L - lift, rtol=1e-8)

    # the two methods against each other: both meet the end position to a relative
    # residual of tol = 1e-9 (the default) of the line length, 7e-7 m; the end force
    # responds to an end displacement at most with the line's axial stiffness over its
    # suspended length (~2e6 N/m; the catenary's geometric stiffness is smaller), so
    # each force is within ~1.4 N, the two within ~3 N of each other: 2e-5 relative of
    # the 217 kN fairlead tension
    for f in ("force_a", "force_b"):
        np.testing.assert_allclose(cat[f].values, sho[f].values, rtol=0, atol=3.0)
    np.testing.assert_allclose(float(cat["tension_a"]), float(sho["tension_a"]), rtol=2e-5)
    # the laid length follows from the vertical balance above: laid = (W - lift - V) / w,
    # so 3 N on the vertical end forces moves it by 3 N / w ~ 3e-3 m
    np.testing.assert_allclose(float(cat["laid_length"]), float(sho["laid_length"]), atol=3e-3)


def test_lazy_wave_with_modules_resting_on_the_seabed(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # 4 m^3 modules lift 25.5 kN each, less than the 31.6 kN the 30 m of line between
    # them weigh: the line between them rests on the seabed and each module lifts it in
    # an arch, laid stretches between lifted ones. 'catenary' (one laid part from the
    # anchor) cannot represent that and must not claim status 0; 'discrete', started
    # from catenary's state, solves it
    ds = _run(tmp_path, "lazywave4", 4.0, ["catenary", "discrete"])
    capsys.readouterr()
    cat, dis = _by_method(ds, "catenary"), _by_method(ds, "discrete")
    assert int(cat["status"]) != 0 and str(cat["message"].values), cat["message"].values
    assert int(dis["status"]) == 0, dis["message"].values
    # the modules are lifted clear of the seabed (z = -300) ...
    z_mod = dis["z"].sel(s=MODULES).values
    assert np.all(z_mod > -300.0 + 1.0), z_mod
    # ... and the line between the last ones lies on it: discrete's seabed is a penalty
    # contact, its nodes there sink by the weight over the seabed stiffness (< 1e-2 m)
    between = dis["z"].sel(s=slice(MODULES[2] + 1.0, MODULES[-1] - 1.0)).values
    assert np.min(np.abs(between + 300.0)) < 1e-2, between
