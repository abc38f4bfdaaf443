"""Analysis settings: statics and the per-case time limit."""

from __future__ import annotations

from pydantic import Field, field_validator

from .base import Positive, StrictModel


class StaticSettings(StrictModel):
    method: str = Field("catenary", description="static solver (see `cablestudy schema`)")
    nodes: int = Field(101, ge=2, le=100_000, description="output points along the line")
    tolerance: Positive = Field(1e-9, le=1e-2, description="relative tolerance [-]")
    max_iterations: int = Field(100, ge=1, le=100_000)
    drag_elements: int | None = Field(
        None, ge=1, le=100_000,
        description="drag elements along the line (method catenary, with current); "
                    "default: nodes - 1, at least 20",
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


class Analysis(StrictModel):
    static: StaticSettings = StaticSettings()
    time_limit: Positive = Field(
        600.0, description="wall-time limit per case [s]; a case over it fails with a message"
    )
