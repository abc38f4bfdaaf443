"""A mooring system in a study: points, bodies and lines joined at the points.

```yaml
points:
  anchor1: {kind: fixed, position: [-400.0, 0.0, -150.0]}
  clump:   {kind: free, position: [-100.0, 0.0, -120.0], mass: 2000.0, volume: 0.25}
  fair1:   {kind: body, body: platform, offset: [-20.0, 0.0, -14.0]}
bodies:
  platform: {kind: prescribed, position: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]}
lines:
  leg1: {a: anchor1, b: clump, segments: [...]}
  leg2: {a: clump, b: fair1, segments: [...]}
```

A body's ``position`` is surge, sway, heave [m] and roll, pitch, yaw [rad] of its
reference point (rotation R = Rz(yaw) Ry(pitch) Rx(roll)); a body point's ``offset`` is
in the body frame from the reference point. A free point is placed by equilibrium under
the lines' pull, its weight ``mass`` g, the buoyancy rho ``volume`` g, ``force`` and,
in a current, its drag; its ``position`` is the starting guess.
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field

from .base import Finite, NonNegative, StrictModel, Vec3
from .line import Line

#: surge, sway, heave [m], roll, pitch, yaw [rad]
Vec6 = Annotated[list[Finite], Field(min_length=6, max_length=6)]


class FixedPoint(StrictModel):
    """A point held at a known position (an anchor)."""

    kind: Literal["fixed"]
    position: Vec3 = Field(description="position [m]; z up, sea surface at z = 0")


class FreePoint(StrictModel):
    """A point found by equilibrium: a bare junction, a clump weight or a buoy."""

    kind: Literal["free"]
    position: Vec3 = Field(description="starting guess of the position [m]")
    mass: NonNegative = Field(0.0, description="lumped mass [kg] (weight m g, down)")
    volume: NonNegative = Field(0.0, description="displaced volume [m^3] (buoyancy rho V g)")
    force: Vec3 = Field([0.0, 0.0, 0.0], description="constant applied force [N]")
    added_mass: NonNegative = Field(
        0.0, description="dynamics: isotropic added mass [kg] (moves with the point's mass)"
    )
    drag_area: NonNegative = Field(
        0.0,
        description="drag coefficient times projected area C_D A [m^2]: drag "
        "1/2 rho C_D A |U| U on the point's velocity U relative to the current (statics: "
        "in environment.current; dynamics: also on the point's motion)",
    )


class BodyPoint(StrictModel):
    """A point fixed on a body (a fairlead)."""

    kind: Literal["body"]
    body: str = Field(description="name of the body (a key of bodies)")
    offset: Vec3 = Field(description="position in the body frame from its reference point [m]")


SystemPoint = Annotated[FixedPoint | FreePoint | BodyPoint, Field(discriminator="kind")]


class PrescribedBody(StrictModel):
    """A body placed at a given 6-DOF position (MoorDyn's coupled / vessel body)."""

    kind: Literal["prescribed"]
    position: Vec6 = Field(
        [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        description="surge, sway, heave [m], roll, pitch, yaw [rad] of the reference point",
    )


class FreeBody(StrictModel):
    """A body found by equilibrium of its lines, its weight (at its centre of gravity),
    its buoyancy (at its centre of buoyancy: the displaced volume at heave 0; giving the
    metacentre here, as MoorPy's ``rM``, makes the buoyancy's moment the small-angle
    hydrostatic restoring moment), its waterplane's heave force and a constant applied
    force at its reference point."""

    kind: Literal["free"]
    position: Vec6 = Field(
        [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        description="starting guess: surge, sway, heave [m], roll, pitch, yaw [rad]",
    )
    mass: NonNegative = Field(0.0, description="mass [kg] (weight m g at center_of_gravity)")
    volume: NonNegative = Field(
        0.0, description="displaced volume [m^3] (buoyancy rho V g at center_of_buoyancy)"
    )
    center_of_gravity: Vec3 = Field(
        [0.0, 0.0, 0.0], description="in the body frame from the reference point [m]"
    )
    center_of_buoyancy: Vec3 = Field(
        [0.0, 0.0, 0.0], description="in the body frame from the reference point [m]"
    )
    force: Vec3 = Field([0.0, 0.0, 0.0], description="constant force at the reference point [N]")
    waterplane_area: NonNegative = Field(
        0.0,
        description="waterplane area A_WP [m^2]: the heave force -rho g A_WP z at the "
        "reference point, z its heave (the volume displaced at heave 0 is volume)",
    )


SystemBody = Annotated[PrescribedBody | FreeBody, Field(discriminator="kind")]


class SystemLine(Line):
    """A line of a system: its make-up as a study's ``line`` and its two end points."""

    a: str = Field(description="point at end A (a key of points)")
    b: str = Field(description="point at end B (a key of points)")
