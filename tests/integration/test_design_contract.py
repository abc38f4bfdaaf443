"""The study-file contract and the dataset conventions of DESIGN.md, checked from the
outside: YAML text -> ``cablestudy run`` / ``validate`` / ``schema`` -> netCDF opened
with xarray.

``DESIGN_EXAMPLE`` is the example study of DESIGN.md ("The study file (the contract)")
copied verbatim. Its full sweep (4 amplitudes x 23 frequencies of time-domain
dynamics) takes about two minutes, so the run here replaces only its two sweep lines by
a 2 x 2 sweep; ``validate`` checks the full 92-case sweep. The variants (each
commented-out end kind, the fluids, depth omitted, weight in the fluid instead of
mass, a seabed, a turning current, attachments) are the example with one edit each.
"""

from __future__ import annotations

import hashlib
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import cablestudy
from cablestudy.analyses.variables import OUTPUTS
from cablestudy.cli import main

ROOT = Path(__file__).resolve().parents[2]

DESIGN_EXAMPLE = """\
name: catenary-in-air             # results go to <out>/<name>.nc
description: Elastic steel catenary between supports at different levels
environment:
  fluid: air                      # air | water | {density: 1025.0}
  gravity: 9.80665
  depth: 320.0                    # omit: no seabed
  seabed: {slope_deg: 0.0, friction: 0.0}
  current:                        # omit: still fluid; piecewise-linear in z
    - {z: 0.0,    speed: 0.514, heading_deg: 0.0}
    - {z: -300.0, speed: 0.1,   heading_deg: 90.0}
line:
  segments:                       # listed from end A to end B
    - length: 100.0               # unstretched [m]
      diameter: 0.02              # hydrodynamic diameter [m]
      mass_per_length: 2.466      # [kg/m]; or weight_in_fluid [N/m] where that is what is known
      axial_stiffness: 6.283e7    # EA [N]
      drag_normal: 1.2
      drag_tangential: 0.01
      added_mass_normal: 1.0
      bending_stiffness: 0.0      # EI [N m^2]
  attachments:                    # point loads, clump weights, buoys
    - {s: 50.0, force: [0.0, 0.0, -500.0]}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}     # both ends fixed
  # b: {kind: force, force: [Tx, Ty, Tz]}           # towing: known force applied to the line at B
  # b: {kind: mooring, force: [Tx, Ty], z: -8.6}    # known horizontal force on the line at B, and B's height
analysis:
  static: {nodes: 100, tolerance: 1.0e-9}
  modal: {modes: 10}              # omit: no modal analysis about the static shape
  dynamic:                        # omit: statics only
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.05, frequency: 0.5}
    method: auto                  # auto | time | frequency
sweep:                            # each key a dotted path into this file;
  analysis.dynamic.excitation.amplitude: [0.025, 0.05, 0.075, 0.1]
  analysis.dynamic.excitation.frequency: {start: 0.1, stop: 1.2, num: 23}
"""  # noqa: E501 (verbatim: one comment line of the example is 109 characters)

FULL_SWEEP = """\
  analysis.dynamic.excitation.amplitude: [0.025, 0.05, 0.075, 0.1]
  analysis.dynamic.excitation.frequency: {start: 0.1, stop: 1.2, num: 23}
"""
#: a 2 x 2 sweep of the same two keys, same forms (a list and {start, stop, num})
SMALL_SWEEP = """\
  analysis.dynamic.excitation.amplitude: [0.025, 0.1]
  analysis.dynamic.excitation.frequency: {start: 0.1, stop: 0.2, num: 2}
"""

B_FIXED = "  b: {kind: fixed, position: [92.5, 0.0, -8.6]}     # both ends fixed\n"
CURRENT = """\
  current:                        # omit: still fluid; piecewise-linear in z
    - {z: 0.0,    speed: 0.514, heading_deg: 0.0}
    - {z: -300.0, speed: 0.1,   heading_deg: 90.0}
"""
DEPTH = "  depth: 320.0                    # omit: no seabed\n"
L, D, M, EA, G = 100.0, 0.02, 2.466, 6.283e7, 9.80665
AREA = math.pi * D**2 / 4.0
F_ATT = 500.0  # the example's attachment: 500 N down at s = 50 m


def _edit(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new)


def statics_of(text: str, *, name: str) -> str:
    """The example as a statics-only study: analysis.dynamic, sweep and modal removed."""
    text = text.split("  dynamic:")[0]
    text = _edit(
        text,
        "  modal: {modes: 10}              # omit: no modal analysis about the static shape\n",
        "",
    )
    return _edit(text, "name: catenary-in-air", f"name: {name}")


def run(tmp_path: Path, text: str, *extra: str) -> xr.Dataset:
    """Run ``text`` through the CLI; the result is ``<out>/<name>.nc``."""
    name = re.search(r"^name: (\S+)", text, re.M).group(1)  # type: ignore[union-attr]
    tmp_path.mkdir(parents=True, exist_ok=True)
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    out = tmp_path / "out"
    if "--scheduler" not in extra:
        extra = ("--scheduler", "synchronous", *extra)
    code = main(["run", str(cfg), "--out", str(out), "--no-cache", "--no-progress", *extra])
    assert code == 0
    return xr.load_dataset(out / f"{name}.nc")


def weight(density: float) -> float:
    """Weight per length in the fluid [N/m]: (m - rho A) g."""
    return (M - density * AREA) * G


# ------------------------------------------------------------------ the example


@pytest.fixture(scope="module")
def example(tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    tmp = tmp_path_factory.mktemp("design")
    return run(tmp, _edit(DESIGN_EXAMPLE, FULL_SWEEP, SMALL_SWEEP))


def test_example_validates_as_written(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    cfg = tmp_path / "design.yaml"
    cfg.write_text(DESIGN_EXAMPLE)
    assert main(["validate", str(cfg)]) == 0
    assert "92 cases (amplitude=4, frequency=23)" in capsys.readouterr().out


def test_example_full_sweep_coordinates_are_the_decimals_written() -> None:
    """{start: 0.1, stop: 1.2, num: 23} gives 0.1, 0.15, ..., 1.2 as written (not
    0.44999999999999996), so that ``ds.sel(frequency=0.45)`` finds its case."""
    from cablestudy.study import parse_study_text
    from cablestudy.study.grid import expand_cases

    axes, cases = expand_cases(parse_study_text(DESIGN_EXAMPLE, "design.yaml"))
    assert [a.name for a in axes] == ["amplitude", "frequency"] and len(cases) == 92
    assert list(axes[1].values[0]) == [float(f"{0.1 + 0.05 * i:.2f}") for i in range(23)]
    assert list(axes[0].values[0]) == [0.025, 0.05, 0.075, 0.1]
    freq = {c.study.analysis.dynamic.excitation.frequency for c in cases}  # type: ignore
    assert freq == set(axes[1].values[0])  # the cases run the coordinate values


def test_example_dims_coordinates_and_units(example: xr.Dataset) -> None:
    ds = example
    assert dict(ds.sizes) == {"amplitude": 2, "frequency": 2, "s": 100, "component": 3, "mode": 10}
    np.testing.assert_array_equal(ds["amplitude"], [0.025, 0.1])
    np.testing.assert_array_equal(ds["frequency"], [0.1, 0.2])  # num values, ends included
    assert ds["amplitude"].attrs["units"] == "m" and ds["frequency"].attrs["units"] == "Hz"
    assert list(ds["component"].values) == ["x", "y", "z"]
    assert ds["tension"].dims == ("amplitude", "frequency", "s")
    assert ds["force_a"].dims == ("amplitude", "frequency", "component")
    assert ds["natural_frequency"].dims == ("amplitude", "frequency", "mode")
    assert ds["tension_max"].dims == ("amplitude", "frequency")
    # a units attribute on every variable; units and long_name on every coordinate;
    # dimensionless and text variables say "1"
    for name in [*ds.data_vars, *ds.coords]:
        attrs = ds[name].attrs
        assert isinstance(attrs.get("units"), str), name
        assert attrs.get("long_name"), name
        if ds[name].dtype.kind in "OUS":
            assert attrs["units"] == "1", name
    expected = {
        "x": "m",
        "y": "m",
        "z": "m",
        "s": "m",
        "tension": "N",
        "force_a": "N",
        "force_b": "N",
        "laid_length": "m",
        "tension_max": "N",
        "tension_min": "N",
        "tension_mean": "N",
        "tension_static": "N",
        "natural_frequency": "Hz",
        "wall_time": "s",
        "status": "1",
        "message": "1",
        "mode": "1",
    }
    assert {k: ds[k].attrs["units"] for k in expected} == expected


def test_example_per_case_bookkeeping_and_provenance(example: xr.Dataset) -> None:
    ds = example
    assert ds["status"].dtype.kind == "i" and np.all(ds["status"] == 0)
    assert all(str(m) == "" for m in ds["message"].values.ravel())
    assert np.all(ds["wall_time"] > 0)
    # the static solution met the tolerance asked for (analysis.static.tolerance)
    assert np.all(ds["static_residual"] <= 1e-9)
    text = _edit(DESIGN_EXAMPLE, FULL_SWEEP, SMALL_SWEEP)
    assert ds.attrs["study_name"] == "catenary-in-air"
    assert ds.attrs["study_yaml"] == text
    assert ds.attrs["study_sha256"] == hashlib.sha256(text.encode()).hexdigest()
    assert ds.attrs["cablestudy_version"] == cablestudy.__version__
    settings = json.loads(ds.attrs["solver_settings"])["analysis"]
    assert settings["static"]["nodes"] == 100 and settings["static"]["tolerance"] == 1e-9
    assert settings["modal"]["modes"] == 10 and settings["dynamic"]["method"] == "auto"


def test_example_statics_frame_and_end_forces(example: xr.Dataset) -> None:
    ds = example.isel(amplitude=0, frequency=0)
    # s: unstretched arc length from end A, `nodes` points
    np.testing.assert_allclose(ds["s"], np.linspace(0.0, L, 100), rtol=0, atol=1e-12 * L)
    # positions absolute: the line starts at A and ends at B (solver tolerance 1e-9 of L)
    pos = np.stack([ds[c].values for c in "xyz"], axis=1)
    np.testing.assert_allclose(pos[0], [0.0, 0.0, 0.0], atol=1e-7)
    np.testing.assert_allclose(pos[-1], [92.5, 0.0, -8.6], atol=1e-7)
    assert float(ds["z"].min()) < -8.6  # z up: the line sags below both supports
    fa, fb = ds["force_a"].values, ds["force_b"].values
    # the force of the line on each support: down, and towards the other support
    assert fa[2] < 0 and fb[2] < 0 and fa[0] > 0 and fb[0] < 0
    # its magnitude is the end tension
    np.testing.assert_allclose(np.linalg.norm(fa), ds["tension"].values[0], rtol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(fb), ds["tension"].values[-1], rtol=1e-9)
    # the supports carry the weight in air and the 500 N point load; the "current" (a
    # wind here) adds a drag of at most 1/2 rho Cd d U^2 L = 0.39 N in any direction
    drag_bound = 0.5 * 1.225 * 1.2 * D * 0.514**2 * L
    np.testing.assert_allclose(fa + fb, [0.0, 0.0, -(weight(1.225) * L + F_ATT)], atol=drag_bound)
    assert float(ds["laid_length"]) == 0.0  # 320 m of depth: far above the seabed


def test_example_modes_and_dynamics(example: xr.Dataset) -> None:
    ds = example
    f = ds["natural_frequency"].values
    assert np.all(f > 0) and np.all(np.diff(f, axis=-1) >= 0)
    # the lowest mode is the out-of-plane sway, (T v')' = m v'': by the Rayleigh quotient
    # its frequency lies between those of strings of length L under the least and the
    # largest tension along the line, f = sqrt(T / m) / (2 L) (m with added mass of air;
    # 1e-3 margin for the stretch, T/EA < 5e-5, and the eigensolver's mesh error)
    tension = ds["tension"].isel(amplitude=0, frequency=0).values
    m = M + 1.225 * AREA
    lo, hi = (math.sqrt(t / m) / (2 * L) for t in (tension.min(), tension.max()))
    assert lo * (1 - 1e-3) < f[0, 0, 0] < hi * (1 + 1e-3)
    # dynamics at the excited end B
    # auto runs the frequency domain where its checks trust it, else the time domain,
    # and says why
    assert set(np.unique(ds["dynamic_method"].values)) <= {"time", "frequency"}
    assert all(r.startswith("auto: ") for r in ds["dynamic_method_reason"].values.ravel())
    tmin, tmean, tmax = (ds[k].values for k in ("tension_min", "tension_mean", "tension_max"))
    assert np.all(tmin <= tmean) and np.all(tmean <= tmax) and np.all(tmin < tmax)
    # the dynamic model's static end tension is the static tension at B, up to the
    # lumped-mass discretisation (80 elements: O((L/80)^2) relative, well below 1e-3)
    np.testing.assert_allclose(ds["tension_static"], ds["tension_b"], rtol=1e-3)
    # far below the first natural frequency the swing grows with the amplitude
    swing = (ds["tension_max"] - ds["tension_min"]).isel(frequency=0).values
    assert swing[1] > 2.0 * swing[0]


# ------------------------------------------------------------------ end kinds


def test_towing_end_force_is_the_applied_force(tmp_path: Path) -> None:
    applied = [2000.0, 100.0, 1500.0]
    text = _edit(
        statics_of(DESIGN_EXAMPLE, name="tow"), B_FIXED, f"  b: {{kind: force, force: {applied}}}\n"
    )
    ds = run(tmp_path, text)
    assert int(ds["status"]) == 0, str(ds["message"].values)
    # the line pushes back on whatever applies the force: force_b = -(applied), exactly
    np.testing.assert_array_equal(ds["force_b"].values, -np.asarray(applied))
    np.testing.assert_allclose([ds[c].values[0] for c in "xyz"], 0.0, atol=1e-9)
    drag_bound = 0.5 * 1.225 * 1.2 * D * 0.514**2 * L
    np.testing.assert_allclose(
        ds["force_a"] + ds["force_b"], [0.0, 0.0, -(weight(1.225) * L + F_ATT)], atol=drag_bound
    )


def test_mooring_end_horizontal_force_and_height(tmp_path: Path) -> None:
    text = _edit(
        statics_of(DESIGN_EXAMPLE, name="moor"),
        B_FIXED,
        "  b: {kind: mooring, force: [2000.0, 0.0], z: -8.6}\n",
    )
    ds = run(tmp_path, text)
    assert int(ds["status"]) == 0, str(ds["message"].values)
    fb = ds["force_b"].values
    np.testing.assert_array_equal(fb[:2], [-2000.0, 0.0])  # the given force, on the line
    assert fb[2] < 0  # the line hangs from B
    np.testing.assert_allclose(float(ds["z"][-1]), -8.6, atol=1e-9)
    assert float(ds["x"][-1]) > 0


@pytest.mark.parametrize(
    "end_b",
    [
        "  b: {kind: force, force: [2000.0, 0.0, 1500.0]}\n",
        "  b: {kind: mooring, force: [2000.0, 0.0], z: -8.6}\n",
    ],
)
def test_design_example_with_towing_or_mooring_end_runs_dynamics(
    tmp_path: Path, end_b: str
) -> None:
    """The commented variants of end B in DESIGN.md's example, with the rest of the file
    as written (dynamic analysis exciting end b): B's static end condition fixes its
    equilibrium position and the excitation moves it about that position. One case of
    the sweep keeps the run short."""
    text = _edit(DESIGN_EXAMPLE, B_FIXED, end_b)
    text = _edit(
        text,
        FULL_SWEEP,
        "  analysis.dynamic.excitation.amplitude: [0.05]\n"
        "  analysis.dynamic.excitation.frequency: [0.2]\n",
    )
    ds = run(tmp_path, text)
    assert int(ds["status"].max()) == 0, ds["message"].values
    if "force:" in end_b and "mooring" not in end_b:
        # towing: the line pulls the attachment with minus the applied force
        np.testing.assert_allclose(
            ds["force_b"].squeeze(), [-2000.0, 0.0, -1500.0], rtol=1e-9, atol=1e-9
        )
    else:
        # mooring: B at the given height, horizontal pull as given
        assert float(ds["z"].squeeze()[-1]) == pytest.approx(-8.6, abs=1e-9)
        assert float(ds["force_b"].squeeze()[0]) == pytest.approx(-2000.0, rel=1e-9)
    assert float(ds["tension_min"].squeeze()) <= float(ds["tension_static"].squeeze())
    assert float(ds["tension_max"].squeeze()) >= float(ds["tension_static"].squeeze())


# ------------------------------------------------------------------ environment


@pytest.mark.parametrize(
    ("fluid", "density"),
    [
        ("air", 1.225),
        ("water", 1025.0),
        ("vacuum", 0.0),
        ("{density: 1025.0}", 1025.0),
        ("{density: 0.0}", 0.0),
    ],
)
def test_fluids_without_depth_or_current(tmp_path: Path, fluid: str, density: float) -> None:
    """No current and no seabed (both keys omitted): the supports carry exactly the
    weight in the fluid, (m - rho A) g L, and the point load."""
    text = statics_of(DESIGN_EXAMPLE, name="fluid")
    text = _edit(_edit(_edit(text, CURRENT, ""), DEPTH, ""), "fluid: air ", f"fluid: {fluid} ")
    ds = run(tmp_path, text)
    assert int(ds["status"]) == 0, str(ds["message"].values)
    total = ds["force_a"] + ds["force_b"]
    # equilibrium holds to the solver tolerance (1e-9) relative to the end tension
    np.testing.assert_allclose(
        total, [0.0, 0.0, -(weight(density) * L + F_ATT)], atol=1e-7 * float(ds["tension_a"])
    )
    assert float(ds["laid_length"]) == 0.0


def test_weight_in_fluid_is_mass_per_length(tmp_path: Path) -> None:
    """In water, weight_in_fluid = (m - rho A) g is the same line as mass_per_length = m:
    same shape and tensions, and the same modes (mass w / g + rho A)."""
    base = _edit(DESIGN_EXAMPLE.split("  dynamic:")[0], "fluid: air ", "fluid: water ")
    base = _edit(base, CURRENT, "")
    by_mass = run(tmp_path / "m", _edit(base, "name: catenary-in-air", "name: by-mass"))
    by_weight = run(
        tmp_path / "w",
        _edit(
            _edit(base, "name: catenary-in-air", "name: by-weight"),
            "mass_per_length: 2.466 ",
            f"weight_in_fluid: {weight(1025.0)!r} ",
        ),
    )
    for k in ("x", "z", "tension", "force_a", "force_b"):
        np.testing.assert_allclose(by_weight[k], by_mass[k], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(
        by_weight["natural_frequency"], by_mass["natural_frequency"], rtol=1e-9
    )


def _mooring_on_seabed(slope_deg: float, friction: float) -> str:
    """A 150 m line in 50 m of water from an anchor on the seabed at A to a fairlead at
    z = -5 m held by a horizontal force of 500 N at B."""
    text = statics_of(DESIGN_EXAMPLE, name="laid")
    text = _edit(_edit(text, CURRENT, ""), "fluid: air ", "fluid: water ")
    text = _edit(text, DEPTH, "  depth: 50.0\n")
    text = _edit(
        text,
        "seabed: {slope_deg: 0.0, friction: 0.0}",
        f"seabed: {{slope_deg: {slope_deg}, friction: {friction}}}",
    )
    text = _edit(text, "length: 100.0 ", "length: 150.0 ")
    text = _edit(text, "    - {s: 50.0, force: [0.0, 0.0, -500.0]}\n", "")
    text = _edit(
        text, "  attachments:                    # point loads, clump weights, buoys\n", ""
    )
    text = _edit(text, "position: [0.0, 0.0, 0.0]", "position: [0.0, 0.0, -50.0]")
    return _edit(text, B_FIXED, "  b: {kind: mooring, force: [500.0, 0.0], z: -5.0}\n")


def test_mooring_line_on_a_flat_seabed(tmp_path: Path) -> None:
    ds = run(tmp_path, _mooring_on_seabed(0.0, 0.0))
    assert int(ds["status"]) == 0, str(ds["message"].values)
    laid = float(ds["laid_length"])
    w, H, h = weight(1025.0), 500.0, 45.0
    # inextensible catenary from the touchdown point: suspended length sqrt(h^2 + 2 h H/w)
    # (Faltinsen 1990, ch. 8); the stretch (T/EA < 2e-5) moves it by less than 1e-2 m
    assert laid == pytest.approx(150.0 - math.sqrt(h * h + 2 * h * H / w), abs=1e-2)
    assert laid > 0
    # seabed at z = -depth: nothing below it, and the laid part on it
    z = ds["z"].values
    assert z.min() >= -50.0 - 1e-9 * 50.0
    on_bed = ds["s"].values <= laid - 1e-6
    np.testing.assert_allclose(z[on_bed], -50.0, atol=1e-9 * 50.0)
    # the suspended part's weight hangs from B; the anchor is pulled horizontally by H
    # (no friction) towards the line
    np.testing.assert_allclose(ds["force_b"], [-H, 0.0, -w * (150.0 - laid)], rtol=1e-9)
    np.testing.assert_allclose(ds["force_a"], [H, 0.0, 0.0], atol=1e-9 * H)


def test_mooring_line_on_a_sloping_seabed_with_friction(tmp_path: Path) -> None:
    flat = run(tmp_path / "flat", _mooring_on_seabed(0.0, 0.0))
    ds = run(tmp_path, _mooring_on_seabed(2.0, 0.3))
    assert int(ds["status"]) == 0, str(ds["message"].values)
    # the seabed rises at 2 deg towards +x through (0, 0, -depth): nothing below it
    ground = -50.0 + math.tan(math.radians(2.0)) * ds["x"].values
    assert np.all(ds["z"].values >= ground - 1e-9 * 50.0)
    assert float(ds["laid_length"]) > 0
    # friction holds part of the pull: the anchor sees less than the 500 N at B
    assert float(ds["tension_a"]) < float(flat["tension_a"])
    np.testing.assert_array_equal(ds["force_b"].values[:2], [-500.0, 0.0])


def test_turning_current_pushes_the_line_downstream(tmp_path: Path) -> None:
    """The example in water: the current flows towards +x at the surface, turning towards
    +y with depth, so the normal drag on every element has non-negative x and y parts,
    the line bows towards +y, and the supports take the drag: force_a + force_b = weight
    + drag, with drag > 0 in x and y."""
    text = _edit(statics_of(DESIGN_EXAMPLE, name="current"), "fluid: air ", "fluid: water ")
    ds = run(tmp_path, text)
    assert int(ds["status"]) == 0, str(ds["message"].values)
    total = (ds["force_a"] + ds["force_b"]).values
    assert total[0] > 0 and total[1] > 0
    assert float(ds["y"].isel(s=50)) > 0
    assert float(ds["y"].min()) >= -1e-9
    still = run(tmp_path / "still", _edit(text, CURRENT, ""))
    assert float(still["y"].max()) == pytest.approx(0.0, abs=1e-9)


def test_attachment_forces_reach_the_supports(tmp_path: Path) -> None:
    text = _edit(
        _edit(statics_of(DESIGN_EXAMPLE, name="att"), CURRENT, ""),
        "force: [0.0, 0.0, -500.0]",
        "force: [100.0, 50.0, -500.0]",
    )
    ds = run(tmp_path, text)
    assert int(ds["status"]) == 0, str(ds["message"].values)
    np.testing.assert_allclose(
        ds["force_a"] + ds["force_b"],
        [100.0, 50.0, -(weight(1.225) * L + 500.0)],
        atol=1e-7 * float(ds["tension_a"]),
    )


# ------------------------------------------------------------------ failures, sweeps


@pytest.mark.parametrize("scheduler", ["synchronous", "threads", "processes"])
def test_failed_case_is_kept_with_nan_status_and_message(tmp_path: Path, scheduler: str) -> None:
    """Sweeping the depth down to 20 m lays the sagging line (lowest point z = -21.5 m
    without a seabed) on the seabed between its supports; the static solver models that
    contact, but the dynamic model has no seabed contact, so the case fails before time
    stepping, and stays in the dataset with NaN data, a nonzero status and a message
    naming the seabed, on either scheduler. Only the failed analysis is blank: its
    variables are NaN, the statics it started from are kept (issue 9, item 6)."""
    text = _edit(DESIGN_EXAMPLE, FULL_SWEEP, "  environment.depth: [320.0, 20.0]\n")
    text = _edit(text, "amplitude: 0.05, frequency: 0.5", "amplitude: 0.05, frequency: 0.2")
    ds = run(tmp_path, text, "--scheduler", scheduler, "--workers", "2")
    assert ds["status"].dims == ("depth",) and ds.sizes["depth"] == 2
    assert ds["depth"].attrs["units"] == "m"
    ok, bad = ds.sel(depth=320.0), ds.sel(depth=20.0)
    assert int(ok["status"]) == 0 and str(ok["message"].values) == ""
    assert int(bad["status"]) != 0 and "seabed" in str(bad["message"].values)
    failed = {a for a in ("static", "modal", "dynamic") if int(bad[f"{a}_status"]) != 0}
    assert failed and all(int(ok[f"{a}_status"]) == 0 for a in ("static", "modal", "dynamic"))
    if "static" not in failed:  # the message names the failed analysis
        assert str(bad["message"].values).startswith(tuple(f"{a} analysis: " for a in failed))
    for name, var in bad.data_vars.items():
        spec = OUTPUTS.get(name)
        if spec is None or spec.analysis is None or var.dtype.kind not in "fi":
            continue
        # NaN only where the variable says what it means (touchdown_min/max: the line
        # does not touch the seabed)
        finite = np.isfinite if not spec.nan_means else lambda v: ~np.isinf(v)
        assert np.all(finite(ok[name].values)), name
        # blank where its own analysis failed or could not start (static failed)
        if spec.analysis in failed:
            assert np.all(np.isnan(var.values)), name
        else:
            assert np.all(finite(var.values)), name
    assert ds.attrs["cases"] == 2 and ds.attrs["cases_failed"] == 1


def test_sweep_axes_name_dimensions_with_units(tmp_path: Path) -> None:
    text = (
        statics_of(DESIGN_EXAMPLE, name="sweeps")
        + """\
sweep:
  ends.b.position.0: {start: 90.0, stop: 95.0, num: 3}
  environment.fluid: [air, water]
  line.segments.0.axial_stiffness: {values: [1.0e6, 6.283e7], name: stiffness}
"""
    )
    ds = run(tmp_path, text)
    assert ds["tension"].dims == ("position_0", "fluid", "stiffness", "s")
    np.testing.assert_array_equal(ds["position_0"], [90.0, 92.5, 95.0])
    assert list(ds["fluid"].values) == ["air", "water"]
    assert ds["position_0"].attrs["units"] == "m" and ds["stiffness"].attrs["units"] == "N"
    assert ds["fluid"].attrs["units"] == "1" and ds["fluid"].attrs["long_name"]
    np.testing.assert_allclose(
        ds["x"].isel(s=-1), ds["position_0"].broadcast_like(ds["x"].isel(s=-1)), atol=1e-7
    )
    assert np.all(ds["status"] == 0)


# ------------------------------------------------------------------ command line


def test_validate_and_bad_input_before_any_work(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text = _edit(DESIGN_EXAMPLE, "method: auto    ", "method: spectral")
    text = _edit(text, "length: 100.0 ", 'length: "100"')
    text = _edit(text, "drag_normal: 1.2", "drag_normall: 1.2")
    text = _edit(text, "fluid: air ", "fluid: oil ")
    cfg = tmp_path / "bad.yaml"
    cfg.write_text(text)
    out = tmp_path / "out"
    assert main(["run", str(cfg), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    expected = [
        f"{cfg}:4: environment.fluid: must be 'air', 'water' or 'vacuum', or a mapping "
        "{density: <kg/m^3>} (got 'oil')",
        f"{cfg}:13: line.segments.0.length: must be a number (got '100')",
        f"{cfg}:17: line.segments.0.drag_normall: unknown key 'drag_normall' (did you mean "
        "'drag_normal'?)",
        f"{cfg}:33: analysis.dynamic.method: unknown dynamic method 'spectral'; allowed: auto, "
        "time, frequency (got 'spectral')",
    ]
    for line in expected:
        assert line in err, (line, err)
    assert not out.exists()  # rejected before any work
    assert main(["validate", str(cfg)]) == 2


def test_schema_lists_the_contract_keys(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["schema"]) == 0
    schema = json.loads(capsys.readouterr().out)
    defs = schema["$defs"]
    assert {"name", "description", "environment", "line", "ends", "analysis", "sweep"} <= set(
        schema["properties"]
    )
    assert {"fluid", "gravity", "depth", "seabed", "current"} <= set(
        defs["Environment"]["properties"]
    )
    assert {
        "length",
        "diameter",
        "mass_per_length",
        "weight_in_fluid",
        "axial_stiffness",
        "drag_normal",
        "drag_tangential",
        "added_mass_normal",
        "bending_stiffness",
    } <= set(defs["Segment"]["properties"])
    assert {"static", "modal", "dynamic"} <= set(defs["Analysis"]["properties"])


def test_make_study_writes_into_results() -> None:
    """`make study CONFIG=...` runs `cablestudy run CONFIG --out results` (read from the
    Makefile: running it would build a fresh virtual environment)."""
    makefile = (ROOT / "Makefile").read_text()
    assert re.search(r"^OUT \?= results$", makefile, re.M)
    recipe = re.search(r"^study:.*\n\t(.*)$", makefile, re.M)
    assert recipe is not None
    assert recipe.group(1) == '$(BIN)/cablestudy run "$(CONFIG)" --out "$(OUT)"'


@pytest.mark.parametrize(
    ("end_b", "expected"),
    [
        ("{kind: force}", "ends.b.force: required key 'force' is missing"),
        ("{kind: force, force: [1.0, 2.0]}", "ends.b.force: must be a list of at least 3 items"),
        ("{kind: mooring, force: [1.0, 2.0]}", "ends.b.z: required key 'z' is missing"),
        (
            "{position: [1.0, 2.0, 3.0]}",
            "ends.b: needs a 'kind': one of 'fixed', 'force', 'mooring' (got {'position'",
        ),
        (
            "{kind: pinned}",
            "ends.b.kind: 'kind' must be one of 'fixed', 'force', 'mooring' (got 'pinned')",
        ),
    ],
)
def test_end_errors_name_the_field_once(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], end_b: str, expected: str
) -> None:
    cfg = tmp_path / "ends.yaml"
    cfg.write_text(_edit(DESIGN_EXAMPLE, B_FIXED, f"  b: {end_b}\n"))
    assert main(["validate", str(cfg)]) == 2
    err = capsys.readouterr().err
    assert f"{cfg}:25: {expected}" in err, err


def test_mooring_line_reversed_is_the_same_line(tmp_path: Path) -> None:
    """Invariance: the seabed mooring defined from the fairlead (A, mooring end) to the
    anchor (B, fixed) is the same line as from anchor to fairlead; s runs from A."""
    text = _mooring_on_seabed(0.0, 0.0)
    fwd = run(tmp_path / "fwd", text)
    text = _edit(
        text,
        "  a: {kind: fixed, position: [0.0, 0.0, -50.0]}\n",
        "  a: {kind: mooring, force: [-500.0, 0.0], z: -5.0}\n",
    )
    text = _edit(
        text,
        "  b: {kind: mooring, force: [500.0, 0.0], z: -5.0}\n",
        "  b: {kind: fixed, position: [0.0, 0.0, -50.0]}\n",
    )
    rev = run(tmp_path / "rev", text)
    assert int(rev["status"]) == 0, str(rev["message"].values)
    assert float(rev["laid_length"]) == pytest.approx(float(fwd["laid_length"]), rel=1e-9)
    mirror = np.array([-1.0, 1.0, 1.0])  # the reversed line lies along -x from its anchor
    np.testing.assert_allclose(rev["force_a"], fwd["force_b"] * mirror, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(rev["force_b"], fwd["force_a"] * mirror, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(rev["z"].values, fwd["z"].values[::-1], atol=1e-9)
    np.testing.assert_allclose(float(rev["z"][0]), -5.0, atol=1e-9)  # A at the given height
