"""End conditions. Forces are on the line; see DESIGN.md for output conventions."""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field

from .base import Finite, StrictModel, Vec2, Vec3

#: end condition of the bending stiffness: moment-free, or the end's direction held
Bending = Literal["pinned", "clamped"]
BENDING_FIELD = Field(
    "pinned",
    description="bending end condition (with bending_stiffness > 0): pinned (no moment) or "
    "clamped (the end's static direction held); time domain, modal and frequency domain",
)


class FixedEnd(StrictModel):
    """End held at a known position."""

    kind: Literal["fixed"]
    position: Vec3 = Field(description="position of the end [m]; z up, sea surface at z = 0")
    bending: Bending = BENDING_FIELD


class ForceEnd(StrictModel):
    """Towing: a known force applied to the line at this end."""

    kind: Literal["force"]
    force: Vec3 = Field(description="force applied to the line at this end [N]")
    bending: Bending = BENDING_FIELD


class MooringEnd(StrictModel):
    """Mooring: a known horizontal force on the line at this end, and its height."""

    kind: Literal["mooring"]
    force: Vec2 = Field(description="horizontal force applied to the line [N]")
    z: Finite = Field(description="height of this end [m]")
    bending: Bending = BENDING_FIELD


End = Annotated[FixedEnd | ForceEnd | MooringEnd, Field(discriminator="kind")]


class Ends(StrictModel):
    a: End
    b: End
