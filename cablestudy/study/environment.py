"""Environment of a study: fluid, gravity, water depth, seabed and current profile."""

from __future__ import annotations

import math
from typing import Annotated, Any, Literal

from pydantic import (
    Discriminator,
    Field,
    Tag,
    ValidationError,
    ValidatorFunctionWrapHandler,
    WrapValidator,
    field_validator,
)

from .base import FieldError, Finite, NonNegative, Positive, StrictModel

#: Densities of the named fluids [kg/m^3].
FLUID_DENSITY = {"air": 1.225, "water": 1025.0, "vacuum": 0.0}


class CustomFluid(StrictModel):
    """A fluid given by its density (0 for vacuum)."""

    density: NonNegative = Field(description="fluid density [kg/m^3]; 0 for vacuum")


def _fluid_form(value: Any) -> str:
    # tag names with brackets are dropped from error paths by the loader, so an error
    # names only the form given: a fluid name, or a mapping {density}
    return "mapping[fluid]" if isinstance(value, dict | CustomFluid) else "name[fluid]"


def _fluid_name(value: Any, handler: ValidatorFunctionWrapHandler) -> Any:
    try:
        return handler(value)
    except ValidationError:
        raise ValueError(
            "must be 'air', 'water' or 'vacuum', or a mapping {density: <kg/m^3>}"
        ) from None


#: a named fluid or a mapping {density}
Fluid = Annotated[
    Annotated[Literal["air", "water", "vacuum"], WrapValidator(_fluid_name), Tag("name[fluid]")]
    | Annotated[CustomFluid, Tag("mapping[fluid]")],
    Discriminator(_fluid_form),
]


class Seabed(StrictModel):
    """Seabed plane through (0, 0, -depth), rising at ``slope_deg`` towards
    ``slope_heading_deg`` (measured from +x towards +y)."""

    slope_deg: Finite = Field(0.0, ge=-60.0, le=60.0, description="seabed slope [deg]")
    slope_heading_deg: Finite = Field(0.0, description="direction of rising seabed [deg]")
    friction: NonNegative = Field(
        0.0,
        description="Coulomb friction coefficient [-] (along the line; also across it "
        "unless friction_lateral is given)",
    )
    friction_lateral: NonNegative | None = Field(
        None,
        description="Coulomb friction coefficient across the line [-] (time domain); "
        "default: friction",
    )
    stiffness: Positive | None = Field(
        None,
        description="normal contact stiffness per length of line [N/m^2] (time domain, and "
        "the laid line's linear spring in modal and frequency-domain analyses); default: the "
        "heaviest segment's weight in the fluid per length over 1 mm, i.e. a static "
        "penetration of 1 mm",
    )
    damping_ratio: NonNegative = Field(
        1.0,
        description="normal contact damping as a fraction of the critical damping of each "
        "node on its contact spring [-] (time domain); default 1: critically damped",
    )


class CurrentPoint(StrictModel):
    """One point of a piecewise-linear current profile."""

    z: Finite = Field(description="height of this point [m], z up, surface at 0")
    speed: NonNegative = Field(description="current speed [m/s]")
    heading_deg: Finite = Field(
        0.0, description="direction the current flows to, from +x towards +y [deg]"
    )


class Environment(StrictModel):
    """Fluid, gravity, depth, seabed, and current (piecewise linear in z)."""

    fluid: Fluid = Field(
        "water", description="surrounding fluid: air, water (1025 kg/m^3), vacuum, or {density}"
    )
    gravity: Positive = Field(9.80665, description="acceleration of gravity [m/s^2]")
    depth: Positive | None = Field(None, description="water depth [m]; omit for no seabed")
    seabed: Seabed = Seabed()
    current: list[CurrentPoint] | None = Field(
        None, description="current profile, piecewise linear in z, constant beyond the ends"
    )

    @field_validator("current")
    @classmethod
    def _distinct_heights(cls, value: list[CurrentPoint] | None) -> list[CurrentPoint] | None:
        if value is None:
            return value
        if len(value) == 0:
            raise ValueError("must list at least one point {z, speed, heading_deg}, or be omitted")
        seen: set[float] = set()
        for i, point in enumerate(value):
            if point.z in seen:
                raise FieldError(
                    (i, "z"),
                    "current points must have distinct heights z; "
                    f"z = {point.z:g} m is listed twice",
                    point.z,
                )
            seen.add(point.z)
        return value

    @property
    def density(self) -> float:
        """Fluid density [kg/m^3]."""
        if isinstance(self.fluid, CustomFluid):
            return self.fluid.density
        return FLUID_DENSITY[self.fluid]

    @property
    def has_current(self) -> bool:
        return bool(self.current) and any(p.speed > 0.0 for p in self.current or [])

    def seabed_z(self, x: Any, y: Any) -> Any:
        """Height [m] of the seabed under (x, y) [m] (numbers or arrays; with a depth)."""
        assert self.depth is not None
        rise, cos, sin = seabed_slope(self.seabed.slope_deg, self.seabed.slope_heading_deg)
        return seabed_height(self.depth, rise, cos, sin, x, y)


def seabed_slope(slope_deg: float, heading_deg: float) -> tuple[float, float, float]:
    """The seabed's rise tan(slope) and the cosine and sine of its heading (math, as
    every check of the study takes them)."""
    heading = math.radians(heading_deg)
    return math.tan(math.radians(slope_deg)), math.cos(heading), math.sin(heading)


def seabed_height(depth: Any, rise: Any, cos: Any, sin: Any, x: Any, y: Any) -> Any:
    """Height [m] of a plane seabed ``depth`` [m] deep at the origin, rising by ``rise``
    along the heading (``cos``, ``sin``), under (x, y) [m]; numbers or arrays (one
    seabed per case in a grid)."""
    return -depth + rise * (x * cos + y * sin)
