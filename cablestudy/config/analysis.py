"""Analysis settings: statics, modal analysis, dynamics and the per-case time limit."""

from __future__ import annotations

import math
from typing import Annotated, Any, Literal

from pydantic import (
    AfterValidator,
    Discriminator,
    Field,
    Tag,
    field_validator,
    model_validator,
)

from .base import Finite, NonNegative, Positive, StrictModel, Vec2, Vec3


class Installation(StrictModel):
    """Steady cable laying (vaz-patel seed, eqs. 3b-4c): the laying frame (ship and
    touchdown point) moves at a constant horizontal velocity and the cable is paid out
    along itself from end B towards end A (A is the touchdown end)."""

    payout_speed: Finite = Field(
        0.0, description="speed of the cable along itself from end B towards end A [m/s]"
    )
    touchdown_velocity: Vec2 = Field(
        [0.0, 0.0], description="horizontal velocity of the ship and touchdown point [m/s]"
    )


class StaticSettings(StrictModel):
    method: str = Field("catenary", description="static solver (see `cablestudy schema`)")
    nodes: int = Field(101, ge=2, le=100_000, description="output points along the line")
    tolerance: Positive = Field(1e-9, le=1e-2, description="relative tolerance [-]")
    max_iterations: int = Field(100, ge=1, le=100_000)
    drag_elements: int | None = Field(
        None,
        ge=1,
        le=100_000,
        description="drag elements along the line (method catenary, with current); "
        "default: nodes - 1, at least 20",
    )
    installation: Installation | None = Field(
        None, description="steady cable laying; omit for a line at rest (static)"
    )
    drag_diameter: Literal["unstretched", "stretched"] = Field(
        "unstretched",
        description="diameter in the static drag law: 'unstretched' d (dodaran-park), or "
        "'stretched' d (1 + e)^(-1/2), thinned as the line stretches at constant volume "
        "(vaz-patel; method shooting); matters only with current or laying",
    )

    @field_validator("method")
    @classmethod
    def _known_method(cls, value: str) -> str:
        from ..statics import STATIC_SOLVERS

        if value not in STATIC_SOLVERS:
            raise ValueError(
                f"unknown static method {value!r}; allowed: {', '.join(sorted(STATIC_SOLVERS))}"
            )
        return value


class ModalSettings(StrictModel):
    """Natural frequencies and mode shapes about the static shape
    (:mod:`cablestudy.dynamics.modal`)."""

    modes: int = Field(10, ge=1, le=1000, description="number of lowest modes [-]")
    elements: int | None = Field(
        None,
        ge=2,
        le=100_000,
        description="bar elements of the modal model [-]; omit: max(100, 20 * modes)",
    )
    mesh: Literal["graded", "uniform"] = Field(
        "graded",
        description="element lengths: 'graded' to equal transverse-wave travel time "
        "(short where the tension is low), or 'uniform' in arc length",
    )
    include_added_mass: bool = Field(
        True, description="add the fluid's added mass (normal, and tangential if given)"
    )
    include_bending: bool = Field(True, description="add the segments' bending stiffness EI")
    mode_shapes: bool = Field(True, description="write mode shapes (mode, s, component)")

    @model_validator(mode="after")
    def _enough_freedom(self) -> ModalSettings:
        n = self.n_elements
        if 3 * (n - 1) < self.modes:
            raise ValueError(
                f"elements = {n} gives at most {3 * (n - 1)} degrees of freedom but modes = "
                f"{self.modes}; allowed: elements >= {-(-self.modes // 3) + 1} for this many modes"
            )
        return self

    @property
    def n_elements(self) -> int:
        """Elements used: as given, or max(100, 20 * modes) (lumped-mass elements converge
        as h^2; on a graded mesh 20 elements per mode keep the highest string mode within
        about (pi / 20)^2 / 24 = 0.1 %)."""
        if self.elements is not None:
            return self.elements
        return min(max(100, 20 * self.modes), 100_000)


# ------------------------------------------------------------------ dynamics
# (time-domain response to prescribed end motion; see cablestudy.dynamics)

#: dynamic methods a study may name, and what each means
DYNAMIC_METHODS = {
    "auto": "choose per case (currently always 'time')",
    "time": "implicit time integration of the discretised line",
}


def _unit_direction(value: list[float]) -> list[float]:
    norm = math.sqrt(sum(v * v for v in value))
    if norm == 0.0:
        raise ValueError("must be a nonzero vector; allowed: any direction of length > 0")
    return value


class HarmonicExcitation(StrictModel):
    """Harmonic motion of one end about its static position:
    ``amplitude * sin(2 pi frequency t + phase) * direction / |direction|``."""

    end: Literal["a", "b"] = Field(description="the end that moves")
    direction: Annotated[Vec3, AfterValidator(_unit_direction)] = Field(
        description="direction of the motion [-] (normalised)"
    )
    amplitude: NonNegative = Field(description="excitation amplitude [m]")
    frequency: Positive = Field(description="excitation frequency [Hz]")
    phase_deg: Finite = Field(0.0, description="phase of the sine [deg]")


class TimeSeriesExcitation(StrictModel):
    """Motion of one end along ``direction`` given as a table of (time [s], displacement
    [m]) pairs, interpolated by a cubic spline (continuous acceleration). With
    ``periodic`` the table repeats with its duration as period (the last displacement
    must equal the first); otherwise the motion holds its last value after the table."""

    end: Literal["a", "b"] = Field(description="the end that moves")
    direction: Annotated[Vec3, AfterValidator(_unit_direction)] = Field(
        description="direction of the motion [-] (normalised)"
    )
    table: list[Vec2] = Field(min_length=4, description="rows [time s, displacement m]")
    periodic: bool = Field(False, description="repeat the table with its duration as period")

    @field_validator("table")
    @classmethod
    def _increasing(cls, value: list[list[float]]) -> list[list[float]]:
        times = [row[0] for row in value]
        if any(b <= a for a, b in zip(times, times[1:], strict=False)):
            raise ValueError(f"table times must increase strictly, got t = {times}")
        if times[0] != 0.0:
            raise ValueError(f"the table must start at t = 0, got t = {times[0]}")
        return value

    @model_validator(mode="after")
    def _closes(self) -> TimeSeriesExcitation:
        if self.periodic:
            first, last = self.table[0][1], self.table[-1][1]
            if abs(last - first) > 1e-9 * max(1.0, abs(first)):
                raise ValueError(
                    f"a periodic table must end where it starts: displacement {last} at the "
                    f"end, {first} at t = 0"
                )
        return self


def _excitation_tag(value: Any) -> str:
    if isinstance(value, dict):
        return "TimeSeriesExcitation" if "table" in value else "HarmonicExcitation"
    return type(value).__name__


Excitation = Annotated[
    Annotated[HarmonicExcitation, Tag("HarmonicExcitation")]
    | Annotated[TimeSeriesExcitation, Tag("TimeSeriesExcitation")],
    Discriminator(_excitation_tag),
]


def _one_or_many(value: Any) -> str:
    # tag names with brackets are dropped from error paths by the loader
    return "list[motions]" if isinstance(value, list) else "single[motion]"


#: one motion, or a list of motions that add up (errors report only the form given)
ExcitationOrList = Annotated[
    Annotated[Excitation, Tag("single[motion]")]
    | Annotated[list[Excitation], Tag("list[motions]")],
    Discriminator(_one_or_many),
]


class HistorySettings(StrictModel):
    """Time histories to keep, resampled uniformly over the last periods of the run."""

    points: list[NonNegative] = Field(
        [], description="arc lengths from end A of the points whose motion is kept [m]"
    )
    periods: Positive = Field(2.0, description="length of the kept record [periods]")
    samples_per_period: int = Field(64, ge=4, le=10_000, description="samples per period")


class DynamicSettings(StrictModel):
    """Time-domain dynamics about the static shape under prescribed end motion.

    ``excitation`` is one motion or a list of motions summed (harmonics at either or both
    ends, or time tables). The run lasts until the per-period maximum and minimum end
    tension change by less than ``steady_tolerance`` (relative to the period's maximum)
    over ``steady_window`` consecutive periods, or ``max_periods`` periods; with
    ``duration`` it lasts that long instead and steady-state detection is off.
    """

    excitation: ExcitationOrList = Field(description="prescribed end motion")
    method: str = Field("auto", description="auto | time (frequency-domain: later)")
    elements: int = Field(80, ge=2, le=10_000, description="elements of the dynamic model")
    points_per_period: int = Field(
        64, ge=8, le=100_000, description="time steps per period of the fastest harmonic"
    )
    max_refinement: int = Field(
        6, ge=0, le=12, description="step halvings allowed around slack-taut transitions"
    )
    tension_resolution: Positive = Field(
        0.2,
        le=10.0,
        description="largest end-tension change in one step, relative to the static "
        "tension [-]; a larger change halves the step (snap loads)",
    )
    spectral_radius: float = Field(
        0.3,
        ge=0.0,
        le=1.0,
        description="generalised-alpha high-frequency spectral radius [-] (1: no damping)",
    )
    newton_tolerance: Positive = Field(
        1e-7, le=1e-2, description="Newton force residual relative to the static tension [-]"
    )
    max_newton_iterations: int = Field(12, ge=2, le=200)
    ramp_periods: NonNegative = Field(
        2.0, description="smooth start of the motion over this many periods [periods]"
    )
    steady_tolerance: Positive = Field(
        0.002, le=0.5, description="steady state: change of per-period max and min tension [-]"
    )
    steady_window: int = Field(2, ge=1, le=100, description="periods that must agree")
    min_periods: int = Field(3, ge=1, description="periods run after the ramp at least")
    max_periods: int = Field(80, ge=1, le=100_000, description="periods run at most")
    period: Positive | None = Field(
        None,
        description="steady-state period [s]; default: the longest harmonic or "
        "periodic-table period",
    )
    duration: Positive | None = Field(
        None, description="fixed run time [s] (no steady-state detection)"
    )
    history: HistorySettings | None = None

    @field_validator("method")
    @classmethod
    def _known_dynamic_method(cls, value: str) -> str:
        if value == "frequency":
            raise ValueError(
                "method 'frequency' (frequency-domain linearised dynamics) "
                f"is not available in this version; allowed: {', '.join(DYNAMIC_METHODS)}"
            )
        if value not in DYNAMIC_METHODS:
            raise ValueError(
                f"unknown dynamic method {value!r}; allowed: {', '.join(DYNAMIC_METHODS)}"
            )
        return value

    @model_validator(mode="after")
    def _period_known(self) -> DynamicSettings:
        items = self.excitation if isinstance(self.excitation, list) else [self.excitation]
        if not items:
            raise ValueError("excitation: list at least one motion")
        harmonic = any(isinstance(e, HarmonicExcitation) for e in items)
        periodic = any(isinstance(e, TimeSeriesExcitation) and e.periodic for e in items)
        if not (harmonic or periodic) and self.period is None and self.duration is None:
            raise ValueError(
                "excitation has no period (only non-periodic tables): give "
                "analysis.dynamic.duration [s] or analysis.dynamic.period [s]"
            )
        return self

    @property
    def excitations(self) -> list[HarmonicExcitation | TimeSeriesExcitation]:
        return list(self.excitation) if isinstance(self.excitation, list) else [self.excitation]


class Analysis(StrictModel):
    static: StaticSettings = StaticSettings()
    modal: ModalSettings | None = Field(
        None, description="modal analysis about the static shape; omit: none"
    )
    time_limit: Positive = Field(
        600.0, description="wall-time limit per case [s]; a case over it fails with a message"
    )
    dynamic: DynamicSettings | None = Field(
        None, description="time-domain dynamics under prescribed end motion; omit: statics only"
    )
