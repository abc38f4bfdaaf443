"""Shared set-up of the dynamics validation tests: the moustafa seed's cable (section
4: d = 0.01 m, L = 10.9774 m, span 10.792 m, m = 0.61 kg/m, EA = 7.854e6 N) as a study,
and a direct run of the time-domain solver keeping every step."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np
import yaml

from cablestudy.analyses.static import solve_static
from cablestudy.analyses.time import dynamic_problem
from cablestudy.dynamics.discrete_line import DiscreteLine
from cablestudy.dynamics.time_problem import DynamicResult
from cablestudy.dynamics.timedomain import simulate
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text

LENGTH, SPAN, MASS, EA, DIAMETER = 10.9774, 10.792, 0.61, 7.854e6, 0.01


def moustafa_study(
    *,
    fluid: str = "water",
    dynamic: dict[str, Any] | None = None,
    segment: dict[str, Any] | None = None,
) -> dict[str, Any]:
    seg = {
        "length": LENGTH,
        "diameter": DIAMETER,
        "mass_per_length": MASS,
        "axial_stiffness": EA,
        **(segment or {}),
    }
    dyn = {
        "excitation": {
            "end": "b",
            "direction": [1.0, 0.0, 0.0],
            "amplitude": 0.05,
            "frequency": 0.5,
        },
        **(dynamic or {}),
    }
    return {
        "name": "moustafa-test",
        "environment": {"fluid": fluid},
        "line": {"segments": [seg]},
        "ends": {
            "a": {"kind": "fixed", "position": [0.0, 0.0, 0.0]},
            "b": {"kind": "fixed", "position": [SPAN, 0.0, 0.0]},
        },
        "analysis": {"static": {"method": "analytic", "tolerance": 1e-12}, "dynamic": dyn},
    }


def run_direct(
    study: dict[str, Any], **overrides: Any
) -> tuple[DynamicResult, DiscreteLine, np.ndarray]:
    """Run one case through the same set-up as the pipeline, keeping every step.
    Returns (result, discrete line, its static positions)."""
    src = parse_study_text(yaml.safe_dump(study))
    _, cases = expand_cases(src)
    case = cases[0]
    static = solve_static(case, None)
    assert static.success, static.message
    problem = dynamic_problem(case, static)
    assert not isinstance(problem, str), problem
    problem = replace(problem, **{"keep_steps": True, **overrides})
    return simulate(problem), problem.line, problem.static_position


def ring_after_pulse(duration: float = 40.0) -> tuple[np.ndarray, np.ndarray]:
    """The moustafa cable in vacuum rung by a small smooth pulse of end B along the span
    (3 mm over 0.6 s, then held): times [s] and end-B tension [N] of every step, 40
    elements, 64 steps per 0.3125 s, no ramp."""
    times = np.linspace(0.0, 0.6, 25)
    bump = 0.003 * np.sin(np.pi * times / 0.6) ** 2
    table = [[float(t), float(u)] for t, u in zip(times, bump, strict=True)]
    study = moustafa_study(
        fluid="vacuum",
        dynamic={
            "excitation": {"end": "b", "direction": [1.0, 0.0, 0.0], "table": table},
            "elements": 40,
            "period": 0.3125,
            "duration": duration,
            "ramp_periods": 0.0,
        },
    )
    res, _, _ = run_direct(study)
    assert res.success, res.message
    rec = res.record
    assert rec is not None
    return rec["t"], np.linalg.norm(rec["end_force"][:, 1], axis=1)
