"""The quasi-static database (analysis.database) and its lookup.

Exact checks: the interpolant reproduces a bicubic polynomial table to round-off (the
not-a-knot spline's node derivatives are exact for cubics, and a bicubic Hermite patch
with exact node data is the polynomial itself); it is C1 across cell boundaries; at the
grid nodes it returns the solved values. Accuracy on a real line: the error against
direct solves falls as h^4 (benchmarks/wp_database.py: 9.8e-4, 8.2e-5, 4.0e-6, 2.1e-7
of the end tension for 5, 9, 17, 33 points a side), so a 17 x 17 grid is held to 1e-5.
"""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses.database import QuasiStaticDatabase, open_database
from cablestudy.cli import main
from cablestudy.statics import STATIC_SOLVERS, EndCondition
from cablestudy.study import load_study
from cablestudy.study.problem import static_problem


def poly(r: np.ndarray, h: np.ndarray) -> np.ndarray:
    return 3.0 + 2.0 * r - r**2 * h + 0.5 * r**3 + 0.25 * h**3 * r**2 - 4.0 * r**3 * h**3


def test_bicubic_polynomials_are_reproduced_and_the_interpolant_is_c1() -> None:
    R = np.array([0.0, 0.3, 0.5, 1.0, 1.4, 2.0])
    H = np.array([-1.0, -0.2, 0.0, 0.7, 1.0])
    db = QuasiStaticDatabase.from_arrays(R, H, {"f": poly(R[:, None], H[None, :])})
    rng = np.random.default_rng(3)
    for r, h in rng.uniform([0, -1], [2, 1], (50, 2)):
        assert db.lookup(r, h)["f"] == pytest.approx(poly(r, h), rel=1e-12, abs=1e-12)
    # C1 on a table that is not a polynomial: value and slope match across r = 0.5
    db = QuasiStaticDatabase.from_arrays(R, H, {"f": np.exp(R[:, None]) * np.sin(3 * H[None, :])})
    eps = 1e-6
    for h in (-0.5, 0.1, 0.9):
        left, mid, right = (db.lookup(0.5 + k * eps, h)["f"] for k in (-1, 0, 1))
        # continuous: the one-sided differences agree to O(eps f'') (~1e-6 here), and
        # a jump in value (or slope) would show as a difference of O(1) (or O(1e-6) *
        # the slope jump / eps)
        slope_l, slope_r = (mid - left) / eps, (right - mid) / eps
        assert abs(slope_l - slope_r) <= 1e-4 * max(abs(slope_l), 1.0)


def test_lookup_outside_the_grid_is_refused_with_its_range() -> None:
    R, H = np.linspace(10.0, 20.0, 5), np.linspace(-3.0, 3.0, 4)
    db = QuasiStaticDatabase.from_arrays(R, H, {"f": np.ones((5, 4))})
    with pytest.raises(
        ValueError, match=r"horizontal distance 10 \.\. 20 m and height difference -3 \.\. 3 m"
    ):
        db.lookup(25.0, 0.0)


STUDY = """\
name: db
environment: {fluid: water}
line:
  segments:
    - {length: 60.0, diameter: 0.09, mass_per_length: 80.0, axial_stiffness: 8.0e8}
    - {length: 140.0, diameter: 0.06, mass_per_length: 12.0, axial_stiffness: 2.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -150.0]}
  b: {kind: fixed, position: [80.0, 96.0, -60.0]}
analysis:
  static: {method: catenary, nodes: 21}
  database:
    horizontal_distance: {start: 110.0, stop: 150.0, num: 17}
    height_difference: {start: 50.0, stop: 100.0, num: 17}
"""


def test_database_yaml_to_netcdf_to_lookup_matches_direct_solves(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    cfg = tmp_path / "db.yaml"
    cfg.write_text(STUDY)
    assert (
        main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous", "--no-cache"])
        == 0
    )
    capsys.readouterr()
    ds = xr.load_dataset(tmp_path / "db.nc")
    assert ds["database_tension_a"].dims == ("horizontal_distance", "height_difference")
    assert ds["database_force_b"].attrs["units"] == "N"
    assert np.all(ds["database_status"] == 0)
    db = open_database(str(tmp_path / "db.nc"))
    study, _ = load_study(str(cfg))
    base = static_problem(study)
    heading = np.arctan2(96.0, 80.0)  # the plane through A and the study's end B
    e = np.array([np.cos(heading), np.sin(heading), 0.0])
    rng = np.random.default_rng(5)
    pts = [(110.0, 50.0), (137.5, 71.875)] + [
        tuple(p) for p in rng.uniform([110, 50], [150, 100], (8, 2))
    ]
    for k, (r, h) in enumerate(pts):
        rB = np.asarray(base.end_a.position) + r * e + np.array([0.0, 0.0, h])
        res = STATIC_SOLVERS["catenary"].solve(
            replace(base, end_b=EndCondition(kind="fixed", position=rB))
        )
        got = db.lookup(r, h)
        scale = np.linalg.norm(res.force_b)
        tol = 1e-9 if k < 2 else 1e-5  # grid nodes: the solved values themselves
        np.testing.assert_allclose(got["force_a"], res.force_a, rtol=0, atol=tol * scale)
        np.testing.assert_allclose(got["force_b"], res.force_b, rtol=0, atol=tol * scale)
        assert got["tension_b"] == pytest.approx(np.linalg.norm(res.force_b), abs=tol * scale)
        if k < 2:
            # the largest tension is max(T_A, T_B) here: it has a kink where the two
            # cross, so it is interpolated to first order only near that line; exact at
            # the nodes
            assert got["tension_max"] == pytest.approx(np.max(res.tension), abs=tol * scale)
    # the command line gives the same numbers as JSON, and refuses outside the grid
    assert main(["lookup", str(tmp_path / "db.nc"), "--at", "130", "75"]) == 0
    out = json.loads(capsys.readouterr().out)
    np.testing.assert_allclose(out["force_b"], db.lookup(130.0, 75.0)["force_b"], rtol=1e-15)
    assert main(["lookup", str(tmp_path / "db.nc"), "--at", "160", "75"]) == 2
    assert "allowed: horizontal distance 110 .. 150 m" in capsys.readouterr().err
    # the database's own file: the same tables on the same grid, and the same lookup
    own = xr.load_dataset(tmp_path / "db.database.nc")
    assert own.attrs["database_grid"] == "cartesian"
    assert own["force_b"].dims == ("horizontal_distance", "height_difference", "component")
    np.testing.assert_array_equal(own["force_b"].values, ds["database_force_b"].values)
    np.testing.assert_array_equal(own["horizontal_distance"], ds["horizontal_distance"])
    assert own["tension_max"].attrs == {"units": "N", "long_name": "largest tension along the line"}
    assert main(["lookup", str(tmp_path / "db.database.nc"), "--at", "130", "75"]) == 0
    assert json.loads(capsys.readouterr().out) == out
