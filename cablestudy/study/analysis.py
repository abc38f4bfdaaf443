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

from .base import (
    Finite,
    NonNegative,
    Positive,
    StrictModel,
    Vec2,
    Vec3,
    unit_direction,
)
from .spectrum import BodySpectrumExcitation, PointSpectrumExcitation, SpectrumExcitation
from .system_dynamics import (
    SYSTEM_HARMONICS,
    SYSTEM_TABLES,
    BodyHarmonic,
    BodyTable,
    HarmonicMotion,
    PointHarmonic,
    PointTable,
    TableMotion,
    system_tag,
)


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


#: static methods a study may name, and what each is (the registry
#: ``cablestudy.statics.STATIC_SOLVERS`` holds the same names; a test keeps them equal;
#: the solvers are not imported here so that validating a study stays light)
STATIC_METHODS = {
    "analytic": "exact elastic catenary of a uniform line between fixed ends (linear "
    "EA; no current, attachments or non-linear law)",
    "catenary": "semi-analytic elastic catenary (dodaran-park): seabed, point loads, "
    "axial laws, current by drag elements",
    "discrete": "equilibrium of the dynamic line model's nodes: bending stiffness EI, "
    "compliant seabed, bodies' drag",
    "shooting": "elevation/azimuth ODE (vaz-patel): sheared currents, seabed slope, "
    "laying, stretched drag diameter",
}


class StaticSettings(StrictModel):
    method: str = Field(
        "catenary",
        description="static solver: "
        + "; ".join(f"{name}: {what}" for name, what in STATIC_METHODS.items()),
        json_schema_extra={"enum": list(STATIC_METHODS)},
    )
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
    strain_warning: Positive = Field(
        0.05,
        le=10.0,
        description="plausibility limit of the static strain [-]: a case whose largest "
        "strain along the line (T / EA, or the axial law's strain; kind spring: extension "
        "/ length) exceeds it keeps status 0 and gets a warning (a law's max_strain still "
        "fails the case); a dynamic analysis's tension envelope is held to it too (a "
        "warning, the case keeps status 0)",
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
    "auto": "per case: 'frequency' where the linear answer can be trusted "
    "(analysis.dynamic.auto), else 'time'",
    "time": "implicit time integration of the discretised line",
    "frequency": "linearised about the static shape, harmonic response per excitation "
    "frequency, drag linearised (cablestudy.dynamics.frequency)",
}

#: settings of the time integration only: refused with method 'frequency'
TIME_ONLY_KEYS = (
    "points_per_period",
    "max_refinement",
    "tension_resolution",
    "spectral_radius",
    "newton_tolerance",
    "max_newton_iterations",
    "ramp_periods",
    "steady_tolerance",
    "step_tolerance",
    "steady_window",
    "min_periods",
    "max_periods",
    "period",
    "duration",
    "history",
    "after_break",
)

#: the steady-state detection's settings: unused by a run of fixed ``duration``
STEADY_KEYS = ("steady_tolerance", "steady_window", "min_periods", "max_periods")


class LinearisationSettings(StrictModel):
    """Drag linearisation of the frequency-domain method (methods 'frequency' and
    'auto'): the equivalent damping is iterated until the nodal velocity amplitudes
    change by less than ``tolerance`` of the largest."""

    tolerance: Positive = Field(
        1e-6, le=1e-2, description="relative change of the velocity amplitudes [-]"
    )
    max_iterations: int = Field(100, ge=1, le=10_000, description="drag iterations at most")
    samples: int | None = Field(
        None,
        ge=8,
        le=4096,
        description="phases per period in the drag fit (describing function) at every "
        "node; unset: every node without current is fitted in closed form (exact), the "
        "others over 32 phases (in closed form too where motion, tangent and current lie in "
        "the x-z plane)",
    )


class AutoSettings(StrictModel):
    """When ``method: auto`` trusts the frequency domain (all must hold), else it runs
    the time domain. Defaults from the study in docs/frequency-domain.md (the Figs. 2-5
    sweep and the chain mooring run by both methods: where these pick the frequency
    domain, max and min tension agree with the time domain within 1 % on Figs. 2-5 and
    1.25 % on the chain, against the 2 % asked for)."""

    min_tension_ratio: float = Field(
        0.7,
        ge=0.0,
        le=1.0,
        description="smallest (static - amplitude) / static element tension along the line "
        "[-]; below it the line nears slack",
    )
    max_amplitude_sag_ratio: NonNegative = Field(
        0.075,
        description="largest nodal displacement amplitude over the static sag (largest "
        "distance of the line from its end chord) [-]; above it geometry is nonlinear",
    )
    max_touchdown_travel: NonNegative = Field(
        0.03,
        description="largest estimated touchdown-point travel amplitude (catenary: touchdown "
        "tension amplitude x height / vertical tension at the top of the suspended stretch) "
        "over the line length [-]; above it the held laid nodes misrepresent the line (chain "
        "mooring: the difference to the time domain grows as the travel squared, about 1.5 % "
        "at 0.043)",
    )


class HarmonicExcitation(HarmonicMotion):
    """Harmonic motion of one end about its static position:
    ``amplitude * sin(2 pi frequency t + phase) * direction / |direction|``. Give the
    ``frequency`` [Hz] or the ``period`` [s] (exactly one; either can be swept): a period
    fills frequency = 1 / period."""

    end: Literal["a", "b"] = Field(description="the end that moves")
    direction: Annotated[Vec3, AfterValidator(unit_direction)] = Field(
        description="direction of the motion [-] (normalised)"
    )
    amplitude: NonNegative = Field(description="excitation amplitude [m]")
    frequency: Positive | None = Field(
        None,
        description="excitation frequency [Hz]; or give period instead (exactly one)",
    )
    period: Positive | None = Field(
        None,
        description="excitation period [s], instead of frequency (exactly one): frequency = "
        "1 / period",
    )
    phase_deg: Finite = Field(0.0, description="phase of the sine [deg]")


class TimeSeriesExcitation(TableMotion):
    """Motion of one end along ``direction`` given as a table of (time [s], displacement
    [m]) pairs, interpolated by a cubic spline (continuous acceleration). With
    ``periodic`` the table repeats with its duration as period (the last displacement
    must equal the first); otherwise it starts at displacement 0, moves as written (not
    ramped: ``ramp_periods`` starts the repeating motions) and holds its last value after
    the table."""

    end: Literal["a", "b"] = Field(description="the end that moves")
    direction: Annotated[Vec3, AfterValidator(unit_direction)] = Field(
        description="direction of the motion [-] (normalised)"
    )
    table: list[Vec2] = Field(min_length=4, description="rows [time s, displacement m]")
    periodic: bool = Field(False, description="repeat the table with its duration as period")


def _excitation_tag(value: Any) -> str:
    if isinstance(value, dict):
        tag = system_tag(value)  # a system's body or point motion
        if tag is not None:
            return tag
        if "spectrum" in value or "wave_spectrum" in value:
            return "SpectrumExcitation"
        return "TimeSeriesExcitation" if "table" in value else "HarmonicExcitation"
    return type(value).__name__


Excitation = Annotated[
    Annotated[HarmonicExcitation, Tag("HarmonicExcitation")]
    | Annotated[TimeSeriesExcitation, Tag("TimeSeriesExcitation")]
    | Annotated[SpectrumExcitation, Tag("SpectrumExcitation")]
    | Annotated[BodyHarmonic, Tag("BodyHarmonic")]
    | Annotated[BodyTable, Tag("BodyTable")]
    | Annotated[PointHarmonic, Tag("PointHarmonic")]
    | Annotated[PointTable, Tag("PointTable")]
    | Annotated[BodySpectrumExcitation, Tag("BodySpectrumExcitation")]
    | Annotated[PointSpectrumExcitation, Tag("PointSpectrumExcitation")],
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
    periods: Positive = Field(
        2.0,
        description="length of the kept record [periods]; a run to steady state lasts at "
        "least that many periods after the ramp, and a record longer than the run "
        "(duration, or max_periods after the ramp) is refused",
    )
    samples_per_period: int = Field(64, ge=4, le=10_000, description="samples per period")
    whole_line: bool = Field(
        False,
        description="also keep position, velocity and effective tension along the whole "
        "line (history_line_position, history_line_velocity, history_line_tension on time "
        "and s): at the static output points, so analysis.static.nodes decimates them "
        "along the line and samples_per_period in time",
    )


class EvenRange(StrictModel):
    """``num`` equally spaced values from ``start`` to ``stop`` (both included, stop above
    start): what :class:`FrequencyRange` and :class:`GridAxis` share."""

    start: float
    stop: float
    num: int

    @model_validator(mode="after")
    def _ordered(self) -> EvenRange:
        if self.stop <= self.start:
            raise ValueError(
                f"stop must exceed start; allowed: stop > {self.start} (got {self.stop})"
            )
        return self

    @property
    def values(self) -> list[float]:
        step = (self.stop - self.start) / (self.num - 1)
        return [float(f"{self.start + i * step:.15g}") for i in range(self.num)]


class FrequencyRange(EvenRange):
    """Frequencies [Hz] from ``start`` to ``stop`` (included), ``num`` of them."""

    start: Positive = Field(description="lowest frequency [Hz]")
    stop: Positive = Field(description="highest frequency [Hz]")
    num: int = Field(200, ge=2, le=100_000, description="number of frequencies [-]")


#: periods a time-domain run may last at most (max_periods, and duration over the
#: slowest harmonic's period)
MAX_PERIODS = 100_000


class DynamicSettings(StrictModel):
    """Time-domain dynamics about the static shape under prescribed end motion.

    ``excitation`` is one motion or a list of motions summed (harmonics at either or both
    ends, or time tables). The run lasts until the per-period maximum and minimum end
    tension change by less than ``steady_tolerance`` (relative to the period's dynamic
    range, maximum - minimum; a change below the Newton tolerance counts as none) over
    ``steady_window`` consecutive periods, or ``max_periods`` periods; with
    ``duration`` it lasts that long instead and steady-state detection is off.
    """

    excitation: ExcitationOrList = Field(description="prescribed end motion")
    method: str = Field(
        "auto",
        description="dynamic method: "
        + "; ".join(f"{name}: {what}" for name, what in DYNAMIC_METHODS.items()),
        json_schema_extra={"enum": list(DYNAMIC_METHODS)},
    )
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
        2.0,
        description="smooth start of the repeating motions (harmonics, spectra, periodic "
        "tables) over this many periods [periods]; a non-periodic table moves as written",
    )
    steady_tolerance: Positive = Field(
        0.002,
        le=0.5,
        description="steady state: change of the per-period max and min tension, relative "
        "to the period's dynamic range (max - min) [-]",
    )
    step_tolerance: Positive = Field(
        0.01,
        le=1.0,
        description="step check of the time domain: where the last period has seabed "
        "landings or lift-offs or slack-taut switches, it is run again at half the step; its "
        "end-tension extremes must agree within this fraction of the period's dynamic range, "
        "else the case carries a 'step' warning [-]",
    )
    steady_window: int = Field(2, ge=1, le=100, description="periods that must agree")
    min_periods: int = Field(3, ge=1, description="periods run after the ramp at least")
    max_periods: int = Field(80, ge=1, le=MAX_PERIODS, description="periods run at most")
    period: Positive | None = Field(
        None,
        description="steady-state period [s]; default: the longest harmonic or "
        "periodic-table period",
    )
    duration: Positive | None = Field(
        None,
        description="fixed run time [s] (no steady-state detection); at most 100000 periods "
        "of the slowest harmonic motion",
    )
    after_break: Literal["continue", "stop"] = Field(
        "continue",
        description="with line.failure, time domain of a kind: catenary line: after the "
        "line parts, continue (the parts move on, no steady-state detection, to duration "
        "or max_periods) or stop the run at the break",
    )
    history: HistorySettings | None = None
    linearisation: LinearisationSettings | None = Field(
        None, description="drag linearisation (methods frequency and auto); omit: defaults"
    )
    auto: AutoSettings | None = Field(None, description="thresholds of method auto; omit: defaults")
    transfer_function: FrequencyRange | None = Field(
        None,
        description="methods frequency and auto: also write the end and line tension per unit "
        "excitation amplitude at these frequencies, on a 'frequency' dimension",
    )

    @field_validator("method")
    @classmethod
    def _known_dynamic_method(cls, value: str) -> str:
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
        harmonic = any(isinstance(e, (HarmonicExcitation, *SYSTEM_HARMONICS)) for e in items)
        periodic = any(
            isinstance(e, (TimeSeriesExcitation, *SYSTEM_TABLES)) and e.periodic for e in items
        ) or any(isinstance(e, SpectrumExcitation) for e in items)
        # method frequency refuses tables itself (_keys_of_the_method): advising it
        # duration or period here, keys it refuses too, would send the user in a circle
        if (
            not (harmonic or periodic)
            and self.period is None
            and self.duration is None
            and self.method != "frequency"
        ):
            raise ValueError(
                "excitation has no period (only non-periodic tables): give "
                "analysis.dynamic.duration [s] or analysis.dynamic.period [s]"
            )
        frequencies = [f for e in items if (f := getattr(e, "frequency", None))]
        if self.duration is not None and frequencies:
            # the same bound as max_periods: a run of more periods of its slowest
            # harmonic than that only reaches the per-case time limit
            periods = self.duration * min(frequencies)
            if periods > MAX_PERIODS:
                raise ValueError(
                    f"duration: {self.duration:g} s is {periods:.3g} periods of the slowest "
                    f"harmonic motion ({min(frequencies):g} Hz); allowed: at most "
                    f"{MAX_PERIODS} periods (as max_periods)"
                )
        return self

    @model_validator(mode="after")
    def _keys_of_the_method(self) -> DynamicSettings:
        method = self.method
        if method == "frequency":
            given = [k for k in TIME_ONLY_KEYS if k in self.model_fields_set]
            if given:
                raise ValueError(
                    f"{', '.join(given)}: used by the time domain only, not by method "
                    "'frequency'; allowed: method 'time' or 'auto' (or remove the key)"
                )
            items = self.excitations
            spectra = [e for e in items if isinstance(e, SpectrumExcitation)]
            if spectra and len(items) != 1:
                raise ValueError(
                    "method 'frequency' solves harmonic motions of one frequency, or one "
                    "spectrum alone; allowed: one spectrum, or method 'time'"
                )
            harmonic = (HarmonicExcitation, *SYSTEM_HARMONICS)  # a system's too (issue 24)
            if not spectra and not all(isinstance(e, harmonic) for e in items):
                raise ValueError(
                    "method 'frequency' needs harmonic excitation or a spectrum (a time table "
                    "is solved by method 'time'); allowed: harmonic motions of one frequency, "
                    "or one spectrum"
                )
            freqs = {e.frequency for e in items if isinstance(e, harmonic)}
            if len(freqs) > 1:
                raise ValueError(
                    f"method 'frequency' solves one excitation frequency per case (got "
                    f"{sorted(freqs)} Hz); allowed: harmonic motions of one frequency, or "
                    "method 'time'"
                )
        if method == "time":
            for key in ("linearisation", "transfer_function"):
                if key in self.model_fields_set:
                    raise ValueError(
                        f"{key}: used by methods 'frequency' and 'auto', not by method "
                        "'time'; allowed: method 'frequency' or 'auto' (or remove the key)"
                    )
        if self.auto is not None and method != "auto":
            raise ValueError(
                f"auto: thresholds of method 'auto', not used by method {method!r}; allowed: "
                "method 'auto' (or remove the key)"
            )
        if (
            self.linearisation is not None
            and self.linearisation.samples is not None
            and any(isinstance(e, SpectrumExcitation) for e in self.excitations)
        ):
            raise ValueError(
                f"linearisation.samples: {self.linearisation.samples} sets the phases of the "
                "harmonic drag fit; a spectrum's drag is linearised statistically (Gauss-"
                "Hermite over the velocity's distribution), which has no phases; allowed: "
                "remove samples, or harmonic excitation"
            )
        if self.transfer_function is not None and not all(  # a system's: system_checks
            isinstance(e, (HarmonicExcitation, *SYSTEM_HARMONICS)) for e in self.excitations
        ):
            raise ValueError(
                "transfer_function: needs harmonic excitation (the tension per unit amplitude "
                "of a harmonic end motion); allowed: harmonic motions"
            )
        return self

    @model_validator(mode="after")
    def _keys_left_unused(self) -> DynamicSettings:
        """Keys that this run's settings leave unused: the steady-state keys when a fixed
        ``duration`` switches the steady-state detection off, a spectrum's
        ``storm_duration`` (the frequency domain's most probable maximum) in the time
        domain and its ``seed`` (the time domain's random phases) in the frequency
        domain. Only keys the study gives are refused (never a default)."""
        if self.duration is not None:
            given = [k for k in STEADY_KEYS if k in self.model_fields_set]
            if given:
                values = ", ".join(f"{k} {getattr(self, k)!r}" for k in given)
                raise ValueError(
                    f"{', '.join(given)}: steady-state settings, unused with duration "
                    f"{self.duration:g} s (the run lasts that long and no steady state is "
                    f"detected) (got {values}); allowed: remove duration (steady-state "
                    "detection) or these keys"
                )
        unused = {"time": "storm_duration", "frequency": "seed"}.get(self.method)
        for e in self.excitations:
            if unused is not None and unused in e.model_fields_set:
                used_by = (
                    "the frequency domain's most probable maximum"
                    if unused == "storm_duration"
                    else "the time domain's random phases"
                )
                allowed = "'frequency' or 'auto'" if unused == "storm_duration" else "'time'"
                raise ValueError(
                    f"excitation.{unused}: sets {used_by}, not used by method "
                    f"{self.method!r} (got {getattr(e, unused)!r}); allowed: method "
                    f"{allowed} (or remove the key)"
                )
        return self

    @model_validator(mode="after")
    def _history_within_the_run(self) -> DynamicSettings:
        """A kept record that fits in the run: within a fixed ``duration``, else within
        ``max_periods`` after the ramp (a steady-state run lasts at least the record's
        periods after the ramp: :attr:`settle_periods`). A longer record would start
        before t = 0 (samples of the state at rest, not of the motion)."""
        if self.history is None or self.method == "frequency":
            return self  # method frequency refuses history (_keys_of_the_method)
        period = self.period if self.period is not None else steady_period(self.excitations)
        if period is None:
            return self  # only non-periodic tables: the run (duration) is the period
        if self.duration is not None:
            longest, what = self.duration / period, f"the run, duration {self.duration:g} s"
            allowed = "or a longer duration"
        else:
            longest = self.max_periods - self.ramp_periods
            what = (
                f"the longest run after the ramp, max_periods {self.max_periods} - "
                f"ramp_periods {self.ramp_periods:g}"
            )
            allowed = "or a larger max_periods"
        if self.history.periods > longest * (1.0 + 1e-9):
            raise ValueError(
                f"history.periods: {self.history.periods:g} periods of {period:g} s is longer "
                f"than {what}: the record would start before the motion (got "
                f"{self.history.periods:g}); allowed: history.periods <= {longest:.6g}, "
                f"{allowed}"
            )
        return self

    @property
    def settle_periods(self) -> int:
        """Periods a steady-state run lasts at least after the ramp: ``min_periods``, or
        the kept record's whole periods where ``history`` asks for more (so that the
        record lies in the motion, not before it)."""
        if self.history is None:
            return self.min_periods
        return max(self.min_periods, math.ceil(self.history.periods - 1e-9))

    @property
    def excitations(self) -> list[HarmonicExcitation | TimeSeriesExcitation | SpectrumExcitation]:
        return list(self.excitation) if isinstance(self.excitation, list) else [self.excitation]


class GridAxis(EvenRange):
    """``num`` equally spaced values from ``start`` to ``stop`` (both included), in the
    unit of the key (m, or deg for ``angle_deg``)."""

    start: Finite = Field(description="first value [m, or deg for angle_deg]")
    stop: Finite = Field(description="last value [m, or deg for angle_deg]")
    num: int = Field(ge=4, le=2000, description="number of values (>= 4: bicubic) [-]")


#: the keys of each database grid: (first axis, second axis)
DATABASE_GRID_KEYS: dict[str, tuple[str, str]] = {
    "cartesian": ("horizontal_distance", "height_difference"),
    "radial": ("distance", "angle_deg"),
}


class DatabaseSettings(StrictModel):
    """The quasi-static database (aqwa seed 5.8.1.4): the static line solved over a grid
    of end-B positions relative to end A (fixed), in the vertical plane through A and the
    study's end B. ``grid: cartesian`` (default) tabulates horizontal distance and height
    difference; ``grid: radial`` (the seed's grid for lines off the seabed) the distance
    from A to B and the angle of the chord A-B above the horizontal. Written to the
    study's dataset (``database_*``) and to ``<name>.database.nc``; ``cablestudy lookup``
    and :func:`cablestudy.analyses.database.open_database` interpolate it (C1 bicubic)."""

    grid: Literal["cartesian", "radial"] = Field(
        "cartesian",
        description="cartesian: horizontal_distance x height_difference; radial (lines "
        "off the seabed, no environment.depth): distance x angle_deg",
    )
    horizontal_distance: GridAxis | None = Field(
        None, description="grid cartesian: horizontal distance from end A to end B [m] (>= 0)"
    )
    height_difference: GridAxis | None = Field(
        None, description="grid cartesian: height of end B above end A, z_B - z_A [m]"
    )
    distance: GridAxis | None = Field(
        None, description="grid radial: distance from end A to end B, |r_B - r_A| [m] (> 0)"
    )
    angle_deg: GridAxis | None = Field(
        None,
        description="grid radial: angle of the chord from A to B above the horizontal "
        "[deg] (-90 .. 90)",
    )

    @model_validator(mode="after")
    def _grid_keys(self) -> DatabaseSettings:
        wanted = DATABASE_GRID_KEYS[self.grid]
        for kind, keys in DATABASE_GRID_KEYS.items():
            for key in keys:
                given = getattr(self, key) is not None
                if kind != self.grid and given:
                    raise ValueError(
                        f"{key}: an axis of grid {kind!r}, not of grid {self.grid!r}; "
                        f"allowed with grid {self.grid!r}: {', '.join(wanted)}"
                    )
                if kind == self.grid and not given:
                    raise ValueError(
                        f"{key}: required by grid {self.grid!r} (its axes: {', '.join(wanted)})"
                    )
        if self.horizontal_distance is not None and self.horizontal_distance.start < 0.0:
            raise ValueError(
                "horizontal_distance.start must be >= 0 (a distance; the direction is that "
                f"from end A to end B) (got {self.horizontal_distance.start})"
            )
        if self.distance is not None and self.distance.start <= 0.0:
            raise ValueError(
                "distance.start must be > 0 (the angle of B about A is undefined at A itself) "
                f"(got {self.distance.start})"
            )
        if self.angle_deg is not None and not (
            -90.0 <= self.angle_deg.start and self.angle_deg.stop <= 90.0
        ):
            raise ValueError(
                "angle_deg must lie in -90 .. 90 (above the horizontal, towards the study's "
                f"end B) (got {self.angle_deg.start} .. {self.angle_deg.stop})"
            )
        return self

    @property
    def axes(self) -> tuple[GridAxis, GridAxis]:
        """The grid's two axes, in the order of :data:`DATABASE_GRID_KEYS`."""
        a, b = (getattr(self, k) for k in DATABASE_GRID_KEYS[self.grid])
        assert a is not None and b is not None
        return a, b


class Analysis(StrictModel):
    static: StaticSettings = StaticSettings()
    database: DatabaseSettings | None = Field(
        None,
        description="quasi-static database of end forces, laid length and tension over a "
        "grid of end-B positions relative to end A; omit: none",
    )
    modal: ModalSettings | None = Field(
        None, description="modal analysis about the static shape; omit: none"
    )
    time_limit: Positive = Field(
        600.0, description="wall-time limit per case [s]; a case over it fails with a message"
    )
    dynamic: DynamicSettings | None = Field(
        None,
        description="dynamics under prescribed end motion (time or frequency domain); "
        "omit: statics only",
    )


def steady_period(excitations: list[Any]) -> float | None:
    """The steady-state period [s] of a list of motions (``analysis.dynamic.period``'s
    default): the longest of the harmonics' periods, a spectrum's repeat period 1 / df
    and a periodic table's duration; None when there are only non-periodic tables."""
    periods = []
    for e in excitations:
        frequency = getattr(e, "frequency", None)
        if frequency:
            periods.append(1.0 / frequency)
        elif isinstance(e, SpectrumExcitation) or hasattr(e, "line_frequencies"):
            periods.append(1.0 / e.line_frequencies[0])
        elif getattr(e, "periodic", False):
            periods.append(float(e.table[-1][0] - e.table[0][0]))
    return max(periods) if periods else None
