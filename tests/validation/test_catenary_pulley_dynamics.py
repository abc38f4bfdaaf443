"""A catenary line sliding over a fixed pulley in the time domain (issue 12 item 4;
aqwa seed 5.8.1.1 friction law), :mod:`cablestudy.dynamics.pulley`.

Checks, on a chain hanging from A over a pulley to B with B moved in surge:
frictionless, the tensions of the elements on both sides of the pulley agree at every
step to the step's Newton tolerance (the outer iteration on the split stops there);
with a large friction factor the line never slides and the run is the run of the same
line with the pulley as a fixed node, step for step; with friction factor 1.5 the
tension ratio never exceeds 1.5^(wrap / 180 deg) and equals it while the line slides;
YAML -> netCDF; config faults refused before work.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses.static import solve_static
from cablestudy.analyses.time import dynamic_problem
from cablestudy.cli import main
from cablestudy.dynamics.pulley import pulley_tensions, slide_bound, wrap_angle
from cablestudy.dynamics.timedomain import simulate
from cablestudy.statics import STATIC_SOLVERS
from cablestudy.statics.base import EndCondition
from cablestudy.statics.pulley import solve_over_pulleys
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import read_study_source
from cablestudy.study.problem import static_problem

STUDY = """\
name: pulley-dynamics
environment: {fluid: water}
line:
  segments:
    - {length: 120.0, diameter: 0.05, mass_per_length: 30.0, axial_stiffness: 1.0e8}
  pulleys:
    - {position: [50.0, 0.0, -5.0], friction_factor: 1.0}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [90.0, 0.0, 0.0]}
analysis:
  static: {method: catenary, nodes: 61}
  dynamic:
    method: METHOD
    elements: 40
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 1.0, frequency: 0.1}
sweep:
  line.pulleys.0.friction_factor: [1.0, 1.5, 100.0]
"""


def runs(tmp_path: Path) -> dict[float, tuple]:
    """Per friction factor: (the dynamic problem, its result with every step kept)."""
    cfg = tmp_path / "pd.yaml"
    cfg.write_text(STUDY.replace("METHOD", "time"))
    _, cases = expand_cases(read_study_source(cfg))
    out = {}
    for case in cases:
        static = solve_static(case, None)
        assert static.status == 0, static.message
        prob = dynamic_problem(case, static)
        assert not isinstance(prob, str), prob
        prob = replace(prob, keep_steps=True, duration=30.0)
        res = simulate(prob)
        assert res.status == 0, res.message
        out[case.coords["friction_factor"]] = (prob, res)
    return out


@pytest.fixture(scope="module")
def pulley_runs(tmp_path_factory: pytest.TempPathFactory) -> dict[float, tuple]:
    return runs(tmp_path_factory.mktemp("pulley-dynamics"))


def _sides(prob, res):  # noqa: ANN001, ANN202
    """Tensions arriving at and leaving the pulley at every step (the line of each step
    rebuilt at its split)."""
    node = prob.pulleys.node
    rec = res.record
    pairs = [
        pulley_tensions(prob.pulleys.rebuild(S), x, T, node)
        for S, x, T in zip(rec["split"], rec["x"], rec["tension"], strict=True)
    ]
    return np.array([p[0][0] for p in pairs]), np.array([p[1][0] for p in pairs])


def test_frictionless_pulley_keeps_equal_tensions_at_every_step(pulley_runs: dict) -> None:
    """The split is solved each step until |T_out - T_in| <= the Newton tolerance [N]
    (an element tension is known to about the residual force Newton leaves), and the
    line does slide (the split moves by metres as B surges by 1 m)."""
    prob, res = pulley_runs[1.0]
    T_in, T_out = _sides(prob, res)
    assert np.all(np.abs(T_out - T_in) <= prob.newton_tolerance)
    split = res.record["split"][:, 0]
    assert split.max() - split.min() > 1.0
    assert res.rejected_steps == 0


def test_large_friction_sticks_and_is_a_fixed_node(pulley_runs: dict) -> None:
    """With factor 100 (bound 100^(wrap/180 deg) ~ 10 at the 90-degree wrap here, while
    the tensions differ by at most 25 %)
    the split never moves, and the run is that of the same line with the pulley node
    simply held: the same implicit steps, so the same tensions to round-off."""
    prob, res = pulley_runs[100.0]
    split = res.record["split"][:, 0]
    assert np.all(split == prob.pulleys.split[0])
    fixed = simulate(replace(prob, pulleys=None))
    assert fixed.status == 0
    np.testing.assert_allclose(res.record["t"], fixed.record["t"], rtol=0, atol=1e-12)
    scale = float(np.max(fixed.record["tension"]))
    np.testing.assert_allclose(res.record["tension"], fixed.record["tension"], atol=1e-9 * scale)
    np.testing.assert_allclose(res.record["x"], fixed.record["x"], atol=1e-9)


def test_friction_bounds_the_tension_ratio(pulley_runs: dict) -> None:
    """Factor 1.5: T_large / T_small <= 1.5^(wrap / 180 deg) at every step (to the
    Newton tolerance over the smaller tension), with equality on the steps where the
    line slid; it slides on some steps and sticks on others."""
    prob, res = pulley_runs[1.5]
    T_in, T_out = _sides(prob, res)
    node = prob.pulleys.node
    wrap = np.array([wrap_angle(x, node)[0] for x in res.record["x"]])
    bound = slide_bound(np.array([1.5]), wrap)
    lo = np.minimum(T_in, T_out)
    ratio = np.maximum(T_in, T_out) / lo
    slack = 2.0 * prob.newton_tolerance / lo
    assert np.all(ratio <= bound * (1.0 + slack))
    split = res.record["split"][:, 0]
    slid = np.nonzero(np.diff(split) != 0.0)[0] + 1
    stuck = np.nonzero(np.diff(split) == 0.0)[0] + 1
    assert len(slid) > 10 and len(stuck) > 10
    np.testing.assert_allclose(ratio[slid], bound[slid], atol=float(np.max(slack[slid])))
    # the line turns by about 90 degrees over the pulley: a bound of about 1.5^0.5
    assert math.degrees(float(np.mean(wrap))) == pytest.approx(90.0, abs=10.0)


def test_yaml_to_netcdf(tmp_path: Path) -> None:
    """`cablestudy run` with method auto: the frequency domain cannot slide a line over
    a pulley, so the time domain runs and says why; the pulley's range of travel is
    written; frictionless it travels, with factor 100 it stays at the discrete model's
    static split (within the continuous statics' split by the discretisation error)."""
    cfg = tmp_path / "pd.yaml"
    cfg.write_text(STUDY.replace("METHOD", "auto").replace("[1.0, 1.5, 100.0]", "[1.0, 100.0]"))
    code = main(
        ["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous", "--no-cache"]
    )
    assert code == 0
    ds = xr.load_dataset(tmp_path / "pulley-dynamics.nc")
    assert list(ds["status"].values) == [0, 0]
    assert all(m == "time" for m in ds["dynamic_method"].values)
    assert "pulleys" in str(ds["dynamic_method_reason"].values[0])
    lo, hi = ds["pulley_arc_length_min"], ds["pulley_arc_length_max"]
    assert lo.attrs["units"] == "m" and lo.dims == ("friction_factor", "pulley")
    assert float(hi[0, 0] - lo[0, 0]) > 1.0
    assert float(hi[1, 0]) == float(lo[1, 0])
    assert float(lo[1, 0]) == pytest.approx(float(ds["pulley_arc_length"][1, 0]), abs=0.5)
    assert float(ds["tension_max"][0]) > float(ds["tension_static"][0])


@pytest.mark.parametrize(
    ("old", "new", "fragment"),
    [
        ("method: METHOD", "method: frequency", "a line sliding over pulleys is modelled by"),
        (
            "  dynamic:\n",
            "  modal: {modes: 3}\n  dynamic:\n",
            "pulleys on a catenary line are supported by the statics",
        ),
        (
            "    elements: 40\n",
            "    elements: 40\n    history: {points: [10.0]}\n",
            "analysis.dynamic.history: not available for a catenary line over pulleys",
        ),
        (
            "environment: {fluid: water}",
            "environment: {fluid: water, depth: 100.0, seabed: {friction: 0.5}}",
            "environment.seabed.friction: 0.5 with a line sliding over pulleys",
        ),
    ],
)
def test_config_faults_are_refused_before_work(
    tmp_path: Path, old: str, new: str, fragment: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert old in STUDY
    cfg = tmp_path / "bad.yaml"
    cfg.write_text(STUDY.replace(old, new).replace("METHOD", "time"))
    assert main(["validate", str(cfg)]) != 0
    assert fragment in capsys.readouterr().err


def test_slow_surge_converges_to_the_statics_over_the_pulley(tmp_path: Path) -> None:
    """Frictionless, B surged by 2 m at 0.002 Hz (quasi-static: at the largest offset
    the line's inertia is m w^2 A L ~ 1 N against 1.2e4 N of tension): the end tension and
    the split there converge at second order in the element length to the statics of
    the line over the pulley with B at that offset (the lumped-mass line's own order;
    the tensions are carried to the pulley through the half-elements' weight)."""
    errors, split_errors = [], []
    for elements in (20, 40, 80):
        cfg = tmp_path / f"qs{elements}.yaml"
        text = STUDY.replace("METHOD", "time").replace("elements: 40", f"elements: {elements}")
        text = text.replace("amplitude: 1.0, frequency: 0.1", "amplitude: 2.0, frequency: 0.002")
        cfg.write_text(text.split("sweep:")[0])
        _, (case,) = expand_cases(read_study_source(cfg))
        static = solve_static(case, None)
        prob = dynamic_problem(case, static)
        assert not isinstance(prob, str), prob
        prob = replace(prob, keep_steps=True, duration=prob.motion.ramp_time + 250.0)
        res = simulate(prob)
        assert res.status == 0, res.message
        j = int(np.argmax(res.record["x"][:, -1, 0]))
        rB = res.record["x"][j, -1]
        assert rB[0] == pytest.approx(92.0, abs=1e-6)
        sp = replace(static_problem(case.study), end_b=EndCondition(kind="fixed", position=rB))
        qs = solve_over_pulleys(sp, np.array([[50.0, 0.0, -5.0]]), STATIC_SOLVERS["catenary"])
        T_qs = float(np.linalg.norm(qs.force_b))
        errors.append(abs(float(np.linalg.norm(res.record["end_force"][j, 1])) / T_qs - 1.0))
        split_errors.append(abs(float(res.record["split"][j, 0] - qs.split[0])))
    # halving the elements divides the errors by about 4 (measured 4.3 and 5.0 for the
    # tension, 3.9 and 4.3 for the split)
    for err in (errors, split_errors):
        assert err[0] / err[1] > 3.0 and err[1] / err[2] > 3.0
    assert errors[-1] < 2e-4
    assert split_errors[-1] < 1e-2


def test_a_line_at_rest_over_a_frictionless_pulley_stays_at_rest(tmp_path: Path) -> None:
    """No excitation: the run starts in the discrete model's own frictionless equilibrium
    (its split solved so the pulley tensions agree to 10 x 1e-9 of the tension, below
    the step's Newton tolerance): the end tension stays the static one to the Newton
    tolerance, and the split moves only by the slides that the residual force Newton
    leaves each step brings about (measured: nodes drift by 3e-7 m over 30 s, the split
    by 2e-8 m; a mismatch of the tolerance is a split change of tol / (dg/dS) ~ 1e-9 m)."""
    cfg = tmp_path / "still.yaml"
    text = STUDY.replace("METHOD", "time").replace("amplitude: 1.0", "amplitude: 0.0")
    cfg.write_text(text.split("sweep:")[0])
    _, (case,) = expand_cases(read_study_source(cfg))
    static = solve_static(case, None)
    prob = dynamic_problem(case, static)
    assert not isinstance(prob, str), prob
    res = simulate(replace(prob, keep_steps=True, duration=30.0))
    assert res.status == 0, res.message
    np.testing.assert_allclose(res.record["split"][:, 0], prob.pulleys.split[0], rtol=0, atol=1e-6)
    assert np.max(np.abs(res.record["x"] - res.record["x"][0])) < 1e-5
    T_end = np.linalg.norm(res.record["end_force"][:, 1], axis=1)
    np.testing.assert_allclose(T_end, res.tension_static, atol=prob.newton_tolerance)
