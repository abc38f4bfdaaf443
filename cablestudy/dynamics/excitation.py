"""Prescribed end motion: sums of harmonics and time tables, started smoothly.

The displacement of an end from its static position is ``r(t) d(t)``, where ``d`` is
the sum of the motions given for that end and the ramp ``r`` rises from 0 to 1 as
``r = (1 - cos(pi t / t_r)) / 2`` over ``t_r``: with ``r(0) = r'(0) = 0`` the end
starts at rest, so the start-up transient is small. Velocity and acceleration follow
by the product rule (both continuous).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit
from scipy.interpolate import CubicSpline, PchipInterpolator


@dataclass(frozen=True, kw_only=True)
class TableMotion:
    """Displacement ``value`` [m] along unit ``direction`` (3,) at ``times`` [s], for end
    0 (A) or 1 (B).

    A ``periodic`` table (its duration the period) is a periodic cubic spline (C2: the
    acceleration is continuous). Otherwise it is a monotone piecewise cubic Hermite
    curve (PCHIP, Fritsch-Carlson): it never leaves the range of neighbouring values, so
    a ramp-and-hold table with sparse points moves as written (a not-a-knot spline
    through 0, 2.5, 5, 5, 5 m at 0, 10, 20, 30, 300 s swung to -158 m in between); its
    acceleration is piecewise continuous. After the table the motion holds its last
    value; the curve's slope there is zero when the table ends on a flat interval (end
    it so, or the end stops abruptly)."""

    end: int
    direction: np.ndarray
    times: np.ndarray
    values: np.ndarray
    periodic: bool = False
    spline: CubicSpline | PchipInterpolator = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        curve = (
            CubicSpline(self.times, self.values, bc_type="periodic")
            if self.periodic
            else PchipInterpolator(self.times, self.values)
        )
        object.__setattr__(self, "spline", curve)

    @property
    def duration(self) -> float:
        return float(self.times[-1] - self.times[0])

    def evaluate(self, t: float) -> tuple[float, float, float]:
        """Displacement [m], velocity [m/s], acceleration [m/s^2] along the direction."""
        if self.periodic:
            t = self.times[0] + (t - self.times[0]) % self.duration
        elif t >= self.times[-1]:
            return float(self.values[-1]), 0.0, 0.0
        return (
            float(self.spline(t)),
            float(self.spline(t, 1)),
            float(self.spline(t, 2)),
        )


@njit(cache=True)
def _harmonics(t, end, direction, amplitude, frequency, phase, out):  # noqa: ANN001, ANN202
    """Add the harmonics' displacement, velocity and acceleration at time ``t`` [s] to
    ``out`` (3, 2, 3): compiled, since the time step calls it once per step."""
    for k in range(amplitude.shape[0]):
        om = 2.0 * math.pi * frequency[k]
        ph = om * t + phase[k]
        s = math.sin(ph)
        c = math.cos(ph)
        e = end[k]
        for a in range(3):
            d = direction[k, a]
            out[0, e, a] += amplitude[k] * s * d
            out[1, e, a] += amplitude[k] * om * c * d
            out[2, e, a] -= amplitude[k] * om * om * s * d


@dataclass(frozen=True, kw_only=True)
class EndMotion:
    """Prescribed motion of both ends about their static positions.

    Parameters
    ----------
    harmonic_end : (k,) end of each harmonic, 0 (A) or 1 (B)
    harmonic_direction : [-] (k, 3) unit directions
    harmonic_amplitude : [m] (k,)
    harmonic_frequency : [Hz] (k,)
    harmonic_phase : [rad] (k,)
    tables : time-table motions
    ramp_time : [s] duration of the smooth start (0: none)
    """

    harmonic_end: np.ndarray
    harmonic_direction: np.ndarray
    harmonic_amplitude: np.ndarray
    harmonic_frequency: np.ndarray
    harmonic_phase: np.ndarray
    tables: tuple[TableMotion, ...] = ()
    ramp_time: float = 0.0

    @property
    def moving_ends(self) -> set[int]:
        ends = {
            int(e)
            for e, a in zip(self.harmonic_end, self.harmonic_amplitude, strict=True)
            if a > 0.0
        }
        return ends | {t.end for t in self.tables}

    def _ramp(self, t: float) -> tuple[float, float, float]:
        tr = self.ramp_time
        if tr <= 0.0 or t >= tr:
            return 1.0, 0.0, 0.0
        if t <= 0.0:
            return 0.0, 0.0, 0.0
        w = math.pi / tr
        c, s = math.cos(w * t), math.sin(w * t)
        return 0.5 * (1.0 - c), 0.5 * w * s, 0.5 * w * w * c

    def unramped(self, t: float) -> np.ndarray:
        """Displacement, velocity, acceleration without the ramp, shape (3, 2, 3):
        [quantity, end, component]."""
        out = np.zeros((3, 2, 3))
        if self.harmonic_amplitude.size:
            _harmonics(
                t,
                self.harmonic_end,
                self.harmonic_direction,
                self.harmonic_amplitude,
                self.harmonic_frequency,
                self.harmonic_phase,
                out,
            )
        for tab in self.tables:
            u, du, ddu = tab.evaluate(t)
            out[0, tab.end] += u * tab.direction
            out[1, tab.end] += du * tab.direction
            out[2, tab.end] += ddu * tab.direction
        return out

    def at(self, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement [m], velocity [m/s], acceleration [m/s^2] of ends A and B at
        time ``t`` [s], each (2, 3), ramp included."""
        raw = self.unramped(t)
        r, dr, ddr = self._ramp(t)
        return (r * raw[0], r * raw[1] + dr * raw[0], r * raw[2] + 2.0 * dr * raw[1] + ddr * raw[0])
