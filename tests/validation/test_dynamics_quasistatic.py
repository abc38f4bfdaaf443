"""Quasi-static limit: an end moved slowly passes through static equilibria, so the
largest and smallest end tension over a period are the exact elastic-catenary
tensions (Irvine, *Cable Structures*, eqs. 2.26-2.27, :mod:`cablestudy.statics.
elastic_catenary`) with end B at the extreme positions span + amplitude and
span - amplitude."""

from __future__ import annotations

import numpy as np
import pytest

from cablestudy.statics.elastic_catenary import solve_between

from .dynamics_helpers import EA, LENGTH, MASS, SPAN, moustafa_study, run_direct


@pytest.mark.parametrize(
    ("end_b", "direction"),
    [
        ((SPAN, 0.0, 0.0), (1.0, 0.0, 0.0)),  # the seed's level supports
        ((10.2, 1.5, -2.5), (0.6, 0.3, -0.74)),  # B lower and aside, oblique motion
    ],
)
def test_slow_motion_reproduces_static_tensions_at_the_extreme_positions(
    end_b: tuple[float, float, float], direction: tuple[float, float, float]
) -> None:
    amplitude, frequency = 0.1, 0.01  # period 100 s, some 60 times the first natural one
    study = moustafa_study(
        fluid="vacuum",
        dynamic={
            "excitation": {
                "end": "b",
                "direction": list(direction),
                "amplitude": amplitude,
                "frequency": frequency,
            },
            "elements": 40,
            "ramp_periods": 1.0,
            "min_periods": 2,
            "max_periods": 6,
            "steady_tolerance": 1e-4,
            "spectral_radius": 0.0,
        },
    )
    study["ends"]["b"]["position"] = list(end_b)
    res, _, _ = run_direct(study, keep_steps=False)
    assert res.success, res.message
    w = MASS * 9.80665
    s = np.array([LENGTH])
    exact = {}
    unit = np.asarray(direction) / np.linalg.norm(direction)
    for sign in (+1.0, -1.0):
        sol = solve_between(
            (0, 0, 0), np.asarray(end_b) + sign * amplitude * unit, LENGTH, w, EA, s
        )
        exact[sign] = float(np.linalg.norm(sol.force_b))
    # Errors allowed: (i) dynamic amplification ~ (f / f1)^2 = (0.01 / 0.59)^2 = 3e-4 of
    # the tension swing (f1 = taut-string fundamental sqrt(H/m)/(2 span)); (ii) the
    # lumped chain of 40 elements against the continuous catenary, O((l/a)^2) ~ 1e-4
    # relative; (iii) sampling the peak with 64 steps per period, 1 - cos(pi/64) = 1.2e-3
    # of the swing. 0.2 % of the tension covers all three with margin.
    assert abs(res.tension_max - exact[+1.0]) <= 2e-3 * exact[+1.0]
    assert abs(res.tension_min - exact[-1.0]) <= 2e-3 * exact[-1.0]
    # and the motion changes the tension by far more than that tolerance (50 times)
    assert exact[+1.0] - exact[-1.0] > 0.1 * exact[+1.0]


@pytest.mark.parametrize(
    "axial",
    [
        {"law": "steel_wire", "stiffness": EA, "offset": 2e-4},
        {"law": "polynomial", "coefficients": [EA / 4, EA * 50.0, EA * 1e4]},
    ],
    ids=["steel_wire", "polynomial"],
)
def test_slow_motion_with_a_nonlinear_law_reproduces_its_static_tensions(axial: dict) -> None:
    """The same quasi-static check with a non-linear axial law in the time domain, on
    the cable pulled taut (B at 10.985 m: strain about 7e-4, where the laws depart from
    EA strain by 30-70 %) and moved by 2 mm: the extreme end tensions are the
    semi-analytic statics' (which integrates the law exactly) with B at the extreme
    positions; same error budget (0.2 %) as above. A dynamic model that used EA instead
    of the law would miss by the law's departure from it."""
    import yaml

    from cablestudy.analyses.static import solve_static
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text

    amplitude, frequency, taut = 0.002, 0.01, 10.985
    study = moustafa_study(
        fluid="vacuum",
        dynamic={
            "excitation": {
                "end": "b",
                "direction": [1.0, 0.0, 0.0],
                "amplitude": amplitude,
                "frequency": frequency,
            },
            "elements": 40,
            "ramp_periods": 1.0,
            "min_periods": 2,
            "max_periods": 6,
            "steady_tolerance": 1e-4,
            "spectral_radius": 0.0,
        },
    )
    seg = study["line"]["segments"][0]
    del seg["axial_stiffness"]
    seg["axial"] = axial
    study["analysis"]["static"]["method"] = "catenary"
    study["ends"]["b"]["position"] = [taut, 0.0, 0.0]
    res, _, _ = run_direct(study, keep_steps=False)
    assert res.success, res.message
    exact = {}
    linear = {}
    for sign in (+1.0, -1.0):
        shifted = yaml.safe_load(yaml.safe_dump(study))
        shifted["ends"]["b"]["position"][0] = taut + sign * amplitude
        del shifted["analysis"]["dynamic"]
        _, cases = expand_cases(parse_study_text(yaml.safe_dump(shifted)))
        static = solve_static(cases[0], None)
        assert static.success, static.message
        exact[sign] = float(np.linalg.norm(static.force_b))
        w = MASS * 9.80665
        end = np.array([taut + sign * amplitude, 0.0, 0.0])
        sol = solve_between((0, 0, 0), end, LENGTH, w, EA, np.array([LENGTH]))
        linear[sign] = float(np.linalg.norm(sol.force_b))
    assert abs(res.tension_max - exact[+1.0]) <= 2e-3 * exact[+1.0]
    assert abs(res.tension_min - exact[-1.0]) <= 2e-3 * exact[-1.0]
    assert abs(exact[+1.0] - linear[+1.0]) > 0.2 * exact[+1.0]
    assert exact[+1.0] - exact[-1.0] > 0.1 * exact[+1.0]  # the motion is felt
