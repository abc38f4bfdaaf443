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
(:meth:`cablestudy.config.study.Study._system_dynamics`).
"""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import AfterValidator, Field, field_validator, model_validator

from .base import FieldError, Finite, NonNegative, Positive, StrictModel, Vec2, Vec3

#: degrees of freedom of a body, in the order of its 6-DOF position
BODY_DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


def _unit(value: list[float]) -> list[float]:
    if math.sqrt(sum(v * v for v in value)) <= 0.0:
        raise ValueError("must be a nonzero vector; allowed: any direction of length > 0")
    return value


def _frequency_or_period(data: object) -> object:
    """Fill ``frequency`` from ``period`` (exactly one of them given)."""
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


def _table_rows(value: list[list[float]]) -> list[list[float]]:
    times = [row[0] for row in value]
    if any(b <= a for a, b in zip(times, times[1:], strict=False)):
        raise ValueError(f"table times must increase strictly, got t = {times}")
    if times[0] != 0.0:
        raise ValueError(f"the table must start at t = 0, got t = {times[0]}")
    return value


def _closed(table: list[list[float]], periodic: bool) -> None:
    if periodic:
        first, last = table[0][1], table[-1][1]
        if abs(last - first) > 1e-9 * max(1.0, abs(first)):
            raise ValueError(
                f"a periodic table must end where it starts: displacement {last} at the "
                f"end, {first} at t = 0"
            )


class BodyHarmonic(StrictModel):
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

    @model_validator(mode="before")
    @classmethod
    def _fill_frequency(cls, data: object) -> object:
        return _frequency_or_period(data)


class BodyTable(StrictModel):
    """Motion of one degree of freedom of a body as a table of (time [s], displacement
    [m] or rotation [rad]) rows, a cubic spline as a line end's table."""

    body: str = Field(description="the body that moves (a key of bodies)")
    dof: Literal["surge", "sway", "heave", "roll", "pitch", "yaw"] = Field(
        description="degree of freedom moved"
    )
    table: list[Vec2] = Field(min_length=4, description="rows [time s, displacement m or rad]")
    periodic: bool = Field(False, description="repeat the table with its duration as period")

    @field_validator("table")
    @classmethod
    def _increasing(cls, value: list[list[float]]) -> list[list[float]]:
        return _table_rows(value)

    @model_validator(mode="after")
    def _closes(self) -> BodyTable:
        _closed(self.table, self.periodic)
        return self


class PointHarmonic(StrictModel):
    """Harmonic motion of a point on its own along ``direction`` (as a line end)."""

    point: str = Field(description="the point that moves (a key of points)")
    direction: Annotated[Vec3, AfterValidator(_unit)] = Field(
        description="direction of the motion [-] (normalised)"
    )
    amplitude: NonNegative = Field(description="amplitude [m]")
    frequency: Positive | None = Field(None, description="frequency [Hz]; or give period")
    period: Positive | None = Field(None, description="period [s], instead of frequency")
    phase_deg: Finite = Field(0.0, description="phase of the sine [deg]")

    @model_validator(mode="before")
    @classmethod
    def _fill_frequency(cls, data: object) -> object:
        return _frequency_or_period(data)


class PointTable(StrictModel):
    """Motion of a point on its own along ``direction`` as a time table."""

    point: str = Field(description="the point that moves (a key of points)")
    direction: Annotated[Vec3, AfterValidator(_unit)] = Field(
        description="direction of the motion [-] (normalised)"
    )
    table: list[Vec2] = Field(min_length=4, description="rows [time s, displacement m]")
    periodic: bool = Field(False, description="repeat the table with its duration as period")

    @field_validator("table")
    @classmethod
    def _increasing(cls, value: list[list[float]]) -> list[list[float]]:
        return _table_rows(value)

    @model_validator(mode="after")
    def _closes(self) -> PointTable:
        _closed(self.table, self.periodic)
        return self


#: the system excitations (a study model checks that a system uses only these, and a
#: one-line study none of them)
SYSTEM_EXCITATIONS = (BodyHarmonic, BodyTable, PointHarmonic, PointTable)
SYSTEM_HARMONICS = (BodyHarmonic, PointHarmonic)
SYSTEM_TABLES = (BodyTable, PointTable)


def system_tag(value: dict) -> str | None:
    """The tag of a system excitation given as a mapping (None: not one)."""
    if "body" in value:
        if "spectrum" in value or "wave_spectrum" in value:
            return "BodySpectrum"
        return "BodyTable" if "table" in value else "BodyHarmonic"
    if "point" in value:
        if "spectrum" in value or "wave_spectrum" in value:
            return "PointSpectrum"
        return "PointTable" if "table" in value else "PointHarmonic"
    return None


def check_system_dynamics(study: object) -> None:
    """Refuse (naming the field, the value and what supports it) what the system time
    domain does not model; resolve every body and point an excitation names. Called by
    the study model for a system with ``analysis.dynamic``."""
    from .analysis import BodySpectrumExcitation, PointSpectrumExcitation  # noqa: PLC0415
    from .system import FreePoint  # noqa: PLC0415

    bodily = (BodyHarmonic, BodyTable, BodySpectrumExcitation)
    kinds = (*SYSTEM_EXCITATIONS, BodySpectrumExcitation, PointSpectrumExcitation)

    dyn = study.analysis.dynamic  # type: ignore[attr-defined]
    points = study.points  # type: ignore[attr-defined]
    bodies = study.bodies  # type: ignore[attr-defined]
    root = ("analysis", "dynamic")
    items = dyn.excitations
    many = isinstance(dyn.excitation, list)

    def at(i: int, key: str) -> tuple:
        return (*root, "excitation", *((i,) if many else ()), key)

    tables: set[tuple[str, str]] = set()
    for i, e in enumerate(items):
        if not isinstance(e, kinds):
            raise FieldError(
                at(i, "end"),
                "a system's motion is given per body degree of freedom (body, dof) or per "
                "point (point, direction), not per line end; allowed: "
                f"body: one of {sorted(bodies) or 'none defined'} with dof: one of "
                f"{list(BODY_DOFS)}, or point: one of {sorted(points)} with direction",
                getattr(e, "end", None),
            )
        if isinstance(e, bodily):
            if e.body not in bodies:
                raise FieldError(
                    at(i, "body"),
                    f"no body of that name; allowed: {sorted(bodies) or 'none defined'}",
                    e.body,
                )
            if bodies[e.body].kind != "prescribed":
                raise FieldError(
                    at(i, "body"),
                    "a free body's own equation of motion is not modelled in the dynamics; "
                    "allowed: a prescribed body (kind: prescribed)",
                    e.body,
                )
            key = (e.body, e.dof)
        else:
            if e.point not in points:
                raise FieldError(
                    at(i, "point"), f"no point of that name; allowed: {sorted(points)}", e.point
                )
            if isinstance(points[e.point], FreePoint):
                raise FieldError(
                    at(i, "point"),
                    "a free point moves by the lines' pull, it cannot be moved as well; "
                    "allowed: a fixed point or a body point",
                    e.point,
                )
            key = (e.point, "point")
        if isinstance(e, SYSTEM_TABLES):
            if key in tables:
                what = f"{e.dof} of body {key[0]}" if key[1] != "point" else f"point {key[0]}"
                raise FieldError(
                    at(i, "table"),
                    f"{what} is already moved by a table; allowed: one table per degree of "
                    "freedom (or per point); add harmonics for more",
                    "table",
                )
            tables.add(key)
    for name, body in bodies.items():
        if body.kind != "prescribed":
            raise FieldError(
                ("bodies", name, "kind"),
                "a free body's own equation of motion is not modelled in the dynamics; "
                "allowed with analysis.dynamic: kind: prescribed (a free body is solved by "
                "analysis.static)",
                body.kind,
            )
    if dyn.method == "frequency":  # the system frequency domain (dynamics/system_frequency)
        for i, e in enumerate(items):
            if not isinstance(e, SYSTEM_HARMONICS):
                raise FieldError(
                    at(i, "spectrum" if hasattr(e, "spectrum") else "table"),
                    "a system's frequency domain solves harmonic motions of one frequency; "
                    "allowed with method 'frequency': body or point harmonics (a spectrum or "
                    "a table is solved by method 'time')",
                    type(e).__name__,
                )
    if dyn.transfer_function is not None:
        raise FieldError(
            (*root, "transfer_function"),
            "transfer_function is not built for a system's frequency domain; allowed for "
            "a system: remove the key (method 'frequency' runs the harmonic response, "
            "'time' the time domain, 'auto' either per case)",
            "transfer_function",
        )
    if "after_break" in dyn.model_fields_set:
        raise FieldError(
            (*root, "after_break"),
            "a system's lines do not part (no failure condition in a system); allowed: "
            "remove the key (it is supported by a one-line study)",
            dyn.after_break,
        )
    hist = dyn.history
    if hist is not None and (hist.points or hist.whole_line):
        key = "points" if hist.points else "whole_line"
        raise FieldError(
            (*root, "history", key),
            "a system keeps the history of each line's end tensions (history_tension_a, "
            "history_tension_b on line and time) and of the body forces; points along a "
            "line and whole-line histories are supported by a one-line study; allowed: "
            "history with periods and samples_per_period",
            getattr(hist, key),
        )


def check_one_line_excitation(study: object) -> None:
    """A one-line study's motions are per line end: a body or point motion needs a
    system."""
    from .analysis import BodySpectrumExcitation, PointSpectrumExcitation  # noqa: PLC0415

    dyn = study.analysis.dynamic  # type: ignore[attr-defined]
    many = isinstance(dyn.excitation, list)
    kinds = (*SYSTEM_EXCITATIONS, BodySpectrumExcitation, PointSpectrumExcitation)
    for i, e in enumerate(dyn.excitations):
        if isinstance(e, kinds):
            key = "body" if hasattr(e, "body") else "point"
            raise FieldError(
                ("analysis", "dynamic", "excitation", *((i,) if many else ()), key),
                f"a {key} motion moves a mooring system (points, bodies, lines); a one-line "
                "study moves its ends: allowed: end: a or b with direction",
                getattr(e, key),
            )
