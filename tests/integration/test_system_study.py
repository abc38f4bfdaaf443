"""A system study (lines joined at points, a body) from YAML to netCDF through the CLI,
its validation, and the one-line study as a system of one line."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses.evaluate import evaluate_case
from cablestudy.analyses.static_grid import evaluate_grid_chunk
from cablestudy.analyses.system import evaluate_system_case, system_model
from cablestudy.analyses.variables import SYSTEM_OUTPUTS
from cablestudy.cli import main
from cablestudy.run.grid_runner import study_grid
from cablestudy.statics import STATIC_SOLVERS
from cablestudy.statics.system import solve_system
from cablestudy.study import parse_study_text
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import StudyError

SEG = "{length: %s, diameter: 0.1, mass_per_length: 20.0, axial_stiffness: 5.0e8}"

#: two legs from anchors on the seabed to a clump, a bridle from the clump to a body
#: fairlead and a third leg from a third anchor straight to the body
SYSTEM = f"""\
name: sys
environment: {{fluid: water, depth: 100.0}}
points:
  anchor1: {{kind: fixed, position: [-300.0, -40.0, -100.0]}}
  anchor2: {{kind: fixed, position: [-300.0, 40.0, -100.0]}}
  anchor3: {{kind: fixed, position: [250.0, 0.0, -100.0]}}
  clump: {{kind: free, position: [-60.0, 0.0, -60.0], mass: 3000.0, volume: 0.2}}
  fair1: {{kind: body, body: buoy, offset: [-5.0, 0.0, -10.0]}}
  fair2: {{kind: body, body: buoy, offset: [5.0, 0.0, -10.0]}}
bodies:
  buoy: {{kind: prescribed, position: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]}}
lines:
  leg1: {{a: anchor1, b: clump, segments: [{SEG % 280.0}]}}
  leg2: {{a: anchor2, b: clump, segments: [{SEG % 280.0}]}}
  bridle: {{a: clump, b: fair1, segments: [{SEG % 70.0}]}}
  leg3: {{a: anchor3, b: fair2, segments: [{SEG % 290.0}]}}
analysis:
  static: {{nodes: 11, tolerance: 1.0e-11}}
sweep:
  bodies.buoy.position.0: {{start: -2.0, stop: 2.0, num: 9, name: surge}}
"""


@pytest.fixture(scope="module")
def dataset(tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    tmp = tmp_path_factory.mktemp("system")
    cfg = tmp / "sys.yaml"
    cfg.write_text(SYSTEM)
    assert (
        main(
            [
                "run",
                str(cfg),
                "--out",
                str(tmp),
                "--no-cache",
                "--no-progress",
                "--scheduler",
                "synchronous",
            ]
        )
        == 0
    )
    return xr.load_dataset(tmp / "sys.nc")


def test_outputs_names_dims_units(dataset: xr.Dataset) -> None:
    ds = dataset
    assert np.all(ds["status"] == 0)
    assert list(ds["line"].values) == ["leg1", "leg2", "bridle", "leg3"]
    assert list(ds["point"].values) == ["clump"]
    assert list(ds["body"].values) == ["buoy"]
    assert list(ds["dof"].values) == ["surge", "sway", "heave", "roll", "pitch", "yaw"]
    expected = {
        "tension_a": ("surge", "line"),
        "force_a": ("surge", "line", "component"),
        "x": ("surge", "line", "s"),
        "tension": ("surge", "line", "s"),
        "arc_length": ("surge", "line", "s"),
        "point_position": ("surge", "point", "component"),
        "body_position": ("surge", "body", "dof"),
        "body_force": ("surge", "body", "dof"),
        "body_stiffness": ("surge", "body", "dof", "dof_j"),
    }
    for name, dims in expected.items():
        assert ds[name].dims == dims, name
        assert ds[name].attrs["units"] == SYSTEM_OUTPUTS[name].units
        assert ds[name].attrs["long_name"] == SYSTEM_OUTPUTS[name].long_name
    np.testing.assert_array_equal(ds["s"], np.arange(11))
    np.testing.assert_array_equal(ds["body_position"].sel(dof="surge", body="buoy"), ds["surge"])
    # the end tension is the magnitude of the end force; the lines end at their points
    np.testing.assert_allclose(
        ds["tension_a"], np.sqrt((ds["force_a"] ** 2).sum("component")), rtol=1e-14
    )
    for c in "xyz":
        np.testing.assert_allclose(
            ds[c].sel(line="bridle").isel(s=0),
            ds["point_position"].sel(point="clump", component=c),
            rtol=0,
            atol=1e-9 * 300.0,
        )


def test_run_equals_the_solver(dataset: xr.Dataset) -> None:
    """The file holds, for each case, what the same study with that one value in its
    sweep gives, bit for bit (every case of a sweep starts where the study alone puts
    it, cablestudy.analyses.system_grid: never from another case), and what the pure solver gives
    from the study's starting positions to 1e-9 of each quantity's scale (the two
    converge the free points to the study's 1e-11 from different starts)."""
    _, cases = expand_cases(parse_study_text(SYSTEM, "sys.yaml"))
    for case in cases[:: len(cases) - 1]:
        here = dataset.isel(surge=case.index[0])
        surge = float(dataset["surge"].values[case.index[0]])
        alone = SYSTEM.replace(
            "{start: -2.0, stop: 2.0, num: 9, name: surge}", f"{{values: [{surge!r}], name: surge}}"
        )
        grid = study_grid(parse_study_text(alone, "sys.yaml"))
        chunk = evaluate_grid_chunk(grid, 0, 1)
        for name in ("body_force", "body_stiffness", "tension_b", "point_position", "x"):
            np.testing.assert_array_equal(here[name].values, chunk.data[name][0], err_msg=name)
        res = solve_system(system_model(case.study), STATIC_SOLVERS["catenary"])
        big = float(np.max(res.body_stiffness[0]))
        np.testing.assert_allclose(
            here["body_stiffness"].values[0], res.body_stiffness[0], atol=1e-9 * big
        )
        tension = [np.linalg.norm(r.force_b) for r in res.lines]
        np.testing.assert_allclose(here["tension_b"].values, tension, atol=1e-9 * max(tension))
        np.testing.assert_allclose(
            here["body_force"].values[0], res.body_force[0], atol=1e-9 * 300.0 * max(tension)
        )


def test_restoring_curve_is_the_integral_of_the_stiffness(dataset: xr.Dataset) -> None:
    """Between sweep points the change of body force equals minus the trapezoidal
    integral of the stiffness column: the trapezoid errs by dx^3 K''/12 per step, so the
    mismatch falls by 8 when dx halves (fitted order >= 2.7) and is small."""
    f = dataset["body_force"].sel(body="buoy").values  # (surge, dof)
    k = dataset["body_stiffness"].sel(body="buoy", dof_j="surge").values  # (surge, dof)
    x = dataset["surge"].values

    def mismatch(step: int) -> float:
        df = f[step::step] - f[:-step:step]
        integral = -0.5 * (k[step::step] + k[:-step:step]) * np.diff(x[::step])[:, None]
        return float(np.max(np.abs(df - integral)))

    e1, e2 = mismatch(2), mismatch(1)
    assert e2 <= 1e-3 * float(np.max(np.abs(f[:, 0] - f[0, 0])))
    assert math.log2(e1 / e2) >= 2.7, (e1, e2)


def test_clump_is_in_equilibrium(dataset: xr.Dataset) -> None:
    """Lines' forces on the clump balance its weight in water (3000 kg - 1025 kg/m^3 *
    0.2 m^3) to the tolerance asked (1e-11 of the largest tension)."""
    ds = dataset
    pull = (ds["force_b"].sel(line="leg1") + ds["force_b"].sel(line="leg2")) + ds["force_a"].sel(
        line="bridle"
    )
    weight = (3000.0 - 1025.0 * 0.2) * 9.80665
    largest = float(ds["tension"].max())
    np.testing.assert_allclose(pull.sel(component="z"), weight, rtol=0, atol=1e-10 * largest)
    np.testing.assert_allclose(pull.sel(component=["x", "y"]), 0.0, rtol=0, atol=1e-10 * largest)


ONE_LINE = """\
name: one
environment: {fluid: water, depth: 100.0}
line:
  segments: [{length: 280.0, diameter: 0.1, mass_per_length: 20.0, axial_stiffness: 5.0e8}]
ends:
  a: {kind: fixed, position: [-250.0, 10.0, -100.0]}
  b: {kind: fixed, position: [0.0, 0.0, -10.0]}
analysis:
  static: {nodes: 11, tolerance: 1.0e-11}
"""

AS_SYSTEM = """\
name: one
environment: {fluid: water, depth: 100.0}
points:
  p: {kind: fixed, position: [-250.0, 10.0, -100.0]}
  q: {kind: fixed, position: [0.0, 0.0, -10.0]}
lines:
  only:
    a: p
    b: q
    segments: [{length: 280.0, diameter: 0.1, mass_per_length: 20.0, axial_stiffness: 5.0e8}]
analysis:
  static: {nodes: 11, tolerance: 1.0e-11}
"""


def test_one_line_study_is_a_system_of_one_line() -> None:
    (_, [line_case]) = expand_cases(parse_study_text(ONE_LINE, "one.yaml"))
    (_, [sys_case]) = expand_cases(parse_study_text(AS_SYSTEM, "sys.yaml"))
    one = evaluate_case(line_case)
    sys = evaluate_system_case(sys_case)
    assert one.status == 0 and sys.status == 0
    for name in ("force_a", "force_b", "tension_a", "tension_b", "x", "z", "tension"):
        np.testing.assert_array_equal(sys.data[name][0], one.data[name], err_msg=name)


def _error(text: str) -> str:
    with pytest.raises(StudyError) as info:
        expand_cases(parse_study_text(text, "sys.yaml"))
    return str(info.value)


@pytest.mark.parametrize(
    ("change", "line_no", "words"),
    [
        (("mass: 3000.0", "mass: 3000.0, drag_area: 1.0"), 7, "drag_area"),
        (("b: fair1, segments", "b: fairX, segments"), 15, "fairX"),
        (("body: buoy, offset: [5.0", "body: boat, offset: [5.0"), 9, "boat"),
        (("static: {nodes", "modal: {modes: 3}\n  static: {nodes"), 18, "one-line study"),
        (("static: {nodes: 11", "static: {method: shooting, nodes: 11"), 18, "catenary, discrete"),
        (("[250.0, 0.0, -100.0]", "[250.0, 0.0, -101.0]"), 6, "below the seabed"),
        (("kind: prescribed,", "kind: moored,"), 11, "prescribed"),
    ],
)
def test_system_faults_are_refused_at_their_line(
    change: tuple[str, str], line_no: int, words: str
) -> None:
    assert change[0] in SYSTEM
    message = _error(SYSTEM.replace(change[0], change[1], 1))
    assert f"sys.yaml:{line_no}" in message, message
    assert words in message, message


def test_a_point_on_no_line_and_both_line_and_lines_are_refused() -> None:
    extra = SYSTEM.replace(
        "bodies:", "  spare: {kind: fixed, position: [0.0, 0.0, -50.0]}\nbodies:"
    )
    assert "on no line" in _error(extra)
    both = SYSTEM.replace(
        "bodies:",
        ONE_LINE.split("environment:")[1].split("\n", 1)[1].split("analysis:")[0] + "bodies:",
    )
    assert "has no 'line'" in _error(both)


def test_sweeps_reach_named_entries() -> None:
    """A point's mass and a line's segment stiffness are swept like any key; each case
    holds its value, and the dimension takes the sweep's name."""
    text = SYSTEM.split("sweep:")[0] + (
        "sweep:\n"
        "  points.clump.mass: {values: [1000.0, 4000.0], name: clump_mass}\n"
        "  lines.bridle.segments.0.axial_stiffness: [1.0e8, 5.0e8]\n"
    )
    axes, cases = expand_cases(parse_study_text(text, "sys.yaml"))
    assert [a.name for a in axes] == ["clump_mass", "axial_stiffness"]
    got = {
        (c.study.points["clump"].mass, c.study.lines["bridle"].segments[0].axial_stiffness)
        for c in cases
    }
    assert got == {(m, k) for m in (1000.0, 4000.0) for k in (1.0e8, 5.0e8)}
    missing = _error(SYSTEM.replace("bodies.buoy.position.0", "bodies.boat.position.0"))
    assert "bodies has no entry 'boat'; allowed: buoy" in missing


def test_a_free_body_through_the_study() -> None:
    """The buoy let free (20 t, 30 m^3, centre of gravity below the centre of buoyancy):
    its position is the equilibrium of the lines, weight and buoyancy."""
    text = SYSTEM.split("sweep:")[0].replace(
        "buoy: {kind: prescribed, position: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]}",
        "buoy: {kind: free, mass: 20000.0, volume: 30.0, center_of_gravity: [0.0, 0.0, -8.0], "
        "center_of_buoyancy: [0.0, 0.0, -2.0]}",
    )
    (_, [case]) = expand_cases(parse_study_text(text, "sys.yaml"))
    rec = evaluate_system_case(case)
    assert rec.status == 0, rec.message
    pose = rec.data["body_position"][0]
    force = rec.data["body_force"][0]
    g, rho = 9.80665, 1025.0
    # vertical: the lines hold the net buoyancy; horizontal: the lines balance
    assert force[2] == pytest.approx(-(rho * 30.0 - 20000.0) * g, rel=1e-10)
    assert np.max(np.abs(force[:2])) <= 1e-10 * abs(force[2])
    assert abs(pose[2]) > 1e-3  # it moved from the starting guess


def test_body_position_sweep_coordinate_names_its_dof() -> None:
    text = SYSTEM.replace("bodies.buoy.position.0", "bodies.buoy.position.5").replace(
        "{start: -2.0, stop: 2.0, num: 9, name: surge}", "[0.0, 0.1]"
    )
    axes, _ = expand_cases(parse_study_text(text, "sys.yaml"))
    assert axes[0].name == "position_5"
    assert axes[0].units == "rad"
    assert axes[0].long_name.startswith("yaw of body buoy")
