"""Line make-up: segments from end A to end B, and attachments."""

from __future__ import annotations

import math
from typing import Annotated, Literal

from pydantic import Field, model_validator

from .base import FieldError, Finite, NonNegative, Positive, StrictModel, Vec3

#: strain [-] (or extension [m] of a spring) up to which a law given without
#: ``max_strain`` is checked to increase
DEFAULT_MAX_STRAIN = 1.0


class _AxialBase(StrictModel):
    max_strain: Positive | None = Field(
        None,
        description="the law is checked to increase from 0 up to this strain [-] (a "
        "spring: extension [m]); a static solution beyond it fails with a message; a "
        "segment's dynamic tension envelope beyond the law's tension there keeps its "
        "results with a strain warning. "
        "Default: 1.0 for a segment; for a spring the largest extension its ends can "
        "reach (from the end positions and the excitation amplitudes)",
    )


class LinearAxial(_AxialBase):
    """``{law: linear, stiffness}``: T = k e, tension-only (today's ``axial_stiffness``)."""

    law: Literal["linear"] = Field(description="linear: T = stiffness * e")
    stiffness: Positive = Field(
        description="EA [N] in strain (segment), or [N/m] in extension (spring)"
    )

    def build(self):  # type: ignore[no-untyped-def]
        from ..physics.axial import LinearLaw

        return LinearLaw(self.stiffness)


class PolynomialAxial(_AxialBase):
    """``{law: polynomial, coefficients: [A, B, C, D, E]}``: T = A e + B e^2 + ... + E e^5
    (aqwa seed 5.8.1.2), e the strain of a segment or the extension [m] of a spring."""

    law: Literal["polynomial"] = Field(description="polynomial in e")
    coefficients: list[Finite] = Field(
        min_length=1,
        max_length=5,
        description="A, B, ... E of T = A e + B e^2 + ... [N] in strain, or "
        "[N/m], [N/m^2], ... in extension (spring); no constant term",
    )

    def build(self):  # type: ignore[no-untyped-def]
        from ..physics.axial import PolynomialLaw

        return PolynomialLaw(tuple(float(c) for c in self.coefficients))


class SteelWireAxial(_AxialBase):
    """``{law: steel_wire, stiffness, offset}``: T = k (e - d (1 - exp(-e/d))), passing
    through zero with zero slope and tending to k (e - d) (aqwa seed 5.8.1.3; the form
    is justified in :class:`cablestudy.physics.axial.SteelWireLaw`)."""

    law: Literal["steel_wire"] = Field(description="steel wire")
    stiffness: Positive = Field(
        description="asymptotic stiffness k [N] in strain, or [N/m] in extension (spring)"
    )
    offset: Positive = Field(
        description="asymptotic offset d [-] in strain, or [m] in extension (spring)"
    )

    def build(self):  # type: ignore[no-untyped-def]
        from ..physics.axial import SteelWireLaw

        return SteelWireLaw(self.stiffness, self.offset)


class TableAxial(_AxialBase):
    """``{law: table, strain: [...], tension: [...]}``: a monotone tension-strain curve
    through (0, 0), interpolated by monotone cubic Hermite polynomials (PCHIP) and
    continued along the last interval's secant."""

    law: Literal["table"] = Field(description="tabulated curve")
    strain: list[NonNegative] = Field(
        min_length=2,
        max_length=10_000,
        description="strain [-] (spring: extension [m]), strictly increasing, from 0",
    )
    tension: list[NonNegative] = Field(
        min_length=2, max_length=10_000, description="tension [N] at each strain, from 0"
    )

    @model_validator(mode="after")
    def _table(self) -> TableAxial:
        if len(self.strain) != len(self.tension):
            raise FieldError(
                ("tension",),
                f"needs one tension per strain ({len(self.strain)} strains); allowed: "
                "lists of equal length",
                len(self.tension),
            )
        if self.strain[0] != 0.0 or self.tension[0] != 0.0:
            raise FieldError(
                ("strain", 0),
                "the table must start at strain 0 with tension 0 (a tension-only law "
                f"passes through zero; got tension {self.tension[0]:g} N there); allowed: "
                "strain[0] = 0 and tension[0] = 0",
                self.strain[0],
            )
        for i in range(1, len(self.strain)):
            if not self.strain[i] > self.strain[i - 1]:
                raise FieldError(
                    ("strain", i),
                    f"strains must increase strictly (previous {self.strain[i - 1]:g}); "
                    "allowed: > previous strain",
                    self.strain[i],
                )
            if not self.tension[i] > self.tension[i - 1]:
                raise FieldError(
                    ("tension", i),
                    f"tension does not increase at strain {self.strain[i]:g} (previous "
                    f"tension {self.tension[i - 1]:g} N): the law would not be monotone "
                    "there; allowed: > previous tension",
                    self.tension[i],
                )
        return self

    def build(self):  # type: ignore[no-untyped-def]
        from ..physics.axial import TableLaw

        return TableLaw(tuple(self.strain), tuple(self.tension))


#: ``axial: {law: ...}``: one model per law, chosen by ``law``
Axial = Annotated[
    LinearAxial | PolynomialAxial | SteelWireAxial | TableAxial, Field(discriminator="law")
]


def check_axial(axial: Axial, max_strain: float, loc: tuple[str | int, ...], unit: str) -> None:
    """Refuse a law whose tension does not increase over [0, max_strain] (it would turn
    non-monotone or negative there), naming the strain where it happens.

    Raises
    ------
    FieldError
        at ``loc`` + the coefficients (or the law) of ``axial``.
    """
    law = axial.build()
    bad = law.first_decrease(max_strain)
    if bad is None:
        return
    slope = float(law.tangent_stiffness(bad * (1.0 + 1e-9) + 1e-300))
    field = "coefficients" if isinstance(axial, PolynomialAxial) else "law"
    raise FieldError(
        (*loc, field),
        f"the tension stops increasing at {unit} {bad:.6g} (dT/de = {slope:.6g} there), "
        f"inside the range 0 .. {max_strain:g} the case can reach (max_strain), so it "
        "would be non-monotone or negative; allowed: a law with dT/de > 0 over that range",
        getattr(axial, "coefficients", axial.law),
    )


class BreakCondition(StrictModel):
    """``failure: {tension: N}``, ``{minimum_breaking_load: N, safety_factor: f}`` and/or
    ``{time: s}``: the line (or a segment) breaks where its tension exceeds the limit
    (tension, or MBL / safety factor), or at the given time. In statics a case over the
    tension limit is recorded as broken (status 10, a message with where and by how
    much) with its static results kept; in analysis.dynamic
    the time domain parts the line at that instant, or at ``time`` (kind spring: the
    spring; kind catenary: the element that reached its limit, or the most loaded one at
    ``time``), and records break_time (and break_s)."""

    tension: Positive | None = Field(None, description="tension limit [N]")
    minimum_breaking_load: Positive | None = Field(
        None, description="minimum breaking load MBL [N]; the limit is MBL / safety_factor"
    )
    safety_factor: Positive | None = Field(
        None, ge=1.0, description="safety factor on the MBL [-] (>= 1; default 1)"
    )
    time: NonNegative | None = Field(
        None,
        description="time at which the line fails [s] from the start of the run "
        "(analysis.dynamic, time domain)",
    )

    @model_validator(mode="after")
    def _one_limit(self) -> BreakCondition:
        if self.tension is not None and self.minimum_breaking_load is not None:
            raise ValueError(
                "give either tension [N] or minimum_breaking_load [N] (with an optional "
                "safety_factor), not both"
            )
        if self.tension is None and self.minimum_breaking_load is None and self.time is None:
            raise ValueError(
                "give a tension limit (tension [N], or minimum_breaking_load [N] with an "
                "optional safety_factor) and/or a failure time [s]"
            )
        if self.tension is not None and self.safety_factor is not None:
            raise FieldError(
                ("safety_factor",),
                "a safety_factor applies to minimum_breaking_load, not to a tension limit; "
                "allowed: omit it, or give minimum_breaking_load instead of tension",
                self.safety_factor,
            )
        return self

    @property
    def limit(self) -> float:
        """The tension [N] at which the line breaks (inf: no tension limit)."""
        if self.tension is not None:
            return float(self.tension)
        if self.minimum_breaking_load is None:
            return math.inf
        return float(self.minimum_breaking_load) / float(self.safety_factor or 1.0)


class LineType(StrictModel):
    """``line_type: {material, nominal_diameter}``: the segment's diameter, mass, EA,
    breaking load and hydrodynamic coefficients from published rules of thumb
    (:mod:`cablestudy.physics.line_types`, ``cablestudy line-types``). A key the segment
    gives itself wins over the filled one."""

    material: Literal[
        "chain_studless",
        "chain_studlink",
        "wire_six_strand",
        "wire_spiral_strand",
        "polyester",
        "nylon",
        "hmpe",
    ] = Field(description="material of the library (cablestudy line-types lists them)")
    nominal_diameter: Positive = Field(
        description="nominal diameter [m]: a chain's bar diameter, a rope's nominal diameter"
    )
    grade: Literal["R3", "R3S", "R4"] | None = Field(
        None,
        description="chain grade, setting the minimum breaking load (chain_studless and "
        "chain_studlink only; default R3)",
    )

    @model_validator(mode="after")
    def _applies(self) -> LineType:
        from ..physics.line_types import CHAIN_MAX_DIAMETER, MATERIALS

        chains = [k for k, m in MATERIALS.items() if m.chain]
        if self.grade is not None and self.material not in chains:
            raise FieldError(
                ("grade",),
                f"a grade applies to chain (material {' or '.join(chains)}), not to "
                f"{self.material}; allowed: omit it",
                self.grade,
            )
        if self.material in chains and self.nominal_diameter > CHAIN_MAX_DIAMETER:
            raise FieldError(
                ("nominal_diameter",),
                f"the chain breaking-load rule c d^2 (44 - 0.08 d) peaks at d = "
                f"{CHAIN_MAX_DIAMETER:.4f} m and falls beyond it; allowed: "
                f"nominal_diameter <= {CHAIN_MAX_DIAMETER:.4f} m, or give the segment's own "
                "keys without line_type",
                self.nominal_diameter,
            )
        return self

    def properties(self) -> dict[str, float]:
        """The keys this line type fills (SI), see
        :func:`cablestudy.physics.line_types.line_type_properties`."""
        from ..physics.line_types import line_type_properties

        return line_type_properties(self.material, self.nominal_diameter, self.grade)


def fill_line_type(data: dict) -> dict:  # type: ignore[type-arg]
    """The raw segment mapping ``data`` with the keys its valid ``line_type`` fills added
    where the segment does not give them (the segment's own keys win): ``diameter``,
    ``mass_per_length``, ``axial_stiffness`` (not with an ``axial`` law), the hydrodynamic
    coefficients, and ``failure.minimum_breaking_load`` where the segment gives a
    ``failure`` mapping with neither ``tension`` nor ``minimum_breaking_load`` and not
    only a ``time``. An invalid ``line_type`` fills nothing (its own errors are
    reported)."""
    raw = data.get("line_type")
    if raw is None:
        return data
    try:
        props = LineType.model_validate(raw).properties()
    except ValueError:
        return data
    out = dict(data)
    mbl = props.pop("minimum_breaking_load")
    for key, value in props.items():
        if key == "axial_stiffness" and "axial" in data:
            continue
        out.setdefault(key, value)
    failure = data.get("failure")
    if (
        isinstance(failure, dict)
        and "tension" not in failure
        and "minimum_breaking_load" not in failure
        and set(failure) != {"time"}
    ):
        out["failure"] = {**failure, "minimum_breaking_load": mbl}
    return out


class Segment(StrictModel):
    """A uniform length of line. Give ``mass_per_length`` [kg/m] or
    ``weight_in_fluid`` [N/m] (or both: the weight then overrides mass minus
    buoyancy in statics, and the mass is used for inertia). ``line_type`` fills the
    keys the segment does not give from the line-type library."""

    length: Positive = Field(description="unstretched length [m]")
    line_type: LineType | None = Field(
        None,
        description="{material, nominal_diameter, grade}: fills diameter, mass_per_length, "
        "axial_stiffness, drag and added-mass coefficients (and failure."
        "minimum_breaking_load in a failure mapping without a limit) from the line-type "
        "library (cablestudy line-types); keys given in the segment win",
    )
    diameter: Positive | None = Field(
        None,
        description="hydrodynamic (and buoyancy) diameter [m]; required unless line_type gives it",
    )
    mass_per_length: NonNegative | None = Field(None, description="mass per length [kg/m]")
    weight_in_fluid: Finite | None = Field(None, description="submerged weight per length [N/m]")
    axial_stiffness: Positive | None = Field(
        None,
        description="axial stiffness EA [N] of a linear tension-only law (the default "
        "law); exclusive with `axial`",
    )
    axial: Axial | None = Field(
        None,
        description="axial law in strain: {law: linear, stiffness} | {law: polynomial, "
        "coefficients: [A, ..., E]} | {law: steel_wire, stiffness, offset} | {law: table, "
        "strain, tension}; exclusive with `axial_stiffness`",
    )
    failure: BreakCondition | None = Field(
        None,
        description="failure (break) condition of this segment, overriding line.failure "
        "here: {tension: N} or {minimum_breaking_load: N, safety_factor: f}",
    )
    drag_normal: NonNegative = Field(1.2, description="normal drag coefficient [-]")
    drag_tangential: NonNegative = Field(0.01, description="tangential drag coefficient [-]")
    added_mass_normal: NonNegative = Field(1.0, description="normal added-mass coefficient [-]")
    added_mass_tangential: NonNegative = Field(0.0, description="tangential added-mass coeff [-]")
    bending_stiffness: NonNegative = Field(0.0, description="bending stiffness EI [N m^2]")
    damping_ratio: NonNegative = Field(
        0.0, le=1.0, description="axial structural damping, fraction of critical [-]"
    )
    damping_transverse: NonNegative = Field(
        0.0,
        description="transverse structural damping per length [N s/m^2]: a force -c v_n per "
        "length on the velocity normal to the line (the ajayi seed's c); time and frequency "
        "domain",
    )

    @model_validator(mode="before")
    @classmethod
    def _line_type(cls, data: object) -> object:
        return fill_line_type(data) if isinstance(data, dict) else data

    @model_validator(mode="after")
    def _mass_or_weight(self) -> Segment:
        if self.diameter is None:
            raise FieldError(
                ("diameter",),
                "required key 'diameter' is missing (hydrodynamic (and buoyancy) diameter "
                "[m]); or give line_type: {material, nominal_diameter}",
                None,
            )
        if self.mass_per_length is None and self.weight_in_fluid is None:
            raise ValueError(
                "give mass_per_length [kg/m] or weight_in_fluid [N/m] (neither was given)"
            )
        if self.axial is not None and self.axial_stiffness is not None:
            raise FieldError(
                ("axial",),
                "give either axial_stiffness (a linear EA [N]) or axial (a law), not both",
                self.axial.law,
            )
        if self.axial is None and self.axial_stiffness is None:
            raise FieldError(
                ("axial_stiffness",),
                "required key 'axial_stiffness' is missing: axial stiffness EA [N] of a "
                "linear law; or give axial: {law: ...} instead",
                None,
            )
        if self.axial is not None:
            check_axial(
                self.axial, self.axial.max_strain or DEFAULT_MAX_STRAIN, ("axial",), "strain"
            )
        return self

    def axial_law(self):  # type: ignore[no-untyped-def]  # -> physics.axial.AxialLaw
        """The segment's axial law (:mod:`cablestudy.physics.axial`)."""
        if self.axial is not None:
            return self.axial.build()
        from ..physics.axial import LinearLaw

        return LinearLaw(float(self.axial_stiffness))  # type: ignore[arg-type]

    @property
    def elastic_stiffness(self) -> float:
        """EA [N] of a linear law (``axial_stiffness`` or ``{law: linear}`` or a polynomial
        with only A); the reference (initial or asymptotic) stiffness of another law."""
        if self.axial_stiffness is not None:
            return float(self.axial_stiffness)
        return float(self.axial_law().reference_stiffness)

    @property
    def is_nonlinear(self) -> bool:
        """True when the axial law is not T = EA e."""
        from ..physics.axial import is_effectively_linear

        return self.axial is not None and not is_effectively_linear(self.axial.build())

    @property
    def area(self) -> float:
        """Displaced cross-section area pi d^2 / 4 [m^2] (inf, not an OverflowError
        that would escape validation, for an absurd diameter)."""
        return math.pi * self.diameter * self.diameter / 4.0

    def mass_in(self, density: float, gravity: float) -> float:
        """Structural mass per length [kg/m]: as given, or weight / g + density * area.

        Parameters
        ----------
        density : float  [kg/m^3]
            Fluid density.
        gravity : float  [m/s^2]
        """
        if self.mass_per_length is not None:
            return self.mass_per_length
        assert self.weight_in_fluid is not None
        return self.weight_in_fluid / gravity + density * self.area

    def weight_in(self, density: float, gravity: float) -> float:
        """Weight per length in the fluid [N/m] (positive down): as given, or
        (mass - density * area) * g."""
        if self.weight_in_fluid is not None:
            return self.weight_in_fluid
        return (self.mass_in(density, gravity) - density * self.area) * gravity


class Attachment(StrictModel):
    """A point load, clump weight or buoy at unstretched arc length ``s`` from A."""

    s: NonNegative = Field(description="position along the line from end A [m]")
    force: Vec3 = Field([0.0, 0.0, 0.0], description="constant applied force [N]")
    mass: NonNegative = Field(0.0, description="lumped mass [kg] (weight and inertia)")
    volume: NonNegative = Field(0.0, description="displaced volume [m^3] (buoyancy)")
    added_mass: NonNegative = Field(
        0.0, description="isotropic added mass of the body [kg] (dynamic analyses)"
    )
    drag_area: NonNegative = Field(
        0.0,
        description="drag coefficient times projected area C_D A [m^2] of the body: isotropic "
        "quadratic drag 1/2 rho C_D A |U| U on the relative velocity (time domain)",
    )
    name: str | None = None


class Pulley(StrictModel):
    """A pulley the line passes over (aqwa seed 5.8.1.1): a fixed point; the line's
    tensions on its two sides satisfy T_large / T_small <= factor^(wrap / 180 deg) (the
    seed's friction factor, given for a 180-degree wrap; 1: frictionless). A kind: spring
    line is straight between pulleys; a kind: catenary line hangs as a catenary between
    them (statics: the frictionless equilibrium, see cablestudy/statics/pulley.py)."""

    position: Vec3 = Field(description="position of the pulley [m]")
    friction_factor: Finite = Field(
        1.0,
        ge=1.0,
        description="T_large / T_small at which the line slides for a 180-degree wrap [-] "
        "(>= 1; 1: frictionless); scaled as factor^(wrap angle / 180 deg)",
    )


class Winch(StrictModel):
    """A winch (aqwa seed 5.8.1: linear and polynomial cables can be winched): in the
    time domain of analysis.dynamic the unstretched length changes at ``speed`` [m/s]
    (positive: paid out, longer) from ``start`` to ``stop`` [s]; on a kind: catenary
    line at end A, as the length of its first element. The statics ignore it."""

    speed: Finite = Field(description="rate of change of the unstretched length [m/s]")
    start: NonNegative = Field(0.0, description="time the winch starts [s]")
    stop: Positive | None = Field(None, description="time the winch stops [s]; omit: never")

    def paid_out(self, t: float) -> float:
        """Change of the unstretched length [m] by time ``t`` [s]."""
        end = t if self.stop is None else min(t, self.stop)
        return self.speed * max(end - self.start, 0.0)


class MoorDynLineRef(StrictModel):
    """``line: {moordyn: path, line: N}``: the line is read from a MoorDyn input file (or
    a RAFT/MoorPy mooring YAML) when the study is loaded, into segments and attachments,
    so a sweep can vary them (``line.segments.0.length``). The environment and the ends
    stay those of the study."""

    moordyn: str = Field(
        min_length=1,
        description="MoorDyn input file or RAFT/MoorPy mooring YAML, relative to the study "
        "file's folder and inside it",
    )
    line: int | str | list[int | str] | None = Field(
        None,
        description="MoorDyn line ID(s) (or mooring-YAML line names) forming the line end "
        "to end; omit: all lines of the file",
    )


class Line(StrictModel):
    """The line: ``kind: catenary`` (default), uniform segments from end A to end B with
    attachments, or ``kind: spring``, a massless straight tension-only cable of
    unstretched ``length`` whose ``axial`` law gives the tension [N] of its extension [m]
    (aqwa seed 5.8.1.1-5.8.1.3: linear, polynomial and steel-wire cables)."""

    kind: Literal["catenary", "spring"] = Field(
        "catenary",
        description="catenary: segments with weight (statics, modal, dynamics); spring: a "
        "massless straight tension-only cable between the ends (length + axial)",
    )
    segments: list[Segment] = Field(
        [], max_length=100, description="kind catenary: segments from end A to end B"
    )
    attachments: list[Attachment] = []
    pulleys: list[Pulley] = Field(
        [],
        max_length=2,
        description="up to two fixed pulleys the line passes over, from end A to end B (both "
        "ends fixed)",
    )
    winch: Winch | None = Field(
        None,
        description="analysis.dynamic (time domain) only: the unstretched length changes "
        "at a speed [m/s] from start to stop [s]; kind catenary: at end A (the first "
        "element's length, its mass per metre kept); the statics ignore it (the state "
        "before it runs), modal analysis is about that static state, method frequency "
        "refuses it",
    )
    length: Positive | None = Field(
        None,
        description="kind spring: unstretched length [m]; kind catenary: the total of the "
        "segments' lengths (filled in; if given it must equal that total)",
    )
    failure: BreakCondition | None = Field(
        None,
        description="failure (break) condition of the whole line: {tension: N} or "
        "{minimum_breaking_load: N, safety_factor: f} (a segment's own failure overrides "
        "it); statics: a case over the limit is recorded as broken (status 10, data kept); "
        "time domain: parts at that instant (break_time, break_s; "
        "analysis.dynamic.after_break); method frequency refuses it",
    )
    axial: Axial | None = Field(
        None,
        description="kind spring: tension [N] in the extension e [m] = distance between "
        "the ends - length: {law: linear, stiffness [N/m]} | {law: polynomial, "
        "coefficients [N/m], [N/m^2], ...} | {law: steel_wire, stiffness [N/m], offset "
        "[m]} | {law: table, strain: extensions [m], tension [N]}",
    )

    @property
    def total_length(self) -> float:
        """Unstretched length of the whole line [m]."""
        if self.kind == "spring":
            return float(self.length or 0.0)
        return float(sum(seg.length for seg in self.segments))

    @property
    def is_spring(self) -> bool:
        return self.kind == "spring"

    @model_validator(mode="after")
    def _attachments_inside(self) -> Line:
        if self.kind == "spring":
            for key in ("segments", "attachments"):
                if getattr(self, key):
                    raise FieldError(
                        (key,),
                        f"a kind: spring line is massless and straight: it has no {key}; "
                        "allowed: length and axial only (use kind: catenary for segments)",
                        len(getattr(self, key)),
                    )
            for key in ("length", "axial"):
                if getattr(self, key) is None:
                    raise FieldError(
                        (key,),
                        f"a kind: spring line needs '{key}' (unstretched length [m] and "
                        "axial law in extension)",
                        None,
                    )
            return self
        if not self.segments:
            raise FieldError(
                ("segments",),
                "a kind: catenary line needs at least one segment; allowed: 1 to 100 "
                "segments (or kind: spring with length and axial)",
                [],
            )
        if self.axial is not None:
            raise FieldError(
                ("axial",),
                "'axial' belongs to a kind: spring line; a catenary line takes its axial "
                "law per segment (line.segments.N.axial)",
                "axial",
            )
        total = self.total_length
        if self.length is not None and abs(self.length - total) > 1e-12 * total:
            raise FieldError(
                ("length",),
                "'length' of a kind: catenary line is the sum of its segments' lengths "
                f"({total:g} m); give the lengths per segment (line.segments.N.length)",
                self.length,
            )
        # ``line.length`` reads as the total unstretched length for either kind
        object.__setattr__(self, "length", total)
        for i, att in enumerate(self.attachments):
            if att.s > total:
                raise FieldError(
                    ("attachments", i, "s"),
                    f"attachment lies beyond the end of the line; allowed 0 <= s <= {total:g} m "
                    "(the total unstretched length of the segments)",
                    att.s,
                )
        return self
