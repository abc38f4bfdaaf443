"""Shared set-up of the dynamics validation tests: the moustafa seed's cable (section
4: d = 0.01 m, L = 10.9774 m, span 10.792 m, m = 0.61 kg/m, EA = 7.854e6 N) as a study,
and a direct run of the time-domain solver keeping every step."""

from __future__ import annotations

from typing import Any

import numpy as np
import yaml

from cablestudy.analyses import discrete_statics, end_motion, roundoff_force, solve_static
from cablestudy.cases import expand_cases
from cablestudy.config.loader import parse_study_text
from cablestudy.dynamics.model import DiscreteLine
from cablestudy.dynamics.timedomain import DynamicProblem, DynamicResult, simulate

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
    line, x_static, msg = discrete_statics(case, static)
    assert not msg, msg
    dyn = case.study.analysis.dynamic
    assert dyn is not None
    motion, period, step = end_motion(dyn)
    kwargs: dict[str, Any] = dict(
        line=line,
        static_position=x_static,
        motion=motion,
        period=period,
        step=step,
        max_refinement=dyn.max_refinement,
        spectral_radius=dyn.spectral_radius,
        newton_tolerance=max(
            dyn.newton_tolerance * float(static.tension.max()), 4.0 * roundoff_force(line, x_static)
        ),
        tension_step=dyn.tension_resolution * float(static.tension.max()),
        steady_tolerance=dyn.steady_tolerance,
        steady_window=dyn.steady_window,
        min_periods=dyn.min_periods,
        max_periods=dyn.max_periods,
        duration=dyn.duration,
        keep_steps=True,
    )
    kwargs.update(overrides)
    return simulate(DynamicProblem(**kwargs)), line, x_static


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
