"""Shared building blocks of the study models: strict frozen base, finite numbers."""

from __future__ import annotations

import math
from typing import Annotated

from pydantic import AfterValidator, BaseModel, ConfigDict, Field


def _finite(value: float) -> float:
    if not math.isfinite(value):
        raise ValueError(f"must be a finite number, got {value!r}")
    return value


class StrictModel(BaseModel):
    """Base of every study model: unknown keys rejected, immutable, no coercion of
    strings into numbers."""

    model_config = ConfigDict(extra="forbid", frozen=True, strict=False)


#: A finite real number (NaN and infinity rejected with the field named).
Finite = Annotated[float, Field(allow_inf_nan=True), AfterValidator(_finite)]
#: A finite number > 0.
Positive = Annotated[float, Field(gt=0.0, allow_inf_nan=True), AfterValidator(_finite)]
#: A finite number >= 0.
NonNegative = Annotated[float, Field(ge=0.0, allow_inf_nan=True), AfterValidator(_finite)]
#: A 3-vector of finite numbers.
Vec3 = Annotated[list[Finite], Field(min_length=3, max_length=3)]
#: A 2-vector of finite numbers.
Vec2 = Annotated[list[Finite], Field(min_length=2, max_length=2)]
