"""The massless tension-only spring line (``line.kind: spring``) against its closed
forms, YAML -> netCDF through the command line.

Exact references (aqwa seed 5.8.1.1-5.8.1.3): the tension is the law of the extension
e = distance - length, zero when slack, directed along the chord; under end motion it
follows the ends at once (no mass). The statics are closed-form or one scalar equation
solved to 1e-12 relative, the dynamic extremes are refined to 1e-12 of the window by
golden section, so the tolerances are 1e-12 relative (1e-9 for the extremes, whose
location error e ~ 1e-12 T gives a tension error far below that).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main
from cablestudy.config.loader import StudyError

POLY = (2.0e5, 1.0e4, 3.0e2)


def T_poly(e: np.ndarray | float) -> np.ndarray:
    e = np.asarray(e, dtype=float)
    return np.where(e > 0, POLY[0] * e + POLY[1] * e**2 + POLY[2] * e**3, 0.0)


def run(tmp_path: Path, text: str, name: str = "spring") -> xr.Dataset:
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    code = main(
        ["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous", "--no-cache"]
    )
    assert code == 0
    return xr.load_dataset(tmp_path / f"{name}.nc")


FIXED = """\
name: spring
line:
  kind: spring
  length: 50.0
  axial: {law: polynomial, coefficients: [2.0e5, 1.0e4, 3.0e2]}
ends:
  a: {kind: fixed, position: [1.0, 2.0, -40.0]}
  b: {kind: fixed, position: [31.0, 42.0, -40.0]}
analysis:
  static: {nodes: 6}
  dynamic:
    excitation: {end: b, direction: [0.6, 0.8, 0.0], amplitude: 0.5, frequency: 0.1}
sweep:
  line.length: [48.0, 49.0, 50.0, 51.0]
"""


def test_spring_statics_and_dynamics_are_the_law_of_the_extension(tmp_path: Path) -> None:
    ds = run(tmp_path, FIXED)
    assert np.all(ds["status"] == 0)
    D = 50.0  # |(30, 40, 0)|
    u = np.array([0.6, 0.8, 0.0])
    for L in (48.0, 49.0, 50.0, 51.0):
        c = ds.sel(length=L)
        T = float(T_poly(D - L))
        assert float(c["tension_a"]) == pytest.approx(T, rel=1e-12, abs=1e-9)
        assert float(c["tension_b"]) == pytest.approx(T, rel=1e-12, abs=1e-9)
        np.testing.assert_allclose(c["force_a"], T * u, rtol=1e-12, atol=1e-9)
        np.testing.assert_allclose(c["force_b"], -T * u, rtol=1e-12, atol=1e-9)
        np.testing.assert_allclose(c["tension"], T, rtol=1e-12, atol=1e-9)
        # straight between the ends (uniform strain: s maps linearly onto the chord)
        np.testing.assert_allclose(c["x"], np.linspace(1.0, 31.0, 6), rtol=0, atol=1e-12)
        np.testing.assert_allclose(c["y"], np.linspace(2.0, 42.0, 6), rtol=0, atol=1e-12)
        # end B moves along the chord by 0.5 sin: extension D - L +- 0.5
        Tmax, Tmin = float(T_poly(D - L + 0.5)), float(T_poly(D - L - 0.5))
        assert float(c["tension_max"]) == pytest.approx(Tmax, rel=1e-9, abs=1e-6)
        assert float(c["tension_min"]) == pytest.approx(Tmin, rel=1e-9, abs=1e-6)
        assert float(c["tension_static"]) == pytest.approx(T, rel=1e-12, abs=1e-9)
    # taut all cycle (L = 48, 49): mean of T(e0 + a sin) = a1 e0 + a2 (e0^2 + a^2/2)
    # + a3 (e0^3 + 3 e0 a^2 / 2), exact
    for L in (48.0, 49.0):
        e0, a = D - L, 0.5
        mean = POLY[0] * e0 + POLY[1] * (e0**2 + a**2 / 2) + POLY[2] * (e0**3 + 1.5 * e0 * a**2)
        assert float(ds["tension_mean"].sel(length=L)) == pytest.approx(mean, rel=1e-12)
    # slack half of the cycle (L = 50): the mean is the integral over the taut half
    a = 0.5
    taut = (POLY[0] * a * 2 + POLY[1] * a**2 * math.pi / 2 + POLY[2] * a**3 * 4 / 3) / (2 * math.pi)
    assert float(ds["tension_mean"].sel(length=50.0)) == pytest.approx(taut, rel=1e-6)
    assert float(ds["tension_min"].sel(length=50.0)) == 0.0
    assert str(ds["dynamic_method"].values.ravel()[0]) == "spring"


TOWED = """\
name: towed
line:
  kind: spring
  length: 50.0
  axial: {law: linear, stiffness: 2.0e5}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: force, force: [3.0e4, 0.0, -4.0e4]}
"""

MOORED = """\
name: moored
line:
  kind: spring
  length: 30.0
  axial: {law: steel_wire, stiffness: 1.0e6, offset: 0.2}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -25.0]}
  b: {kind: mooring, force: [1.5e5, 2.0e5], z: 0.0}
"""


def test_towed_and_moored_springs_balance_their_forces(tmp_path: Path) -> None:
    ds = run(tmp_path, TOWED, "towed")
    F = np.array([3.0e4, 0.0, -4.0e4])
    T = 5.0e4
    pos_b = np.array([float(ds[k].isel(s=-1)) for k in "xyz"])
    # along the force, stretched by T / k
    np.testing.assert_allclose(pos_b, (50.0 + T / 2.0e5) * F / T, rtol=1e-13, atol=1e-12)
    np.testing.assert_allclose(ds["force_b"], -F, rtol=1e-13)
    ds = run(tmp_path, MOORED, "moored")
    H = np.array([1.5e5, 2.0e5])
    fb = ds["force_b"].values
    np.testing.assert_allclose(fb[:2], -H, rtol=1e-11)
    pos_b = np.array([float(ds[k].isel(s=-1)) for k in "xyz"])
    assert pos_b[2] == pytest.approx(0.0, abs=1e-12)
    # the line is along its tension, and its length is L + e(T) of the steel-wire law
    T = float(ds["tension_b"])
    D = float(np.linalg.norm(pos_b - [0.0, 0.0, -25.0]))
    k, d = 1.0e6, 0.2
    e = D - 30.0
    assert k * (e - d * (1.0 - math.exp(-e / d))) == pytest.approx(T, rel=1e-11)
    np.testing.assert_allclose(-fb / T, (pos_b - [0, 0, -25.0]) / D, rtol=1e-11)


BREAK = """\
name: parted
line:
  kind: spring
  length: 50.0
  axial: {law: linear, stiffness: 2.0e5}
  failure: {tension: 2.0e5}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [50.5, 0.0, 0.0]}
analysis:
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 1.0, frequency: 0.1}
    ramp_periods: 0.0
"""


def test_spring_parts_when_the_tension_reaches_the_limit(tmp_path: Path) -> None:
    """T(t) = k (0.5 + sin(2 pi f t)) reaches 2e5 N when sin = 0.5: t = 1 / (12 f)."""
    ds = run(tmp_path, BREAK, "parted")
    assert float(ds["break_time"]) == pytest.approx(1.0 / 1.2, rel=1e-10)
    assert float(ds["tension_max"]) == pytest.approx(2.0e5, rel=1e-10)
    assert float(ds["tension_min"]) == 0.0


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        (
            FIXED.replace("coefficients: [2.0e5, 1.0e4, 3.0e2]", "coefficients: [2.0e5, -1.0e5]"),
            "stops increasing at extension [m] 1",
        ),
        (
            FIXED.replace("  static: {nodes: 6}\n", "  static: {nodes: 6}\n  modal: {modes: 2}\n"),
            "a massless spring has no modes",
        ),
        (TOWED.replace("[3.0e4, 0.0, -4.0e4]", "[0.0, 0.0, 0.0]"), "zero force on a massless"),
        (
            FIXED.replace(
                "kind: spring\n", "kind: spring\n  segments: []\n  attachments: [{s: 1.0}]\n"
            ),
            "a kind: spring line is massless and straight",
        ),
    ],
)
def test_spring_config_faults_are_refused_before_work(
    tmp_path: Path, text: str, fragment: str
) -> None:
    cfg = tmp_path / "bad.yaml"
    cfg.write_text(text)
    from cablestudy.cli import main as cli

    with pytest.raises((StudyError, SystemExit)):
        try:
            code = cli(["validate", str(cfg)])
        except StudyError as exc:
            assert fragment in str(exc)
            raise
        raise SystemExit(code)
