"""method: frequency end to end (YAML to netCDF) and its validation messages."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import StudyError, parse_study_text

STUDY = """
name: freq
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
  analysis.dynamic.excitation.frequency: [0.3, 0.7]
"""


def _run(tmp_path: Path, text: str, name: str = "freq") -> xr.Dataset:
    text = text.replace("name: freq", f"name: {name}")
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    args = ["run", str(cfg), "--out", str(tmp_path), "--scheduler", "synchronous", "--no-cache"]
    assert main(args) == 0
    return xr.load_dataset(tmp_path / f"{name}.nc")


def test_frequency_study_runs_to_netcdf(tmp_path: Path) -> None:
    ds = _run(tmp_path, STUDY)
    assert np.all(ds["status"] == 0)
    assert np.all(ds["dynamic_method"] == "frequency")
    assert np.all(ds["dynamic_method_reason"] == "method: frequency")
    for name in ("tension_max", "tension_min", "tension_mean", "tension_amplitude_a"):
        assert ds[name].dims == ("amplitude", "frequency") and ds[name].attrs["units"] == "N"
    assert ds["tension_phase_b"].attrs["units"] == "deg"
    assert ds["tension_envelope_max"].dims == ("amplitude", "frequency", "s")
    t0, tmax, tmin = (ds[k].values for k in ("tension_static", "tension_max", "tension_min"))
    # linear: the swing is symmetric about the static tension, the mean is static
    np.testing.assert_allclose(tmax - t0, t0 - tmin, rtol=1e-12)
    np.testing.assert_allclose(ds["tension_mean"].values, t0, rtol=1e-12)
    # no drag (vacuum): the response is exactly proportional to the amplitude
    amp = ds["tension_amplitude_b"].values
    np.testing.assert_allclose(amp[1], 2.0 * amp[0], rtol=1e-10)
    np.testing.assert_allclose(ds["tension_phase_b"][1], ds["tension_phase_b"][0], atol=1e-8)
    # the static tension at B is the static result's; the envelope ends at the end values
    np.testing.assert_allclose(t0, ds["tension_b"].values, rtol=1e-12)
    np.testing.assert_allclose(ds["tension_envelope_max"].isel(s=-1), tmax, rtol=1e-12)
    np.testing.assert_allclose(ds["tension_envelope_min"].isel(s=-1), tmin, rtol=1e-12)
    env = ds["tension_envelope_max"] - ds["tension"]
    assert float(env.min()) >= 0.0
    assert np.all(ds["tension_max_line"] >= ds["tension_envelope_max"].max("s") - 1e-9)


@pytest.mark.parametrize(
    ("old", "new", "words"),
    [
        (
            "    elements: 40",
            "    elements: 40\n    points_per_period: 32",
            "points_per_period: used by the time domain only",
        ),
        (
            "excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.05, frequency: 0.5}",
            "excitation: {end: b, direction: [1.0, 0.0, 0.0], "
            "table: [[0, 0], [1, 1], [2, -1], [3, 0]], periodic: true}",
            "method 'frequency' needs harmonic excitation",
        ),
        (
            "excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.05, frequency: 0.5}",
            "excitation: [{end: b, direction: [1, 0, 0], amplitude: 0.05, frequency: 0.5}, "
            "{end: a, direction: [1, 0, 0], amplitude: 0.05, frequency: 0.6}]",
            "one excitation frequency per case",
        ),
        (
            "    method: frequency",
            "    method: time\n    linearisation: {tolerance: 1.0e-5}",
            "linearisation: used by methods 'frequency' and 'auto'",
        ),
        (
            "    method: frequency",
            "    method: frequency\n    auto: {min_tension_ratio: 0.5}",
            "auto: thresholds of method 'auto'",
        ),
        (  # the phases of the harmonic fit mean nothing to a spectrum's statistical one
            "excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.05, frequency: 0.5}\n"
            "    method: frequency",
            "excitation: {end: b, direction: [1.0, 0.0, 0.0], components: 16, "
            "spectrum: [[0.2, 1.0e-4], [0.8, 1.0e-4]]}\n    method: frequency\n"
            "    linearisation: {samples: 64}",
            "linearisation.samples: 64 sets the phases of the harmonic drag fit",
        ),
    ],
)
def test_keys_another_method_needs_are_refused(old: str, new: str, words: str) -> None:
    text = STUDY.replace(old, new)
    assert text != STUDY
    with pytest.raises(StudyError) as info:
        expand_cases(parse_study_text(text))
    msg = str(info.value)
    assert "analysis.dynamic" in msg and words in msg, msg


TRANSFER = STUDY.replace(
    "    elements: 40\n",
    "    elements: 40\n    transfer_function: {start: 0.1, stop: 1.0, num: 10}\n",
).replace("  analysis.dynamic.excitation.frequency: [0.3, 0.7]\n", "")


def test_transfer_function_on_a_frequency_dimension(tmp_path: Path) -> None:
    ds = _run(tmp_path, TRANSFER, "transfer")
    assert np.all(ds["status"] == 0)
    assert ds["tension_rao_b"].dims == ("amplitude", "frequency")
    assert ds["tension_rao_line"].dims == ("amplitude", "frequency", "s")
    assert ds["frequency"].attrs["units"] == "Hz" and ds["tension_rao_b"].attrs["units"] == "N/m"
    np.testing.assert_allclose(ds["frequency"], np.linspace(0.1, 1.0, 10), rtol=1e-14)
    # at the excitation frequency (0.5 Hz) the transfer function is the case's own
    # amplitude per unit excitation amplitude, at both ends, with the same phase
    at = ds.sel(frequency=0.5)
    for end in ("a", "b"):
        np.testing.assert_allclose(
            at[f"tension_rao_{end}"], ds[f"tension_amplitude_{end}"] / ds["amplitude"], rtol=1e-10
        )
        np.testing.assert_allclose(at[f"tension_rao_phase_{end}"], ds[f"tension_phase_{end}"])
    # no drag: the same transfer function for every amplitude; along the line it ends
    # at the end values
    np.testing.assert_allclose(ds["tension_rao_b"][0], ds["tension_rao_b"][1], rtol=1e-10)
    np.testing.assert_allclose(ds["tension_rao_line"].isel(s=-1), ds["tension_rao_b"], rtol=1e-12)
    np.testing.assert_allclose(ds["tension_rao_line"].isel(s=0), ds["tension_rao_a"], rtol=1e-12)


def test_transfer_function_refuses_a_frequency_sweep_axis() -> None:
    from cablestudy.analyses.evaluate import check_supported

    text = STUDY.replace(
        "    elements: 40\n", "    elements: 40\n    transfer_function: {start: 0.1, stop: 1.0}\n"
    )
    src = parse_study_text(text)
    _, cases = expand_cases(src)
    with pytest.raises(StudyError) as info:
        check_supported(cases, src)
    assert "analysis.dynamic.transfer_function: writes its own 'frequency' dimension" in str(
        info.value
    )


MOORING = """
name: moor
environment: {fluid: water, depth: 100.0, seabed: {friction: 0.5}}
line:
  segments:
    - {length: 300.0, diameter: 0.1, weight_in_fluid: 500.0, axial_stiffness: 5.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -100.0]}
  b: {kind: fixed, position: [240.0, 0.0, 0.0]}
analysis:
  static: {method: catenary, nodes: 101, tolerance: 1.0e-9}
  dynamic:
    excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.2, frequency: 0.1}
    method: frequency
"""


def test_laid_line_sticks_on_a_frictional_seabed(tmp_path: Path) -> None:
    """Seabed friction is linearised as sticking: each laid node is held by its stick
    spring (stiffness per length k_t, the contact stiffness: the line's submerged weight
    over 1 mm), so the motion dies out into the laid stretch like exp(-d / lambda) with
    lambda = sqrt(EA / k_t) (a bar on an elastic foundation): 31.6 m here. Three lambdas
    from touchdown the tension amplitude is below 5 % of its largest value, and nothing
    reaches the anchor."""
    ds = _run(tmp_path, MOORING, "moor")
    assert int(ds["status"]) == 0, str(ds["message"].values)
    laid = float(ds["laid_length"])
    assert laid > 100.0
    assert float(ds["tension_amplitude_b"]) > 0.0
    assert float(ds["tension_amplitude_a"]) == 0.0
    decay = math.sqrt(5.0e8 / (500.0 / 1e-3))
    amp = (ds["tension_envelope_max"] - ds["tension"]).values
    deep = ds["s"].values < laid - 3.0 * decay
    assert deep.any()
    assert np.all(amp[deep] <= 0.05 * amp.max())
    assert amp[ds["s"].values > laid].min() > 0.1 * amp.max()  # the suspended part moves


def test_auto_with_histories_runs_time_and_still_writes_the_transfer_function(
    tmp_path: Path,
) -> None:
    text = (
        STUDY.replace("method: frequency", "method: auto")
        .replace(
            "    elements: 40\n",
            "    elements: 20\n    history: {points: [5.0]}\n"
            "    transfer_function: {start: 0.1, stop: 1.0, num: 4}\n",
        )
        .replace("  analysis.dynamic.excitation.frequency: [0.3, 0.7]\n", "")
    )
    ds = _run(tmp_path, text, "autohist")
    assert np.all(ds["status"] == 0)
    assert np.all(ds["dynamic_method"] == "time")
    assert np.all(ds["dynamic_method_reason"] == "auto: time histories asked for")
    assert "history_tension" in ds and ds["tension_rao_b"].dims == ("amplitude", "frequency")
    assert np.all(np.isfinite(ds["tension_rao_b"]))


def test_spectrum_study_runs_to_netcdf(tmp_path: Path) -> None:
    text = STUDY.replace(
        "excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.05, frequency: 0.5}",
        "excitation: {end: b, direction: [1.0, 0.0, 0.0], components: 16, "
        "spectrum: [[0.2, 1.0e-4], [0.8, 1.0e-4]]}",
    ).replace(
        "sweep:\n  analysis.dynamic.excitation.amplitude: [0.01, 0.02]\n"
        "  analysis.dynamic.excitation.frequency: [0.3, 0.7]\n",
        "sweep:\n  analysis.dynamic.excitation.storm_duration: [3600.0, 10800.0]\n",
    )
    ds = _run(tmp_path, text, "spectrum")
    assert np.all(ds["status"] == 0)
    assert ds["tension_psd_b"].dims == ("storm_duration", "frequency")
    assert ds["frequency"].attrs["units"] == "Hz" and ds["tension_psd_b"].attrs["units"] == "N^2/Hz"
    np.testing.assert_allclose(ds["frequency"], 0.05 * np.arange(1, 17), rtol=1e-12)
    # linear (vacuum): the standard deviation does not depend on the storm duration, the
    # most probable maximum grows with it as sqrt(2 ln N)
    np.testing.assert_allclose(ds["tension_std_b"][0], ds["tension_std_b"][1], rtol=1e-12)
    rise = (ds["tension_max"] - ds["tension_static"]) / ds["tension_std_b"]
    np.testing.assert_allclose(rise[1] ** 2 - rise[0] ** 2, 2.0 * np.log(3.0), rtol=1e-10)


def test_spectrum_and_harmonics_together_are_refused_by_frequency() -> None:
    text = STUDY.replace(
        "excitation: {end: b, direction: [1.0, 0.0, 0.0], amplitude: 0.05, frequency: 0.5}",
        "excitation: [{end: b, direction: [1, 0, 0], amplitude: 0.05, frequency: 0.5}, "
        "{end: a, direction: [1, 0, 0], spectrum: [[0.2, 1.0e-4], [0.8, 1.0e-4]]}]",
    )
    with pytest.raises(StudyError) as info:
        expand_cases(parse_study_text(text))
    assert "one spectrum alone" in str(info.value)


def test_jonswap_times_rao_spectrum() -> None:
    from cablestudy.study.analysis import SpectrumExcitation

    ex = SpectrumExcitation(
        end="b",
        direction=[1.0, 0.0, 0.0],
        wave_spectrum={"hs": 2.0, "tp": 8.0, "gamma": 3.3},
        rao=[[0.0, 1.0], [2.0, 1.0]],
        components=2000,
    )
    # unit RAO: the motion variance is the wave variance, (Hs / 4)^2 (DNV's JONSWAP
    # normalisation A_gamma = 1 - 0.287 ln gamma holds the integral to about 1 %)
    var = 0.5 * sum(a * a for a in ex.line_amplitudes)
    np.testing.assert_allclose(var, (2.0 / 4.0) ** 2, rtol=0.02)
    with pytest.raises(ValueError, match="either spectrum"):
        SpectrumExcitation(
            end="b",
            direction=[1.0, 0.0, 0.0],
            spectrum=[[0.1, 1.0], [0.5, 1.0]],
            rao=[[0.0, 1.0], [2.0, 1.0]],
        )


def test_an_unbounded_touchdown_travel_is_said_in_words_not_as_inf() -> None:
    """A touchdown point with no submerged weight to hold it has no travel bound: method
    auto distrusts the frequency domain there and says why without a non-physical number
    (issue 21: every number in a reason is a physical value)."""
    import math

    from cablestudy.analyses.frequency import _judged
    from cablestudy.dynamics.validity import Validity
    from cablestudy.study.analysis import DynamicSettings

    dyn = DynamicSettings.model_validate(
        {"excitation": {"end": "b", "direction": [1, 0, 0], "amplitude": 0.1, "frequency": 0.1}}
    )
    v = Validity(min_tension_ratio=0.9, amplitude_sag_ratio=0.01, touchdown_travel=math.inf)
    out = _judged({}, v, dyn, True, 3, 0.0)
    assert out.distrust == "touchdown travel unbounded: no submerged weight at the touchdown point"
    assert "inf" not in out.distrust
