"""The radial quasi-static database (analysis.database.grid: radial, the aqwa seed's grid
for lines off the seabed) and the database's own file, through YAML -> cablestudy run
-> <name>.database.nc -> cablestudy lookup.

The line: a suspended two-section line in water, no seabed (chain 60 m of 80 kg/m over
wire 140 m of 12 kg/m), end B over distances 100..150 m from end A and chord angles
-30..30 deg: every tabulated end force is a smooth (analytic) function of (d, a) there,
so the bicubic Hermite patches with not-a-knot spline slopes err as h^4.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses.database import (
    QUANTITIES,
    QuasiStaticDatabase,
    grid_values,
    open_database,
    solve_database,
)
from cablestudy.cli import main
from cablestudy.statics import STATIC_SOLVERS, EndCondition
from cablestudy.study import Study, load_study
from cablestudy.study.problem import static_problem

D0, D1, A0, A1 = 100.0, 150.0, -30.0, 30.0

LINE = {
    "segments": [
        {"length": 60.0, "diameter": 0.09, "mass_per_length": 80.0, "axial_stiffness": 8e8},
        {"length": 140.0, "diameter": 0.06, "mass_per_length": 12.0, "axial_stiffness": 2e8},
    ]
}


def study(n: int) -> Study:
    return Study.model_validate(
        {
            "name": "radial",
            "environment": {"fluid": "water"},
            "line": LINE,
            "ends": {
                "a": {"kind": "fixed", "position": [0.0, 0.0, -150.0]},
                "b": {"kind": "fixed", "position": [130.0, 0.0, -140.0]},
            },
            "analysis": {
                "static": {"method": "catenary", "nodes": 21, "tolerance": 1e-12},
                "database": {
                    "grid": "radial",
                    "distance": {"start": D0, "stop": D1, "num": n},
                    "angle_deg": {"start": A0, "stop": A1, "num": n},
                },
            },
        }
    )


def direct(st: Study, x: float, z: float, heading: float = 0.0):  # noqa: ANN201
    """A direct static solve with end B at (x, z) from end A in the database's plane."""
    base = static_problem(st)
    e = np.array([math.cos(heading), math.sin(heading), 0.0])
    rB = np.asarray(base.end_a.position) + x * e + np.array([0.0, 0.0, z])
    res = STATIC_SOLVERS["catenary"].solve(
        replace(base, end_b=EndCondition(kind="fixed", position=rB))
    )
    assert res.status == 0, res.message
    return res


def test_radial_lookup_error_falls_as_h4_against_direct_solves() -> None:
    rng = np.random.default_rng(7)
    d = rng.uniform(D0, D1, 60)
    a = np.radians(rng.uniform(A0, A1, 60))
    pts = np.column_stack((d * np.cos(a), d * np.sin(a)))  # looked up by (x, z)
    ref_study = study(4)
    refs = np.array(
        [np.concatenate((r.force_a, r.force_b)) for r in (direct(ref_study, *p) for p in pts)]
    )
    scale = float(np.max(np.linalg.norm(refs[:, 3:], axis=1)))
    errors = []
    for n in (9, 17, 33):  # cell size halves each time
        st = study(n)
        data = solve_database(st)
        assert np.all(data["database_radial_status"] == 0)
        P, Q = grid_values(st)
        db = QuasiStaticDatabase.from_arrays(
            P, Q, {k: data[f"database_radial_{k}"] for k in QUANTITIES}, grid="radial"
        )
        got = np.array(
            [np.concatenate((o["force_a"], o["force_b"])) for o in (db.lookup(*p) for p in pts)]
        )
        errors.append(float(np.max(np.abs(got - refs))) / scale)
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # bicubic Hermite patches with spline slopes: O(h^4) on a smooth table; the largest
    # error over 60 random points sits at varying places within a cell, so the observed
    # order scatters about 4 (measured 4.4 and 4.5 here, 3.3 pre-asymptotically from
    # 5 points a side): held to >= 3.6
    assert np.all(orders >= 3.6), (errors, orders)
    # the direct solves are converged to 1e-12, far below the finest table's error
    assert errors[-1] < 1e-6, errors


def test_radial_grid_is_c1_in_x_z_across_cell_boundaries() -> None:
    # a radial table of f = exp(d/100) sin(2a): the interpolant and its slope in x are
    # continuous across the cell boundary d = 125 m (a node of the 5-point distance
    # axis) when approached along x at fixed z
    P = np.linspace(D0, D1, 5)
    Q = np.radians(np.linspace(A0, A1, 7))
    f = np.exp(P[:, None] / 100.0) * np.sin(2.0 * Q[None, :])
    db = QuasiStaticDatabase.from_arrays(P, Q, {"f": f}, grid="radial")
    z = 20.0
    x0 = math.sqrt(125.0**2 - z**2)
    eps = 1e-5
    left, mid, right = (db.lookup(x0 + k * eps, z)["f"] for k in (-1, 0, 1))
    slope_l, slope_r = (mid - left) / eps, (right - mid) / eps
    # one-sided differences agree to O(eps f'') ~ 1e-9; a slope jump would show as O(1e-3)
    assert abs(slope_l - slope_r) <= 1e-6 * max(abs(slope_l), 1.0)


def test_radial_lookup_outside_the_grid_is_refused_with_its_range() -> None:
    P = np.linspace(D0, D1, 5)
    Q = np.radians(np.linspace(A0, A1, 5))
    db = QuasiStaticDatabase.from_arrays(P, Q, {"f": np.ones((5, 5))}, grid="radial")
    allowed = "allowed: distance 100 .. 150 m and angle -30 .. 30 deg"
    with pytest.raises(ValueError, match=allowed):
        db.lookup(10.0, 120.0)  # angle 85 deg
    with pytest.raises(ValueError, match=allowed):
        db.lookup(200.0, 0.0)  # too far


STUDY = """\
name: radial
environment: {fluid: water}
line:
  segments:
    - {length: 60.0, diameter: 0.09, mass_per_length: 80.0, axial_stiffness: 8.0e8}
    - {length: 140.0, diameter: 0.06, mass_per_length: 12.0, axial_stiffness: 2.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -150.0]}
  b: {kind: fixed, position: [78.0, 104.0, -140.0]}
analysis:
  static: {method: catenary, nodes: 21}
  database:
    grid: radial
    distance: {start: 100.0, stop: 150.0, num: 17}
    angle_deg: {start: -30.0, stop: 30.0, num: 17}
"""


def _run(cfg: Path, out: Path, *extra: str) -> int:
    return main(["run", str(cfg), "--out", str(out), "--scheduler", "synchronous", *extra])


def test_radial_yaml_to_database_file_to_cli_lookup(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    cfg = tmp_path / "radial.yaml"
    cfg.write_text(STUDY)
    assert _run(cfg, tmp_path, "--no-cache") == 0
    assert "radial.database.nc: the quasi-static database" in capsys.readouterr().out
    path = tmp_path / "radial.database.nc"
    ds = xr.load_dataset(path)
    assert ds.attrs["database_grid"] == "radial"
    assert ds.attrs["study_name"] == "radial" and ds.attrs["database_of"] == "radial.nc"
    assert json.loads(ds.attrs["line"])["segments"][1]["length"] == 140.0
    assert ds["force_b"].dims == ("distance", "angle", "component")
    assert ds["angle"].attrs["units"] == "rad" and ds["distance"].attrs["units"] == "m"
    np.testing.assert_allclose(np.degrees(ds["angle"].values), np.linspace(-30, 30, 17))
    for name in QUANTITIES:
        assert ds[name].attrs["units"] in ("N", "m") and ds[name].attrs["long_name"]
    assert np.all(ds["point_status"] == 0) and int(ds["status"]) == 0
    heading = math.atan2(104.0, 78.0)  # the plane through A and the study's end B
    assert float(ds["heading"]) == pytest.approx(heading, rel=1e-15)
    # the study dataset keeps its own copy, on the same grid
    st_ds = xr.load_dataset(tmp_path / "radial.nc")
    np.testing.assert_array_equal(st_ds["database_radial_force_b"].values, ds["force_b"].values)

    study_cfg, _ = load_study(str(cfg))
    for x, z in ((120.0, 10.0), (95.0, -40.0), (140.0, 50.0)):
        assert main(["lookup", str(path), "--at", str(x), str(z)]) == 0
        got = json.loads(capsys.readouterr().out)
        res = direct(study_cfg, x, z, heading)
        scale = float(np.linalg.norm(res.force_b))
        # 17 points a side: the h^4 error measured above is ~6e-6 of the largest end
        # tension at this grid; 3e-5 leaves room for where the points fall in a cell
        np.testing.assert_allclose(got["force_a"], res.force_a, rtol=0, atol=3e-5 * scale)
        np.testing.assert_allclose(got["force_b"], res.force_b, rtol=0, atol=3e-5 * scale)
        assert got["laid_length"] == 0.0 or abs(got["laid_length"]) < 1e-9
        # the study's own file gives the same numbers
        assert main(["lookup", str(tmp_path / "radial.nc"), "--at", str(x), str(z)]) == 0
        assert json.loads(capsys.readouterr().out) == got
    assert main(["lookup", str(path), "--at", "10", "120"]) == 2
    err = capsys.readouterr().err
    assert "allowed: distance 100 .. 150 m and angle -30 .. 30 deg" in err


SWEPT = """\
name: swept
environment: {fluid: water}
line:
  segments:
    - {length: 60.0, diameter: 0.09, mass_per_length: 80.0, axial_stiffness: 8.0e8}
    - {length: 140.0, diameter: 0.06, mass_per_length: 12.0, axial_stiffness: 2.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -150.0]}
  b: {kind: fixed, position: [130.0, 0.0, -140.0]}
analysis:
  static: {method: catenary, nodes: 21}
  database:
    grid: radial
    distance: {start: 100.0, stop: 150.0, num: 5}
    angle_deg: {start: -30.0, stop: 30.0, num: 5}
sweep:
  line.segments.0.axial_stiffness: [8.0e8, 2.0e6]
"""


def test_swept_database_file_holds_a_case_dimension_and_a_resumed_run_rewrites_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    cfg = tmp_path / "swept.yaml"
    cfg.write_text(SWEPT)
    assert _run(cfg, tmp_path) == 0  # with the cache
    path = tmp_path / "swept.database.nc"
    first = xr.load_dataset(path)
    # a catenary sweep over a stiffness would run as arrays (cablestudy.analyses.static_grid), which
    # has no database: the study runs case by case and keeps it
    assert first["force_b"].dims == ("axial_stiffness", "distance", "angle", "component")
    assert list(first["axial_stiffness"].values) == [8.0e8, 2.0e6]
    assert first["case_hash"].dims == ("axial_stiffness",)
    assert len({str(h) for h in first["case_hash"].values}) == 2
    # a softer chain stretches more: the end tension differs between the cases
    t = first["tension_b"].values
    assert np.all(np.abs(t[0] - t[1]) > 0.0)
    # a case is selected as in the study dataset
    capsys.readouterr()
    assert main(["lookup", str(path), "--at", "120", "5", "--sel", "axial_stiffness=2e6"]) == 0
    got = json.loads(capsys.readouterr().out)
    db = open_database(str(tmp_path / "swept.nc"), axial_stiffness=2.0e6)
    assert got["force_b"] == db.lookup(120.0, 5.0)["force_b"].tolist()
    assert main(["lookup", str(path), "--at", "120", "5"]) == 2
    assert "select one case" in capsys.readouterr().err
    # a sweep dimension of one value is that case's: no --sel needed
    one = tmp_path / "one.database.nc"
    first.isel(axial_stiffness=[1]).to_netcdf(one)
    assert main(["lookup", str(one), "--at", "120", "5"]) == 0
    assert json.loads(capsys.readouterr().out) == got

    # resumed from the cache (every case reused, the file lost): the same file again
    path.unlink()
    assert _run(cfg, tmp_path) == 0
    assert "2 reused from cache" in capsys.readouterr().out
    again = xr.load_dataset(path)
    ignore = {"history"}  # the run's timestamp
    assert {k: v for k, v in again.attrs.items() if k not in ignore} == {
        k: v for k, v in first.attrs.items() if k not in ignore
    }
    xr.testing.assert_identical(again.drop_attrs(), first.drop_attrs())

    # the study no longer asks for a database: the old file goes, as it no longer
    # describes the study
    cfg.write_text(SWEPT.split("  database:")[0] + "sweep:" + SWEPT.split("sweep:")[1])
    assert _run(cfg, tmp_path, "--no-cache") == 0
    assert not path.exists()


def test_per_case_grids_are_kept_per_case(tmp_path: Path) -> None:
    # the grid swept: the database file holds it per case (distance_grid), and a lookup
    # of each case uses its own grid
    cfg = tmp_path / "g.yaml"
    cfg.write_text(
        SWEPT.replace("name: swept", "name: g").replace(
            "  line.segments.0.axial_stiffness: [8.0e8, 2.0e6]",
            "  analysis.database.distance.stop: [140.0, 150.0]",
        )
    )
    assert _run(cfg, tmp_path, "--no-cache") == 0
    ds = xr.load_dataset(tmp_path / "g.database.nc")
    assert ds["distance_grid"].dims == ("stop", "distance")
    assert ds["distance_grid"].values[0, -1] == 140.0
    db = open_database(str(tmp_path / "g.database.nc"), stop=140.0)
    with pytest.raises(ValueError, match=r"distance 100 \.\. 140 m"):
        db.lookup(145.0, 0.0)
    assert open_database(str(tmp_path / "g.database.nc"), stop=150.0).lookup(145.0, 0.0)


@pytest.mark.parametrize(
    ("database", "expected"),
    [
        (
            "{grid: radial, horizontal_distance: {start: 1, stop: 2, num: 4},"
            " height_difference: {start: 1, stop: 2, num: 4}}",
            "horizontal_distance: an axis of grid 'cartesian', not of grid 'radial'; "
            "allowed with grid 'radial': distance, angle_deg",
        ),
        (
            "{grid: radial, distance: {start: 1, stop: 2, num: 4}}",
            "angle_deg: required by grid 'radial'",
        ),
        (
            "{grid: radial, distance: {start: 0, stop: 2, num: 4},"
            " angle_deg: {start: 0, stop: 10, num: 4}}",
            "distance.start must be > 0",
        ),
        (
            "{grid: radial, distance: {start: 1, stop: 2, num: 4},"
            " angle_deg: {start: 0, stop: 100, num: 4}}",
            "angle_deg must lie in -90 .. 90",
        ),
        (
            "{grid: polar, distance: {start: 1, stop: 2, num: 4},"
            " angle_deg: {start: 0, stop: 10, num: 4}}",
            "'cartesian' or 'radial'",
        ),
    ],
)
def test_radial_keys_are_validated(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], database: str, expected: str
) -> None:
    cfg = tmp_path / "bad.yaml"
    cfg.write_text(STUDY.split("  database:")[0] + f"  database: {database}\n")
    assert main(["validate", str(cfg)]) == 2
    assert expected in capsys.readouterr().err


def test_radial_grid_with_a_seabed_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    cfg = tmp_path / "bad.yaml"
    cfg.write_text(STUDY.replace("{fluid: water}", "{fluid: water, depth: 300.0}"))
    assert main(["validate", str(cfg)]) == 2
    err = capsys.readouterr().err
    assert "analysis.database.grid: 'radial'" in err
    assert "got environment.depth 300 m" in err
    assert "allowed: grid 'radial' without environment.depth, or grid 'cartesian'" in err


def test_a_sweep_mixing_grid_kinds_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    cfg = tmp_path / "mixed.yaml"
    cfg.write_text(
        STUDY
        + "sweep:\n  analysis.database:\n"
        + "    - {grid: radial, distance: {start: 100, stop: 150, num: 5},"
        + " angle_deg: {start: -30, stop: 30, num: 5}}\n"
        + "    - {horizontal_distance: {start: 100, stop: 150, num: 5},"
        + " height_difference: {start: -30, stop: 30, num: 5}}\n"
    )
    assert main(["validate", str(cfg)]) == 2
    err = capsys.readouterr().err
    assert "analysis.database.grid: the sweep gives grids ['cartesian', 'radial']" in err
