"""The small things of issue 23: --version, no traceback for a closed pipe or a missing
result, CF status flags, history, numeric attributes, excitation period, 'did you mean'
for the usual symbols, and the licence field."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import tomllib
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr

import cablestudy
from cablestudy.cli import EXIT_BROKEN_PIPE, main
from cablestudy.run.conventions import STATUS_MEANINGS, is_status_variable
from cablestudy.study.loader import StudyError, parse_study_text, validate_data

ROOT = Path(__file__).resolve().parents[2]


def test_version(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as exit_:
        main(["--version"])
    assert exit_.value.code == 0
    assert capsys.readouterr().out == f"cablestudy {cablestudy.__version__}\n"


def test_a_closed_pipe_ends_quietly() -> None:
    """``cablestudy schema | head``: the reader is gone before the first write (its end of
    the pipe closed before the command starts, so the EPIPE is certain)."""
    read, write = os.pipe()
    os.close(read)
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    proc = subprocess.run(
        [sys.executable, "-m", "cablestudy", "schema"],
        stdout=write,
        stderr=subprocess.PIPE,
        env=env,
        check=False,
        timeout=600,  # a bound on a hang, not a speed check (the machine may be loaded)
    )
    os.close(write)
    assert proc.stderr == b""  # no BrokenPipeError traceback
    assert proc.returncode == EXIT_BROKEN_PIPE == 141  # as a shell reports SIGPIPE


def test_figures_without_a_result_say_so_in_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code = main(["figures", "--no-run", "--results", str(tmp_path), "--out", str(tmp_path / "f")])
    err = capsys.readouterr().err
    assert code == 1
    assert err.count("\n") == 1 and "Traceback" not in err
    assert re.fullmatch(
        rf"cannot build the figures: {re.escape(str(tmp_path))}/(\S+)\.nc is missing; make "
        rf"it with `cablestudy run configs/\1\.yaml --out {re.escape(str(tmp_path))}`, or "
        r"run `cablestudy figures` without --no-run\n",
        err,
    )


STATIC = """
name: small
environment: {fluid: water}
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {method: catenary, nodes: 21}
"""


def _run(tmp_path: Path, text: str, name: str) -> tuple[xr.Dataset, list[str]]:
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text.replace("name: small", f"name: {name}"))
    args = ["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous", "--no-cache"]
    assert main(args) == 0
    return xr.load_dataset(tmp_path / f"{name}.nc"), args


@pytest.mark.parametrize(
    "sweep",
    # one case (the case-by-case writer) and an end sweep (the array path's writer)
    ["", "sweep:\n  ends.b.position.0: [90.0, 92.5]\n"],
    ids=["case", "array"],
)
def test_status_flags_history_and_numeric_attributes(tmp_path: Path, sweep: str) -> None:
    ds, args = _run(tmp_path, STATIC + sweep, "small")
    statuses = [str(v) for v in ds.data_vars if is_status_variable(str(v))]
    assert "status" in statuses and "static_status" in statuses
    for name in statuses:
        var = ds[name]
        assert var.attrs["flag_values"].dtype == var.dtype
        assert var.attrs["flag_values"].tolist() == [0, 1, 2, 3, 4, 5, 6, 7, 9, 10, 11]
        meanings = var.attrs["flag_meanings"].split(" ")
        assert meanings[0] == "ok" and meanings[-2:] == ["line_broken", "not_verified"]
        assert meanings == list(STATUS_MEANINGS.values())
        assert set(np.unique(var.values)) <= set(STATUS_MEANINGS)  # every code is named
    # CF history: "time: command line", the command as typed
    history = ds.attrs["history"]
    stamp, _, command = history.partition(": ")
    assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\+00:00", stamp)
    assert command == "cablestudy " + " ".join(args)
    # numeric attributes are numbers in the file, not text
    with netCDF4.Dataset(tmp_path / "small.nc") as nc:
        n_cases = 1 if not sweep else 2
        assert isinstance(nc.getncattr("cases"), np.integer) and nc.cases == n_cases
        assert isinstance(nc.getncattr("cases_failed"), np.integer) and nc.cases_failed == 0


FREQ = """
name: small
environment: {fluid: vacuum}
line:
  segments:
    - {length: 10.9774, diameter: 0.01, mass_per_length: 0.61, axial_stiffness: 7.854e+6}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [10.792, 0.0, 0.0]}
analysis:
  static: {method: analytic}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.05, frequency: 0.5}
    method: frequency
    elements: 40
sweep:
  analysis.dynamic.excitation.amplitude: [0.01, 0.02]
  analysis.dynamic.excitation.frequency: [0.5, 0.25]
"""


def test_excitation_period_sweep_is_the_frequency_sweep(tmp_path: Path) -> None:
    by_f, _ = _run(tmp_path, FREQ, "by-frequency")
    text = FREQ.replace("frequency: 0.5}", "period: 2.0}").replace(
        "excitation.frequency: [0.5, 0.25]", "excitation.period: [2.0, 4.0]"
    )
    by_t, _ = _run(tmp_path, text, "by-period")
    assert by_t["tension_max"].dims == ("amplitude", "period")
    assert by_t["period"].values.tolist() == [2.0, 4.0]
    assert by_t["period"].attrs["units"] == "s"
    assert np.all(by_t["status"] == 0)
    # 1/2 and 1/4 are exact: the same cases, so the same numbers to the last bit
    for name in ("tension_max", "tension_min", "tension_amplitude_b"):
        np.testing.assert_array_equal(by_t[name].values, by_f[name].values)


def _problems(text: str) -> list[str]:
    src = parse_study_text(text)
    with pytest.raises(StudyError) as err:
        validate_data(src.data, src)
    return err.value.problems


def test_frequency_or_period_exactly_one() -> None:
    body = FREQ.split("sweep:")[0]
    both = body.replace("frequency: 0.5}", "frequency: 0.5, period: 2.0}")
    assert _problems(both) == [
        "13: analysis.dynamic.excitation.period: give the excitation frequency [Hz] or its "
        "period [s], not both (frequency 0.5 is given too); allowed: exactly one of them "
        "(got 2.0)"
    ]
    neither = body.replace(", frequency: 0.5}", "}")
    assert _problems(neither) == [
        "13: analysis.dynamic.excitation.frequency: required key 'frequency' is missing "
        "(excitation frequency [Hz]); or give period [s] instead (got None)"
    ]


def test_did_you_mean_for_the_usual_symbols() -> None:
    text = STATIC.replace("axial_stiffness: 6.283e7}", "EA: 6.283e7, Cd: 1.2, MBL: 1.0e6}")
    problems = _problems(text)
    assert len(problems) == 3
    assert problems[0].startswith(
        "6: line.segments.0.EA: unknown key 'EA' (did you mean 'axial_stiffness'? EA is the "
        "axial stiffness EA [N]); allowed keys here: added_mass_normal, "
    )
    assert problems[1].startswith(
        "6: line.segments.0.Cd: unknown key 'Cd' (did you mean 'drag_normal'? Cd is the "
        "normal drag coefficient); allowed keys here: "
    )
    assert problems[2].startswith(
        "6: line.segments.0.MBL: unknown key 'MBL' (did you mean 'failure: "
        "{minimum_breaking_load: ...}'? MBL is the minimum breaking load [N]); allowed "
    )
    # inside failure the key itself is suggested; where the key is not allowed, nothing
    fail = STATIC.replace("6.283e7}", "6.283e7, failure: {MBL: 1.0e6}}")
    assert "(did you mean 'minimum_breaking_load'? MBL is the minimum" in _problems(fail)[0]
    ends = STATIC.replace("kind: fixed, position: [0.0, 0.0, 0.0]", "kind: fixed, EA: 1.0")
    assert "did you mean" not in _problems(ends)[0]


def test_licence_is_an_spdx_expression_with_its_file() -> None:
    meta = tomllib.loads((ROOT / "pyproject.toml").read_text())
    assert meta["project"]["license"] == "MIT"  # PEP 639: a string, not a table
    files = meta["project"]["license-files"]
    assert files and all((ROOT / f).is_file() for f in files)
    assert "MIT License" in (ROOT / files[0]).read_text()
    # setuptools reads a licence expression from 77.0 on; older ones refuse the string
    (req,) = [r for r in meta["build-system"]["requires"] if r.startswith("setuptools")]
    assert req == "setuptools>=77.0.3"


DATABASE = STATIC.replace(
    "static: {method: catenary, nodes: 21}",
    "static: {method: catenary, nodes: 21}\n  database:\n"
    "    horizontal_distance: {start: 90.0, stop: 95.0, num: 4}\n"
    "    height_difference: {start: -10.0, stop: -5.0, num: 4}",
)


def test_database_status_tables_carry_the_flags_in_both_files(tmp_path: Path) -> None:
    ds, _ = _run(tmp_path, DATABASE, "small")
    own = xr.load_dataset(tmp_path / "small.database.nc")
    for var in (ds["database_status"], own["status"]):
        assert var.attrs["flag_values"].dtype == var.dtype  # CF: the variable's type
        assert var.attrs["flag_values"].tolist() == list(STATUS_MEANINGS)
        assert var.attrs["flag_meanings"] == " ".join(STATUS_MEANINGS.values())
        assert np.all(var == 0)


def test_every_status_code_of_the_package_has_a_flag_meaning() -> None:
    """Every ``STATUS_*`` integer of every module of the package (wherever a move puts
    it) is one of the flags the result files explain."""
    import importlib
    import pkgutil

    modules = [
        importlib.import_module(info.name)
        for info in pkgutil.walk_packages(cablestudy.__path__, "cablestudy.")
        if info.name != "cablestudy.__main__"
    ]
    codes = {
        value
        for module in modules
        for name, value in vars(module).items()
        if name.startswith("STATUS_") and isinstance(value, int)
    }
    assert codes == set(STATUS_MEANINGS)
