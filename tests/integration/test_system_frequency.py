"""Mooring systems in the frequency domain (issue 24), from the study file to the
dataset: ``method: frequency`` on MoorPy's case8 (spar, three polyester legs with
bridles and free junctions) moved in surge, through the command line.

Checks: the contract's names and dimensions; the outputs are the pure module's
(:mod:`cablestudy.dynamics.system_frequency`) for the same system, bit for bit; the
linear extremes are the static tension plus and minus the amplitude; mirror legs
(1 and 3) respond alike; a sweep of the amplitude shares the statics and the model;
and what the system frequency domain does not solve is refused naming the field."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses.counters import COUNTERS
from cablestudy.cli import main
from cablestudy.study.loader import StudyError, parse_study_text

CONFIG = Path(__file__).parents[2] / "configs" / "system-case8-surge.yaml"


def _text(dynamic: str) -> str:
    text = CONFIG.read_text()
    head = text[: text.index("  dynamic:")]
    return head + dynamic


FREQUENCY = """\
  dynamic:
    excitation: {body: body1, dof: surge, amplitude: 2.0, frequency: 0.1}
    method: frequency
    elements: 20  # per line
sweep:
  analysis.dynamic.excitation.amplitude: [1.0, 2.0]
"""


@pytest.fixture(scope="module")
def case8(tmp_path_factory: pytest.TempPathFactory) -> xr.Dataset:
    tmp = tmp_path_factory.mktemp("case8f")
    cfg = tmp / "case8.yaml"
    cfg.write_text(_text(FREQUENCY))
    args = ["run", str(cfg), "--out", str(tmp), "--no-cache", "--no-progress"]
    before = COUNTERS["system_assemblies"]
    assert main([*args, "--scheduler", "synchronous"]) == 0
    # one linear model for the two amplitudes (one static problem)
    assert COUNTERS["system_assemblies"] - before == 1
    return xr.load_dataset(tmp / "system-case8-surge.nc")


def test_case8_frequency_domain_end_to_end(case8: xr.Dataset) -> None:
    ds = case8
    assert np.all(ds.status.values == 0), ds.message.values
    assert list(ds.dynamic_method.values) == ["frequency", "frequency"]
    for end in ("a", "b"):
        amp = ds[f"tension_amplitude_{end}"]
        assert amp.dims == ("amplitude", "line") and amp.attrs["units"] == "N"
        static = ds[f"tension_{end}"]
        np.testing.assert_allclose(ds[f"tension_max_{end}"], static + amp, rtol=1e-12)
        np.testing.assert_allclose(ds[f"tension_min_{end}"], static - amp, rtol=1e-12)
        np.testing.assert_allclose(ds[f"tension_mean_{end}"], static, rtol=1e-12)
    for k in ("tension_envelope_max", "tension_envelope_min"):
        assert ds[k].dims == ("amplitude", "line", "s")
    np.testing.assert_allclose(ds.tension_envelope_max[..., 0], ds.tension_max_a, rtol=1e-12)
    assert ds.body_force_max.dims == ("amplitude", "body", "dof")
    # legs 1 and 3 mirror each other about the y-z plane: same amplitudes
    names = list(ds.line.values)
    np.testing.assert_allclose(
        ds.tension_amplitude_b.sel(line=names[2]),
        ds.tension_amplitude_b.sel(line=names[8]),
        rtol=1e-9,
    )


def test_the_dataset_is_the_pure_module(case8: xr.Dataset) -> None:
    """The runner adds nothing: the amplitudes are those of system_linear and
    solve_system_harmonic called on the study's own system."""
    from cablestudy.analyses.frequency import drag_settings
    from cablestudy.analyses.system import system_model
    from cablestudy.analyses.system_frequency import harmonic_motion, system_frequency_model
    from cablestudy.statics import STATIC_SOLVERS
    from cablestudy.statics.system import solve_system
    from cablestudy.study.grid import expand_cases
    from tests.system_frequency_reference import solve_system_harmonic

    _, cases = expand_cases(parse_study_text(_text(FREQUENCY), "case8.yaml"))
    case = cases[1]  # amplitude 2 m
    system = system_model(case.study)
    static = solve_system(system, STATIC_SOLVERS["catenary"])
    model = system_frequency_model(case, system, static)
    X, U, f = harmonic_motion(case.study)
    assert f == 0.1 and X[0, 0] == -2j and not np.any(U)
    res = solve_system_harmonic(
        model, 2.0 * math.pi * f, X, drag_settings(case.study.analysis.dynamic), point_excitation=U
    )
    assert res.status == 0, res.message
    np.testing.assert_array_equal(
        case8.tension_amplitude_a.sel(amplitude=2.0).values, np.abs(res.end_tension[:, 0])
    )


@pytest.mark.parametrize(
    ("dynamic", "words"),
    [
        (
            "  dynamic:\n    excitation: {body: body1, dof: surge, table: "
            "[[0, 0], [1, 1], [2, 0], [3, 0]], periodic: true}\n    method: frequency\n",
            "method 'time'",
        ),
        (
            "  dynamic:\n    excitation: {body: body1, dof: surge, amplitude: 1.0, "
            "frequency: 0.1}\n    method: frequency\n    transfer_function: {}\n",
            "transfer_function",
        ),
        (
            "  dynamic:\n    excitation: {body: body1, dof: surge, amplitude: 1.0, "
            "frequency: 0.1}\n    method: time\n    linearisation: {tolerance: 1.0e-6}\n",
            "linearisation",
        ),
    ],
)
def test_what_the_system_frequency_domain_does_not_solve_is_refused(
    dynamic: str, words: str
) -> None:
    from cablestudy.study.grid import expand_cases

    with pytest.raises(StudyError) as err:
        expand_cases(parse_study_text(_text(dynamic), "case8.yaml"))
    assert words in str(err.value), str(err.value)
