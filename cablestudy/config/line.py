"""Line make-up: segments from end A to end B, and attachments."""

from __future__ import annotations

import math

from pydantic import Field, model_validator

from .base import FieldError, Finite, NonNegative, Positive, StrictModel, Vec3


class Segment(StrictModel):
    """A uniform length of line. Give ``mass_per_length`` [kg/m] or
    ``weight_in_fluid`` [N/m] (or both: the weight then overrides mass minus
    buoyancy in statics, and the mass is used for inertia)."""

    length: Positive = Field(description="unstretched length [m]")
    diameter: Positive = Field(description="hydrodynamic (and buoyancy) diameter [m]")
    mass_per_length: NonNegative | None = Field(None, description="mass per length [kg/m]")
    weight_in_fluid: Finite | None = Field(None, description="submerged weight per length [N/m]")
    axial_stiffness: Positive = Field(description="axial stiffness EA [N]")
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

    @model_validator(mode="after")
    def _mass_or_weight(self) -> Segment:
        if self.mass_per_length is None and self.weight_in_fluid is None:
            raise ValueError(
                "give mass_per_length [kg/m] or weight_in_fluid [N/m] (neither was given)"
            )
        return self

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
    segments: list[Segment] = Field(min_length=1, max_length=100)
    attachments: list[Attachment] = []

    @property
    def length(self) -> float:
        return float(sum(seg.length for seg in self.segments))

    @model_validator(mode="after")
    def _attachments_inside(self) -> Line:
        total = self.length
        for i, att in enumerate(self.attachments):
            if att.s > total:
                raise FieldError(
                    ("attachments", i, "s"),
                    f"attachment lies beyond the end of the line; allowed 0 <= s <= {total:g} m "
                    "(the total unstretched length of the segments)",
                    att.s,
                )
        return self
