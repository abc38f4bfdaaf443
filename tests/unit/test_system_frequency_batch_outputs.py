"""The frequency domain's outputs of a system study computed for a sweep's cases at once
(cablestudy.analyses.system_frequency._solve_group, issue 24) are those of each case
from its own result (system_frequency_outputs, the envelopes put on the ``s`` grid)
bit for bit, in the same order of variables, whether the case is solved alone or in
its sweep."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from cablestudy.analyses import system_dynamic, system_frequency
from cablestudy.analyses.frequency import drag_settings
from cablestudy.analyses.system import _statics
from cablestudy.analyses.system_frequency import (
    _envelope_grid,
    _solve_group,
    system_frequency_model,
)
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text
from tests.system_frequency_reference import system_frequency_outputs

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "system-case8-surge.yaml"


def _one_by_one(res, model, system, static) -> dict[str, np.ndarray]:  # noqa: ANN001
    """A case's outputs from its result alone (the per-case path of the study)."""
    values = system_frequency_outputs(res, static.body_force)
    n_out = system.lines[0].problem.n_nodes
    grid = _envelope_grid(model, n_out)
    values["z_envelope_max"] = [
        red.line.position[:, 2] + np.abs(u[:, 2])
        for red, u in zip(model.lines, res.displacement, strict=True)
    ]
    keys = ("tension_envelope_max", "tension_envelope_min", "z_envelope_max")
    env = {k: (grid @ np.concatenate(values[k])).reshape(len(model.lines), n_out) for k in keys}
    return {
        **{k: np.asarray(v) for k, v in values.items() if k not in env},
        **env,
        "linearisation_iterations": np.asarray(res.iterations),
    }


@pytest.fixture(autouse=True)
def _caches_left_as_found() -> object:
    """The analyses' per-process caches (statics, linear models) as they were: other
    tests count the builds their run makes."""
    caches = (system_frequency._MODEL_CACHE, system_dynamic._STATIC_CACHE)
    saved = [dict(c) for c in caches]
    yield
    for cache, items in zip(caches, saved, strict=True):
        cache.clear()
        cache.update(items)


def test_outputs_of_a_sweep_at_once_are_each_case_s() -> None:
    text = CONFIG.read_text().replace("    points_per_period: 128\n", "    method: frequency\n")
    text += "sweep:\n  analysis.dynamic.excitation.frequency: [0.05, 0.2, 0.45]\n"
    _, cases = expand_cases(parse_study_text(text, "<test>"))
    system, static = _statics(cases[0], math.inf)[:2]
    model = system_frequency_model(cases[0], system, static)
    settings = drag_settings(cases[0].study.analysis.dynamic)
    swept = _solve_group(cases, model, system, static, settings)
    for case, (res, values, bad) in zip(cases, swept, strict=True):
        assert res.status == 0 and not bad
        (alone,) = _solve_group([case], model, system, static, settings)
        for got in (values, alone[1]):
            want = _one_by_one(res, model, system, static)
            assert list(got) == list(want)
            for key, v in want.items():
                assert got[key].shape == v.shape and got[key].dtype == v.dtype, key
                np.testing.assert_array_equal(got[key], v, err_msg=key)
