"""Small-amplitude free vibration against Irvine's linear theory.

After a small smooth pulse of end B along the span, the line rings in its in-plane
modes; the test reads the first symmetric mode's frequency from the spectral peak of
the end tension between 1.4 and 2.2 Hz (the first antisymmetric mode, near 1.15 Hz,
lies outside that band). Irvine (*Cable Structures*, 1981, section 3.2; Irvine &
Caughey 1974) gives its circular frequency from

    tan(w/2) = w/2 - (4 / lambda^2) (w/2)^3,   w = omega l / sqrt(H / m),
    lambda^2 = (m g l / H)^2 l / (H L_e / EA),  L_e = l (1 + 8 (d/l)^2),

for a shallow cable of span l, horizontal tension H, mass m per length and sag d. The
moustafa cable (sag/span 0.081) is near the theory's shallow limit of 1/8, so the
agreement expected is that of the parabolic approximation, about (d/l)^2 ~ 1 %.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from cablestudy.statics.elastic_catenary import solve_between

from .dynamics_helpers import EA, LENGTH, MASS, SPAN, ring_after_pulse

G = 9.80665


def irvine_first_symmetric(H: float, sag: float) -> float:
    """Frequency [Hz] of the first symmetric in-plane mode (Irvine's equation)."""
    le = SPAN * (1.0 + 8.0 * (sag / SPAN) ** 2)
    lam2 = (MASS * G * SPAN / H) ** 2 * SPAN / (H * le / EA)

    def f(w: float) -> float:
        return math.tan(w / 2) - w / 2 + 4.0 / lam2 * (w / 2) ** 3

    w = brentq(f, math.pi * 1.0001, math.pi * 2.9999)
    return w * math.sqrt(H / MASS) / (2.0 * math.pi * SPAN)


def dominant_frequency(t: np.ndarray, y: np.ndarray, band: tuple[float, float]) -> float:
    """Frequency [Hz] of the largest spectral peak of ``y(t)`` inside ``band``: Hann
    window, 32-fold zero padding, parabolic interpolation of the peak."""
    dt = 0.01
    tu = np.arange(t[0], t[-1], dt)
    yu = np.interp(tu, t, y)
    yu = (yu - yu.mean()) * np.hanning(tu.size)
    n = 32 * tu.size
    spec = np.abs(np.fft.rfft(yu, n))
    freq = np.fft.rfftfreq(n, dt)
    inside = np.flatnonzero((freq > band[0]) & (freq < band[1]))
    k = inside[np.argmax(spec[inside])]
    a, b, c = np.log(spec[k - 1 : k + 2])
    shift = 0.5 * (a - c) / (a - 2 * b + c)
    return float(freq[k] + shift * (freq[1] - freq[0]))


def test_free_vibration_matches_irvine_first_symmetric_mode() -> None:
    t, tension = ring_after_pulse()
    late = t > 2.0
    measured = dominant_frequency(t[late], tension[late], (1.4, 2.2))
    sol = solve_between((0, 0, 0), (SPAN, 0, 0), LENGTH, MASS * G, EA, np.linspace(0, LENGTH, 201))
    H = float(sol.force_a[0])
    sag = float(-sol.position[:, 2].min())
    expected = irvine_first_symmetric(H, sag)
    # Irvine's shallow (parabolic) theory neglects terms of relative size
    # (8/3) (d/l)^2 = 1.7 % (mass per horizontal length, tension varying along the
    # arc); the chain of 40 elements is within 0.15 % of one with 80, the steps of
    # 1/64 of 0.3125 s put the period elongation of generalised-alpha near 0.05 %, and
    # the spectral peak is read to ~0.1 %: 2 % in all (observed: -1.2 %)
    assert abs(measured - expected) <= 0.02 * expected, (measured, expected)
    # and the result is far from the taut-string fundamental (sag matters here)
    string = math.sqrt(H / MASS) / (2 * SPAN)
    assert measured > 1.3 * string
