"""The ``axial`` and ``failure`` keys at validation: every fault refused before any work,
at its line, naming the field, the value and what is allowed (or which analyses and
methods support it)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main

BASE = """\
name: laws
environment: {fluid: water}
line:
  segments:
    - length: 120.0
      diameter: 0.08
      mass_per_length: 30.0
      axial: {law: polynomial, coefficients: [4.0e6, 2.0e7, 5.0e7]}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -60.0]}
  b: {kind: fixed, position: [95.0, 0.0, -5.0]}
analysis:
  static: {method: catenary, nodes: 21}
"""


def validate(tmp_path: Path, text: str, capsys: pytest.CaptureFixture[str]) -> tuple[int, str]:
    cfg = tmp_path / "study.yaml"
    cfg.write_text(text)
    code = main(["validate", str(cfg)])
    return code, capsys.readouterr().err


def test_the_base_study_is_valid(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, err = validate(tmp_path, BASE, capsys)
    assert code == 0, err


@pytest.mark.parametrize(
    ("old", "new", "fragments"),
    [
        (  # both keys
            "      axial: {law",
            "      axial_stiffness: 1.0e7\n      axial: {law",
            ["study.yaml:9:", "line.segments.0.axial", "not both"],
        ),
        (  # decreasing from strain 0.25: dT/de = 4e6 - 1.6e7 e
            "coefficients: [4.0e6, 2.0e7, 5.0e7]",
            "coefficients: [4.0e6, -8.0e6]",
            ["line.segments.0.axial.coefficients", "stops increasing at strain 0.25"],
        ),
        (  # negative from the start
            "coefficients: [4.0e6, 2.0e7, 5.0e7]",
            "coefficients: [-4.0e6, 2.0e7]",
            ["stops increasing at strain 0 "],
        ),
        (  # a table whose tension falls
            "{law: polynomial, coefficients: [4.0e6, 2.0e7, 5.0e7]}",
            "{law: table, strain: [0.0, 0.01, 0.02], tension: [0.0, 5.0e4, 4.0e4]}",
            ["line.segments.0.axial.tension.2", "does not increase at strain 0.02"],
        ),
        (  # unknown law
            "law: polynomial",
            "law: quadratic",
            ["line.segments.0.axial.law", "'law' must be one of", "'steel_wire'"],
        ),
        (  # the closed form needs a linear law
            "method: catenary",
            "method: analytic",
            ["'analytic' does not support a non-linear axial law", "'catenary' or 'shooting'"],
        ),
        (  # catenary takes a non-linear law with a seabed too (a valid variant)
            "environment: {fluid: water}",
            "environment: {fluid: water, depth: 200.0}",
            [],
        ),
        (  # break with the catenary time domain
            "ends:\n",
            "  failure: {tension: 1.0e5}\nends:\n",
            [],
        ),
        (  # a failure time with statics only: unused, so refused
            "ends:\n",
            "  failure: {time: 10.0}\nends:\n",
            ["line.failure.time: a failure time applies to analysis.dynamic"],
        ),
        (  # safety factor without an MBL
            "ends:\n",
            "  failure: {tension: 1.0e5, safety_factor: 2.0}\nends:\n",
            ["line.failure.safety_factor", "applies to minimum_breaking_load"],
        ),
    ],
)
def test_axial_faults_are_refused_at_their_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], old: str, new: str, fragments: list[str]
) -> None:
    assert old in BASE
    code, err = validate(tmp_path, BASE.replace(old, new), capsys)
    if not fragments:  # a valid variant
        assert code == 0, err
        return
    assert code != 0
    for f in fragments:
        assert f in err, f"{f!r} not in {err}"


def test_break_is_refused_by_the_frequency_domain_only(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The linearised line cannot part: method frequency refuses a failure key naming
    the methods that model it; time and auto (which then runs the time domain) accept."""
    dynamic = (
        "  dynamic:\n    method: {method}\n    excitation: {{end: b, direction: [1, 0, 0], "
        "amplitude: 0.5, frequency: 0.2}}\n"
    )
    base = BASE.replace(
        "axial: {law: polynomial, coefficients: [4.0e6, 2.0e7, 5.0e7]}",
        "axial_stiffness: 4.0e7",
    ).replace("ends:\n", "  failure: {minimum_breaking_load: 3.0e5, safety_factor: 1.67}\nends:\n")
    code, err = validate(tmp_path, base + dynamic.format(method="frequency"), capsys)
    assert code != 0
    assert "line.failure: a break condition (the line parts) is modelled by the time domain" in err
    assert "allowed: method time or auto" in err
    for method in ("time", "auto"):
        code, err = validate(tmp_path, base + dynamic.format(method=method), capsys)
        assert code == 0, err


def test_static_break_is_recorded_with_where_and_by_how_much(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """The line's top tension is ~ w L + H: a limit swept across it breaks some cases;
    broken cases keep their static data and get status 10 with the place and excess."""
    text = BASE.replace("ends:\n", "  failure: {tension: 1.0}\nends:\n") + (
        "sweep:\n  line.failure.tension: {values: [1.0e4, 1.0e6], name: break_tension}\n"
    )
    cfg = tmp_path / "study.yaml"
    cfg.write_text(text)
    assert (
        main(["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous", "--no-cache"])
        == 0
    )
    ds = xr.load_dataset(tmp_path / "laws.nc")
    broken = ds.sel(break_tension=1.0e4)
    intact = ds.sel(break_tension=1.0e6)
    assert int(broken["status"]) == 10 and int(intact["status"]) == 0
    # the static results are kept, identical to the intact case's
    np.testing.assert_array_equal(broken["x"], intact["x"])
    T = intact["tension"].values
    j = int(np.argmax(T))
    msg = str(broken["message"].values)
    assert f"at s = {float(ds.s[j]):.6g} m" in msg
    assert f"by {T[j] - 1.0e4:.6g} N" in msg
    assert ds.attrs["cases_failed"] == 0 and ds.attrs["cases_broken"] == 1
