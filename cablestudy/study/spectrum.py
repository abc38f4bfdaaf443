"""Excitation by a motion spectrum: a given motion spectrum, or a wave spectrum (JONSWAP)
times a motion RAO, for a line end, a body's degree of freedom or a point."""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import AfterValidator, Field, field_validator, model_validator

from .base import Positive, StrictModel, Vec2, Vec3, unit_direction


class Jonswap(StrictModel):
    """JONSWAP wave spectrum (DNV-RP-C205 3.5.5): significant wave height, peak
    period and peak enhancement factor."""

    hs: Positive = Field(description="significant wave height [m]")
    tp: Positive = Field(description="peak period [s]")
    gamma: float = Field(3.3, ge=1.0, le=7.0, description="peak enhancement factor [-]")

    def density(self, f: float) -> float:
        """Wave elevation spectral density [m^2/Hz] at frequency ``f`` [Hz]."""
        if f <= 0.0:
            return 0.0
        w, wp = 2.0 * math.pi * f, 2.0 * math.pi / self.tp
        sigma = 0.07 if w <= wp else 0.09
        pm = 5.0 / 16.0 * self.hs**2 * wp**4 * w**-5 * math.exp(-1.25 * (w / wp) ** -4)
        peak = self.gamma ** math.exp(-0.5 * ((w - wp) / (sigma * wp)) ** 2)
        return (1.0 - 0.287 * math.log(self.gamma)) * pm * peak * 2.0 * math.pi


def _interp(table: list[list[float]], f: float) -> float:
    """Linear interpolation in a (x, y) table, zero outside it."""
    xs = [r[0] for r in table]
    if f < xs[0] or f > xs[-1]:
        return 0.0
    i = max(j for j in range(len(xs)) if xs[j] <= f)
    if i == len(xs) - 1:
        return table[-1][1]
    w = (f - xs[i]) / (xs[i + 1] - xs[i])
    return (1.0 - w) * table[i][1] + w * table[i + 1][1]


class SpectrumExcitation(StrictModel):
    """Irregular motion of one end along ``direction``: a one-sided displacement spectral
    density S(f) [m^2/Hz], either given as a table ``spectrum`` of (frequency [Hz],
    density [m^2/Hz]) rows, or as a JONSWAP wave spectrum ``wave_spectrum`` times the
    squared motion RAO ``rao`` (rows of frequency [Hz] and displacement per wave
    amplitude [m/m]); tables are interpolated linearly, zero outside. It is represented
    by ``components`` spectral lines ``f_k = k df``, ``df = f_max / components``
    (``f_max`` the last frequency of the table or the RAO), of amplitude
    ``sqrt(2 S(f_k) df)``: the frequency domain sums their responses (variance), the
    time domain runs the realisation with random phases drawn with ``seed``; it repeats
    after ``1 / df``."""

    end: Literal["a", "b"] = Field(description="the end that moves")
    direction: Annotated[Vec3, AfterValidator(unit_direction)] = Field(
        description="direction of the motion [-] (normalised)"
    )
    spectrum: list[Vec2] | None = Field(
        None,
        min_length=2,
        description="rows [frequency Hz, displacement spectral density m^2/Hz]",
    )
    wave_spectrum: Jonswap | None = Field(None, description="JONSWAP waves (with rao)")
    rao: list[Vec2] | None = Field(
        None, min_length=2, description="rows [frequency Hz, motion per wave amplitude m/m]"
    )
    components: int = Field(64, ge=4, le=4096, description="spectral lines [-]")
    seed: int = Field(0, ge=0, description="seed of the random phases (time domain) [-]")
    storm_duration: Positive = Field(
        10800.0, description="duration of the most probable maximum (frequency domain) [s]"
    )

    @field_validator("spectrum", "rao")
    @classmethod
    def _valid_table(cls, value: list[list[float]] | None) -> list[list[float]] | None:
        if value is None:
            return value
        freqs = [row[0] for row in value]
        if any(b <= a for a, b in zip(freqs, freqs[1:], strict=False)) or freqs[0] < 0.0:
            raise ValueError(f"frequencies must be >= 0 and increase strictly, got {freqs}")
        if any(row[1] < 0.0 for row in value) or not any(row[1] > 0.0 for row in value):
            raise ValueError("values must be >= 0 and not all zero")
        return value

    @model_validator(mode="after")
    def _one_form(self) -> SpectrumExcitation:
        table = self.spectrum is not None
        waves = self.wave_spectrum is not None or self.rao is not None
        if table == waves or (waves and (self.wave_spectrum is None or self.rao is None)):
            raise ValueError(
                "give either spectrum (a displacement density table) or wave_spectrum "
                "together with rao; allowed: one of the two forms"
            )
        return self

    @property
    def f_max(self) -> float:
        table = self.spectrum if self.spectrum is not None else self.rao
        assert table is not None
        return table[-1][0]

    @property
    def line_frequencies(self) -> list[float]:
        df = self.f_max / self.components
        return [df * k for k in range(1, self.components + 1)]

    def density(self, f: float) -> float:
        """Displacement spectral density [m^2/Hz] at ``f`` [Hz]."""
        if self.spectrum is not None:
            return _interp(self.spectrum, f)
        assert self.wave_spectrum is not None and self.rao is not None
        return self.wave_spectrum.density(f) * _interp(self.rao, f) ** 2

    @property
    def line_amplitudes(self) -> list[float]:
        """Amplitudes [m] of the spectral lines: sqrt(2 S(f_k) df)."""
        df = self.f_max / self.components
        return [math.sqrt(2.0 * self.density(f) * df) for f in self.line_frequencies]


#: why a system's spectrum refuses a line end's keys, and what it takes instead
_NOT_A_LINE_END = {
    "end": (
        "a system's motion names a body (body, dof) or a point (point, direction), not a "
        "line end; allowed: remove end"
    ),
    "direction": (
        "a body's motion spectrum moves it in its degree of freedom (dof), not along a "
        "direction; allowed: remove direction (a point moved on its own by a spectrum "
        "takes point and direction)"
    ),
}


class BodySpectrumExcitation(SpectrumExcitation):
    """Irregular motion of one degree of freedom of a body of a system (issue 24): the
    spectrum of a line end's motion (a density table, or JONSWAP waves times the
    degree of freedom's RAO, m/m or rad/m), the same spectral lines and seeded phases."""

    end: None = Field(None, description="(a line end's key: a body moves by dof)")
    direction: None = Field(None, description="(a line end's key: a body moves by dof)")
    body: str = Field(description="the body that moves (a key of bodies)")
    dof: Literal["surge", "sway", "heave", "roll", "pitch", "yaw"] = Field(
        description="degree of freedom moved [m or rad]"
    )

    @field_validator("end", "direction", mode="before")
    @classmethod
    def _line_end_keys(cls, value: object, info: object) -> object:
        # said in words: pydantic's own text was "must be None"
        if value is not None:
            raise ValueError(_NOT_A_LINE_END[info.field_name])  # type: ignore[attr-defined]
        return value


class PointSpectrumExcitation(SpectrumExcitation):
    """Irregular motion of a point of a system on its own along ``direction``: the
    spectrum of a line end's motion."""

    end: None = Field(None, description="(a line end's key: a point moves by name)")
    point: str = Field(description="the point that moves (a key of points)")

    @field_validator("end", mode="before")
    @classmethod
    def _line_end_key(cls, value: object) -> object:
        if value is not None:
            raise ValueError(_NOT_A_LINE_END["end"])
        return value
