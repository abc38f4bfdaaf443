"""A sweep over excitation settings reuses the statics and the linear model: on the
92-case Figs. 2-5 sweep of the moustafa seed (4 amplitudes x 23 frequencies, one
static problem) the frequency domain solves the statics once at the output points and
once at the dynamic model's nodes, and assembles the linear model once."""

from __future__ import annotations

from pathlib import Path

from cablestudy.analyses.counters import COUNTERS
from cablestudy.analyses.evaluate import evaluate_case, evaluate_chunk
from cablestudy.analyses.frequency import _LAST_PROBLEM, _LINEAR_CACHE
from cablestudy.analyses.line_model import _DISCRETE_CACHE
from cablestudy.analyses.static import _LAST_STATIC_OUTPUTS, _STATIC_CACHE
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "moustafa-figs2-5.yaml"


def test_figs2_5_sweep_solves_statics_and_assembles_once() -> None:
    text = CONFIG.read_text().replace("method: auto", "method: frequency")
    _, cases = expand_cases(parse_study_text(text))
    assert len(cases) == 92 and len({c.static_hash for c in cases}) == 1
    _STATIC_CACHE.clear()
    _LINEAR_CACHE.clear()
    COUNTERS.clear()
    records = evaluate_chunk(cases)
    assert all(r.status == 0 for r in records), {r.message for r in records}
    assert all(str(r.data["dynamic_method"]) == "frequency" for r in records)
    assert COUNTERS["static_solves"] == 2
    assert COUNTERS["linear_assemblies"] == 1


def test_shared_static_outputs_and_problem_give_each_case_its_own_result() -> None:
    """Cases that share a static problem share its outputs and problem object within a
    chunk; each record equals the one the case gets alone, in a fresh process state."""
    import numpy as np

    text = CONFIG.read_text().replace("method: auto", "method: frequency")
    _, cases = expand_cases(parse_study_text(text))
    picked = cases[::23] + cases[5:7]
    chunk = evaluate_chunk(picked)
    for case, rec in zip(picked, chunk, strict=True):
        _STATIC_CACHE.clear()
        _LAST_STATIC_OUTPUTS.clear()
        _LINEAR_CACHE.clear()
        _LAST_PROBLEM.clear()
        alone = evaluate_case(case)
        assert (rec.status, rec.message) == (alone.status, alone.message)
        assert set(rec.data) == set(alone.data)
        for name, value in alone.data.items():
            assert np.asarray(rec.data[name]).tobytes() == np.asarray(value).tobytes(), name
    # the shared arrays are the same objects, not copies made per case
    assert chunk[0].data["elevation"] is chunk[1].data["elevation"]


def test_a_time_domain_sweep_solves_its_statics_and_builds_its_line_once() -> None:
    """Cases that differ only in excitation share one static solve and one lumped-mass
    line with its discrete equilibrium in the time domain too (issue 20, item 3)."""
    text = CONFIG.read_text().replace("method: auto", "method: time")
    text = text.replace("{start: 0.1, stop: 1.2, num: 23}", "[0.3, 0.6]")
    text = text.replace("[0.025, 0.05, 0.075, 0.1]", "[0.025, 0.05]")
    _, cases = expand_cases(parse_study_text(text))
    assert len(cases) == 4
    _STATIC_CACHE.clear()
    _DISCRETE_CACHE.clear()
    COUNTERS.clear()
    records = evaluate_chunk(cases)
    assert all(r.status == 0 for r in records), {r.message for r in records}
    assert COUNTERS["static_solves"] == 1
    assert COUNTERS["line_assemblies"] == 1
