"""System statics from starts where a line lies slack, and system legs with a clump at
their touchdown, YAML -> netCDF through the CLI.

Before (main at stop 28): a free point started where one of its lines would lie slack on
the seabed failed ("... lies slack on the seabed and its laid shape is not determined")
although a taut equilibrium exists (the guide's own example from its clump at
(-60, 0, -60): 5 of 5 cases; MoorPy's case8 with one junction moved down: 6 of 6); and a
leg whose touchdown came to rest at a 5 t clump did not converge ("free-point
equilibrium did not converge in 100 iterations"). Checks: every start of a grid of
starts (slack, taut, placed too high) reaches the same equilibrium; the moved case8
equals the case8 from its file's start and MoorPy's ``solveEquilibrium`` from the
moved start; the clump leg solves at every offset with the junction in equilibrium; a
free body started where one of its lines is slack reaches the pose of a taut start."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from cablestudy.cli import main

G = 9.80665
RHO = 1025.0
SEG = "{length: %s, diameter: 0.1, mass_per_length: 100.0, axial_stiffness: 5.0e8}"

#: the guide's example (docs/guide/systems.md): a 280 m leg from an anchor to a 3 t clump,
#: a 70 m bridle from the clump to a body fairlead; the clump's start swept
CLUMP = """\
name: NAME
environment: {fluid: water, depth: 100.0}
points:
  anchor1: {kind: fixed, position: [-300.0, 0.0, -100.0]}
  clump:   {kind: free, position: [-60.0, 0.0, -60.0], mass: 3000.0, volume: 0.2}
  fair1:   {kind: body, body: buoy, offset: [-5.0, 0.0, -10.0]}
bodies:
  buoy: {kind: prescribed, position: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]}
lines:
  leg1:   {a: anchor1, b: clump, segments: [LEG]}
  bridle: {a: clump, b: fair1, segments: [BRIDLE]}
sweep:
SWEEP
"""


def _run(tmp_path: Path, name: str, text: str) -> xr.Dataset:
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    out = tmp_path / name
    assert main(["run", str(cfg), "--out", str(out), "--no-cache"]) == 0
    return xr.load_dataset(out / f"{name}.nc")


def test_every_start_reaches_the_same_taut_equilibrium(tmp_path: Path) -> None:
    # starts from x = -200 to -10, z = -98 (near the seabed) to -5 (near the surface).
    # leg1's seabed path from its anchor at x = -300 plus the rise is 102, 140, 195, 197
    # and 235 m from (-200, -98), (-200, -60), (-200, -5), (-105, -98), (-105, -60):
    # shorter than its 280 m, so leg1 lies slack at those starts; 280 m from (-60, -60)
    # (the guide's start, just slack); from (-10, -5) both lines are stretched far past
    # their length (the clump placed too high)
    sweep = (
        "  points.clump.position.0: [-200.0, -105.0, -60.0, -10.0]\n"
        "  points.clump.position.2: [-98.0, -60.0, -5.0]\n"
    )
    text = CLUMP.replace("NAME", "starts").replace("SWEEP", sweep)
    text = text.replace("LEG", SEG % 280.0).replace("BRIDLE", SEG % 70.0)
    ds = _run(tmp_path, "starts", text)
    assert np.all(ds["status"].values == 0), ds["message"].values
    # the compiled system Newton takes every start (slack lines included): no fallback
    assert not any("fallback" in str(w) for w in ds["warning"].values.ravel())
    pos = ds["point_position"].sel(point="clump").values  # (x0, z0, 3)
    ref = pos[2, 0]  # the start (-60, 0, -60): the guide's
    # the equilibrium's net force is below the system tolerance (1e-9 of the largest
    # tension T); the clump hangs from the taut bridle, whose softest restoring
    # stiffness is the pendulum's T_bridle / L_bridle: positions agree to 1e-9 T / (T /
    # 70 m) = 7e-8 m, and the Newton's polishing step gives far better
    T = float(ds["tension_b"].sel(line="bridle").max())
    k_pend = float(ds["tension_b"].sel(line="bridle").min()) / 70.0
    tol = 1e-9 * T / k_pend
    assert np.max(np.abs(pos - ref)) <= tol, np.max(np.abs(pos - ref))
    # the taut equilibrium: leg1 lies partly on the seabed, its touchdown tension > 0
    assert float(ds["tension_a"].sel(line="leg1").min()) > 0.0
    # the clump's balance from the lines' end forces: weight 3000 g less buoyancy 0.2 rho g
    net = (
        ds["force_b"].sel(line="leg1").values
        + ds["force_a"].sel(line="bridle").values
        + np.array([0.0, 0.0, -(3000.0 - RHO * 0.2) * G])
    )
    assert np.max(np.abs(net)) <= 1e-8 * T


def test_case8_with_a_junction_started_slack_matches_its_file_start_and_moorpy(
    tmp_path: Path,
) -> None:
    base = Path(__file__).resolve().parents[2] / "configs" / "system-spread-bridles.yaml"
    text = base.read_text().replace(
        "bodies.spar.position.0: {start: 0.0, stop: 10.0, num: 6, name: surge}",
        "bodies.spar.position.0: {start: 0.0, stop: 10.0, num: 2, name: surge}",
    )
    moved = text.replace(
        "junction1: {kind: free, position: [34.64, -20.0, -50.0]}",
        "junction1: {kind: free, position: [50.0, -29.0, -88.0]}",
    )
    assert moved != text
    ref = _run(tmp_path, "file", text.replace("name: system-spread-bridles", "name: file"))
    ds = _run(tmp_path, "moved", moved.replace("name: system-spread-bridles", "name: moved"))
    assert np.all(ds["status"].values == 0), ds["message"].values
    # leg1 (160 m) from anchor1 (172.7, -100, -100) to (50, -29, -88): the seabed path
    # 141.8 m plus the 12 m rise is 153.8 m < 160 m: slack at the start
    assert np.hypot(172.7 - 50.0, -100.0 + 29.0) + 12.0 < 160.0
    # both solves converge to 1e-10 of the largest tension (the config's tolerance) on
    # junctions held by polyester legs of stiffness ~ EA / L = 3e7 / 160 ~ 2e5 N/m
    # axially, a pendulum's T / L ~ 1e5 N / 45 m ~ 2e3 N/m across: ~1e-10 * 1e6 N / 2e3
    # N/m = 5e-8 m on positions, 1e-9 relative on forces
    np.testing.assert_allclose(ds["point_position"], ref["point_position"], rtol=0, atol=5e-8)
    scale = float(np.max(np.abs(ref["body_force"].values)))
    np.testing.assert_allclose(ds["body_force"], ref["body_force"], rtol=0, atol=1e-9 * scale)

    import moorpy

    ms = moorpy.System(
        file=str(Path(__file__).resolve().parents[1] / "data" / "moorpy" / "tests" / "case8.dat"),
        rho=1025.0,
        g=9.81,
    )
    ms.pointList[3].setPosition([50.0, -29.0, -88.0])
    ms.initialize()
    assert ms.solveEquilibrium(tol=1e-9)
    at0 = ds.isel(surge=0)
    # MoorPy's tolerance 1e-9 m on the points, its catenary to ~1e-10 relative: 1e-7 m
    for name, k in (("junction1", 3), ("junction2", 7), ("junction3", 11)):
        np.testing.assert_allclose(
            at0["point_position"].sel(point=name).values, ms.pointList[k].r, rtol=0, atol=1e-7
        )


CLUMP_LEG = """\
name: clumpleg
environment:
  fluid: water
  depth: 200.0
  seabed: {friction: 0.02}
points:
  anchor: {kind: fixed, position: [0.0, 0.0, -200.0]}
  junction: {kind: free, position: [770.0, 0.0, -60.0], mass: 200.0}
  fair: {kind: body, body: vessel, offset: [0.0, 0.0, -20.0]}
bodies:
  vessel: {kind: prescribed, position: [820.0, 0.0, 0.0, 0.0, 0.0, 0.0]}
lines:
  leg:
    a: anchor
    b: junction
    segments:
      - {length: 500.0, diameter: 0.137, mass_per_length: 115.0, weight_in_fluid: 981.0,
         axial_stiffness: 4.9e+8}
      - {length: 340.0, diameter: 0.076, mass_per_length: 29.0, weight_in_fluid: 240.0,
         axial_stiffness: 5.2e+8}
    attachments:
      - {s: 640.0, mass: 5000.0, name: clump}
  bridle:
    a: junction
    b: fair
    segments:
      - {length: 60.0, diameter: 0.076, mass_per_length: 29.0, weight_in_fluid: 240.0,
         axial_stiffness: 5.2e+8}
sweep:
  bodies.vessel.position.0: [800.0, 810.0, 815.0, 820.0, 830.0]
"""


def test_system_leg_with_a_clump_at_its_touchdown(tmp_path: Path) -> None:
    ds = _run(tmp_path, "clumpleg", CLUMP_LEG)
    assert np.all(ds["status"].values == 0), ds["message"].values
    laid = ds["laid_length"].sel(line="leg").values
    # the touchdown runs from past the clump (laid 652.8 m at 800) onto it and off it;
    # 810 (failed before) and 815 rest at the clump: laid length exactly its 640 m
    assert laid[0] > 640.0 and laid[-1] < 640.0
    assert np.sum(np.abs(laid - 640.0) <= 1e-9) >= 2, laid
    # the junction's balance from the verified lines' end forces (weight 200 kg, no
    # volume), to the system tolerance (1e-9 of the largest tension) times the
    # verification's allowance
    T = float(ds["tension_b"].max())
    net = (
        ds["force_b"].sel(line="leg").values
        + ds["force_a"].sel(line="bridle").values
        + np.array([0.0, 0.0, -200.0 * G])
    )
    assert np.max(np.abs(net)) <= 1e-8 * T
    # the fairlead tension grows monotonically as the vessel moves out, across the
    # clump's resting range (a continuous state; a wrong branch would jump)
    assert np.all(np.diff(ds["tension_b"].sel(line="bridle").values) > 0.0)


def test_free_body_started_where_a_line_is_slack(tmp_path: Path) -> None:
    # test_system_study's system with its buoy let free (20 t, 30 m^3, as there) and started at
    # surge 0 and 100 m: from 100 m, leg3 (290 m) from its anchor at x = 250 to the
    # fairlead at x = 105, 10 m down, is slack (seabed path 145 m + rise 90 m < 290 m),
    # which failed before ("leg3 ... lies slack on the seabed"). Both starts reach the
    # same pose
    from tests.integration.test_system_study import SYSTEM

    body = (
        "buoy: {kind: free, position: [X0, 0.0, 0.0, 0.0, 0.0, 0.0], mass: 20000.0, "
        "volume: 30.0, center_of_gravity: [0.0, 0.0, -8.0], center_of_buoyancy: [0.0, 0.0, -2.0]}"
    )
    text = SYSTEM.split("sweep:")[0].replace(
        "buoy: {kind: prescribed, position: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]}", body
    )
    assert 250.0 - 105.0 + 90.0 < 290.0
    poses = []
    for x0 in ("0.0", "100.0"):
        ds = _run(
            tmp_path,
            f"free{x0[:-2]}",
            text.replace("name: sys", f"name: free{x0[:-2]}").replace("X0", x0),
        )
        assert int(ds["status"]) == 0, str(ds["message"].values)
        poses.append(ds["body_position"].values[0])
        # the body's balance: lines, weight and buoyancy (constant, no waterplane)
        force = ds["body_force"].values[0]
        np.testing.assert_allclose(force[2], -(RHO * 30.0 - 20000.0) * G, rtol=1e-9)
    # both converge the body's net load to the system tolerance (1e-11 of the largest
    # tension, the study's) over a restoring stiffness of the lines ~ tension / length:
    # ~1e-11 * 300 m, a few 1e-9 m; the polishing step squares it
    np.testing.assert_allclose(poses[1], poses[0], rtol=0, atol=1e-8)
