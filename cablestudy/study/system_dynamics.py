"""Excitation of a mooring system in the dynamics: a body moved in its degrees of
freedom, or a point moved on its own.

```yaml
analysis:
  dynamic:
    excitation:     # one entry or a list (several degrees of freedom at once)
      - {body: platform, dof: surge, amplitude: 2.0, frequency: 0.1, phase_deg: 0.0}
      - {body: platform, dof: pitch, table: [[0, 0.0], [5, 0.02], [10, 0.0], [15, 0.0]],
         periodic: true}
      - {point: fair1, direction: [1, 0, 0], amplitude: 0.5, frequency: 0.2}
```

A body's motion is the sum of its entries per degree of freedom (surge, sway, heave
[m]; roll, pitch, yaw [rad]) about its static position; every point on it follows the
exact rigid-body motion (rotation R = Rz(yaw) Ry(pitch) Rx(roll), not small-angle). A
point's own motion (a fixed point or a body point) moves it along ``direction`` about
its static position, as a line end's motion does. The references (which body, which
point) are checked by the study model, which knows the system's names
(:meth:`cablestudy.study.study.Study._system_dynamics`).
"""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import AfterValidator, Field, field_validator, model_validator

from .base import (
    FieldError,
    Finite,
    NonNegative,
    Positive,
    StrictModel,
    Vec2,
    Vec3,
    unit_direction,
)

#: degrees of freedom of a body, in the order of its 6-DOF position
BODY_DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


class HarmonicMotion(StrictModel):
    """The check shared by the harmonic motions (of an end, a body or a point): exactly one
    of ``frequency`` and ``period``, a period filling frequency = 1 / period."""

    @model_validator(mode="before")
    @classmethod
    def _fill_frequency(cls, data: object) -> object:
        if not isinstance(data, dict):
            return data
        has_f = data.get("frequency") is not None
        has_t = data.get("period") is not None
        if has_f and has_t:
            raise FieldError(
                ("period",),
                f"give the excitation frequency [Hz] or its period [s], not both (frequency "
                f"{data['frequency']!r} is given too); allowed: exactly one of them",
                data["period"],
            )
        if not has_f and not has_t:
            raise FieldError(
                ("frequency",),
                "required key 'frequency' is missing (excitation frequency [Hz]); or give "
                "period [s] instead",
                None,
            )
        period = data.get("period")
        if has_t and isinstance(period, int | float) and not isinstance(period, bool):
            if math.isfinite(period) and period > 0.0:
                return {**data, "frequency": 1.0 / period}
        return data


class TableMotion(StrictModel):
    """The checks shared by the time-table motions (of an end, a body or a point): the
    ``table``'s times start at 0 and increase strictly; a ``periodic`` table ends where
    it starts; a non-periodic one starts at displacement 0 (it moves as written, not
    ramped)."""

    @field_validator("table", check_fields=False)
    @classmethod
    def _increasing(cls, value: list[list[float]]) -> list[list[float]]:
        times = [row[0] for row in value]
        if any(b <= a for a, b in zip(times, times[1:], strict=False)):
            raise ValueError(f"table times must increase strictly, got t = {times}")
        if times[0] != 0.0:
            raise ValueError(f"the table must start at t = 0, got t = {times[0]}")
        return value

    @model_validator(mode="after")
    def _closes(self) -> TableMotion:
        first, last = self.table[0][1], self.table[-1][1]  # type: ignore[attr-defined]
        if self.periodic:  # type: ignore[attr-defined]
            if abs(last - first) > 1e-9 * max(1.0, abs(first)):
                raise ValueError(
                    f"a periodic table must end where it starts: displacement {last} at the "
                    f"end, {first} at t = 0"
                )
        elif first != 0.0:
            # a non-periodic table moves as written, without the ramp of the repeating
            # motions (dynamics/excitation.py): it starts at the static position
            raise ValueError(
                f"a non-periodic table starts at the static position: its displacement at "
                f"t = 0 must be 0, got {first}; allowed: 0 (or periodic: true, which the "
                "ramp starts smoothly)"
            )
        return self


class BodyHarmonic(HarmonicMotion):
    """Harmonic motion of one degree of freedom of a body about its static position:
    ``amplitude * sin(2 pi frequency t + phase)``."""

    body: str = Field(description="the body that moves (a key of bodies)")
    dof: Literal["surge", "sway", "heave", "roll", "pitch", "yaw"] = Field(
        description="degree of freedom moved"
    )
    amplitude: NonNegative = Field(description="amplitude [m] (surge/sway/heave) or [rad]")
    frequency: Positive | None = Field(None, description="frequency [Hz]; or give period")
    period: Positive | None = Field(None, description="period [s], instead of frequency")
    phase_deg: Finite = Field(0.0, description="phase of the sine [deg]")


class BodyTable(TableMotion):
    """Motion of one degree of freedom of a body as a table of (time [s], displacement
    [m] or rotation [rad]) rows, a cubic spline as a line end's table."""

    body: str = Field(description="the body that moves (a key of bodies)")
    dof: Literal["surge", "sway", "heave", "roll", "pitch", "yaw"] = Field(
        description="degree of freedom moved"
    )
    table: list[Vec2] = Field(min_length=4, description="rows [time s, displacement m or rad]")
    periodic: bool = Field(False, description="repeat the table with its duration as period")


class PointHarmonic(HarmonicMotion):
    """Harmonic motion of a point on its own along ``direction`` (as a line end)."""

    point: str = Field(description="the point that moves (a key of points)")
    direction: Annotated[Vec3, AfterValidator(unit_direction)] = Field(
        description="direction of the motion [-] (normalised)"
    )
    amplitude: NonNegative = Field(description="amplitude [m]")
    frequency: Positive | None = Field(None, description="frequency [Hz]; or give period")
    period: Positive | None = Field(None, description="period [s], instead of frequency")
    phase_deg: Finite = Field(0.0, description="phase of the sine [deg]")


class PointTable(TableMotion):
    """Motion of a point on its own along ``direction`` as a time table."""

    point: str = Field(description="the point that moves (a key of points)")
    direction: Annotated[Vec3, AfterValidator(unit_direction)] = Field(
        description="direction of the motion [-] (normalised)"
    )
    table: list[Vec2] = Field(min_length=4, description="rows [time s, displacement m]")
    periodic: bool = Field(False, description="repeat the table with its duration as period")


#: the system excitations (a study model checks that a system uses only these, and a
#: one-line study none of them)
SYSTEM_EXCITATIONS = (BodyHarmonic, BodyTable, PointHarmonic, PointTable)
SYSTEM_HARMONICS = (BodyHarmonic, PointHarmonic)
SYSTEM_TABLES = (BodyTable, PointTable)


def system_tag(value: dict) -> str | None:
    """The tag of a system excitation given as a mapping (None: not one)."""
    if "body" in value:
        if "spectrum" in value or "wave_spectrum" in value:
            return "BodySpectrumExcitation"  # the class name: error paths drop it
        return "BodyTable" if "table" in value else "BodyHarmonic"
    if "point" in value:
        if "spectrum" in value or "wave_spectrum" in value:
            return "PointSpectrumExcitation"
        return "PointTable" if "table" in value else "PointHarmonic"
    return None
