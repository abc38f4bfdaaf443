"""Prescribed end motion: sums of harmonics and time tables, started smoothly.

The displacement of an end from its static position is ``r(t) d(t)``, where ``d`` is
the sum of the motions given for that end and the ramp ``r`` rises from 0 to 1 as
``r = (1 - cos(pi t / t_r)) / 2`` over ``t_r``: with ``r(0) = r'(0) = 0`` the end
starts at rest, so the start-up transient is small. Velocity and acceleration follow
by the product rule (both continuous). The ramp starts the repeating motions
(harmonics, spectral lines, periodic tables); a non-periodic table starts at 0 (its
first displacement, checked in the study) and is added as written, unramped.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numba import njit

if TYPE_CHECKING:  # imported where a table is built: a harmonic-only run never loads it
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
        from scipy.interpolate import CubicSpline, PchipInterpolator

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

    def __post_init__(self) -> None:
        args = (
            np.asarray(self.harmonic_end, dtype=np.int64),
            np.asarray(self.harmonic_direction, dtype=float).reshape(-1, 3),
            np.asarray(self.harmonic_amplitude, dtype=float),
            np.asarray(self.harmonic_frequency, dtype=float),
            np.asarray(self.harmonic_phase, dtype=float),
            float(self.ramp_time),
            *table_args([t.end for t in self.tables], self.tables),
        )
        object.__setattr__(self, "_kernel_args", args)

    def kernel_args(self) -> tuple:
        """The motion as the arrays :func:`motion_at` takes (harmonics, ramp, tables as
        piecewise cubics)."""
        return self._kernel_args  # type: ignore[attr-defined]

    def at(self, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Displacement [m], velocity [m/s], acceleration [m/s^2] of ends A and B at
        time ``t`` [s], each (2, 3), ramp included."""
        out = np.zeros((3, 2, 3))
        motion_at(t, *self.kernel_args(), out)
        return out[0], out[1], out[2]


def table_args(owners: list[int], tables: Sequence[TableMotion]) -> tuple:
    """Time tables as the arrays :func:`motion_at` takes: what each moves (``owners``:
    its end, or its motion slot), its direction, periodic flag and last value, and the
    piecewise cubics (all breakpoints, all coefficients, each table's offsets into
    them)."""
    xs = [np.asarray(t.spline.x, dtype=float) for t in tables]
    xo = np.cumsum([0] + [x.size for x in xs])
    co = np.cumsum([0] + [x.size - 1 for x in xs])
    return (
        np.array(owners, dtype=np.int64),
        np.array([t.direction for t in tables], dtype=float).reshape(-1, 3),
        np.array([t.periodic for t in tables], dtype=np.bool_),
        np.array([t.values[-1] for t in tables], dtype=float),
        np.concatenate(xs) if xs else np.zeros(0),
        np.concatenate([t.spline.c for t in tables], axis=1) if tables else np.zeros((4, 0)),
        xo.astype(np.int64),
        co.astype(np.int64),
    )


@njit(cache=True)
def _table(t, k, periodic, last, xs, cs, xo, co):  # noqa: ANN001, ANN202
    """Displacement, velocity, acceleration of table ``k`` (a piecewise cubic, the
    table's spline) at ``t`` [s]: wrapped into the period when periodic, the last value
    held after a non-periodic table's end, extrapolated before its start."""
    x0 = xs[xo[k]]
    x1 = xs[xo[k + 1] - 1]
    if periodic[k]:
        t = x0 + (t - x0) % (x1 - x0)
    elif t >= x1:
        return last[k], 0.0, 0.0
    lo = xo[k]
    hi = xo[k + 1] - 2  # last interval's left breakpoint
    i = lo
    if t >= xs[hi]:
        i = hi
    elif t > xs[lo]:
        a, b = lo, hi
        while b - a > 1:  # xs[a] <= t < xs[b]
            m = (a + b) // 2
            if xs[m] <= t:
                a = m
            else:
                b = m
        i = a
    j = co[k] + (i - lo)
    d = t - xs[i]
    c0, c1, c2, c3 = cs[0, j], cs[1, j], cs[2, j], cs[3, j]
    return (
        ((c0 * d + c1) * d + c2) * d + c3,
        (3.0 * c0 * d + 2.0 * c1) * d + c2,
        6.0 * c0 * d + 2.0 * c1,
    )


@njit(cache=True)
def motion_at(  # noqa: ANN201
    t,
    h_end,
    h_dir,
    h_amp,
    h_freq,
    h_phase,
    ramp_time,
    tab_end,
    tab_dir,
    tab_periodic,
    tab_last,
    tab_x,
    tab_c,
    tab_xo,
    tab_co,
    out,
):  # noqa: ANN001
    """Displacement, velocity and acceleration of ends A and B at ``t`` [s], ramp
    included, into ``out`` (3, 2, 3) [quantity, end, component] (overwritten): the
    harmonics and the tables of :class:`EndMotion`'s :meth:`~EndMotion.kernel_args`.
    A system's motion slots take the same call with ``out`` (3, slots, 3) and the slot
    of each harmonic and table in place of its end
    (:func:`.system_kernels.drives_at`)."""
    for q in range(3):
        for e in range(out.shape[1]):
            for a in range(3):
                out[q, e, a] = 0.0
    _harmonics(t, h_end, h_dir, h_amp, h_freq, h_phase, out)
    _add_tables(
        t, True, tab_end, tab_dir, tab_periodic, tab_last, tab_x, tab_c, tab_xo, tab_co, out
    )
    tr = ramp_time
    if tr > 0.0 and t < tr:
        if t <= 0.0:
            r = dr = ddr = 0.0
        else:
            w = math.pi / tr
            c, s = math.cos(w * t), math.sin(w * t)
            r, dr, ddr = 0.5 * (1.0 - c), 0.5 * w * s, 0.5 * w * w * c
        for e in range(out.shape[1]):
            for a in range(3):
                u, du, ddu = out[0, e, a], out[1, e, a], out[2, e, a]
                out[0, e, a] = r * u
                out[1, e, a] = r * du + dr * u
                out[2, e, a] = r * ddu + 2.0 * dr * du + ddr * u
    # a non-periodic table is the motion as written (it starts at 0, the static
    # position: study/system_dynamics.py), not ramped: a ramp of ramp_periods x the
    # run's period (the duration, when nothing repeats) scaled it, so the end never
    # reached the table's displacement within the run
    _add_tables(
        t, False, tab_end, tab_dir, tab_periodic, tab_last, tab_x, tab_c, tab_xo, tab_co, out
    )


@njit(cache=True)
def _add_tables(  # noqa: ANN202
    t, periodic, tab_end, tab_dir, tab_periodic, tab_last, tab_x, tab_c, tab_xo, tab_co, out
):  # noqa: ANN001
    """Add the tables whose periodic flag is ``periodic`` to ``out`` (as
    :func:`motion_at`)."""
    for k in range(tab_end.shape[0]):
        if tab_periodic[k] != periodic:
            continue
        u, du, ddu = _table(t, k, tab_periodic, tab_last, tab_x, tab_c, tab_xo, tab_co)
        e = tab_end[k]
        for a in range(3):
            d = tab_dir[k, a]
            out[0, e, a] += u * d
            out[1, e, a] += du * d
            out[2, e, a] += ddu * d
