"""A clump weight at the touchdown point of a laid chain + wire mooring, YAML -> netCDF.

For a finite range of fairlead positions the touchdown point (TDP) stays at the clump
while the seabed carries part R of its weight (0 <= R <= W): the line lies straight on
the seabed up to the clump and leaves it there with a kink. Before the pinned contact
state (:mod:`cablestudy.statics.contact_pin`) the seabed-contact Newton's residual jumped
as the TDP crossed the clump and these cases failed with "line search failed in the
seabed-contact Newton iteration" (2,695 of 2,696 such cases in a 2,000-case sweep).

Checks: the cases solve with status 0 and the TDP at the clump; the suspended part,
solved on its own as a free-hanging wire from the clump's position, gives the same
fairlead force (an independent solve); the seabed reaction lies in [0, W]; the anchor
tension equals the fairlead's horizontal tension less the friction on the laid line and
on the clump (mu R); and the fairlead tension is continuous as the fairlead moves the
TDP onto, along and off the clump; with the clump hanging, MoorPy (a point of that
mass between lines) gives the same fairlead force and clump position.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main

G = 9.80665
MU = 0.02  # low enough that the anchor keeps tension (the check below)
W_CLUMP = 5000.0 * G  # no displaced volume: its weight in water [N]
W_CHAIN, W_WIRE = 981.0, 240.0  # [N/m] weight in the fluid
CLUMP_S = 640.0

STUDY = """\
name: {name}
description: chain + wire mooring with a 5 t clump at the touchdown point
environment:
  fluid: water
  depth: 200.0
  seabed: {{friction: {mu}}}
line:
  segments:
{segments}
{attachments}
ends:
  a: {{kind: fixed, position: [{xa}, 0.0, -200.0]}}
  b: {{kind: fixed, position: [820.0, 0.0, -20.0]}}
analysis:
  static: {{nodes: {nodes}}}
sweep:
  ends.b.position.0: {xs}
"""
CHAIN = (
    "    - {length: 500.0, diameter: 0.137, mass_per_length: 115.0, weight_in_fluid: 981.0,"
    " axial_stiffness: 4.9e+8}\n"
)
WIRE = (
    "    - {{length: {length}, diameter: 0.076, mass_per_length: 29.0, weight_in_fluid: 240.0,"
    " axial_stiffness: 5.2e+8}}\n"
)


def _run(tmp_path: Path, name: str, xs: list[float], **kw: object) -> xr.Dataset:
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(STUDY.format(name=name, xs=xs, **kw))
    out = tmp_path / name
    assert main(["run", str(cfg), "--out", str(out), "--no-cache"]) == 0
    return xr.load_dataset(out / f"{name}.nc")


def _full(tmp_path: Path, xs: list[float], mu: float = MU) -> xr.Dataset:
    return _run(
        tmp_path,
        "clump",
        xs,
        mu=mu,
        segments=CHAIN + WIRE.format(length=400.0),
        attachments=f"  attachments:\n    - {{s: {CLUMP_S}, mass: 5000.0, name: clump}}",
        xa=0.0,
        nodes=46,  # samples every 20 m: one at the clump
    )


def test_clump_pinned_at_touchdown_matches_its_suspended_part_alone(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # the fairlead positions of the sweep that failed on main with the clump at s = 640
    xs = [810.0, 815.0, 820.0, 825.0]
    full = _full(tmp_path, xs)
    assert np.all(full["status"] == 0), full["message"].values
    # the TDP is held at the clump (round-off of the solved TDP coordinate)
    np.testing.assert_allclose(full["laid_length"].values, CLUMP_S, rtol=0, atol=1e-9)
    at = full.sel(s=CLUMP_S)
    np.testing.assert_allclose(at["z"].values, -200.0, rtol=0, atol=1e-9)

    # the suspended 260 m of wire on its own, hanging from the clump's solved position
    part = [
        _run(
            tmp_path,
            f"part{i}",
            [x],
            mu=MU,
            segments=WIRE.format(length=900.0 - CLUMP_S),
            attachments="",
            xa=float(at["x"].values[i]),
            nodes=11,
        )
        for i, x in enumerate(xs)
    ]
    capsys.readouterr()
    fb_part = np.array([p["force_b"].values[0] for p in part])
    fa_part = np.array([p["force_a"].values[0] for p in part])
    assert all(np.all(p["status"] == 0) for p in part)
    # both solves meet a relative residual ~1e-9 of the line length on positions; the
    # fairlead force of a taut catenary amplifies that by its stiffness over its
    # tension (< 1e3 here): 1e-6 relative is a safe margin above both
    np.testing.assert_allclose(full["force_b"].values, fb_part, rtol=1e-6)
    # the wire pulls the clump up by V; the seabed carries the rest R = W - V of the
    # clump's weight: 0 < R < W strictly inside the pinned range, and the fairlead
    # moving away lifts more of it (R decreasing)
    V = np.abs(fa_part[:, 2])  # the wire's vertical pull on the clump
    R = W_CLUMP - V
    assert np.all(R > 0.0) and np.all(R < W_CLUMP), R
    assert np.all(np.diff(R) < 0.0), R
    # anchor tension: the horizontal tension H, less friction mu w per metre of laid
    # line (500 m chain, 140 m wire) and mu R at the clump (straight, flat seabed, still
    # water: the laid line carries tension along x only). Exact for this model; the
    # tolerance is the solve's relative residual times H.
    H = np.abs(full["force_b"].values[:, 0])
    expected = H - MU * (500.0 * W_CHAIN + 140.0 * W_WIRE + R)
    assert np.all(expected > 0.0)
    np.testing.assert_allclose(np.abs(full["force_a"].values[:, 0]), expected, rtol=1e-6)


def test_fairlead_tension_continuous_as_the_clump_lifts_off_the_seabed(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # the reported study's friction (0.5); the fairlead moves 2 m in 0.1 m steps from the
    # clump lying at the TDP (pinned, part of its weight on the seabed) to the clump
    # hanging and the TDP moved back towards the anchor
    xs = [float(x) for x in np.linspace(824.0, 826.0, 21)]
    ds = _full(tmp_path, xs, mu=0.5)
    capsys.readouterr()
    assert np.all(ds["status"] == 0), ds["message"].values
    laid = ds["laid_length"].values
    pinned = np.abs(laid - CLUMP_S) <= 1e-9
    # both states are in the sweep: pinned first, then lifted (TDP before the clump)
    assert pinned[0] and not pinned[-1] and np.all(laid[~pinned] < CLUMP_S)
    assert np.all(np.diff(laid) <= 1e-9)
    T = ds["tension_b"].values
    dT = np.diff(T)
    assert np.all(dT > 0.0)
    # continuity across lift-off: no increment stands out of the local slope. A jump
    # like the one the friction on the clump would make if the pinned state were not
    # continuous at its ends (mu W = 24.5 kN) would be 10x the largest 0.1 m increment
    # here (~2 kN); the slope only drops at lift-off (the TDP starts to move back and
    # the suspended length grows) and varies by < 2x over these 2 m, so 2x the median
    # increment bounds every increment of a continuous curve
    assert dT.max() <= 2.0 * np.median(dT), dT


def test_suspended_clump_matches_moorpy(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # the clump hanging 100 m from the fairlead, no friction: MoorPy (NREL) with the
    # line as three lines (chain, wire to the clump, wire to the fairlead) between an
    # anchor, a free massless point, the free 5 t clump and the fixed fairlead
    import moorpy

    ds = _run(
        tmp_path,
        "hung",
        [820.0],
        mu=0.0,
        segments=CHAIN + WIRE.format(length=400.0),
        attachments="  attachments:\n    - {s: 800.0, mass: 5000.0, name: clump}",
        xa=0.0,
        nodes=46,
    ).isel(position_0=0)
    capsys.readouterr()
    assert int(ds["status"]) == 0 and float(ds["laid_length"]) < 800.0  # clump hangs

    rho = 1025.0
    ms = moorpy.System(depth=200.0, rho=rho, g=G)
    for name, mass, w, ea, dnom in (
        ("chain", 115.0, W_CHAIN, 4.9e8, 137.0),
        ("wire", 29.0, W_WIRE, 5.2e8, 76.0),
    ):
        d_vol = float(np.sqrt((mass - w / G) / rho * 4.0 / np.pi))
        ms.setLineType(dnommm=dnom, d_vol=d_vol, mass=mass, w=w, EA=ea, name=name)
    ms.addPoint(1, [0.0, 0.0, -200.0])
    ms.addPoint(0, [480.0, 0.0, -200.0])
    ms.addPoint(0, [700.0, 0.0, -120.0], m=5000.0, v=0.0)
    ms.addPoint(1, [820.0, 0.0, -20.0])
    ms.addLine(500.0, "chain", pointA=1, pointB=2)
    ms.addLine(300.0, "wire", pointA=2, pointB=3)
    ms.addLine(100.0, "wire", pointA=3, pointB=4)
    ms.initialize()
    ms.solveEquilibrium(tol=1e-6)
    # MoorPy's equilibrium tolerance 1e-6 m on the free points; the line is ~1e3 times
    # stiffer in force than that over its tension (a few 1e5 N/m at ~1e5 N): 1e-5
    # relative on forces, 1e-4 m on the clump's position bound both answers' errors
    np.testing.assert_allclose(ds["force_b"].values, ms.lineList[2].fB, rtol=1e-5)
    clump = [float(ds["x"].sel(s=800.0)), float(ds["z"].sel(s=800.0))]
    np.testing.assert_allclose(clump, ms.pointList[2].r[[0, 2]], rtol=0, atol=1e-4)
