"""cablestudy.analyses.plausibility: which kept results are warned of, and how a case's warnings
are joined (the end-to-end cases are in tests/integration/test_run_warnings.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cablestudy.analyses import evaluate
from cablestudy.analyses.evaluate import evaluate_case
from cablestudy.analyses.plausibility import (
    dynamic_warnings,
    joined,
    largest_strain,
    slack_warning,
    strain_warning,
    unsettled_warning,
)
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text


def test_largest_strain_takes_the_laws_strain_or_t_over_ea_and_skips_nan() -> None:
    tension = np.array([[1.0e6, 3.0e6, np.nan], [np.nan, np.nan, np.nan]])
    ea = np.array([1.0e8, 1.0e8, 1.0e8])
    out = largest_strain(tension, ea)
    assert out[0] == 0.03 and math.isnan(out[1])
    assert largest_strain(tension, ea, strain=np.array([[0.1, 0.2, 0.3], [0, 0, 0]]))[0] == 0.3


def test_a_strain_at_or_below_the_limit_or_unknown_is_no_warning() -> None:
    assert strain_warning(0.05, 0.05) == ""
    assert strain_warning(math.nan, 0.05) == ""
    assert strain_warning(0.0501, 0.05).startswith("strain: largest strain 0.0501 above ")


def _dyn(**values: float) -> dict[str, np.ndarray]:
    base = {
        "tension_min": 50.0,
        "tension_envelope_min": np.array([40.0, 45.0]),
        "steady_converged": 1,
        "periods": 7.0,
    }
    base.update(values)
    return {k: np.asarray(v) for k, v in base.items()}


def test_slack_at_the_excited_end_or_along_the_line() -> None:
    assert dynamic_warnings(_dyn(), max_periods=80) == []
    assert dynamic_warnings(_dyn(tension_min=0.0), max_periods=80) == [
        slack_warning(0.0, "at the excited end")
    ]
    along = _dyn(tension_envelope_min=np.array([12.0, -3.0]))
    assert dynamic_warnings(along, max_periods=80) == [slack_warning(-3.0, "along the line")]


def test_unsettled_only_when_max_periods_stopped_a_run_that_looked_for_a_steady_state() -> None:
    stopped = _dyn(steady_converged=0, periods=80.0)
    assert dynamic_warnings(stopped, max_periods=80) == [unsettled_warning(80.0, 80)]
    # a fixed duration looks for no steady state; a run ended before max_periods did not
    # stop there
    assert dynamic_warnings(stopped, max_periods=80, fixed_duration=True) == []
    assert dynamic_warnings(_dyn(steady_converged=0, periods=4.0), max_periods=80) == []


def test_a_line_that_parted_is_not_warned_of_its_zero_tension() -> None:
    parted = _dyn(tension_min=0.0, steady_converged=0, periods=80.0, break_time=3.5)
    assert dynamic_warnings(parted, max_periods=80) == []
    intact = _dyn(tension_min=0.0, break_time=math.nan)
    assert len(dynamic_warnings(intact, max_periods=80)) == 1


def test_a_cases_warnings_are_joined_in_kind_order() -> None:
    assert joined(["", "fallback: b", "strain: a"]) == "strain: a; fallback: b"
    assert joined([]) == ""


WIRE = """\
name: wire
environment: {fluid: water}
line:
  segments:
    - {length: 550.0, diameter: 0.076, mass_per_length: 24.0, axial_stiffness: 3.3e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -190.0]}
  b: {kind: fixed, position: [600.0, 0.0, -10.0]}
analysis:
  static: {method: analytic, nodes: 11}
"""


def test_a_fault_in_the_checks_leaves_the_case_ok_and_says_it_went_unchecked(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    (case,) = expand_cases(parse_study_text(WIRE))[1]

    def broken(*args: object) -> str:
        raise ValueError("no such thing")

    # chord hypot(600, 180) m over 550 m: strain 0.139
    assert evaluate_case(case).warning.startswith("strain: largest strain 0.139 ")
    monkeypatch.setattr(evaluate, "case_warnings", broken)
    rec = evaluate_case(case)
    assert rec.status == 0 and "tension" in rec.data
    assert rec.warning.startswith(
        "unchecked: the plausibility checks failed (ValueError: no such thing at broken:"
    )


def test_a_stretch_slack_in_statics_is_not_warned_as_going_slack() -> None:
    """A laid stretch that seabed friction has emptied of tension is slack in statics
    already: its dynamic minimum of 0 (time domain) or a small negative linear swing
    (frequency domain) is not the line going slack. A point taut in statics that reaches
    zero still is (the new user's chain leg, issue 23's trial: 'linear' and 'slack' at
    once)."""
    import numpy as np

    from cablestudy.analyses.plausibility import dynamic_warnings

    static = np.array([0.0, 0.0, 0.0, 5.0e4, 6.0e4])
    quiet = {
        "tension_min": np.asarray(5.9e4),
        "tension_envelope_min": np.array([-0.57, 0.0, -0.2, 4.9e4, 5.9e4]),
    }
    assert dynamic_warnings(quiet, max_periods=10, static_tension=static) == []
    loud = dict(quiet, tension_envelope_min=np.array([-0.57, 0.0, -0.2, -3.0, 5.9e4]))
    (warning,) = dynamic_warnings(loud, max_periods=10, static_tension=static)
    assert warning.startswith("slack:") and "-3 N" in warning and "along the line" in warning
