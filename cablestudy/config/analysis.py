"""Analysis settings: statics, modal analysis and the per-case time limit."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, field_validator, model_validator

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


class ModalSettings(StrictModel):
    """Natural frequencies and mode shapes about the static shape
    (:mod:`cablestudy.dynamics.modal`)."""

    modes: int = Field(10, ge=1, le=1000, description="number of lowest modes [-]")
    elements: int | None = Field(
        None, ge=2, le=100_000,
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


class Analysis(StrictModel):
    static: StaticSettings = StaticSettings()
    modal: ModalSettings | None = Field(
        None, description="modal analysis about the static shape; omit: none"
    )
    time_limit: Positive = Field(
        600.0, description="wall-time limit per case [s]; a case over it fails with a message"
    )
