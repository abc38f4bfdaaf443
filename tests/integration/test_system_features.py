"""System features from YAML to netCDF through `cablestudy run`: lines with bending
stiffness by method discrete, and current drag on the lines and on free points."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses.evaluate import evaluate_case
from cablestudy.analyses.system import evaluate_system_case, system_model
from cablestudy.cli import main
from cablestudy.statics import STATIC_SOLVERS
from cablestudy.statics.system_methods import solve_system_by
from cablestudy.study import parse_study_text
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import StudyError
from tests.integration.test_system_study import SYSTEM

RHO, G = 1025.0, 9.80665
SEG = "{length: %s, diameter: 0.1, mass_per_length: 20.0, axial_stiffness: 5.0e8%s}"

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


# ---------------------------------------------------------------------- current

CURRENT = "current: [{z: 0.0, speed: 1.0}, {z: -100.0, speed: 0.3}]"

#: the integration system, mirror-symmetric about y = 0, in a current along +x that
#: weakens with depth, with drag on the clump (C_D A = 2 m^2)
IN_CURRENT = (
    SYSTEM.replace("fluid: water,", f"fluid: water, {CURRENT},")
    .replace(
        "clump: {kind: free, position: [-60.0, 0.0, -60.0], mass: 3000.0, volume: 0.2}",
        "clump: {kind: free, position: [-30.0, 0.0, -75.0], mass: 3000.0, volume: 0.2, "
        "drag_area: 2.0}",
    )
    .replace("nodes: 11", "nodes: 21")
    .replace("{start: -2.0, stop: 2.0, num: 9, name: surge}", "{values: [0.0]}")
)


@pytest.fixture(scope="module", params=["catenary", "discrete"])
def current(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    """The system in a current by each method (discrete: the drag of its nodes)."""
    text = IN_CURRENT.replace("static: {", f"static: {{method: {request.param}, ")
    return run(tmp_path_factory.mktemp("current"), text, "current")


def test_system_in_a_current_runs_end_to_end_with_mirror_symmetry(current: xr.Dataset) -> None:
    """A current along x on a system symmetric about y = 0: the legs either side carry
    mirrored forces, the clump stays on y = 0, the body feels no sway, roll or yaw, and
    its stiffness does not couple the symmetric motions to the antisymmetric ones. The
    free-point Newton ends at 1e-11 of the largest tension: that times the tension is
    the symmetry's bound on forces, over the stiffness (~1e2 N/m) on positions."""
    ds = current.isel({current["body_force"].dims[0]: 0})
    assert int(ds["status"]) == 0, str(ds["message"].values)
    scale = float(ds["tension_a"].max())
    mirror = np.array([1.0, -1.0, 1.0])
    for end in ("force_a", "force_b"):
        np.testing.assert_allclose(
            ds[end].sel(line="leg1").values,
            mirror * ds[end].sel(line="leg2").values,
            rtol=0,
            atol=1e-9 * scale,
        )
    assert abs(float(ds["point_position"].sel(point="clump", component="y"))) <= 1e-9 * scale / 1e2
    F = ds["body_force"].sel(body="buoy")
    np.testing.assert_allclose(F.sel(dof=["sway", "roll", "yaw"]), 0.0, atol=1e-9 * scale * 10.0)
    K = ds["body_stiffness"].sel(body="buoy").values
    sym, anti = [0, 2, 4], [1, 3, 5]
    k_scale = float(np.max(np.abs(K)))
    assert np.max(np.abs(K[np.ix_(sym, anti)])) <= 1e-8 * k_scale
    assert np.max(np.abs(K[np.ix_(anti, sym)])) <= 1e-8 * k_scale
    # the current pushes the clump down-stream of where still water puts it
    # (x = -29.206 m, test_system_study's case at surge 0): by 0.17 m
    assert float(ds["point_position"].sel(point="clump", component="x")) > -29.206 + 0.1


def test_clump_in_a_current_balances_its_drag(current: xr.Dataset) -> None:
    """The lines' pull on the clump, its weight in water and its drag 1/2 rho C_D A |U| U
    (U the current at its height, interpolated in the profile) sum to zero, to the
    system's tolerance (1e-11 of the largest tension)."""
    ds = current.isel({current["body_force"].dims[0]: 0})
    z = float(ds["point_position"].sel(point="clump", component="z"))
    u = float(np.interp(z, [-100.0, 0.0], [0.3, 1.0]))
    drag = np.array([0.5 * RHO * 2.0 * u * u, 0.0, 0.0])
    pull = ds["force_b"].sel(line=["leg1", "leg2"]).sum("line") + ds["force_a"].sel(line="bridle")
    weight = np.array([0.0, 0.0, -(3000.0 - RHO * 0.2) * G])
    scale = float(ds["tension_a"].max())
    np.testing.assert_allclose(pull.values + weight + drag, 0.0, atol=1e-9 * scale)


ONE_LINE_FORCE = f"""\
name: one
environment: {{fluid: water, depth: 100.0, {CURRENT}}}
line:
  segments: [{{length: 120.0, diameter: 0.1, mass_per_length: 20.0, axial_stiffness: 5.0e8}}]
ends:
  a: {{kind: fixed, position: [-100.0, 10.0, -100.0]}}
  b: {{kind: force, force: [3000.0, 500.0, 8000.0]}}
analysis:
  static: {{nodes: 21, tolerance: 1.0e-11}}
"""

#: the same line as a system: end B a free point carrying the same force (a buoy)
AS_SYSTEM_FORCE = f"""\
name: one
environment: {{fluid: water, depth: 100.0, {CURRENT}}}
points:
  anchor: {{kind: fixed, position: [-100.0, 10.0, -100.0]}}
  buoy: {{kind: free, position: [0.0, 0.0, -40.0], force: [3000.0, 500.0, 8000.0]}}
lines:
  only:
    a: anchor
    b: buoy
    segments: [{{length: 120.0, diameter: 0.1, mass_per_length: 20.0, axial_stiffness: 5.0e8}}]
analysis:
  static: {{nodes: 21, tolerance: 1.0e-11}}
"""


def test_a_system_of_one_line_in_a_current_is_the_one_line_solution() -> None:
    """A line from an anchor to a free point pulled by a constant force, in a sheared
    current: the system's free-point Newton (each line's drag iterated in its own solve,
    its stiffness at frozen drag) finds where the one-line solver puts a force end.
    Both converge to 1e-11 of the tension; the point's position agrees to that over the
    line's stiffness across its length (~T / L ~ 1e2 N/m): 1e-8 m asked (of a 120 m
    line), the tensions to 1e-9 of the largest."""
    (_, [line_case]) = expand_cases(parse_study_text(ONE_LINE_FORCE, "one.yaml"))
    (_, [sys_case]) = expand_cases(parse_study_text(AS_SYSTEM_FORCE, "sys.yaml"))
    one = evaluate_case(line_case)
    sys = evaluate_system_case(sys_case)
    assert one.status == 0 and sys.status == 0, (one.message, sys.message)
    scale = float(np.max(one.data["tension"]))
    for name in ("x", "y", "z"):
        np.testing.assert_allclose(sys.data[name][0], one.data[name], rtol=0, atol=1e-8 * 120.0)
    np.testing.assert_allclose(sys.data["tension"][0], one.data["tension"], atol=1e-9 * scale)
    np.testing.assert_allclose(sys.data["force_a"][0], one.data["force_a"], atol=1e-9 * scale)
    np.testing.assert_allclose(sys.data["point_position"][0, 0], one.data["x"][-1], atol=1e-6)


@pytest.mark.parametrize(
    ("changes", "words"),
    [
        # a point's drag without a current would be silently zero
        ([("volume: 0.2}", "volume: 0.2, drag_area: 1.0}")], "points.clump.drag_area"),
        # the stretched drag diameter is method shooting's, which systems do not use
        (
            [
                ("fluid: water,", f"fluid: water, {CURRENT},"),
                ("static: {nodes", "static: {drag_diameter: stretched, nodes"),
            ],
            "analysis.static.drag_diameter",
        ),
        # a lumped body's drag in a current: method discrete's, not catenary's
        (
            [
                ("fluid: water,", f"fluid: water, {CURRENT},"),
                (
                    "bridle: {a: clump, b: fair1, segments:",
                    "bridle: {a: clump, b: fair1, attachments: [{s: 10.0, drag_area: 1.0}], "
                    "segments:",
                ),
            ],
            "lines.bridle.attachments.0.drag_area",
        ),
    ],
)
def test_what_a_system_in_a_current_cannot_use_is_refused_by_name(
    changes: list[tuple[str, str]], words: str
) -> None:
    text = SYSTEM
    for old, new in changes:
        assert old in text
        text = text.replace(old, new, 1)
    with pytest.raises(StudyError) as info:
        expand_cases(parse_study_text(text, "sys.yaml"))
    assert words in str(info.value)


# ------------------------------------------------- a line on the seabed from free points

#: a buoy held by a riser from an anchor, and a shared line from the buoy to a floater
#: that lies on the seabed between them (a shared mooring's sagging line)
SAGGING = f"""\
name: sag
environment: {{fluid: water, depth: 50.0}}
points:
  anchor: {{kind: fixed, position: [-200.0, 0.0, -50.0]}}
  buoy: {{kind: free, position: [-120.0, 0.0, -20.0], mass: 500.0, volume: 1.5}}
  fair: {{kind: body, body: float, offset: [0.0, 0.0, -5.0]}}
bodies:
  float: {{kind: prescribed, position: [60.0, 0.0, 0.0, 0.0, 0.0, 0.0]}}
lines:
  riser: {{a: anchor, b: buoy, segments: [{SEG % (60.0, "")}]}}
  shared: {{a: buoy, b: fair, segments: [{SEG % (250.0, "")}]}}
analysis:
  static: {{method: discrete, nodes: 31, tolerance: 1.0e-10}}
"""


def test_a_line_on_the_seabed_between_free_and_body_points_by_method_discrete(
    tmp_path: Path,
) -> None:
    """Method discrete solves a line lying on the seabed between a free point and a body
    point (its end stiffness from the model's tangent, seabed springs included); the
    buoy balances the lines' pull, its weight and its buoyancy to the system's
    tolerance. Method catenary solves it too (the line's end stiffness at the free point
    from differences of its solves): the same balance, its touchdown within one of the
    discrete model's elements (h = 250 m / 30, where its touchdown is resolved) and
    the buoy within a tenth of one."""
    ds = run(tmp_path, SAGGING, "sag").squeeze()
    assert int(ds["status"]) == 0, str(ds["message"].values)
    assert float(ds["laid_length"].sel(line="shared")) > 100.0  # most of it on the seabed
    pull = ds["force_b"].sel(line="riser") + ds["force_a"].sel(line="shared")
    load = np.array([0.0, 0.0, -(500.0 - RHO * 1.5) * G])
    scale = float(ds["tension_a"].max())
    np.testing.assert_allclose(pull.values + load, 0.0, atol=1e-8 * scale)
    (_, [case]) = expand_cases(
        parse_study_text(SAGGING.replace("method: discrete", "method: catenary"), "s.yaml")
    )
    record = evaluate_system_case(case)
    assert record.status == 0, record.message
    exact = record.data
    pull = exact["force_b"][0] + exact["force_a"][1]  # riser and shared, as above
    np.testing.assert_allclose(pull + load, 0.0, atol=1e-8 * scale)
    h = 250.0 / 30.0
    laid = float(ds["laid_length"].sel(line="shared"))
    assert abs(exact["laid_length"][list(ds["line"].values).index("shared")] - laid) < h
    buoy = ds["point_position"].values.reshape(-1, 3)[0]
    assert np.abs(exact["point_position"][0] - buoy).max() < 0.1 * h


def test_strain_warning_of_a_system_names_its_lines(tmp_path: Path) -> None:
    """analysis.static.strain_warning is used by a system as by one line: each line's
    largest strain T / EA (EA 5e8 N, tensions 6 to 46 kN: strains 1e-5 to 1e-4) against
    it; with the limit at 1e-6 the case keeps status 0 with a warning naming the lines
    above it, with the default-like 1.0 none."""
    text = SYSTEM.replace("tolerance: 1.0e-11}", "tolerance: 1.0e-11, strain_warning: 1.0e-6}")
    text = text.replace("{start: -2.0, stop: 2.0, num: 9, name: surge}", "{values: [0.0]}")
    ds = run(tmp_path, text, "strained").squeeze()
    assert int(ds["status"]) == 0
    warning = str(ds["warning"].values)
    assert "strain" in warning and "strain_warning" in warning
    # T / EA of each line from the file: the lines above 1e-6 are the ones named
    strain = ds["tension"].max("s") / 5.0e8
    named = warning.rsplit("(lines ", 1)[1].rstrip(")").split(", ")
    assert named == [str(n) for n in ds["line"].values[strain.values > 1e-6]]
    plain = run(tmp_path, text.replace("strain_warning: 1.0e-6", "strain_warning: 1.0"), "calm")
    assert str(plain["warning"].squeeze().values) == ""
