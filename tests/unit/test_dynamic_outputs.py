"""Outputs a dynamic analyst expects (issue 9, item 7), YAML -> netCDF through the CLI:
the tension envelope along the line, the touchdown point's travel, and time histories
of the whole line."""

from __future__ import annotations

from collections import OrderedDict
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses import line_model
from cablestudy.analyses import static as static_analysis
from cablestudy.cli import main

#: a sagging 11 m cable between supports at one level (the moustafa seed's cable)
CABLE = """
line:
  segments:
    - {length: 10.9774, diameter: 0.01, mass_per_length: 0.61, axial_stiffness: 7.854e6}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [10.792, 0.0, 0.0]}
"""


@pytest.fixture(autouse=True)
def _fresh_caches(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(static_analysis, "_STATIC_CACHE", OrderedDict())
    monkeypatch.setattr(line_model, "_DISCRETE_CACHE", OrderedDict())


def _run(tmp_path: Path, name: str, text: str) -> xr.Dataset:
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(f"name: {name}\n{text}")
    argv = ["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous", "--no-cache"]
    assert main(argv) == 0
    ds = xr.load_dataset(tmp_path / f"{name}.nc")
    assert np.all(ds["status"].values == 0), ds["message"].values
    return ds


def test_envelope_brackets_statics_contains_end_extremes_and_line_history(
    tmp_path: Path,
) -> None:
    mid = 10.9774 / 2.0  # a static output point (21 nodes)
    ds = _run(
        tmp_path,
        "envelope",
        "environment: {fluid: water}\n"
        + CABLE
        + f"""analysis:
  static: {{method: analytic, nodes: 21}}
  dynamic:
    excitation: {{end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.05, frequency: 0.5}}
    method: time
    elements: 20
    history: {{points: [{mid!r}], whole_line: true, samples_per_period: 16}}
""",
    )
    env_max, env_min = ds["tension_envelope_max"], ds["tension_envelope_min"]
    assert env_max.dims == ("s",) and env_max.attrs["units"] == "N"
    # the swing (about 20 N) is far above the model's discretisation error of its
    # statics (0.15 N at 20 elements, see the quasi-static test): strict bracket
    tension = ds["tension"].values
    assert np.all(env_max.values > tension) and np.all(env_min.values < tension)
    # at the excited end (B, the last s) the envelope is the end tension's extremes:
    # the same per-step samples over the same window (rtol: the norm's rounding)
    np.testing.assert_allclose(env_max.values[-1], float(ds["tension_max"]), rtol=1e-14)
    np.testing.assert_allclose(env_min.values[-1], float(ds["tension_min"]), rtol=1e-14)
    assert float(env_max.max()) == pytest.approx(float(ds["tension_max_line"]), rel=1e-14)
    # no seabed in this study: no touchdown point to track
    assert "touchdown_min" not in ds and "touchdown_max" not in ds

    # the whole line's history at the point's s is the point history (same interpolation
    # in s and in time, so equal to rounding)
    k = int(np.argmin(np.abs(ds["s"].values - mid)))
    assert ds["s"].values[k] == pytest.approx(mid, abs=1e-12)
    pos = ds["history_line_position"].isel(s=k).values  # (time, component)
    vel = ds["history_line_velocity"].isel(s=k).values
    disp = ds["history_displacement"].isel(point=0).values
    assert ds["history_line_position"].dims == ("time", "s", "component")
    assert ds["history_line_tension"].dims == ("time", "s")
    np.testing.assert_allclose(vel, ds["history_velocity"].isel(point=0).values, atol=1e-12)
    np.testing.assert_allclose(pos - pos[0], disp - disp[0], atol=1e-12)
    # the line's tension history at the excited end is the end tension history, and
    # stays inside the envelope (the envelope also holds steps between the samples)
    hist_t = ds["history_line_tension"].values
    np.testing.assert_allclose(hist_t[:, -1], ds["history_tension"].values, rtol=1e-14)
    assert np.all(hist_t <= env_max.values[None, :] * (1 + 1e-12))
    assert np.all(hist_t >= env_min.values[None, :] * (1 - 1e-12))


def test_quasi_static_envelope_is_the_statics_at_the_extreme_positions(tmp_path: Path) -> None:
    """End B moved 0.05 m along the span at 0.01 Hz, 60 times below the first natural
    frequency (0.59 Hz): the line passes through static equilibria, so the envelope is
    the static tension with B at +0.05 m (max: a longer span pulls harder everywhere)
    and at -0.05 m (min). What remains is the lumped-mass discretisation error, O(h^2):
    it must fall about fourfold from 20 to 40 elements, and at 40 elements stay within
    the Richardson estimate |e20 - e40| / 3 (with a 50 % margin), plus the inertia left
    in a quasi-static motion, (f / f1)^2 of the swing."""
    statics = _run(
        tmp_path,
        "qs-statics",
        "environment: {fluid: vacuum}\n"
        + CABLE
        + """analysis:
  static: {method: analytic, nodes: 41}
sweep:
  ends.b.position.0: [10.742, 10.842]
""",
    )
    ds = _run(
        tmp_path,
        "qs-dynamic",
        "environment: {fluid: vacuum}\n"
        + CABLE
        + """analysis:
  static: {method: analytic, nodes: 41}
  modal: {modes: 1}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.05, frequency: 0.01}
    method: time
sweep:
  analysis.dynamic.elements: [20, 40]
""",
    )
    f1 = float(ds["natural_frequency"].isel(elements=1, mode=0))
    low, high = statics["tension"].values
    inertia = (0.01 / f1) ** 2 * float(np.max(high - low))
    for var, ref in (("tension_envelope_max", high), ("tension_envelope_min", low)):
        e20, e40 = (ds[var].isel(elements=i).values - ref for i in (0, 1))
        assert np.max(np.abs(e40)) < 0.35 * np.max(np.abs(e20)), var  # h^2: 0.25
        bound = 1.5 * np.max(np.abs(e20 - e40)) / 3.0 + inertia
        assert np.max(np.abs(e40)) <= bound, (var, np.max(np.abs(e40)), bound)
        # and the envelope is no mere offset of the statics at the middle position:
        # it differs from it by the quasi-static swing, 300 times the error
        assert np.max(np.abs(e40)) < 0.01 * np.max(high - low)


CHAIN = """environment: {fluid: water, depth: 50.0}
line:
  segments:
    - {length: 100.0, diameter: 0.05, mass_per_length: 50.0, axial_stiffness: 2.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -50.0]}
  b: {kind: fixed, position: [85.0, 0.0, -5.0]}
"""


def test_touchdown_travel_of_a_slowly_moved_mooring(tmp_path: Path) -> None:
    """A chain anchored on the seabed at A, its fairlead B moved 0.5 m along the span at
    0.002 Hz (quasi-static): the touchdown point travels between the static touchdown
    points (the laid lengths from A) with B at +0.5 m (nearest A) and -0.5 m. The
    lumped model with its penalty seabed resolves where the line leaves the seabed to
    within its node spacing (contact acts at nodes): tolerance half an element, 1 m."""
    statics = _run(
        tmp_path,
        "td-statics",
        CHAIN + "analysis:\n  static: {nodes: 101}\nsweep:\n  ends.b.position.0: [84.5, 85.5]\n",
    )
    ds = _run(
        tmp_path,
        "td-dynamic",
        CHAIN
        + """analysis:
  static: {nodes: 101}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.5, frequency: 0.002}
    method: time
    elements: 50
""",
    )
    near_b, near_a = statics["laid_length"].values  # span 84.5 m: more chain laid
    assert near_b - near_a > 5.0  # the travel (5.7 m) is well above the tolerance
    h = 100.0 / 50
    assert float(ds["touchdown_max"]) == pytest.approx(near_b, abs=h / 2)
    assert float(ds["touchdown_min"]) == pytest.approx(near_a, abs=h / 2)
    assert ds["touchdown_max"].attrs["units"] == "m"


def test_a_seabed_the_line_never_touches_gives_nan_touchdown_not_a_failure(
    tmp_path: Path,
) -> None:
    ds = _run(
        tmp_path,
        "deep",
        CHAIN.replace("depth: 50.0", "depth: 500.0")
        + """analysis:
  static: {nodes: 11}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.5, frequency: 0.05}
    method: time
    elements: 10
""",
    )
    assert int(ds["dynamic_status"]) == 0
    assert np.isnan(float(ds["touchdown_min"])) and np.isnan(float(ds["touchdown_max"]))
