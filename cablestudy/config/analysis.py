"""Analysis settings: statics and the per-case time limit."""

from __future__ import annotations

from pydantic import Field, field_validator

from .base import Finite, Positive, StrictModel, Vec2


class Installation(StrictModel):
    """Steady cable laying (vaz-patel seed, eqs. 3b-4c): the laying frame (ship and
    touchdown point) moves at a constant horizontal velocity and the cable is paid out
    along itself from end B towards end A (A is the touchdown end)."""

    payout_speed: Finite = Field(
        0.0, description="speed of the cable along itself from end B towards end A [m/s]")
    touchdown_velocity: Vec2 = Field(
        [0.0, 0.0], description="horizontal velocity of the ship and touchdown point [m/s]")


class StaticSettings(StrictModel):
    method: str = Field("catenary", description="static solver (see `cablestudy schema`)")
    nodes: int = Field(101, ge=2, le=100_000, description="output points along the line")
    tolerance: Positive = Field(1e-9, le=1e-2, description="relative tolerance [-]")
    max_iterations: int = Field(100, ge=1, le=100_000)
    installation: Installation | None = Field(
        None, description="steady cable laying; omit for a line at rest (static)")

    @field_validator("method")
    @classmethod
    def _known_method(cls, value: str) -> str:
        from ..statics import STATIC_SOLVERS

        if value not in STATIC_SOLVERS:
            raise ValueError(
                f"unknown static method {value!r}; allowed: {', '.join(sorted(STATIC_SOLVERS))}"
            )
        return value


class Analysis(StrictModel):
    static: StaticSettings = StaticSettings()
    time_limit: Positive = Field(
        600.0, description="wall-time limit per case [s]; a case over it fails with a message"
    )
