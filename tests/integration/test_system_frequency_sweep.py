"""A sweep of frequency of a system's frequency domain from the study file to the dataset
(issue 24): the cases of a chunk that share the linear model are solved in one compiled
sweep (cablestudy.analyses.system_frequency.sweep_chunk), each from the quasi-static
start. The dataset holds for every case the answer of the case alone bit for bit, with
the same drag iterations (a case's record never depends on the cases run beside it),
and the wall time of the sweep shared out (every case's positive)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import xarray as xr

from cablestudy.cli import main
from cablestudy.study.loader import parse_study_text

CONFIG = Path(__file__).parents[2] / "configs" / "system-case8-surge.yaml"
FREQUENCIES = np.linspace(0.02, 0.5, 24)
SWEEP = """\
  dynamic:
    excitation: {body: body1, dof: surge, amplitude: 2.0, frequency: 0.1}
    method: frequency
    elements: 10
sweep:
  analysis.dynamic.excitation.frequency: [%s]
"""


def test_a_frequency_sweep_through_the_command_line_is_the_cases_alone(tmp_path: Path) -> None:
    from cablestudy.analyses.frequency import drag_settings
    from cablestudy.analyses.system import system_model
    from cablestudy.analyses.system_frequency import harmonic_motion, system_frequency_model
    from cablestudy.statics import STATIC_SOLVERS
    from cablestudy.statics.system import solve_system
    from cablestudy.study.grid import expand_cases
    from tests.system_frequency_reference import solve_system_harmonic

    text = CONFIG.read_text()
    text = text[: text.index("  dynamic:")] + SWEEP % ", ".join(f"{f:.6g}" for f in FREQUENCIES)
    cfg = tmp_path / "case8.yaml"
    cfg.write_text(text)
    args = ["run", str(cfg), "--out", str(tmp_path), "--no-cache", "--no-progress"]
    assert main([*args, "--scheduler", "synchronous"]) == 0
    ds = xr.load_dataset(tmp_path / "system-case8-surge.nc")
    assert np.all(ds.status.values == 0), ds.message.values
    assert np.all(ds.wall_time.values > 0.0)
    _, cases = expand_cases(parse_study_text(text, "case8.yaml"))
    system = system_model(cases[0].study)
    static = solve_system(system, STATIC_SOLVERS["catenary"])
    iterations = 0
    for k, case in enumerate(cases):
        model = system_frequency_model(case, system, static)
        X, U, f = harmonic_motion(case.study)
        alone = solve_system_harmonic(
            model, 2.0 * math.pi * f, X, drag_settings(case.study.analysis.dynamic), U
        )
        assert alone.status == 0, alone.message
        iterations += alone.iterations
        for name, ref in (
            ("tension_amplitude_a", np.abs(alone.end_tension[:, 0])),
            ("tension_amplitude_b", np.abs(alone.end_tension[:, 1])),
        ):
            got = ds[name].isel(frequency=k).values
            np.testing.assert_array_equal(got, ref)  # a case's record is its own alone
        # the envelope (computed for all the sweep's cases at once) ends at the end
        # tensions' extremes and is the static tension plus and minus the amplitude
        hi = ds.tension_envelope_max.isel(frequency=k).values
        lo = ds.tension_envelope_min.isel(frequency=k).values
        amp = np.abs(alone.end_tension)
        bar = 1e-6 * amp.max()  # the amplitudes' bar
        np.testing.assert_allclose(hi[:, -1] - alone.tension_static[:, 1], amp[:, 1], atol=bar)
        np.testing.assert_allclose(alone.tension_static[:, 0] - lo[:, 0], amp[:, 0], atol=bar)
    # each case from the quasi-static start, as alone: the same iterations
    assert int(ds.linearisation_iterations.sum()) == iterations
