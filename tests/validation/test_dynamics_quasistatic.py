"""Quasi-static limit: an end moved slowly passes through static equilibria, so the
largest and smallest end tension over a period are the exact elastic-catenary
tensions (Irvine, *Cable Structures*, eqs. 2.26-2.27, :mod:`cablestudy.statics.
elastic_catenary`) with end B at the extreme positions span + amplitude and
span - amplitude."""

from __future__ import annotations

import numpy as np

from cablestudy.statics.elastic_catenary import solve_between

from .dynamics_helpers import EA, LENGTH, MASS, SPAN, moustafa_study, run_direct


def test_slow_motion_reproduces_static_tensions_at_the_extreme_positions() -> None:
    amplitude, frequency = 0.1, 0.01  # period 100 s, some 60 times the first natural one
    study = moustafa_study(fluid="vacuum", dynamic={
        "excitation": {"end": "b", "direction": [1.0, 0.0, 0.0], "amplitude": amplitude,
                       "frequency": frequency},
        "elements": 40, "ramp_periods": 1.0, "min_periods": 2, "max_periods": 6,
        "steady_tolerance": 1e-4, "spectral_radius": 0.0})
    res, _, _ = run_direct(study, keep_steps=False)
    assert res.success, res.message
    w = MASS * 9.80665
    s = np.array([LENGTH])
    exact = {}
    for sign in (+1.0, -1.0):
        sol = solve_between((0, 0, 0), (SPAN + sign * amplitude, 0, 0), LENGTH, w, EA, s)
        exact[sign] = float(np.linalg.norm(sol.force_b))
    # Errors allowed: (i) dynamic amplification ~ (f / f1)^2 = (0.01 / 0.59)^2 = 3e-4 of
    # the tension swing (f1 = taut-string fundamental sqrt(H/m)/(2 span)); (ii) the
    # lumped chain of 40 elements against the continuous catenary, O((l/a)^2) ~ 1e-4
    # relative; (iii) sampling the peak with 64 steps per period, 1 - cos(pi/64) = 1.2e-3
    # of the swing. 0.2 % of the tension covers all three with margin.
    assert abs(res.tension_max - exact[+1.0]) <= 2e-3 * exact[+1.0]
    assert abs(res.tension_min - exact[-1.0]) <= 2e-3 * exact[-1.0]
    # and the motion does change the tension by much more than that tolerance
    assert exact[+1.0] - exact[-1.0] > 0.3 * exact[+1.0]
