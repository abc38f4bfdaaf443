"""Contract defects an outside check reported, each through YAML -> ``cablestudy run`` ->
netCDF (issue: contract fixes):

1. ``tension_static`` says what each dynamic method writes (the frequency domain: the
   static solver's end tension, which it linearises about);
2. a spectrum solved in the frequency domain on a line lying on the seabed writes the
   touchdown range (``touchdown_min``/``touchdown_max``), the most probable maximum
   travel over the storm;
3. every status variable's CF ``flag_values`` has the variable's own (integer) type in
   the file, ``database_status`` included;
4. ``analysis.modal.mode_shapes`` swept: the NaN of the cases without mode shapes is
   explained by a ``nan_means`` attribute (and the variable is absent when no case
   writes it);
5. a missing study file is reported as missing, by path, with exit status 2 and no
   line number.
"""

from __future__ import annotations

import math
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main
from cablestudy.run.conventions import STATUS_MEANINGS
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text


def _run(tmp_path: Path, name: str, text: str) -> Path:
    """Run the study ``text`` (its name ``name``) through the command line; the path of
    its result file."""
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    out = tmp_path / "out"
    args = ["run", str(cfg), "--out", str(out), "--no-cache", "--no-progress"]
    assert main([*args, "--scheduler", "synchronous"]) == 0
    return out / f"{name}.nc"


# -- 5. a missing study file ------------------------------------------------------------


@pytest.mark.parametrize("command", ["run", "validate"])
def test_missing_study_file_is_named_without_a_line_number(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], command: str
) -> None:
    missing = tmp_path / "missing.yaml"
    extra = ["--out", str(tmp_path / "out")] if command == "run" else []
    assert main([command, str(missing), *extra]) == 2
    err = capsys.readouterr().err
    assert (
        f"{missing}: cannot read the study file: it does not exist (no file at {missing.resolve()})"
    ) in err
    assert ":0:" not in err and "line 0" not in err and "Traceback" not in err
    assert not (tmp_path / "out").exists()


# -- 1. tension_static of the frequency domain -----------------------------------------

#: the moustafa cable (d = 0.01 m, L = 10.9774 m between supports 10.792 m apart, level),
#: end B moved 1 mm along the span at 0.5 Hz, in the frequency domain
MOUSTAFA = """
name: {name}
environment: {{fluid: water, gravity: 9.80665}}
line:
  segments:
    - {{length: 10.9774, diameter: 0.01, mass_per_length: 0.61, axial_stiffness: 7.854e+6,
       drag_normal: 1.2, drag_tangential: 0.01, added_mass_normal: 1.0}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, 0.0]}}
  b: {{kind: fixed, position: [10.792, 0.0, 0.0]}}
analysis:
  static: {{method: analytic, nodes: 21, tolerance: 1.0e-12}}
  modal: {{modes: 3, elements: 20}}
  dynamic:
    excitation: {{end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.001, frequency: 0.5}}
    method: frequency
    elements: 20
"""


def test_frequency_domain_tension_static_is_the_static_solvers(tmp_path: Path) -> None:
    ds = xr.load_dataset(_run(tmp_path, "fd-static", MOUSTAFA.format(name="fd-static")))
    assert int(ds["status"]) == 0 and str(ds["dynamic_method"].values) == "frequency"
    # the frequency domain linearises about the static solution (of the analytic
    # catenary, exact at any node count): its tension_static is the static solver's end
    # tension at the excited end B to rounding (1e-12 tolerance of the solve)
    np.testing.assert_allclose(float(ds["tension_static"]), float(ds["tension_b"]), rtol=1e-9)
    # and its metadata say so for both methods, naming which ran
    long_name = ds["tension_static"].attrs["long_name"]
    assert "dynamic model" not in long_name
    for words in ("time domain's own discretised model", "frequency domain", "static solver"):
        assert words in long_name, words
    assert "dynamic_method" in long_name


def test_time_domain_tension_static_converges_to_the_static_solvers(tmp_path: Path) -> None:
    """The time domain's tension_static is its own lumped model's at rest: it differs
    from the static solver's (exact, analytic) by the model's discretisation error,
    second order in the element length (measured 1.06e-3, 2.66e-4, 6.65e-5 relative on
    20, 40, 80 elements): halving the elements quarters it (3.5 to 4.5 allows for the
    next order, ~h^2 of the error itself: 5 % at 20 elements)."""
    errors = []
    for n in (20, 40):
        name = f"td-static-{n}"
        text = MOUSTAFA.format(name=name).replace("method: frequency", "method: time")
        text = text.replace("    elements: 20\n", f"    elements: {n}\n")
        ds = xr.load_dataset(_run(tmp_path, name, text))
        assert str(ds["dynamic_method"].values) == "time"
        errors.append(abs(float(ds["tension_static"]) / float(ds["tension_b"]) - 1.0))
    assert 1e-4 < errors[0] < 1e-2 and 3.5 < errors[0] / errors[1] < 4.5, errors


# -- 2. a spectrum's touchdown range ----------------------------------------------------

#: a chain mooring (configs/chain-mooring-surge.yaml with fewer elements) without drag:
#: the linear responses to the spectral lines are then independent of one another and of
#: their amplitudes, so the spectrum's statistics follow exactly from a harmonic sweep
CHAIN = """
name: {name}
environment:
  fluid: water
  depth: 200.0
  seabed: {{friction: 0.5}}
line:
  segments:
    - {{length: 800.0, diameter: 0.1533, mass_per_length: 141.0, axial_stiffness: 6.0e+8,
       drag_normal: 0.0, drag_tangential: 0.0, damping_ratio: 0.8}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, -200.0]}}
  b: {{kind: fixed, position: [750.0, 0.0, -10.0]}}
analysis:
  static: {{nodes: 41}}
  dynamic:
    excitation: {excitation}
    method: frequency
    elements: 40
{sweep}"""
SPECTRUM = (
    "{end: b, direction: [1.0, 0.0, 0.0], components: 4, storm_duration: 3600.0,"
    " spectrum: [[0.0, 2.0], [0.12, 2.0]]}"
)


def test_spectrum_on_the_seabed_writes_the_touchdown_range(tmp_path: Path) -> None:
    text = CHAIN.format(name="chain-spectrum", excitation=SPECTRUM, sweep="")
    (case,) = expand_cases(parse_study_text(text))[1]
    spec = case.study.analysis.dynamic.excitations[0]  # type: ignore[union-attr]
    freqs, amps = np.array(spec.line_frequencies), np.array(spec.line_amplitudes)
    sp = xr.load_dataset(_run(tmp_path, "chain-spectrum", text))
    assert int(sp["status"]) == 0, str(sp["message"].values)
    assert "touchdown_min" in sp and "touchdown_max" in sp
    lo, hi = float(sp["touchdown_min"]), float(sp["touchdown_max"])
    assert np.isfinite(lo) and np.isfinite(hi) and lo < hi
    assert "most probable maximum" in sp["touchdown_max"].attrs["long_name"]
    # the same line's harmonic responses at the spectral lines, 1 m each
    harmonic = "{end: b, direction: [1.0, 0.0, 0.0], amplitude: 1.0, frequency: 0.03}"
    sweep = (
        "sweep:\n  analysis.dynamic.excitation.frequency: ["
        + ", ".join(repr(float(f)) for f in freqs)
        + "]\n"
    )
    hd = xr.load_dataset(
        _run(
            tmp_path,
            "chain-lines",
            CHAIN.format(name="chain-lines", excitation=harmonic, sweep=sweep),
        )
    )
    assert np.all(hd["status"] == 0)
    h_lo, h_hi = hd["touchdown_min"].values, hd["touchdown_max"].values
    point = 0.5 * (h_lo + h_hi)
    # one static touchdown point for every case and the spectrum (the same static line)
    np.testing.assert_allclose(point, 0.5 * (lo + hi), rtol=1e-12)
    # the travel is linear in the touchdown element's tension variation r_k per metre of
    # line k: the spectrum's most probable maximum is sigma sqrt(2 ln(T / T_z)), with
    # sigma^2 = m0 = sum (a_k r_k)^2 / 2, m2 = sum w_k^2 (a_k r_k)^2 / 2, T_z = 2 pi
    # sqrt(m0 / m2) (frequency.irregular); equal to rounding (no drag: the responses are
    # linear and independent, the same solves)
    r = 0.5 * (h_hi - h_lo) * amps
    w = 2.0 * math.pi * freqs
    m0, m2 = 0.5 * np.sum(r**2), 0.5 * np.sum(w**2 * r**2)
    tz = 2.0 * math.pi * math.sqrt(m0 / m2)
    expected = math.sqrt(m0) * math.sqrt(2.0 * math.log(3600.0 / tz))
    np.testing.assert_allclose(0.5 * (hi - lo), expected, rtol=1e-9)


# -- 3. CF flag_values of every status variable ----------------------------------------

DATABASE = """
name: {name}
environment: {{fluid: water, depth: 200.0}}
line:
  segments:
    - {{length: 150.0, diameter: 0.1, mass_per_length: 150.0, axial_stiffness: 8.0e8}}
    - {{length: 220.0, diameter: 0.08, mass_per_length: 25.0, axial_stiffness: 4.0e8}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, -200.0]}}
  b: {{kind: fixed, position: [290.0, 0.0, -20.0]}}
analysis:
  static: {{method: catenary, nodes: 11}}
  database:
    horizontal_distance: {{start: 250.0, stop: 400.0, num: 4}}
    height_difference: {{start: 160.0, stop: 200.0, num: 4}}
sweep:
  analysis.static.max_iterations: [50, 1]
"""


def _check_flags(path: Path) -> list[str]:
    """The status variables of the file at ``path``, each checked as CF asks: its
    ``flag_values`` of the variable's own type (in the file, as written), an integer
    type, and every value it holds one of them. Returns their names."""
    names = []
    with netCDF4.Dataset(path) as nc:
        for name, var in nc.variables.items():
            if "flag_values" not in var.ncattrs():
                continue
            names.append(name)
            flags = np.asarray(var.getncattr("flag_values"))
            assert flags.dtype == var.dtype, (path.name, name, flags.dtype, var.dtype)
            assert var.dtype.kind == "i", (path.name, name, var.dtype)
            assert flags.tolist() == list(STATUS_MEANINGS)
            var.set_auto_maskandscale(False)
            assert set(np.unique(var[...])) <= set(flags.tolist()), (path.name, name)
    return names


def test_status_flags_have_the_variables_integer_type(tmp_path: Path) -> None:
    db = _run(tmp_path, "db-flags", DATABASE.format(name="db-flags"))
    ds = xr.load_dataset(db)
    ok, failed = ds.sel(max_iterations=50), ds.sel(max_iterations=1)
    # one Newton iteration does not settle the seabed contact: the case's statics fail,
    # its database is not solved (5) and its tables are NaN; the other case's are solved
    assert int(failed["static_status"]) != 0 and np.all(failed["database_status"] == 5)
    assert np.all(np.isnan(failed["database_tension_a"]))
    assert int(ok["static_status"]) == 0 and np.all(ok["database_status"] == 0)
    assert np.all(np.isfinite(ok["database_tension_a"]))
    paths = [db, db.with_name("db-flags.database.nc")]
    paths.append(_run(tmp_path, "fd-flags", MOUSTAFA.format(name="fd-flags")))
    paths.append(
        _run(
            tmp_path,
            "spectrum-flags",
            CHAIN.format(name="spectrum-flags", excitation=SPECTRUM, sweep=""),
        )
    )
    checked = {p.name: _check_flags(p) for p in paths}
    assert "database_status" in checked["db-flags.nc"]
    assert {"status", "point_status"} <= set(checked["db-flags.database.nc"])
    assert {"status", "static_status", "modal_status", "dynamic_status"} <= set(
        checked["fd-flags.nc"]
    )
    assert "dynamic_status" in checked["spectrum-flags.nc"]


# -- 4. mode shapes switched off --------------------------------------------------------

MODAL = """
name: {name}
environment: {{fluid: air}}
line:
  segments:
    - {{length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, 0.0]}}
  b: {{kind: fixed, position: [92.5, 0.0, -8.6]}}
analysis:
  static: {{nodes: 11}}
  modal: {{modes: 3, elements: 20{shapes}}}
sweep:
  line.segments.0.length: [100.0, 101.0]
{sweep}"""


def test_mode_shapes_switched_off_are_absent_or_explained(tmp_path: Path) -> None:
    off = xr.load_dataset(
        _run(
            tmp_path,
            "shapes-off",
            MODAL.format(name="shapes-off", shapes=", mode_shapes: false", sweep=""),
        )
    )
    assert "mode_shape" not in off and "natural_frequency" in off
    swept = xr.load_dataset(
        _run(
            tmp_path,
            "shapes-swept",
            MODAL.format(
                name="shapes-swept",
                shapes="",
                sweep="  analysis.modal.mode_shapes: [true, false]\n",
            ),
        )
    )
    assert np.all(swept["status"] == 0) and np.all(swept["message"] == "")
    shape = swept["mode_shape"]
    assert "mode_shapes is false" in shape.attrs["nan_means"]
    assert np.all(np.isnan(shape.sel(mode_shapes=False)))
    assert np.all(np.isfinite(shape.sel(mode_shapes=True)))
    # the natural frequencies do not depend on the switch
    np.testing.assert_array_equal(
        swept["natural_frequency"].sel(mode_shapes=True),
        swept["natural_frequency"].sel(mode_shapes=False),
    )
    # the attribute is the registry's, on every variable that gives NaN a meaning
    assert "nan_means" not in swept["natural_frequency"].attrs


def test_every_declared_status_variable_is_an_integer() -> None:
    """The registry behind every analysis's outputs (one line, systems, the database's
    layouts): each variable that carries the status flags is declared an integer, so
    that its ``flag_values`` (of the variable's type) are integers in every dataset."""
    from cablestudy.analyses.variables import CASE_VARIABLES, OUTPUTS, SYSTEM_OUTPUTS
    from cablestudy.run.conventions import is_status_variable

    registries = {"outputs": OUTPUTS, "system": SYSTEM_OUTPUTS, "case": CASE_VARIABLES}
    statuses = [
        (where, name, spec.dtype)
        for where, registry in registries.items()
        for name, spec in registry.items()
        if is_status_variable(name)
    ]
    names = {name for _, name, _ in statuses}
    assert {"status", "static_status", "database_status", "database_radial_status"} <= names
    assert all(dtype == "int64" for _, _, dtype in statuses), statuses
