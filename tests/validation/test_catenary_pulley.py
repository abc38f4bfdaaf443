"""A catenary line over fixed pulleys (issue 12 item 4; aqwa seed 5.8.1.1), statics.

The line is a chain of fixed-fixed catenaries A -> P1 (-> P2) -> B whose split along s is
solved so that the tension is continuous over each frictionless pulley
(:mod:`cablestudy.statics.pulley`). Checks: the tension mismatch over each pulley is
within the asked tolerance; a symmetric V splits symmetrically; a pulley placed on the
no-pulley catenary's own curve changes nothing (the sub-lines are pieces of that curve:
the fixed-fixed catenary through its own points is unique); the supports and pulleys
carry the line's weight; YAML -> netCDF; config faults refused before any work.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main
from cablestudy.statics import STATIC_SOLVERS, Medium, StaticProblem
from cablestudy.statics.pulley import solve_over_pulleys, sub_problems
from tests.statics_helpers import fixed, make_line

WATER = Medium(density=1025.0, gravity=9.80665)
#: a two-segment line with a clump weight at s = 20 m
COMPOSITE = make_line(
    [70.0, 50.0], [300.0, 120.0], [2.0e8, 5.0e7], attachments=[(20.0, (0.0, 0.0, -2000.0))]
)


def problem(line, a, b, n=121, tol=1e-10):  # noqa: ANN001, ANN201
    return StaticProblem(
        line=line, medium=WATER, end_a=fixed(*a), end_b=fixed(*b), n_nodes=n, tolerance=tol
    )


@pytest.mark.parametrize("method", ["catenary", "shooting"])
@pytest.mark.parametrize(
    "pulleys",
    [np.array([[45.0, 0.0, -30.0]]), np.array([[30.0, 5.0, -25.0], [70.0, -5.0, -20.0]])],
)
def test_frictionless_pulley_gives_equal_tensions(method: str, pulleys: np.ndarray) -> None:
    """Re-solving each sub-line at the reported split, the tension arriving at a pulley
    equals the tension leaving it. The split's Newton stops when the mismatch is below
    the asked tolerance (1e-10 of the tension); the sub-lines are solved to 1e-2 of
    that, so the re-solve agrees to 2e-10."""
    prob = problem(COMPOSITE, (0.0, 0.0, 0.0), (100.0, 0.0, -5.0))
    solver = STATIC_SOLVERS[method]
    res = solve_over_pulleys(prob, pulleys, solver)
    assert res.status == 0, res.message
    assert res.residual <= 1e-10
    subs = [
        solver.solve(replace(p, tolerance=1e-12))
        for p in sub_problems(prob, pulleys, res.split)  # type: ignore[attr-defined]
    ]
    for left, right in zip(subs[:-1], subs[1:], strict=True):
        Tl, Tr = np.linalg.norm(left.force_b), np.linalg.norm(right.force_a)
        assert Tl == pytest.approx(Tr, rel=2e-10)
    # the line's tension along s is continuous over the pulleys too
    np.testing.assert_allclose(np.linalg.norm(res.force_a), res.tension[0], rtol=1e-9)
    # the supports and the pulleys carry the weight of the line and of the clump
    W = 300.0 * 70.0 + 120.0 * 50.0 + 2000.0
    total = res.force_a + res.force_b + res.pulley_force.sum(axis=0)  # type: ignore[attr-defined]
    np.testing.assert_allclose(total, [0.0, 0.0, -W], atol=1e-8 * W)


def test_symmetric_v_splits_at_the_middle() -> None:
    """A uniform line from A to B at equal height over a pulley midway below: the mirror
    image x -> 100 - x, s -> L - s is a solution too, and it is unique, so the split is
    L / 2 and the shape symmetric. The split's error is the tension mismatch (1e-11)
    over dT/dS (about EA / L), far below 1e-9 m."""
    line = make_line([140.0], [200.0], [1.0e8])
    prob = problem(line, (0.0, 0.0, 0.0), (100.0, 0.0, 0.0), n=141, tol=1e-11)
    res = solve_over_pulleys(prob, np.array([[50.0, 0.0, -40.0]]), STATIC_SOLVERS["catenary"])
    assert res.status == 0, res.message
    assert res.split[0] == pytest.approx(70.0, abs=1e-9)  # type: ignore[attr-defined]
    np.testing.assert_allclose(res.position[:, 0], 100.0 - res.position[::-1, 0], atol=1e-8)
    np.testing.assert_allclose(res.position[:, 2], res.position[::-1, 2], atol=1e-8)
    np.testing.assert_allclose(res.tension, res.tension[::-1], rtol=1e-9)
    # the pulley is pulled straight down by both halves
    assert abs(res.pulley_force[0, 0]) < 1e-8 * res.tension.max()  # type: ignore[attr-defined]


@pytest.mark.parametrize("method", ["catenary", "shooting", "analytic"])
def test_pulley_on_the_catenarys_own_curve_changes_nothing(method: str) -> None:
    """Pulleys at points of the line's own no-pulley solution: the sub-lines are pieces
    of that curve (unique between their ends), so the split falls at those points' s and
    tensions and shape are unchanged. Tolerances: the solvers' own accuracy at 1e-10 (the
    shooting solver integrates to 1e-12 relative, its end tension agrees to a few 1e-9);
    positions between output points come from the oversampled cubic spline."""
    if method == "analytic":  # the analytic solver takes a uniform line without loads
        line = make_line([120.0], [250.0], [1.0e8])
    else:
        line = COMPOSITE
    prob = problem(line, (0.0, 0.0, 0.0), (90.0, 0.0, -10.0))
    solver = STATIC_SOLVERS[method]
    base = solver.solve(prob)
    assert base.status == 0
    for nodes in ([37], [31, 88]):
        pulleys = base.position[nodes]
        res = solve_over_pulleys(prob, pulleys, solver)
        assert res.status == 0, res.message
        T = float(np.max(base.tension))
        np.testing.assert_allclose(res.split, base.s[nodes], atol=1e-7)  # type: ignore[attr-defined]
        np.testing.assert_allclose(res.force_a, base.force_a, atol=1e-8 * T)
        np.testing.assert_allclose(res.force_b, base.force_b, atol=1e-8 * T)
        np.testing.assert_allclose(res.tension, base.tension, atol=1e-8 * T)
        np.testing.assert_allclose(res.position, base.position, atol=1e-7)
        # the line runs straight through: the pulleys carry nothing
        np.testing.assert_allclose(res.pulley_force, 0.0, atol=1e-8 * T)  # type: ignore[attr-defined]


STUDY = """\
name: pulley
environment: {fluid: water}
line:
  segments:
    - {length: 60.0, diameter: 0.05, mass_per_length: 50.0, axial_stiffness: 2.0e8}
    - {length: 60.0, diameter: 0.05, mass_per_length: 20.0, axial_stiffness: 1.0e8}
  pulleys:
    - {position: [50.0, 0.0, -5.0], friction_factor: 1.5}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [90.0, 0.0, 0.0]}
analysis:
  static: {method: METHOD, nodes: 61, tolerance: 1.0e-10}
sweep:
  line.pulleys.0.position.2: [-10.0, 0.0]
"""


def run(tmp_path: Path, text: str) -> xr.Dataset:
    cfg = tmp_path / "pulley.yaml"
    cfg.write_text(text)
    code = main(
        ["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous", "--no-cache"]
    )
    assert code == 0
    return xr.load_dataset(tmp_path / "pulley.nc")


def test_yaml_to_netcdf(tmp_path: Path) -> None:
    """The study through `cablestudy run`: both methods agree, the pulley sits on the
    line at pulley_arc_length, and supports plus pulley carry the line's weight in water
    (to the solvers' 1e-10)."""
    ds = {m: run(tmp_path, STUDY.replace("METHOD", m)) for m in ("catenary", "shooting")}
    cat, sho = ds["catenary"], ds["shooting"]
    assert int(cat["status"].max()) == 0 and int(sho["status"].max()) == 0
    assert cat["pulley_force"].attrs["units"] == "N"
    assert cat["pulley_arc_length"].dims == ("position_2", "pulley")
    area = np.pi * 0.05**2 / 4
    W = 9.80665 * ((50.0 - 1025.0 * area) * 60.0 + (20.0 - 1025.0 * area) * 60.0)
    total = cat["force_a"] + cat["force_b"] + cat["pulley_force"].sum("pulley")
    np.testing.assert_allclose(total.values, np.tile([0.0, 0.0, -W], (2, 1)), atol=1e-8 * W)
    for key in ("tension_a", "tension_b", "pulley_arc_length"):
        np.testing.assert_allclose(cat[key].values, sho[key].values, rtol=1e-7)
    # the output point nearest the pulley lies within the sampling of it
    for i, zp in enumerate((-10.0, 0.0)):
        sp = float(cat["pulley_arc_length"][i, 0])
        j = int(np.argmin(np.abs(cat["s"].values - sp)))
        gap = np.hypot(float(cat["x"][i, j]) - 50.0, float(cat["z"][i, j]) - zp)
        assert gap <= abs(float(cat["s"][j]) - sp) * (1 + 1e-3)


@pytest.mark.parametrize(
    ("old", "new", "fragment"),
    [
        ("method: METHOD", "method: discrete", "allowed with line.pulleys: analytic, catenary"),
        (
            "  static: {method: METHOD",
            "  database: {horizontal_distance: {start: 80, stop: 90, num: 4}, "
            "height_difference: {start: -5, stop: 5, num: 4}}\n  static: {method: catenary",
            "analysis.database: not supported for a kind: catenary line over pulleys",
        ),
        (
            "b: {kind: fixed, position: [90.0, 0.0, 0.0]}",
            "b: {kind: force, force: [1.0e4, 0, 0]}",
            "a line over pulleys needs both ends fixed",
        ),
        (
            "method: METHOD",
            "method: catenary, installation: {payout_speed: 1.0}",
            "does not pass over fixed pulleys",
        ),
    ],
)
def test_config_faults_are_refused_before_work(
    tmp_path: Path, old: str, new: str, fragment: str, capsys: pytest.CaptureFixture[str]
) -> None:
    cfg = tmp_path / "bad.yaml"
    assert old in STUDY
    cfg.write_text(STUDY.replace(old, new).replace("METHOD", "catenary"))
    assert main(["validate", str(cfg)]) != 0
    assert fragment in capsys.readouterr().err


def test_moordyn_export_refuses_pulleys(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A MoorDyn point holds a line, it does not let it slide: no silent export."""
    cfg = tmp_path / "pulley.yaml"
    cfg.write_text(STUDY.replace("METHOD", "catenary"))
    code = main(["export", "moordyn", str(cfg), "--case", "position_2=0.0"])
    assert code != 0
    assert "line.pulleys: a line over fixed pulleys has no MoorDyn" in capsys.readouterr().err


def test_mooring_over_a_fairlead_pulley_where_newton_stalls() -> None:
    """A chain from an anchor on the seabed over a fairlead pulley up to a deck point
    2 m off the pulley's vertical: the short upper sub-line turns taut within
    millimetres of the split and the lower one can only lengthen by lifting off, so
    Newton on the split stalls; the bracketed fallback (regula falsi on the monotone
    mismatch) finds the split. Re-solving the sub-lines there gives equal tensions to
    the tolerance; supports, pulley and seabed carry the weight (the seabed the laid
    part's: w times the laid length, rigid and frictionless). Method shooting agrees
    (checked once: 1e-9 of the tensions, 1e-9 m of the split, 24 s)."""
    from cablestudy.statics.base import Medium as Med

    line = make_line([560.0], [1000.0], [6.0e8])
    sea = Med(density=1025.0, gravity=9.80665, depth=100.0)
    prob = StaticProblem(
        line=line,
        medium=sea,
        end_a=fixed(0.0, 0.0, -100.0),
        end_b=fixed(452.0, 0.0, 10.0),
        n_nodes=101,
        tolerance=1e-9,
    )
    pulley = np.array([[450.0, 0.0, -5.0]])
    solver = STATIC_SOLVERS["catenary"]
    res = solve_over_pulleys(prob, pulley, solver)
    assert res.status == 0, res.message
    assert res.iterations > 12  # the fallback ran
    subs = [
        solver.solve(replace(p, tolerance=1e-12))
        for p in sub_problems(prob, pulley, res.split)  # type: ignore[attr-defined]
    ]
    T = np.linalg.norm(subs[0].force_b)
    assert np.linalg.norm(subs[1].force_a) == pytest.approx(T, rel=2e-9)
    W = 1000.0 * 560.0
    laid = res.laid_length
    assert 0.0 < laid < 560.0
    total = res.force_a + res.force_b + res.pulley_force.sum(axis=0)  # type: ignore[attr-defined]
    np.testing.assert_allclose(total, [0.0, 0.0, -(W - 1000.0 * laid)], atol=1e-6 * W)


@pytest.mark.parametrize(
    "pulleys",
    [np.array([[45.0, 0.0, -30.0]]), np.array([[30.0, 5.0, -25.0], [70.0, -5.0, -20.0]])],
)
def test_bracketed_fallback_finds_newtons_split(
    pulleys: np.ndarray, monkeypatch: pytest.MonkeyPatch
) -> None:
    """With no Newton iterations allowed the fallback alone (regula falsi; nested for two
    pulleys) finds the split Newton finds, to the mismatch tolerance over dT/dS."""
    import cablestudy.statics.pulley as pulley_module

    prob = problem(COMPOSITE, (0.0, 0.0, 0.0), (100.0, 0.0, -5.0))
    solver = STATIC_SOLVERS["catenary"]
    newton = solve_over_pulleys(prob, pulleys, solver)
    monkeypatch.setattr(pulley_module, "NEWTON_ITERATIONS", 0)
    fallback = solve_over_pulleys(prob, pulleys, solver)
    assert fallback.status == 0, fallback.message
    assert fallback.residual <= 1e-10
    np.testing.assert_allclose(fallback.split, newton.split, atol=1e-7)  # type: ignore[attr-defined]
    np.testing.assert_allclose(fallback.force_a, newton.force_a, rtol=1e-8)
