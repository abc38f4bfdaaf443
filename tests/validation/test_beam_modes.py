"""Bending in the shared line model against exact beam frequencies, through modal
analysis (which takes the time-domain model's own tangents) and through a time-domain
ring-down of the same model: the tensioned beam (beam-string) with pinned ends, and the
Euler-Bernoulli beam at (almost) zero tension with pinned and with clamped ends."""

from __future__ import annotations

import math

import numpy as np
import pytest
import yaml

from cablestudy.dynamics.discrete_line import DynamicExtras
from cablestudy.dynamics.modal import ModalProblem, modal_analysis
from cablestudy.statics.base import EndCondition, Medium, StaticResult

from ..line_models import one_segment

L, M, EI, EA = 10.0, 2.0, 500.0, 1.0e9
VACUUM = Medium(density=0.0, gravity=9.80665)
CLAMPED_BETA_L = np.array([4.730040745, 7.853204624, 10.99560784])


def straight(n: int, tension: float, *, clamped: bool) -> ModalProblem:
    """A weightless straight beam along x between fixed ends, at ``tension`` [N]."""
    line = one_segment(
        length=L, weight=0.0, mass=M, axial_stiffness=EA, bending_stiffness=EI, diameter=0.05
    )
    s = np.linspace(0.0, L, n + 1)
    span = L * (1.0 + tension / EA)
    pos = np.stack([s * span / L, np.zeros_like(s), np.zeros_like(s)], 1)
    static = StaticResult(
        s=s,
        position=pos,
        tension=np.full(n + 1, tension),
        force_a=np.array([-tension, 0.0, 0.0]),
        force_b=np.array([tension, 0.0, 0.0]),
    )
    clamp = np.array([[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]]) if clamped else np.zeros((2, 3))
    return ModalProblem(
        line=line,
        medium=VACUUM,
        end_a=EndCondition(kind="fixed", position=pos[0]),
        end_b=EndCondition(kind="fixed", position=pos[-1]),
        static=static,
        n_modes=6,
        extras=DynamicExtras(clamp_direction=clamp),
    )


def transverse(res) -> np.ndarray:  # noqa: ANN001
    """The distinct transverse frequencies (each comes twice: y and z)."""
    f = res.frequency
    np.testing.assert_allclose(f[0::2], f[1::2], rtol=1e-9)
    return f[0::2]


def test_tensioned_beam_frequencies_converge_to_the_beam_string_formula() -> None:
    """f_n = n / (2L) sqrt(T/m) sqrt(1 + (n pi / L)^2 EI / T), pinned ends, with EI and T
    of equal weight in the first mode ((pi/L)^2 EI / T = 1 at T = 49.3 N). Lumped mass and
    second differences: error O((n pi h / L)^2), so halving h divides it by 4 +- 0.4,
    and it is under 0.3 % for the third mode at 80 elements ((3 pi / 80)^2 / 4 ~ 3.5e-3
    bounds the two schemes' leading terms)."""
    T = (math.pi / L) ** 2 * EI
    n = np.arange(1, 4)
    exact = n / (2 * L) * math.sqrt(T / M) * np.sqrt(1 + (n * math.pi / L) ** 2 * EI / T)
    errs = []
    for elements in (20, 40, 80):
        res = modal_analysis(straight(elements, T, clamped=False))
        assert res.success, res.message
        errs.append(np.abs(transverse(res) / exact - 1.0))
    ratio = errs[1] / errs[2]
    assert np.all((ratio > 3.6) & (ratio < 4.4)), ratio
    assert errs[2].max() < 3e-3


@pytest.mark.parametrize("clamped", [False, True])
def test_zero_tension_limit_is_the_euler_bernoulli_beam(clamped: bool) -> None:
    """At T L^2 / EI = 2e-6 the string term shifts the frequencies by under 1e-7: the
    beam's own f_n = (beta_n L)^2 / (2 pi L^2) sqrt(EI / m), with beta_n L = n pi
    (pinned) or 4.730, 7.853, 10.996 (clamped). Pinned converges as h^2; the clamped
    end's half-element curvature converges as h: within 2 % at 160 elements and
    falling by about 2 per halving."""
    T = 1e-6 * EI / L**2 * 2
    beta_l = CLAMPED_BETA_L if clamped else math.pi * np.arange(1, 4)
    exact = beta_l**2 / (2 * math.pi * L**2) * math.sqrt(EI / M)
    errs = []
    for elements in (40, 80, 160):
        res = modal_analysis(straight(elements, T, clamped=clamped))
        assert res.success, res.message
        errs.append(np.abs(transverse(res)[:3] / exact - 1.0))
    ratio = errs[1] / errs[2]
    if clamped:
        assert np.all(ratio > 1.7), (errs, ratio)
        assert errs[2].max() < 2e-2, errs
    else:
        assert np.all((ratio > 3.6) & (ratio < 4.4)), ratio
        assert errs[2].max() < 2e-3, errs


def test_time_domain_ring_down_of_a_bending_beam_rings_at_the_modal_frequency() -> None:
    """One line model: the time-domain solver integrates the forces whose tangents modal
    analysis takes. A taut beam with EI (both terms of equal weight), nearly weightless,
    is plucked out of plane by a 0.1 mm pulse of end B (small: a string stretched by its
    own vibration stiffens, by EA (pi a / 2L)^2, negligible here) and left to ring; the period of
    the midspan's out-of-plane motion (zero crossings over 4 periods) must be the modal
    analysis' first out-of-plane period on the same 40-element mesh, to the time
    integration's period error: generalised-alpha is second order, (omega h)^2 / 12
    ~ 3e-5 at 365 steps a period, plus the interpolated zero crossings (~1e-4); 1e-3
    allowed. A model where the time domain and modal analysis assembled different
    bending terms would miss by the bending term's share of the frequency (~30 %)."""
    from .dynamics_helpers import run_direct

    tension = (math.pi / L) ** 2 * EI
    ea = 1.0e7
    study = {
        "name": "ring",
        "environment": {"fluid": "vacuum", "gravity": 1e-6},
        "line": {
            "segments": [
                {
                    "length": L,
                    "diameter": 0.05,
                    "mass_per_length": M,
                    "axial_stiffness": ea,
                    "bending_stiffness": EI,
                }
            ]
        },
        "ends": {
            "a": {"kind": "fixed", "position": [0.0, 0.0, 0.0]},
            "b": {"kind": "fixed", "position": [L * (1 + tension / ea), 0.0, 0.0]},
        },
        "analysis": {
            "static": {"method": "discrete", "nodes": 41},
            "modal": {"modes": 2, "elements": 40, "mesh": "uniform"},
            "dynamic": {
                "excitation": {
                    "end": "b",
                    "direction": [0.0, 1.0, 0.0],
                    "table": [[0.0, 0.0], [0.1, 1e-4], [0.2, 0.0], [0.3, 0.0]],
                },
                "method": "time",
                "elements": 40,
                "period": 0.5,
                "points_per_period": 64,
                "duration": 13.0,
                "ramp_periods": 0.0,
                "spectral_radius": 1.0,
            },
        },
    }
    res, line, _ = run_direct(study)
    assert res.status == 0, res.message

    from cablestudy.analyses.modal import solve_modal
    from cablestudy.analyses.static import solve_static
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text

    _, cases = expand_cases(parse_study_text(yaml.safe_dump(study)))
    modes = solve_modal(cases[0], solve_static(cases[0], None), None)
    assert modes.success, modes.message
    first = next(k for k, shape in enumerate(modes.mode_shape) if np.abs(shape[:, 1]).max() > 0.9)
    np.testing.assert_allclose(modes.s, line.s, atol=1e-12)  # the same nodes
    # the first mode's coordinate (mass-weighted projection): one clean frequency
    t = res.record["t"]
    q = res.record["x"][:, :, 1] @ (line.mass * modes.mode_shape[first, :, 1])
    late = t > 0.5
    t, q = t[late], q[late] - q[late].mean()
    k = np.flatnonzero(np.sign(q[:-1]) != np.sign(q[1:]))
    crossings = t[k] - q[k] * (t[k + 1] - t[k]) / (q[k + 1] - q[k])
    period = 2.0 * float(np.mean(np.diff(crossings)))
    assert len(crossings) >= 8
    assert abs(period * modes.frequency[first] - 1.0) < 1e-3, (period, modes.frequency[first])
