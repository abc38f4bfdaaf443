"""The time-domain analysis of a case: the run about its static solution
(:func:`cablestudy.dynamics.timedomain.simulate`) and its outputs.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..statics import (
    STATUS_NUMERICAL,
    StaticResult,
)
from ..study.analysis import (
    DynamicSettings,
)
from ..study.cases import Case
from .line_model import (
    discrete_statics,
    element_breaks,
    end_motion,
    march_settings,
    roundoff_force,
    winch_settings,
)
from .plausibility import STEP_WARNING_KEY

if TYPE_CHECKING:  # imported where used: `cablestudy validate` needs none of them
    from ..dynamics.time_problem import DynamicProblem, DynamicResult


def solve_dynamic(case: Case, static: StaticResult, deadline: float | None) -> DynamicResult:
    from ..dynamics.time_problem import DynamicResult
    from ..dynamics.timedomain import simulate

    problem = dynamic_problem(case, static)
    if isinstance(problem, str):
        return DynamicResult(status=STATUS_NUMERICAL, message=problem)
    return simulate(problem, deadline=deadline)


def dynamic_problem(case: Case, static: StaticResult) -> DynamicProblem | str:
    """The time-domain run of the case about its static solution (or why the discrete
    static equilibrium it starts from was not found)."""
    from ..dynamics.time_problem import DynamicProblem

    dyn = case.study.analysis.dynamic
    assert dyn is not None
    sliding = None
    if case.study.line.pulleys:
        from .pulley import pulley_discrete_statics

        line, x_static, msg, anchor, sliding = pulley_discrete_statics(case, static)
    else:
        line, x_static, msg, anchor = discrete_statics(case, static)
    if msg:
        return msg
    motion, period, step = end_motion(dyn)
    first = dyn.excitations[0]
    hist = dyn.history
    return DynamicProblem(
        line=line,
        static_position=x_static,
        motion=motion,
        period=period,
        step=step,
        excited_end=0 if first.end == "a" else 1,
        newton_tolerance=max(
            dyn.newton_tolerance * float(np.nanmax(static.tension)),
            4.0 * roundoff_force(line, x_static),
        ),
        tension_step=dyn.tension_resolution * float(np.nanmax(static.tension)),
        history_s=np.asarray(hist.points if hist else [], dtype=float),
        history_periods=hist.periods if hist else 0.0,
        history_samples=hist.samples_per_period if hist else 1,
        anchor=anchor,
        history_line=bool(hist and hist.whole_line),
        # a node within a millionth of the line's length of the seabed touches it (the
        # statics' rule); the penalty contact sinks laid nodes below the plane anyway
        touchdown_tolerance=1e-6 * max(float(line.s[-1]), 1.0),
        after_break=dyn.after_break,
        **element_breaks(case.study, line),
        **winch_settings(case.study.line.winch),
        pulleys=sliding,
        # the step check (cablestudy.dynamics.step_check); not over sliding pulleys,
        # whose run is its own (documented)
        step_tolerance=None if sliding is not None else dyn.step_tolerance,
        points_per_period=dyn.points_per_period,
        **march_settings(dyn),
    )


def dynamic_outputs(
    res: DynamicResult, dyn: DynamicSettings, s_out: np.ndarray
) -> dict[str, np.ndarray]:
    """The time domain's outputs; along-line ones at the static output points ``s_out``
    [m] (the dataset's ``s``)."""
    from ..dynamics.discrete_line import interpolate_nodes
    from .along_line import tension_along

    s_out = np.asarray(s_out, dtype=float)
    out: dict[str, np.ndarray] = {
        "tension_static": np.asarray(res.tension_static),
        "tension_max": np.asarray(res.tension_max),
        "tension_min": np.asarray(res.tension_min),
        "tension_mean": np.asarray(res.tension_mean),
        "tension_max_line": np.asarray(res.tension_max_line),
        "tension_max_spread": np.asarray(res.tension_max_spread),
        "tension_min_spread": np.asarray(res.tension_min_spread),
        "steady_converged": np.asarray(int(res.steady_converged)),
        "periods": np.asarray(res.periods),
        "dynamic_steps": np.asarray(res.steps),
        "newton_iterations": np.asarray(res.newton_iterations),
        "rejected_steps": np.asarray(res.rejected_steps),
        "dynamic_method": np.asarray("time"),
    }
    if res.step_warning:  # the step check's (a warning, not a variable: evaluate.py)
        out[STEP_WARNING_KEY] = res.step_warning
    if res.touchdown_tracked:  # a seabed to touch: NaN when the line does not touch it
        out["touchdown_min"] = np.asarray(res.touchdown_min)
        out["touchdown_max"] = np.asarray(res.touchdown_max)
    if res.split_min.size:
        # a line over pulleys: its nodes move along the material as it slides, so the
        # elements' extremes belong to no fixed point of the line (no envelope)
        out["pulley_arc_length_min"] = res.split_min
        out["pulley_arc_length_max"] = res.split_max
    elif res.element_tension_max.size:
        out["tension_envelope_max"] = tension_along(
            s_out, res.line_s, res.element_tension_max, res.end_tension_max
        )
        out["tension_envelope_min"] = tension_along(
            s_out, res.line_s, res.element_tension_min, res.end_tension_min
        )
        out["z_envelope_max"] = np.interp(s_out, res.line_s, res.z_max)
    if res.history is not None and "line_position" in res.history:
        h = res.history
        out["history_line_position"] = interpolate_nodes(res.line_s, s_out, h["line_position"])
        out["history_line_velocity"] = interpolate_nodes(res.line_s, s_out, h["line_velocity"])
        out["history_line_tension"] = np.array(
            [
                tension_along(s_out, res.line_s, el, ends)
                for el, ends in zip(h["line_element_tension"], h["line_end_tension"], strict=True)
            ]
        ).reshape(-1, s_out.size)
    if res.history is not None:
        h = res.history
        out.update(
            {
                "history_time": h["time"],
                "history_tension": h["tension"],
                "history_displacement": h["displacement"],
                "history_velocity": h["velocity"],
                "history_acceleration": h["acceleration"],
                "history_point_s": np.asarray(
                    dyn.history.points if dyn.history else [], dtype=float
                ),
            }
        )
    return out
