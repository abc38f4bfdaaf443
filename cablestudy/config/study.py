"""The study file: the top-level model and its cross-field checks."""

from __future__ import annotations

import math
import re
from typing import Any

from pydantic import ConfigDict, Field, field_validator, model_validator

from .analysis import Analysis
from .base import FieldError, StrictModel
from .ends import Ends, FixedEnd, MooringEnd
from .environment import Environment
from .line import Line, MoorDynLineRef

_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.\-]*$")


def _line_or_reference(schema: dict[str, Any]) -> None:
    """JSON Schema: ``line`` is the line itself or ``{moordyn: path, line: N}``, which the
    loader resolves into the line before validation (:class:`MoorDynLineRef`)."""
    line = schema.get("properties", {}).get("line")
    if line is not None:
        ref = MoorDynLineRef.model_json_schema()
        schema["properties"]["line"] = {"anyOf": [line, ref]}


class Study(StrictModel):
    """A whole study file. ``sweep`` is kept raw here and expanded by
    :func:`cablestudy.cases.expand_cases`."""

    model_config = ConfigDict(**StrictModel.model_config, json_schema_extra=_line_or_reference)

    name: str = Field(description="study name; results go to <out>/<name>.nc")
    description: str = ""
    environment: Environment = Environment()
    line: Line
    ends: Ends
    analysis: Analysis = Analysis()
    sweep: dict[str, Any] = Field(
        {},
        description="parameter sweeps: dotted path -> values; expanded by cablestudy.cases",
        json_schema_extra={
            "propertyNames": {"pattern": r"^(zip|[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z0-9_]+)*)$"},
            "additionalProperties": {
                "anyOf": [
                    {"type": "array", "minItems": 1},
                    {
                        "type": "object",
                        "required": ["start", "stop", "num"],
                        "properties": {
                            "start": {"type": "number"},
                            "stop": {"type": "number"},
                            "num": {"type": "integer", "minimum": 1},
                            "name": {"type": "string"},
                        },
                        "additionalProperties": False,
                    },
                    {
                        "type": "object",
                        "required": ["start", "stop", "step"],
                        "properties": {
                            "start": {"type": "number"},
                            "stop": {"type": "number"},
                            "step": {"type": "number"},
                            "name": {"type": "string"},
                        },
                        "additionalProperties": False,
                    },
                    {
                        "type": "object",
                        "required": ["values"],
                        "properties": {
                            "values": {"type": "array", "minItems": 1},
                            "name": {"type": "string"},
                        },
                        "additionalProperties": False,
                    },
                ]
            },
            "properties": {
                "zip": {
                    "type": "array",
                    "minItems": 1,
                    "items": {
                        "type": "object",
                        "required": ["name"],
                        "properties": {"name": {"type": "string"}},
                        "additionalProperties": {"type": "array", "minItems": 1},
                    },
                }
            },
        },
    )

    @field_validator("name")
    @classmethod
    def _file_name(cls, value: str) -> str:
        if not _NAME.match(value):
            raise ValueError(
                f"name {value!r} must be usable as a file name: letters, digits, '_', '-', '.', "
                "starting with a letter or digit"
            )
        return value

    @model_validator(mode="after")
    def _physical(self) -> Study:
        """Cross-field checks: a solvable pair of ends, ends above the seabed, and a
        non-negative mass for every segment given by its weight in the fluid."""
        env = self.environment
        rho, g = env.density, env.gravity
        for i, seg in enumerate(self.line.segments):
            if seg.mass_per_length is None and seg.mass_in(rho, g) < 0.0:
                assert seg.weight_in_fluid is not None
                raise FieldError(
                    ("line", "segments", i, "weight_in_fluid"),
                    f"implies a negative mass per length w/g + rho*A = "
                    f"{seg.mass_in(rho, g):.6g} kg/m (fluid density {rho:g} kg/m^3, "
                    f"diameter {seg.diameter:g} m); allowed weight_in_fluid >= "
                    f"-rho*g*A = {-rho * g * seg.area:.6g} N/m, or give mass_per_length",
                    seg.weight_in_fluid,
                )
        a, b = self.ends.a, self.ends.b
        if not isinstance(a, FixedEnd) and not isinstance(b, FixedEnd):
            raise FieldError(
                ("ends",),
                f"end a is '{a.kind}' and end b is '{b.kind}'; at least one end must be "
                "'fixed' for the static problem to have a unique solution",
                {"a": a.kind, "b": b.kind},
            )
        if isinstance(a, FixedEnd) and isinstance(b, FixedEnd) and not self.line.is_spring:
            weights = [seg.weight_in(rho, g) for seg in self.line.segments]
            chord = math.dist(a.position, b.position)
            length = self.line.total_length
            weightless = all(w == 0.0 for w in weights) and not any(
                att.mass != rho * att.volume or any(att.force) for att in self.line.attachments
            )
            if weightless and chord <= length:
                raise FieldError(
                    ("ends", "b", "position"),
                    f"the line has no weight in the fluid and the distance between its fixed "
                    f"ends ({chord:g} m) is not longer than its unstretched length "
                    f"({length:g} m), so its static shape is undetermined; allowed: ends more "
                    "than the line length apart, or a line with weight",
                    list(b.position),
                )
        if env.depth is not None:
            rise = math.tan(math.radians(env.seabed.slope_deg))
            heading = math.radians(env.seabed.slope_heading_deg)
            for label, end in (("a", a), ("b", b)):
                if isinstance(end, FixedEnd):
                    x, y, z, key = *end.position, "position"
                elif isinstance(end, MooringEnd):
                    x, y, z, key = math.nan, math.nan, end.z, "z"
                else:
                    continue
                ground = -env.depth + (
                    rise * (x * math.cos(heading) + y * math.sin(heading))
                    if math.isfinite(x)
                    else 0.0
                )
                if z < ground - 1e-9 * env.depth:
                    raise FieldError(
                        ("ends", label, key),
                        f"end {label} lies below the seabed (z = {z:g} m, seabed at "
                        f"z = {ground:g} m there); allowed z >= seabed height",
                        end.position if isinstance(end, FixedEnd) else end.z,
                    )
        return self
