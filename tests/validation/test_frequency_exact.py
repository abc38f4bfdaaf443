"""Frequency domain against exact solutions.

1. A taut, weightless (neutrally buoyant, no drag, no added mass) bar driven along
   its axis at end B: the lumped-mass chain has the closed-form response
   u_j = X sin(j th) / sin(N th), 2 (1 - cos th) = w^2 m h^2 / EA, and the continuous
   bar u(s) = X sin(k s) / sin(k L), k = w sqrt(m / EA). The solver must reproduce the
   discrete solution to round-off and converge to the continuous one as h^2 (lumped
   mass, linear elements).
2. The moustafa cable in vacuum at a frequency far below its first mode: the tension
   change per unit end motion is the static stiffness dT_B/dx_B, taken by central
   differences of the exact (analytic) elastic catenary.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from .frequency_helpers import SPAN, evaluate, study_text

L, EA, RHO = 10.0, 7.854e6, 1025.0
MASS = RHO * math.pi * 0.01**2 / 4.0  # neutrally buoyant: no weight, no sag
STRAIN = 1e-3
C_AXIAL = math.sqrt(EA / MASS)
F_AXIAL = C_AXIAL / (2.0 * L)  # first axial mode of the bar [Hz]


def bar_text(n: int, frequency: float) -> str:
    return f"""
name: bar
environment: {{fluid: water}}
line:
  segments:
    - {{length: {L}, diameter: 0.01, mass_per_length: {MASS!r}, axial_stiffness: {EA},
       drag_normal: 0.0, drag_tangential: 0.0, added_mass_normal: 0.0}}
ends:
  a: {{kind: fixed, position: [0.0, 0.0, 0.0]}}
  b: {{kind: fixed, position: [{L * (1 + STRAIN)!r}, 0.0, 0.0]}}
analysis:
  static: {{method: analytic, nodes: 101, tolerance: 1.0e-12}}
  dynamic:
    excitation: {{end: b, direction: [1.0, 0.0, 0.0], amplitude: 1.0, frequency: {frequency}}}
    method: frequency
    elements: {n}
"""


def bar_discrete(n: int, frequency: float) -> tuple[float, float]:
    """End tension amplitudes (A, B) [N] of the N-element lumped chain per metre of
    end motion: element tensions EA/h (u_1 - u_0) at A and EA/h (u_N - u_N-1) less
    the inertia of the end node's mass m h / 2 at B (the support carries both)."""
    w = 2.0 * math.pi * frequency
    h = L / n
    th = math.acos(1.0 - w**2 * MASS * h**2 / (2.0 * EA))
    t_a = EA / h * math.sin(th) / math.sin(n * th)
    t_b = EA / h * (1.0 - math.sin((n - 1) * th) / math.sin(n * th)) - w**2 * MASS * h / 2.0
    return abs(t_a), abs(t_b)


def bar_continuous(frequency: float) -> tuple[float, float]:
    k = 2.0 * math.pi * frequency / C_AXIAL
    return abs(EA * k / math.sin(k * L)), abs(EA * k * math.cos(k * L) / math.sin(k * L))


@pytest.mark.parametrize("n", [10, 40])
@pytest.mark.parametrize("ratio", [0.37, 1.6])  # below and between the first two modes
def test_axial_bar_matches_the_discrete_closed_form_to_roundoff(n: int, ratio: float) -> None:
    f = ratio * F_AXIAL
    rec = evaluate(bar_text(n, f))[0]
    assert rec.status == 0, rec.message
    t_a, t_b = bar_discrete(n, f)
    # a banded LU of a matrix with condition ~ (EA / h) / (w^2 m h) ~ n^2: relative
    # round-off far below 1e-9
    np.testing.assert_allclose(float(rec.data["tension_amplitude_a"]), t_a, rtol=1e-9)
    np.testing.assert_allclose(float(rec.data["tension_amplitude_b"]), t_b, rtol=1e-9)


def test_axial_bar_converges_to_the_continuous_bar_as_h_squared() -> None:
    f = 0.37 * F_AXIAL
    exact = np.array(bar_continuous(f))
    errors = []
    for n in (10, 20, 40, 80):
        rec = evaluate(bar_text(n, f))[0]
        got = np.array(
            [float(rec.data["tension_amplitude_a"]), float(rec.data["tension_amplitude_b"])]
        )
        errors.append(np.abs(got / exact - 1.0))
    errors = np.array(errors)
    order = np.log2(errors[:-1] / errors[1:])
    # lumped mass: the dispersion error is (k h)^2 / 24 per unit k L: second order
    assert np.all(order > 1.9) and np.all(order < 2.1), order
    assert np.all(errors[-1] < 1e-4)


def test_quasi_static_limit_is_the_static_stiffness() -> None:
    delta = 1e-5  # central difference: error (delta / sag)^2 ~ 1e-10 relative
    t_b = [
        float(evaluate(study_text(span=SPAN + sg * delta, dynamic=False))[0].data["tension_b"])
        for sg in (1.0, -1.0)
    ]
    stiffness = (t_b[0] - t_b[1]) / (2.0 * delta)  # dT_B / dx_B [N/m]
    errors = []
    for n in (20, 40, 80):
        # 1e-3 Hz: inertia enters as (f / f_1)^2 ~ 4e-6 of the first mode (~0.5 Hz)
        rec = evaluate(study_text(elements=n, amplitude=1.0, frequency=1e-3))[0]
        assert rec.status == 0, rec.message
        errors.append(abs(float(rec.data["tension_amplitude_b"]) / stiffness - 1.0))
        # moving B away from A raises the tension in phase with the motion
        assert abs(float(rec.data["tension_phase_b"])) < 1e-3
    order = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # the linear model samples the exact static shape at its nodes: chords instead of
    # arcs give an O(h^2) error in the tangent stiffness
    assert np.all(order > 1.8) and np.all(order < 2.3), (errors, order)
    assert errors[-1] < 2e-4
