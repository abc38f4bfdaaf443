"""Single-line dynamics checked from outside, as an external evaluator would: YAML text
(tests/dynamics_contract.py, written from DESIGN.md and the user guide) ->
``cablestudy run CONFIG --out DIR`` -> netCDF read with xarray, against the study-file
contract and the dataset conventions of DESIGN.md, and against physics a user checks:
the frequency against the time domain where both hold the same linear physics, ends
swapped, the frame turned, a phase of 180 degrees against the reversed direction, a
periodic table against the harmonic it samples, the quasi-static limit against the
static offset curve, a spectrum's variance, a string's natural frequencies, a spring's
algebraic tension and the database against a static run. Bad inputs are refused before
any work, naming the field, the value and what is allowed.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from cablestudy.cli import main
from tests.dynamics_contract import LAID_SURGE, STUDIES, air, bent, laid, mirrored, turned, water
from tests.integration.test_contract_external_line import axis_values, dim_name, run

#: units of the dynamic outputs (docs/guide/results.md, docs/frequency-domain.md)
UNITS = {
    "tension_max": "N",
    "tension_min": "N",
    "tension_mean": "N",
    "tension_static": "N",
    "tension_envelope_max": "N",
    "tension_envelope_min": "N",
    "z_envelope_max": "m",
    "tension_amplitude_a": "N",
    "tension_amplitude_b": "N",
    "tension_phase_a": "deg",
    "tension_phase_b": "deg",
    "tension_rao_a": "N/m",
    "tension_rao_b": "N/m",
    "tension_rao_phase_a": "deg",
    "tension_rao_phase_b": "deg",
    "tension_rao_line": "N/m",
    "tension_std_a": "N",
    "tension_std_b": "N",
    "tension_psd_a": "N^2/Hz",
    "tension_psd_b": "N^2/Hz",
    "history_displacement": "m",
    "history_velocity": "m/s",
    "history_acceleration": "m/s^2",
    "history_tension": "N",
    "history_time": "s",
    "history_line_position": "m",
    "history_line_velocity": "m/s",
    "history_line_tension": "N",
    "natural_frequency": "Hz",
    "mode_shape": "m",
    "touchdown_min": "m",
    "touchdown_max": "m",
    "database_tension_b": "N",
    "database_force_b": "N",
    "status": "1",
    "message": "1",
    "wall_time": "s",
}


def dynamic_conventions(ds: xr.Dataset, text: str) -> list[str]:
    """The conventions of DESIGN.md a one-line dynamic dataset keeps; the faults found."""
    bad: list[str] = []
    doc = yaml.safe_load(text)
    sweep = doc.get("sweep") or {}
    dims = [dim_name(p, s) for p, s in sweep.items()]
    for path, spec in sweep.items():
        name = dim_name(path, spec)
        if ds.sizes.get(name) != len(axis_values(spec)):
            bad.append(f"sweep {path}: no dimension {name}: {dict(ds.sizes)}")
    for name in [*ds.data_vars, *ds.coords]:
        attrs = ds[name].attrs
        if not isinstance(attrs.get("units"), str) or not attrs.get("long_name"):
            bad.append(
                f"{name}: units {attrs.get('units')!r}, long_name {attrs.get('long_name')!r}"
            )
        if name in UNITS and attrs.get("units") != UNITS[name]:
            bad.append(f"{name}: units {attrs.get('units')!r}, not {UNITS[name]!r}")
    for name in ("status", "message", "wall_time"):
        if name not in ds or list(ds[name].dims) != dims:
            bad.append(f"{name}: not one per case on {dims}")
    if ds.attrs.get("study_yaml") != text:
        bad.append("the study's YAML text is not in the global attributes")
    analysis = doc.get("analysis", {})
    wanted = []
    if analysis.get("dynamic"):
        wanted += ["tension_max", "tension_min", "tension_mean", "tension_static"]
        wanted += ["dynamic_status", "dynamic_method", "steady_converged"]
    if analysis.get("modal"):
        wanted += ["natural_frequency", "modal_status"]
    bad += [f"{name}: missing" for name in wanted if name not in ds]
    if "frequency" in ds.coords and ds["frequency"].attrs.get("units") != "Hz":
        bad.append("frequency: not in Hz")
    if bad:
        return bad
    for at in np.ndindex(*[ds.sizes[d] for d in dims]):
        c = ds.isel(dict(zip(dims, at, strict=True)))
        status, message = int(c["status"]), str(c["message"].values)
        if status != 0:
            if not message:
                bad.append(f"case {at}: status {status} without a message")
            continue
        if message or not float(c["wall_time"]) > 0.0:
            bad.append(f"case {at}: ok with message {message!r}, wall_time {c['wall_time']}")
        if "dynamic_status" in c and int(c["dynamic_status"]) != 0:
            bad.append(f"case {at}: status 0 with dynamic_status {int(c['dynamic_status'])}")
        for name in wanted:
            if c[name].dtype.kind == "f" and not np.all(np.isfinite(c[name].values)):
                bad.append(f"case {at}: {name} not finite with status 0")
        if "tension_max" in wanted:
            low, mean, high, static = (
                float(c[f"tension_{k}"]) for k in ("min", "mean", "max", "static")
            )
            if not low <= min(mean, static) <= max(mean, static) <= high:
                bad.append(f"case {at}: min {low} mean {mean} static {static} max {high}")
            if str(c["dynamic_method"].values) not in ("time", "frequency", "spring"):
                bad.append(f"case {at}: dynamic_method {c['dynamic_method'].values}")
            if float(c["steady_converged"]) not in (0.0, 1.0):
                bad.append(f"case {at}: steady_converged {float(c['steady_converged'])}")
    return bad


@pytest.mark.parametrize("key", sorted(STUDIES))
def test_dynamic_study_keeps_every_convention(tmp_path: Path, key: str) -> None:
    text = STUDIES[key]
    ds = run(tmp_path, text)
    assert np.all(ds["status"] == 0), ds["message"].values
    assert dynamic_conventions(ds, text) == []


def _run(tmp_path: Path, text: str) -> xr.Dataset:
    name = yaml.safe_load(text)["name"]
    return run(tmp_path / name, text)


def _amplitude(ds: xr.Dataset) -> np.ndarray:
    return 0.5 * (ds["tension_max"] - ds["tension_min"]).values


# ------------------------------------------------------------------ time against frequency


def test_time_and_frequency_domain_agree_where_the_physics_is_linear(tmp_path: Path) -> None:
    """The same linear line, damped by the (linear) transverse damping both methods
    share, drag off, 2 mm at three frequencies around its first modes: the dynamic
    tension range of the time domain is the frequency domain's. Measured 0.05, 0.06 and
    0.19 %; the time domain's error is its step's, O((2 pi / 64)^2 / 12) ~ 1e-3 of the
    response at 64 steps per period, and its geometric nonlinearity at 2 mm of 46 m;
    bound 0.5 %. Each method's static end tension is its own model's (both 80 elements,
    the frequency domain about the static solver's shape): they agree to the lumped-mass
    discretisation, 4.2e-5 here (bound 1e-4)."""
    td = _run(tmp_path, STUDIES["water-damped-time"])
    fd = _run(tmp_path, STUDIES["water-damped-frequency"])
    assert (td["dynamic_method"] == "time").all() and (fd["dynamic_method"] == "frequency").all()
    np.testing.assert_allclose(_amplitude(td), _amplitude(fd), rtol=5e-3)
    np.testing.assert_allclose(td["tension_static"], fd["tension_static"], rtol=1e-4)


def test_time_and_frequency_domain_agree_in_a_cross_current(tmp_path: Path) -> None:
    """A current across the line's plane, 0.5 m/s, drag linearised about it (the tangent
    2 c |U| where the motion is smaller than the current): the end tension range of the
    two methods at 2 and 10 mm agrees to 0.14 % (measured); bound 0.5 %."""
    td = _run(tmp_path, STUDIES["water-cross-current-time"])
    fd = _run(tmp_path, STUDIES["water-cross-current-frequency"])
    np.testing.assert_allclose(_amplitude(td), _amplitude(fd), rtol=5e-3)


def test_a_spectrum_gives_the_same_variance_in_both_methods(tmp_path: Path) -> None:
    """32 spectral lines of a flat displacement density: the frequency domain's
    end-tension standard deviation against that of the time domain's realisation over
    one repeat period (1 / df = 128 s), where the variance of a sum of sinusoids is
    exactly the sum of their halved squared amplitudes: measured 1.4559 N against
    1.4549 N (0.07 %); bound 1 % (the time step's error, as above, and the random
    phases' cross terms, which vanish over the whole period)."""
    td = _run(tmp_path, STUDIES["water-spectrum-time"])
    fd = _run(tmp_path, STUDIES["water-spectrum-frequency"])
    record = td["history_tension"].values[:-1]  # one whole period, the end sample left out
    assert td["history_time"].values[-1] - td["history_time"].values[0] == pytest.approx(128.0)
    assert float(np.std(record)) == pytest.approx(float(fd["tension_std_b"]), rel=1e-2)
    assert fd["tension_psd_b"].dims == ("frequency",)


# ------------------------------------------------------------------ invariances


@pytest.mark.parametrize("method", ["time", "frequency"])
def test_swapping_ends_a_and_b_mirrors_the_dynamics(tmp_path: Path, method: str) -> None:
    """The line and its excitation described from the other end: the excited end's
    tensions are the same (to round-off: the same equations in reverse node order,
    1e-9), end A's outputs are end B's, and the envelopes along s are reversed."""
    fwd = _run(tmp_path, STUDIES[f"air-{method}"])
    mir = _run(tmp_path, mirrored(STUDIES[f"air-{method}"], f"mirror-{method}"))
    for name in ("tension_max", "tension_min", "tension_mean", "tension_static"):
        assert float(mir[name]) == pytest.approx(float(fwd[name]), rel=1e-9)
    for name in ("tension_envelope_max", "tension_envelope_min"):
        np.testing.assert_allclose(mir[name].values, fwd[name].values[::-1], rtol=1e-9)
    if method == "frequency":
        assert float(mir["tension_amplitude_a"]) == pytest.approx(
            float(fwd["tension_amplitude_b"]), rel=1e-9
        )


@pytest.mark.parametrize("method", ["time", "frequency"])
def test_a_frame_turned_about_z_gives_the_same_tensions(tmp_path: Path, method: str) -> None:
    """Ends and excitation turned by 30 degrees about z: the tensions do not move (to
    round-off of the turned coordinates, 1e-9)."""
    ref = _run(tmp_path, STUDIES[f"air-{method}"])
    rot = _run(tmp_path, turned(STUDIES[f"air-{method}"], f"turned-{method}", 30.0))
    for name in ("tension_max", "tension_min", "tension_mean", "tension_static"):
        assert float(rot[name]) == pytest.approx(float(ref[name]), rel=1e-9)


@pytest.mark.parametrize("method", ["time", "frequency"])
def test_a_phase_of_180_degrees_is_the_reversed_direction(tmp_path: Path, method: str) -> None:
    """End A moved along d with phase 180 deg is end A moved along -d: the same case, so
    the same numbers to round-off, with bending (pinned) and a lumped body with drag."""
    a = _run(tmp_path, STUDIES[f"bent-pinned-{method}"])
    b = _run(
        tmp_path,
        bent(
            f"bent-reversed-{method}",
            method,
            "pinned",
            "{end: a, direction: [-1.0, 0.0, -0.2], amplitude: 0.005, frequency: 0.2}",
        ),
    )
    for name in ("tension_max", "tension_min", "tension_mean"):
        np.testing.assert_allclose(a[name].values, b[name].values, rtol=1e-9)


def test_a_periodic_table_of_a_sine_is_the_harmonic(tmp_path: Path) -> None:
    """A periodic table sampling the harmonic 64 times a period, interpolated by a cubic
    spline (error ~ (2 pi / 64)^4 / 384 = 2.4e-7 of the amplitude), runs the harmonic's
    case: the tensions agree to 1e-6 of the dynamic range (measured 2e-7)."""
    table = _run(tmp_path, STUDIES["air-table"])
    harmonic = _run(tmp_path, STUDIES["air-time"])
    scale = float(harmonic["tension_max"] - harmonic["tension_min"])
    for name in ("tension_max", "tension_min", "tension_mean"):
        assert abs(float(table[name]) - float(harmonic[name])) < 1e-6 * scale


def test_bending_with_a_body_agrees_between_the_methods(tmp_path: Path) -> None:
    """EI, pinned ends, a body with mass, volume, added mass and drag area: 5 mm at end
    A, 0.05 and 0.3 Hz: the tension ranges agree to 0.05 and 0.17 % (measured; bound
    0.5 %, as the damped line above)."""
    td = _run(tmp_path, STUDIES["bent-pinned-time"])
    fd = _run(tmp_path, STUDIES["bent-pinned-frequency"])
    np.testing.assert_allclose(_amplitude(td), _amplitude(fd), rtol=5e-3)


# ------------------------------------------------------------------ outputs on request


def test_histories_follow_the_prescribed_motion(tmp_path: Path) -> None:
    """The kept record: end B moves by the amplitude along the unit direction (the
    direction [1, 0, 0.5] normalised), end A not at all, and the whole line's tension
    at end B spans the steady window's max and min (the record samples 16 times a period
    of the 64 steps: its extremes lie within the sampled sine's 1 - cos(pi/16) = 2 % of
    the range inside them)."""
    ds = _run(tmp_path, STUDIES["air-history"])
    d = ds["history_displacement"]
    assert d.dims == ("point", "time", "component")
    np.testing.assert_allclose(ds["history_point_s"], [0.0, 10.1, 20.2])
    unit = np.array([1.0, 0.0, 0.5]) / math.hypot(1.0, 0.5)
    t = ds["history_time"].values
    expected = 0.002 * np.sin(2 * math.pi * 0.3 * t)[:, None] * unit
    np.testing.assert_allclose(d.isel(point=-1).values, expected, atol=1e-12)
    assert np.all(d.isel(point=0).values == 0.0)
    end = ds["history_line_tension"].isel(s=-1).values
    high, low = float(ds["tension_max"]), float(ds["tension_min"])
    assert low - 1e-9 <= end.min() and end.max() <= high + 1e-9
    assert end.max() - end.min() > 0.98 * (high - low)
    # a record longer than the shortest run to steady state (ramp 2 + 3 periods): the
    # run lasts long enough to keep it after the ramp (it began 10 s before t = 0, where
    # it held the state at rest, with status 0)
    long = _run(
        tmp_path,
        air(
            "air-long-history",
            "time",
            extra="    history: {points: [20.2], periods: 8, samples_per_period: 8}\n",
        ),
    )
    ramp_end = 2.0 / 0.3
    assert float(long["history_time"][0]) >= ramp_end - 1e-9
    assert float(long["periods"]) >= 2.0 + 8.0 - 1e-9


def test_the_transfer_function_is_the_tension_per_metre_of_motion(tmp_path: Path) -> None:
    """At the excitation's own frequency the transfer function times the amplitude is
    the tension amplitude (the same linear solve): with the direction [1, 0, 0.5] it
    gave 1.118 times too much (divided by the largest component of the motion, 0.894 of
    the amplitude). In air the line is linear, so an amplitude of 0 (the small-motion
    limit, once RAOs of 0 with status 0) gives the same transfer function."""
    ds = _run(tmp_path, STUDIES["air-auto-transfer"])
    assert str(ds["dynamic_method"].values) == "frequency"
    rao = ds["tension_rao_b"].sel(frequency=0.3)
    assert ds["tension_rao_b"].dims == ("frequency",)
    assert float(rao) * 0.002 == pytest.approx(float(ds["tension_amplitude_b"]), rel=1e-9)
    zero = air(
        "air-transfer-zero",
        "frequency",
        excitation="{end: b, direction: [1.0, 0.0, 0.5], amplitude: 0.0, frequency: 0.3}",
        extra="    transfer_function: {start: 0.1, stop: 0.5, num: 5}\n",
    )
    small = _run(tmp_path, zero)
    assert np.all(small["status"] == 0)
    # air's drag on 1 cm at 2 mm of motion changes the tensions by < 1e-6 of them
    np.testing.assert_allclose(small["tension_rao_b"], ds["tension_rao_b"], rtol=1e-5)


def test_sweeps_of_direction_end_elements_steps_and_duration(tmp_path: Path) -> None:
    """A labelled direction axis and an end axis (sway of a line in the x-z plane moves
    no tension at first order: amplitude 0 in the frequency domain); elements converge at
    second order towards the static solver's end tension (differences 0.37, 0.093 N:
    ratio 4 for twice the elements, bound 3.5..4.5); 32 instead of 64 steps a period
    lowers the range by 0.8 % (generalised-alpha is second order: the 64-step error is
    then a quarter of the 32-step one, 0.27 %, as the frequency domain's 1.2253 N
    against 1.2131 and 1.2229 N shows; bound 1.5 %); a fixed duration runs its periods
    (3 and 6 at 0.3 Hz)."""
    ds = _run(tmp_path, STUDIES["air-direction-end"])
    assert list(ds["motion"].values) == ["surge", "sway", "heave"]
    assert list(ds["end"].values) == ["a", "b"]
    assert np.all(
        ds["tension_amplitude_b"].sel(motion="sway").values == pytest.approx(0.0, abs=1e-9)
    )
    assert np.all(ds["tension_amplitude_b"].sel(motion="surge").values > 1.0)
    el = _run(tmp_path, STUDIES["air-elements-steps"])
    static = el["tension_static"].isel(points_per_period=0).values
    exact = float(el["tension_b"].isel(elements=0, points_per_period=0))
    ratio = (exact - static[1]) / (exact - static[2])
    assert 3.5 < ratio < 4.5 and abs(exact - static[2]) < 1e-4 * exact
    rng = _amplitude(el)
    np.testing.assert_allclose(rng[:, 0], rng[:, 1], rtol=1.5e-2)
    assert np.all(rng[:, 0] < rng[:, 1])
    dur = _run(tmp_path, STUDIES["air-duration"])
    np.testing.assert_array_equal(dur["periods"].values, [3.0, 6.0])
    assert dur["history_time"].values[:, -1] == pytest.approx([10.0, 20.0])


# ------------------------------------------------------------------ against statics


def test_slow_motion_of_a_laid_line_follows_the_static_offset_curve(tmp_path: Path) -> None:
    """The fairlead of a line lying on the seabed moved slowly: the frequency domain at
    5 cm and 0.002 Hz gives dT = dT/dx * amplitude of the static solver's offset curve
    (central difference over the same 5 cm) to 0.6 % (the laid line's known -0.66 %
    at 40 elements, docs/frequency-domain.md; bound 1.5 %); the time domain at 1 m and
    120 elements gives the static tensions of the end at +-1 m to 0.04 % (bound 0.2 %:
    the touchdown, moving 2 m, is resolved by 1.25 m elements)."""
    offsets = laid(
        "laid-offsets", extra="sweep:\n  ends.b.position.0: [119.0, 119.95, 120.0, 120.05, 121.0]\n"
    )
    curve = _run(tmp_path, offsets)["tension_b"].values
    slope = (curve[3] - curve[1]) / 2.0
    fd = _run(tmp_path, STUDIES["laid-slow-frequency"])
    assert float(fd["tension_amplitude_b"]) == pytest.approx(slope, rel=1.5e-2)
    td = _run(tmp_path, STUDIES["laid-slow-time"])
    assert float(td["tension_max"]) == pytest.approx(curve[4], rel=2e-3)
    assert float(td["tension_min"]) == pytest.approx(curve[0], rel=2e-3)
    assert 0.0 < float(td["touchdown_min"]) < float(td["touchdown_max"]) < 150.0


def test_seabed_friction_and_auto_keep_the_laid_line_consistent(tmp_path: Path) -> None:
    """Method auto on a laid line, with and without friction, at 5 cm (the frequency
    domain trusted) and 2 m (near slack: the time domain): each case records which
    method ran and why, and both give the touchdown point's range of travel about the
    static laid length (within an element, 2.5 m): the frequency domain's was missing
    (NaN with status 0 where the line touches the seabed; now the static touchdown point
    +- the catenary estimate of its travel that auto checks). Small motion: the two
    ranges' widths agree within a factor 2 (0.12 and 0.18 m measured: the estimate
    against the time domain's compliant, node-by-node seabed)."""
    ds = _run(tmp_path, STUDIES["laid-friction-auto"])
    methods = {str(m) for m in ds["dynamic_method"].values.ravel()}
    assert methods == {"time", "frequency"}, methods
    for at in np.ndindex(ds["status"].shape):
        c = ds.isel(amplitude=at[0], friction=at[1])
        assert str(c["dynamic_method_reason"].values).startswith("auto")
        laid_length = float(c["laid_length"])
        low, high = float(c["touchdown_min"]), float(c["touchdown_max"])
        assert low - 2.5 < laid_length < high + 2.5, (at, low, laid_length, high)
        assert float(c["tension_min"]) < float(c["tension_b"]) < float(c["tension_max"])
    fd = ds.sel(amplitude=0.05, friction=0.0)
    assert str(fd["dynamic_method"].values) == "frequency"
    td = _run(tmp_path, laid("laid-small-time", LAID_SURGE % "time"))
    # seen from the other end the touchdown point is at L - s
    fwd = _run(tmp_path, laid("laid-small-frequency", LAID_SURGE % "frequency"))
    mir = _run(tmp_path, mirrored(laid("x", LAID_SURGE % "frequency"), "laid-mirrored"))
    assert float(mir["touchdown_min"]) == pytest.approx(150.0 - float(fwd["touchdown_max"]))
    assert float(mir["touchdown_max"]) == pytest.approx(150.0 - float(fwd["touchdown_min"]))
    width_fd = float(fd["touchdown_max"] - fd["touchdown_min"])
    width_td = float(td["touchdown_max"] - td["touchdown_min"])
    assert 0.5 < width_fd / width_td < 2.0


def test_modes_of_a_string_in_water_carry_the_added_mass(tmp_path: Path) -> None:
    """A taut 10.1 m string (sag/span 1.5e-3): the out-of-plane modes f_n = n / (2 L)
    sqrt(T / mu) with mu the mass per stretched length, plus rho pi d^2 / 4 per
    unstretched length with added mass; the lumped-mass error is (n pi h / L)^2 / 24
    < 5e-5 at 200 elements (n <= 3); bound 1e-4."""
    ds = _run(tmp_path, STUDIES["modal-string-water"])
    tension = float(ds["tension"].isel(include_added_mass=0, s=25))
    strain, span = tension / 1.0e6, 10.1
    added = 1025.0 * math.pi * 0.05**2 / 4.0
    n = np.arange(1, 4)
    for flag, extra in ((True, added), (False, 0.0)):
        mu = (3.0 + extra) / (1.0 + strain)
        theory = n / (2 * span) * math.sqrt(tension / mu)
        f = ds["natural_frequency"].sel(include_added_mass=flag).values
        # each string mode comes as a pair (in and out of the plane); the out-of-plane
        # one is the pure string's
        out_of_plane = [f[np.argmin(np.abs(f - ft))] for ft in theory]
        np.testing.assert_allclose(out_of_plane, theory, rtol=1e-4)


def test_a_spring_line_follows_its_law_along_the_motion(tmp_path: Path) -> None:
    """A linear spring of 1000 N/m stretched 0.5 m, end B moved 0.1 m: along the line
    500 +- 100 N; across it 500 N to 1000 (sqrt(10.5^2 + 0.1^2) - 10) N; the motion
    reversed gives the same range."""
    ds = _run(tmp_path, STUDIES["spring-linear"])
    np.testing.assert_allclose(
        ds["tension_max"].values, [600.0, 1000 * (math.hypot(10.5, 0.1) - 10), 600.0], rtol=1e-9
    )
    np.testing.assert_allclose(ds["tension_min"].values, [400.0, 500.0, 400.0], rtol=1e-9)
    assert np.all(ds["dynamic_method"] == "spring")


def test_the_database_holds_the_static_solutions_of_its_grid(tmp_path: Path) -> None:
    """The study's own end B lies on a grid point (120 m away at 40 deg, 45 m above A):
    the database's values there are the static run's, to the solver's 1e-9, in the
    plane turned to 40 degrees."""
    ds = _run(tmp_path, STUDIES["database-turned"])
    p = ds.sel(horizontal_distance=120.0, height_difference=45.0)
    assert float(ds["database_heading"]) == pytest.approx(math.radians(40.0), rel=1e-9)
    for name in ("tension_a", "tension_b", "laid_length"):
        assert float(p[f"database_{name}"]) == pytest.approx(float(ds[name]), rel=1e-9)
    np.testing.assert_allclose(p["database_force_b"], ds["force_b"], rtol=1e-9, atol=1e-6)
    # the radial grid (a line off the seabed): end B 20 m from A at 30 degrees above it,
    # in the plane turned to +y; the angle written in rad (conventions: output angles)
    radial = _run(tmp_path, STUDIES["database-radial"])
    assert radial["angle"].attrs["units"] == "rad"
    q = radial.sel(distance=20.0).isel(angle=-1)
    assert float(q["angle"]) == pytest.approx(math.radians(30.0), rel=1e-12)
    assert float(radial["database_heading"]) == pytest.approx(math.pi / 2, rel=1e-12)
    for name in ("tension_a", "tension_b"):
        assert float(q[f"database_radial_{name}"]) == pytest.approx(float(radial[name]), rel=1e-9)
    np.testing.assert_allclose(q["database_radial_force_b"], radial["force_b"], atol=1e-7)


# ------------------------------------------------------------------ bad input


#: (name, study text, what the refusal must say): each a key a run would ignore, or a
#: value no analysis can take; refused by ``cablestudy validate`` before any work
BAD: list[tuple[str, str, list[str]]] = [
    (
        "duration-with-steady-keys",
        air(
            "x",
            "time",
            extra="    duration: 50.0\n    steady_tolerance: 0.01\n    max_periods: 10\n",
        ),
        ["steady_tolerance, max_periods", "duration 50 s", "got steady_tolerance 0.01", "allowed"],
    ),
    (
        "storm-duration-in-the-time-domain",
        water(
            "x",
            "time",
            excitation="{end: b, direction: [1, 0, 0], spectrum: [[0.1, 0.01], [0.2, 0.01]],"
            " storm_duration: 3600.0}",
        ),
        ["storm_duration", "method 'time'", "got 3600.0", "allowed: method 'frequency' or 'auto'"],
    ),
    (
        "seed-in-the-frequency-domain",
        water(
            "x",
            "frequency",
            excitation="{end: b, direction: [1, 0, 0], spectrum: [[0.1, 0.01], [0.2, 0.01]],"
            " seed: 3}",
        ),
        ["excitation.seed", "method 'frequency'", "got 3", "allowed: method 'time'"],
    ),
    (
        "spring-with-line-model-keys",
        STUDIES["spring-linear"].replace(
            "frequency: 0.5}\n", "frequency: 0.5}\n    elements: 40\n    spectral_radius: 0.5\n"
        ),
        ["analysis.dynamic.elements", "kind: spring", "got 40", "analysis.dynamic.spectral_radius"],
    ),
    (
        "zero-direction",
        air(
            "x", "time", excitation="{end: b, direction: [0, 0, 0], amplitude: 0.1, frequency: 0.3}"
        ),
        ["excitation.direction", "nonzero", "got [0, 0, 0]"],
    ),
    (
        "frequency-and-period",
        air(
            "x",
            "time",
            excitation="{end: b, direction: [1, 0, 0], amplitude: 0.1, frequency: 0.3,"
            " period: 2.0}",
        ),
        ["excitation.period", "not both", "got 2.0"],
    ),
    (
        "time-steps-in-the-frequency-domain",
        air("x", "frequency", extra="    points_per_period: 32\n"),
        ["points_per_period", "method 'frequency'", "allowed: method 'time' or 'auto'"],
    ),
    (
        "transfer-function-in-the-time-domain",
        air("x", "time", extra="    transfer_function: {start: 0.1, stop: 0.3, num: 3}\n"),
        ["transfer_function", "method 'time'", "allowed: method 'frequency' or 'auto'"],
    ),
    (
        "a-time-table-in-the-frequency-domain",
        air(
            "x",
            "frequency",
            excitation="{end: b, direction: [1, 0, 0],"
            " table: [[0, 0], [1, 0.1], [2, 0.1], [3, 0.1]]}",
        ),
        ["method 'frequency' needs harmonic excitation or a spectrum", "allowed"],
    ),
    (
        "history-longer-than-the-run",
        air(
            "x",
            "time",
            extra="    duration: 5.0\n    history: {points: [20.2], periods: 4}\n",
        ),
        ["history.periods", "longer than the run, duration 5 s", "got 4", "allowed"],
    ),
    (
        "history-beyond-the-line",
        air("x", "time", extra="    history: {points: [25.0]}\n"),
        ["history.points.0", "25.0", "allowed 0 <= s <= 20.2"],
    ),
    (
        "transfer-function-against-a-frequency-sweep",
        air(
            "x",
            "frequency",
            extra="    transfer_function: {start: 0.1, stop: 0.3, num: 3}\n"
            "sweep:\n  analysis.dynamic.excitation.frequency: [0.1, 0.2]\n",
        ),
        ["transfer_function", "'frequency'", "name the sweep axis otherwise"],
    ),
]


@pytest.mark.parametrize(("key", "text", "says"), BAD, ids=[b[0] for b in BAD])
def test_bad_dynamic_input_is_refused_before_any_work(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], key: str, text: str, says: list[str]
) -> None:
    path = tmp_path / f"{key}.yaml"
    path.write_text(text)
    assert main(["validate", str(path)]) == 2
    err = capsys.readouterr().err
    for fragment in says:
        assert fragment in err, err


# ------------------------------------------------------------------ known, reported defects


def test_a_steady_time_domain_answer_has_settled_extremes(tmp_path: Path) -> None:
    """A taut line in still water with drag only (no structural damping), 1 cm at 0.2 Hz
    between its first two modes: the start's free vibration decays slowly, so a run
    called steady must show per-period maxima and minima that no longer move relative to
    the tension range (2 N on 1512 N), and then it agrees with the frequency domain.

    The steady test allows each extreme to move by ``steady_tolerance`` (0.002) of the
    range per period, so the spreads, over ``steady_window`` + 1 = 3 periods, are at most
    twice that (judged against the tension instead, they moved 4.5 % of the range and the
    answer was 3.6 % off). The leftover free vibration moves each extreme by about its
    own amplitude from one period to the next (its phase turns), so each extreme is
    within about 0.002 of the range of its settled value and the range within 2 x 0.002.
    Against the frequency domain at 256 steps per period: that 0.4 % plus the step's
    error, 0.85 % of the range at 64 steps per period (the settled time domain at 64
    against 256 steps: the drag-only resonance is sensitive to the integrator's period
    error), scaled by (64 / 256)^2 to 0.05 %: bound 0.45 %. Measured: 0.16 % (at 64
    steps 0.95 %: 0.85 % step, 0.1 % leftover; the frequency domain agrees with the
    settled time domain at 256 steps to 0.02 %)."""
    tol = 0.002  # analysis.dynamic.steady_tolerance's default, which the studies use
    exc = "{end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.01, frequency: 0.2}"
    ds = _run(tmp_path, water("still-drag-time", "time", damping=0.0, excitation=exc))
    fine = _run(
        tmp_path,
        water(
            "still-drag-fine",
            "time",
            damping=0.0,
            excitation=exc,
            extra="    points_per_period: 256\n",
        ),
    )
    fd = _run(tmp_path, water("still-drag-frequency", "frequency", damping=0.0, excitation=exc))
    for td in (ds, fine):
        assert float(td["steady_converged"]) == 1.0
        span = float(td["tension_max"] - td["tension_min"])
        spread = max(float(td["tension_max_spread"]), float(td["tension_min_spread"]))
        assert spread <= 2 * tol * span
    np.testing.assert_allclose(_amplitude(fine), _amplitude(fd), rtol=2 * tol + 0.85e-2 / 16)


def test_clamped_ends_start_the_time_domain_from_the_static_tension(tmp_path: Path) -> None:
    """Clamped ends, EI 500 N m^2, static method discrete on the dynamic model's own 80
    elements: the time domain's static end tension is the statics' (as with pinned ends,
    where they agree to 1e-9) and the frequency domain's. A clamp holds the end's static
    direction, that of the static solution's end element, which is moment-free there:
    the statics is the pinned one, and the time domain, clamped to the same direction,
    starts at rest in it (its Newton stops within 1e-9 of the tension, below the 1e-6
    asked). Clamped to the cable solution's chord instead, the end tensions differed by
    0.24 N (2e-4) and the gap did not shrink with refinement."""
    exc = "{end: a, direction: [1.0, 0.0, 0.2], amplitude: 0.005, frequency: 0.2}"
    td = _run(tmp_path, bent("clamped-time", "time", "clamped", exc))
    fd = _run(tmp_path, bent("clamped-frequency", "frequency", "clamped", exc))
    np.testing.assert_allclose(fd["tension_static"], td["tension_a"], rtol=1e-9)
    np.testing.assert_allclose(td["tension_static"], td["tension_a"], rtol=1e-6)
    # the clamp acts in the dynamics only: the static line is the pinned one (to the
    # Newton tolerance of the statics, 1e-9 of the tension); the tension ranges are not
    # (measured 2.7 and 1.0 % larger clamped, at 0.05 and 0.3 Hz), and both methods
    # hold the same clamp (they agree to 0.02 and 0.18 %; bound 0.5 % as pinned, above)
    pinned = _run(tmp_path, STUDIES["bent-pinned-time"])
    np.testing.assert_allclose(td["tension_a"], pinned["tension_a"], rtol=1e-9)
    assert np.all(np.abs(_amplitude(td) / _amplitude(pinned) - 1.0) > 5e-3)
    np.testing.assert_allclose(_amplitude(td), _amplitude(fd), rtol=5e-3)
