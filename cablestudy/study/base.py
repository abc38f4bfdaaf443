"""Shared building blocks of the study models: strict frozen base, finite numbers, and
the error type validators raise to point at a field below the model they check."""

from __future__ import annotations

import math
from typing import Annotated, Any

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field


class FieldError(ValueError):
    """A validation fault located at ``loc`` (a path relative to the model whose validator
    raises it), with the offending ``value``. The loader appends ``loc`` to the model's
    YAML path, so the message points at the line of the field itself.

    Parameters
    ----------
    loc : tuple of str and int
        Path below the validated model, e.g. ``("attachments", 0, "s")``.
    message : str
        What is wrong and what is allowed.
    value : Any
        The offending value, shown as ``(got value)``.
    """

    def __init__(self, loc: tuple[str | int, ...], message: str, value: Any) -> None:
        super().__init__(f"{message} (got {value!r})")
        self.loc = tuple(loc)
        self.message = message
        self.value = value


def _finite(value: Any) -> Any:
    """Reject NaN and infinity before any range check (so the message says why)."""
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError("must be a finite number; NaN and infinity are not allowed")
    return value


class StrictModel(BaseModel):
    """Base of every study model: unknown keys rejected, immutable, and strict types (a
    quoted string is never read as a number, nor ``true`` as 1, nor 2.5 as a count)."""

    model_config = ConfigDict(extra="forbid", frozen=True, strict=True)


#: A finite real number (NaN and infinity rejected with the field named).
Finite = Annotated[float, Field(allow_inf_nan=True), BeforeValidator(_finite)]
#: A finite number > 0.
Positive = Annotated[float, Field(gt=0.0, allow_inf_nan=True), BeforeValidator(_finite)]
#: A finite number >= 0.
NonNegative = Annotated[float, Field(ge=0.0, allow_inf_nan=True), BeforeValidator(_finite)]
#: A 3-vector of finite numbers.
Vec3 = Annotated[list[Finite], Field(min_length=3, max_length=3)]
#: A 2-vector of finite numbers.
Vec2 = Annotated[list[Finite], Field(min_length=2, max_length=2)]


def unit_direction(value: list[float]) -> list[float]:
    """A direction vector must not be zero (it is normalised where used)."""
    norm = math.sqrt(sum(v * v for v in value))
    if norm == 0.0:
        raise ValueError("must be a nonzero vector; allowed: any direction of length > 0")
    return value
