"""Per-analysis status (issue 9, item 6): YAML -> netCDF through the CLI and the runner.

A failed analysis blanks only its own variables; ``<analysis>_status`` says which
failed, ``status`` and ``message`` summarise the case, and the cache keeps failures that
a rerun would repeat but not those of the time limit.
"""

from __future__ import annotations

from collections import OrderedDict
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses import evaluate, line_model
from cablestudy.analyses import static as static_analysis
from cablestudy.analyses.common import STATUS_NOT_RUN
from cablestudy.analyses.dynamic import run_dynamic
from cablestudy.analyses.variables import OUTPUTS, CaseRecord
from cablestudy.cli import main
from cablestudy.run.runner import run_study
from cablestudy.statics import STATUS_NUMERICAL, STATUS_TIME_LIMIT
from cablestudy.study.grid import expand_cases, expand_grid
from cablestudy.study.loader import parse_study_text
from tests.dataset_helpers import assemble

CABLE = """
environment: {fluid: water}
line:
  segments:
    - {length: 10.9774, diameter: 0.01, mass_per_length: 0.61, axial_stiffness: 7.854e6}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [10.792, 0.0, 0.0]}
"""
STATIC = "  static: {method: analytic, nodes: 21}\n"
MODAL = "  modal: {modes: 3, elements: 20}\n"
#: a real dynamic failure: a 0.5 m, 2 Hz end motion started without a ramp on a taut
#: 11 m cable, with Newton allowed 2 iterations, fails at the smallest step
FAILING_DYNAMIC = """\
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.5, frequency: 2.0}
    method: time
    elements: 10
    max_newton_iterations: 2
    max_refinement: 0
    ramp_periods: 0.0
"""
GENTLE_DYNAMIC = """\
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.02, frequency: 0.5}
    method: time
    elements: 10
"""


def _study(name: str, *analysis: str) -> str:
    return f"name: {name}\n{CABLE}analysis:\n" + "".join(analysis)


@pytest.fixture(autouse=True)
def _fresh_caches(monkeypatch: pytest.MonkeyPatch) -> None:
    # each run solves its statics afresh: equal statics are then equal by computation
    monkeypatch.setattr(static_analysis, "_STATIC_CACHE", OrderedDict())
    monkeypatch.setattr(line_model, "_DISCRETE_CACHE", OrderedDict())


def _run(tmp_path: Path, text: str) -> xr.Dataset:
    name = text.split("\n", 1)[0].split(": ")[1]
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    argv = ["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous", "--no-cache"]
    main(argv)
    static_analysis._STATIC_CACHE.clear()
    line_model._DISCRETE_CACHE.clear()
    return xr.load_dataset(tmp_path / f"{name}.nc")


STATIC_VARS = ("x", "y", "z", "tension", "force_a", "force_b", "tension_a", "laid_length")
DYNAMIC_VARS = [k for k, v in OUTPUTS.items() if v.analysis == "dynamic"]


def test_status_variables_exist_only_for_analyses_asked_for(tmp_path: Path) -> None:
    ds = _run(tmp_path, _study("only-static", STATIC))
    assert int(ds["static_status"]) == 0 and int(ds["status"]) == 0
    assert "modal_status" not in ds and "dynamic_status" not in ds
    assert ds["static_status"].dtype == np.int64
    assert ds["static_status"].attrs["units"] == "1" and ds["static_status"].attrs["long_name"]


def test_dynamic_failure_keeps_statics_and_modes_bit_for_bit(tmp_path: Path) -> None:
    failed = _run(tmp_path, _study("dyn-fails", STATIC, MODAL, FAILING_DYNAMIC))
    statics = _run(tmp_path, _study("statics", STATIC, MODAL))
    assert int(failed["static_status"]) == 0 and int(failed["modal_status"]) == 0
    assert int(failed["dynamic_status"]) == STATUS_NUMERICAL
    assert int(failed["status"]) == STATUS_NUMERICAL
    message = str(failed["message"].item())
    assert message.startswith("dynamic analysis: Newton did not converge"), message
    for name in (*STATIC_VARS, "natural_frequency", "mode_shape"):
        assert np.all(np.isfinite(failed[name].values)), name
        np.testing.assert_array_equal(failed[name].values, statics[name].values, err_msg=name)
    np.testing.assert_array_equal(failed["s"].values, statics["s"].values)
    for name in DYNAMIC_VARS:
        if name in failed and failed[name].dtype.kind == "f":
            assert np.all(np.isnan(failed[name].values)), name
    assert failed["tension_max"].attrs["units"] == "N"  # declared although blank
    assert str(failed["dynamic_method"].item()) == ""


def test_modal_failure_keeps_statics_and_still_runs_the_dynamics(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from cablestudy.dynamics.modal import STATUS_SLACK, ModalResult

    def slack(case, static, deadline):  # noqa: ANN001, ANN202
        return ModalResult.failed(static.s, 3, STATUS_SLACK, "the static line is slack")

    ok = _run(tmp_path, _study("modal-ok", STATIC, MODAL, GENTLE_DYNAMIC))
    monkeypatch.setattr(evaluate, "solve_modal", slack)
    ds = _run(tmp_path, _study("modal-fails", STATIC, MODAL, GENTLE_DYNAMIC))
    assert int(ok["status"]) == 0 and int(ok["modal_status"]) == 0
    assert int(ds["modal_status"]) == STATUS_SLACK and int(ds["status"]) == STATUS_SLACK
    assert int(ds["static_status"]) == 0 and int(ds["dynamic_status"]) == 0
    assert str(ds["message"].item()) == "modal analysis: the static line is slack"
    assert np.all(np.isnan(ds["natural_frequency"])) and np.all(np.isnan(ds["mode_shape"]))
    assert np.all(np.isnan(ds["modal_dof"]))
    for name in (*STATIC_VARS, "tension_max", "tension_min", "tension_mean", "periods"):
        np.testing.assert_array_equal(ds[name].values, ok[name].values, err_msg=name)
    assert np.isfinite(float(ds["tension_max"]))


def test_static_failure_leaves_the_other_analyses_not_run(tmp_path: Path) -> None:
    text = _study("static-fails", STATIC, MODAL, GENTLE_DYNAMIC).replace(
        "analysis:\n", "analysis:\n  time_limit: 1.0e-9\n"
    )
    ds = _run(tmp_path, text)
    assert int(ds["static_status"]) == STATUS_TIME_LIMIT == int(ds["status"])
    assert int(ds["modal_status"]) == STATUS_NOT_RUN
    assert int(ds["dynamic_status"]) == STATUS_NOT_RUN
    assert str(ds["message"].item()).startswith("time limit")  # the static solver's own
    assert np.all(np.isnan(ds["tension"]))


def test_non_finite_values_are_charged_to_their_analysis(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    real = run_dynamic

    def nan_max(case, static, deadline):  # noqa: ANN001, ANN202
        status, message, out = real(case, static, deadline)
        out["tension_max"] = np.asarray(np.nan)
        return status, message, out

    monkeypatch.setattr(evaluate, "run_dynamic", nan_max)
    ds = _run(tmp_path, _study("nan-dyn", STATIC, GENTLE_DYNAMIC))
    assert int(ds["static_status"]) == 0 and int(ds["dynamic_status"]) == STATUS_NUMERICAL
    assert str(ds["message"].item()) == "dynamic analysis: non-finite values in tension_max"
    assert np.all(np.isfinite(ds["tension"])) and np.isnan(float(ds["tension_min"]))


def test_cache_keeps_a_dynamic_failure_but_retries_a_dynamic_time_limit(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    def timed_out(case, static, deadline):  # noqa: ANN001, ANN202
        return STATUS_TIME_LIMIT, "time limit reached at t = 1 s of the dynamic run", {}

    def broken(case, static, deadline):  # noqa: ANN001, ANN202
        return STATUS_NUMERICAL, "Newton did not converge", {}

    src = parse_study_text(_study("cached", STATIC, GENTLE_DYNAMIC), "cached.yaml")
    grid = expand_grid(src)
    for solver, reused in ((timed_out, 0), (broken, 0), (broken, 1)):
        monkeypatch.setattr(evaluate, "run_dynamic", solver)
        summary = run_study(src, grid, tmp_path, scheduler="synchronous", progress=False)
        ds = xr.load_dataset(summary.path)
        assert summary.n_reused == reused
        assert int(ds["dynamic_status"]) != 0 and np.all(np.isfinite(ds["tension"]))
        assert str(ds["message"].item()).startswith("dynamic analysis: ")


def test_assembly_blanks_only_the_failed_analysis() -> None:
    text = _study("asm", STATIC, GENTLE_DYNAMIC) + "sweep:\n  analysis.dynamic.elements: [10, 12]\n"
    src = parse_study_text(text, "asm.yaml")
    axes, cases = expand_cases(src)
    records = {}
    for c in cases:
        bad = c.index == (1,)
        records[c.hash] = CaseRecord(
            hash=c.hash,
            index=c.index,
            status=2 if bad else 0,
            message="dynamic analysis: boom" if bad else "",
            wall_time=0.0,
            data={
                "arc_length": np.array([0.0, 1.0]),
                "tension": np.array([3.0, 4.0]),
                "tension_max": np.asarray(5.0),
                "static_status": np.asarray(0),
                "dynamic_status": np.asarray(2 if bad else 0),
            },
        )
    ds = assemble(axes, cases, records, src)
    np.testing.assert_array_equal(ds["tension"].values, [[3.0, 4.0], [3.0, 4.0]])
    np.testing.assert_array_equal(ds["tension_max"].values, [5.0, np.nan])
    np.testing.assert_array_equal(ds["dynamic_status"].values, [0, 2])
    assert ds.attrs["cases_failed"] == 1
