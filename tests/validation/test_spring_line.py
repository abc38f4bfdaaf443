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
from cablestudy.study.loader import StudyError

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


def test_vectorised_end_motion_is_the_time_domains() -> None:
    """The spring's vectorised end displacements equal EndMotion.at (ramp, several
    harmonics on both ends, a time table) at random times."""
    from cablestudy.dynamics.excitation import EndMotion, TableMotion
    from cablestudy.dynamics.spring import end_displacements

    motion = EndMotion(
        harmonic_end=np.array([0, 1, 1]),
        harmonic_direction=np.array([[1.0, 0, 0], [0.6, 0.8, 0], [0, 0, 1.0]]),
        harmonic_amplitude=np.array([0.2, 0.5, 0.1]),
        harmonic_frequency=np.array([0.1, 0.25, 0.7]),
        harmonic_phase=np.array([0.0, 1.0, -2.0]),
        tables=(
            TableMotion(
                end=1,
                direction=np.array([0.0, 1.0, 0.0]),
                times=np.array([0.0, 5.0, 10.0, 20.0, 40.0]),
                values=np.array([0.0, 0.3, -0.1, 0.2, 0.0]),
            ),
        ),
        ramp_time=12.0,
    )
    t = np.random.default_rng(2).uniform(-1.0, 40.0, 50)
    got = end_displacements(motion, t)
    want = np.array([motion.at(float(ti))[0] for ti in t])
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-15)


def test_spring_fails_at_its_failure_time(tmp_path: Path) -> None:
    """failure.time before the tension limit: the line parts then (window = the first
    period, ramp 0): break_time is that time, the window's maximum is the tension's
    maximum before it, k (0.5 + sin(2 pi f t)) over [0, 0.5 s]."""
    text = BREAK.replace("failure: {tension: 2.0e5}", "failure: {tension: 1.0e6, time: 0.5}")
    ds = run(tmp_path, text, "parted")
    assert float(ds["break_time"]) == pytest.approx(0.5, rel=1e-12)
    assert float(ds["tension_max"]) == pytest.approx(
        2.0e5 * (0.5 + math.sin(math.pi * 0.1)), rel=1e-9
    )
    # a failure time without dynamics is refused (it would be unused)
    cfg = tmp_path / "static.yaml"
    cfg.write_text(text.split("analysis:")[0])
    assert main(["validate", str(cfg)]) != 0


PULLEY = """\
name: pulley
line:
  kind: spring
  length: 30.0
  axial: {law: linear, stiffness: 1.0e5}
  pulleys:
    - {position: [10.0, 0.0, 0.0]}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [10.0, 0.0, -21.0]}
analysis:
  static: {nodes: 7}
"""


def test_frictionless_pulley_gives_equal_tensions(tmp_path: Path) -> None:
    """Path 10 + 21 m over a pulley for a 30 m spring: T = k (31 - 30) on both spans,
    the pulley carries T (u_out - u_in) = T (-1, 0, -1)."""
    ds = run(tmp_path, PULLEY, "pulley")
    T = 1.0e5
    assert float(ds["tension_a"]) == pytest.approx(T, rel=1e-13)
    assert float(ds["tension_b"]) == pytest.approx(T, rel=1e-13)
    np.testing.assert_allclose(ds["force_a"], [T, 0.0, 0.0], atol=1e-9)
    np.testing.assert_allclose(ds["force_b"], [0.0, 0.0, T], atol=1e-9)
    np.testing.assert_allclose(ds["pulley_force"].values[0], [-T, 0.0, -T], atol=1e-9)
    # the line runs A -> pulley -> B along s (uniform strain: 10/31 of L on span 1)
    assert float(ds["x"].isel(s=-1)) == pytest.approx(10.0)
    assert float(ds["z"].isel(s=-1)) == pytest.approx(-21.0)


@pytest.mark.parametrize(("wrap_deg", "factor"), [(180.0, 2.0), (90.0, 3.0)])
def test_sliding_over_a_pulley_holds_the_seeds_friction_ratio(
    wrap_deg: float, factor: float
) -> None:
    """End B pulled away, then back: while the line slides the larger tension over the
    smaller is factor^(wrap / 180 deg) (the seed's law: the factor holds for a
    180-degree wrap); while it sticks the ratio stays below that."""
    from cablestudy.dynamics.excitation import EndMotion
    from cablestudy.dynamics.spring import SpringDynamicProblem, march_with_friction
    from cablestudy.physics.axial import PolynomialLaw

    th = math.radians(wrap_deg)
    pulley = np.array([10.0, 0.0, 0.0])
    out_dir = np.array([math.cos(th), 0.0, -math.sin(th)])  # leaves turning by th
    rB = pulley + 8.0 * out_dir
    motion = EndMotion(
        harmonic_end=np.array([1]),
        harmonic_direction=out_dir[None, :],
        harmonic_amplitude=np.array([0.5]),
        harmonic_frequency=np.array([0.1]),
        harmonic_phase=np.array([0.0]),
    )
    law = PolynomialLaw((1.0e5, 2.0e4))
    prob = SpringDynamicProblem(
        law=law,
        length=17.5,
        position_a=np.zeros(3),
        position_b=rB,
        motion=motion,
        window=(0.0, 10.0),
        pulleys=pulley[None, :],
        friction=np.array([factor]),
    )
    t = np.linspace(0.0, 10.0, 2001)
    T = march_with_friction(prob, t, 17.5 * np.array([10.0, 8.0]) / 18.0)
    taut = np.minimum(T[:, 0], T[:, 1]) > 0.0
    assert taut.sum() > 1000
    ratio = np.maximum(T[:, 0], T[:, 1])[taut] / np.minimum(T[:, 0], T[:, 1])[taut]
    bound = factor ** (wrap_deg / 180.0)
    assert np.all(ratio <= bound * (1 + 1e-9))
    # at the largest pull the line has slid: the ratio is at the bound
    j = int(np.argmax(T[:, 1]))
    assert T[j, 1] / T[j, 0] == pytest.approx(bound, rel=1e-9)
    assert ratio.max() == pytest.approx(bound, rel=1e-9)


WINCH = """\
name: winch
line:
  kind: spring
  length: 50.0
  axial: {law: linear, stiffness: 2.0e5}
  winch: {speed: -0.01, start: 10.0, stop: 60.0}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [50.2, 0.0, 0.0]}
analysis:
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.0, frequency: 0.1}
    duration: 100.0
    ramp_periods: 0.0
"""


def test_winch_hauling_in_a_spring(tmp_path: Path) -> None:
    """Ends still, the winch hauls in 0.01 m/s from 10 s to 60 s: T = k (0.2 + 0.01
    (t - 10)) between, k 0.2 before, k 0.7 after: over the 100 s run the minimum is
    k 0.2, the maximum k 0.7 and the mean k (0.2 10 + mean ramp 0.45 50 + 0.7 40) / 100."""
    ds = run(tmp_path, WINCH, "winch")
    k = 2.0e5
    assert float(ds["tension_static"]) == pytest.approx(k * 0.2, rel=1e-12)
    assert float(ds["tension_min"]) == pytest.approx(k * 0.2, rel=1e-9)
    assert float(ds["tension_max"]) == pytest.approx(k * 0.7, rel=1e-9)
    mean = k * (0.2 * 10 + 0.45 * 50 + 0.7 * 40) / 100
    # trapezoidal rule over the run, exact on the linear pieces; the two kinks between
    # grid points cost O(h^2) (h = 100 s / 4096+): below 1e-6 relative
    assert float(ds["tension_mean"]) == pytest.approx(mean, rel=1e-6)
