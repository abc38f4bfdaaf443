"""The dynamic analysis end to end: study YAML -> cases -> netCDF, through the CLI."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import StudyError, parse_study_text

CABLE = """
environment: {fluid: water}
line:
  segments:
    - {length: 10.9774, diameter: 0.01, mass_per_length: 0.61, axial_stiffness: 7.854e6}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [10.792, 0.0, 0.0]}
"""

CONTRACT = (
    "name: contract\n"
    + CABLE
    + """
analysis:
  static: {method: analytic}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.05, frequency: 0.5}
    method: time
    elements: 10
sweep:
  analysis.dynamic.excitation.amplitude: [0.025, 0.05]
  analysis.dynamic.excitation.frequency: {start: 0.3, stop: 0.6, num: 2}
"""
)


def _run(tmp_path: Path, text: str, name: str) -> xr.Dataset:
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    assert (
        main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous", "--no-cache"])
        == 0
    )
    return xr.load_dataset(tmp_path / f"{name}.nc")


def test_contract_study_runs_to_netcdf(tmp_path: Path) -> None:
    ds = _run(tmp_path, CONTRACT, "contract")
    assert ds["tension_max"].dims == ("amplitude", "frequency")
    assert ds["frequency"].attrs["units"] == "Hz"
    assert ds["amplitude"].attrs["units"] == "m"
    assert np.all(ds["status"].values == 0)
    assert np.all(ds["dynamic_method"].values == "time")
    assert np.all(ds["dynamic_method_reason"].values == "method: time")
    assert np.all(ds["steady_converged"].values == 1)
    t0 = ds["tension_static"].values
    assert np.all(ds["tension_max"].values > t0) and np.all(ds["tension_min"].values < t0)
    # the swing grows with the amplitude (taut, far below resonance: about linearly)
    swing = (ds["tension_max"] - ds["tension_min"]).values
    assert np.all(swing[1] > 1.5 * swing[0])
    for name in (
        "tension_max",
        "tension_min",
        "tension_mean",
        "tension_static",
        "tension_max_line",
        "dynamic_steps",
        "newton_iterations",
        "rejected_steps",
        "periods",
        "steady_converged",
    ):
        assert "units" in ds[name].attrs and ds[name].attrs["long_name"]
    assert "time" not in ds.dims  # no histories unless asked for
    # the along-line maximum is at least the end maximum
    assert np.all(ds["tension_max_line"].values >= ds["tension_max"].values - 1e-9)


def test_dynamic_settings_stay_out_of_the_static_hash() -> None:
    _, cases = expand_cases(parse_study_text(CONTRACT))
    assert len({c.hash for c in cases}) == 4
    assert len({c.static_hash for c in cases}) == 1


def test_unknown_dynamic_method_is_rejected_at_validation() -> None:
    text = CONTRACT.replace("method: time", "method: spectral")
    with pytest.raises(StudyError) as info:
        expand_cases(parse_study_text(text))
    msg = str(info.value)
    assert "analysis.dynamic.method" in msg and "'spectral'" in msg
    assert "allowed: auto, time, frequency" in msg


def test_history_of_a_moved_end_is_its_prescribed_motion(tmp_path: Path) -> None:
    # end A: harmonic with a phase; end B: a periodic table (a smooth bump, 2 s period)
    times = np.linspace(0.0, 2.0, 41)
    bump = 0.02 * np.sin(np.pi * times / 2.0) ** 2
    table = ", ".join(f"[{t:.4f}, {u:.8f}]" for t, u in zip(times, bump, strict=True))
    text = (
        "name: two-ends\n"
        + CABLE
        + f"""
analysis:
  static: {{method: analytic}}
  dynamic:
    excitation:
      - {{end: a, direction: [0.0, 0.0, 1.0], amplitude: 0.03, frequency: 0.5,
          phase_deg: 90.0}}
      - {{end: b, direction: [1.0, 0.0, 0.0], table: [{table}], periodic: true}}
    elements: 10
    max_periods: 12
    history: {{points: [0.0, 5.4887], periods: 1.0, samples_per_period: 32}}
"""
    )
    ds = _run(tmp_path, text, "two-ends")
    assert int(ds["status"]) == 0, str(ds["message"].values)
    assert ds["history_displacement"].dims == ("point", "time", "component")
    assert ds.sizes["time"] == 33
    t = ds["history_time"].values
    # end A follows 0.03 sin(2 pi 0.5 t + 90 deg) vertically (after the ramp); its
    # samples are the prescribed positions at the steps, interpolated by cubic
    # Hermite with the exact velocities: error O(h^4), far below 1e-6 m
    expected = 0.03 * np.sin(2 * math.pi * 0.5 * t + math.pi / 2)
    disp_a = ds["history_displacement"].isel(point=0)
    np.testing.assert_allclose(disp_a.sel(component="z").values, expected, atol=1e-6)
    np.testing.assert_allclose(disp_a.sel(component="x").values, 0.0, atol=1e-12)
    # the midpoint moves, mostly vertically (the sag changes)
    mid = ds["history_displacement"].isel(point=1)
    assert float(np.ptp(mid.sel(component="z").values)) > 0.01


def test_a_response_that_has_not_settled_is_flagged(tmp_path: Path) -> None:
    text = CONTRACT.replace(
        "    elements: 10",
        "    elements: 10\n    ramp_periods: 1.0\n"
        "    min_periods: 2\n    max_periods: 3\n"
        "    steady_tolerance: 1.0e-12",
    )
    text = text.split("sweep:")[0]
    ds = _run(tmp_path, text.replace("name: contract", "name: unsettled"), "unsettled")
    assert int(ds["status"]) == 0
    assert int(ds["steady_converged"]) == 0
    assert float(ds["periods"]) == pytest.approx(3.0)
    assert float(ds["tension_max_spread"]) > 0.0


def test_excitation_errors_name_the_field_once() -> None:
    text = CONTRACT.replace("amplitude: 0.05, frequency: 0.5}", "amplitude: 0.05}")
    with pytest.raises(StudyError) as info:
        expand_cases(parse_study_text(text.split("sweep:")[0]))
    # one problem (not one per union member), at the field, saying it is missing
    assert len(info.value.problems) == 1
    problem = info.value.problems[0]
    assert problem.split(":")[0].isdigit()
    assert "analysis.dynamic.excitation.frequency: required key" in problem
    assert "missing" in problem


def test_unexcited_mooring_end_is_refused_saying_what_to_write(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A mooring end that the excitation does not move (a constant horizontal force at a
    held height) is no support the line can move against: rejected before any work,
    with what to write instead."""
    text = CONTRACT.replace("static: {method: analytic}", "static: {method: catenary}").replace(
        "a: {kind: fixed, position: [0.0, 0.0, 0.0]}",
        "a: {kind: mooring, force: [-100.0, 0.0], z: 0.0}",
    )
    cfg = tmp_path / "moored.yaml"
    cfg.write_text(text)
    assert main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous"]) == 2
    err = capsys.readouterr().err
    assert "ends.a.kind: 'mooring' is not supported with analysis.dynamic" in err
    assert "kind 'fixed' at the static position" in err and "kind 'force' for a free end" in err
    assert not (tmp_path / "contract.nc").exists()  # nothing ran


@pytest.mark.parametrize(
    "end_b",
    ["{kind: force, force: [100.0, 0.0, 20.0]}", "{kind: mooring, force: [90.0, 0.0], z: 0.0}"],
)
def test_excited_force_or_mooring_end_moves_about_its_static_position(
    tmp_path: Path, end_b: str
) -> None:
    """DESIGN.md's towing and mooring variants of end B with the dynamic analysis as
    written: the static end condition fixes B's equilibrium position, and the excitation
    moves B about it. The dynamic model's own discrete statics (10 elements) must carry
    the same end tension as the semi-analytic solution up to the lumping error,
    O((h / L)^2) = 1e-2 for 10 elements (measured 4.5e-3 towing, 4.3e-3 mooring); a
    wrong end position (e.g. B left at the origin of its force) would be O(1)."""
    text = CONTRACT.replace("static: {method: analytic}", "static: {method: catenary}").replace(
        "b: {kind: fixed, position: [10.792, 0.0, 0.0]}", f"b: {end_b}"
    )
    ds = _run(tmp_path, text, "contract")
    assert np.all(ds["status"].values == 0), ds["message"].values
    rel = np.abs(ds["tension_static"] - ds["tension_b"]) / ds["tension_b"]
    assert float(rel.max()) < 1e-2
    assert np.all(ds["tension_min"] < ds["tension_static"])
    assert np.all(ds["tension_max"] > ds["tension_static"])
    if "force" in end_b and "mooring" not in end_b:
        # towing: the end tension is the applied force's magnitude
        np.testing.assert_allclose(ds["tension_b"], np.hypot(100.0, 20.0), rtol=1e-9)
