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
from .system import BodyPoint, FixedPoint, FreePoint, SystemBody, SystemLine, SystemPoint
from .system_checks import check_one_line_excitation, check_system_dynamics

#: the physical systems whose layout passed (:meth:`Study._system`): ids -> objects
_LAYOUTS: dict[tuple[int, ...], tuple[Any, ...]] = {}
_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.\-]*$")


def _line_or_reference(schema: dict[str, Any]) -> None:
    """JSON Schema: ``line`` is the line itself or ``{moordyn: path, line: N}``, which the
    loader resolves into the line before validation (:class:`MoorDynLineRef`)."""
    line = schema.get("properties", {}).get("line")
    if line is not None:
        ref = MoorDynLineRef.model_json_schema()
        # optional (a system has none) but never null when given
        given = [alt for alt in line.get("anyOf", [line]) if alt.get("type") != "null"]
        schema["properties"]["line"] = {"anyOf": [*given, ref]}
        if "description" in line:
            schema["properties"]["line"]["description"] = line["description"]
    ends = schema.get("properties", {}).get("ends")
    if ends is not None and "anyOf" in ends:
        given = [alt for alt in ends["anyOf"] if alt.get("type") != "null"]
        schema["properties"]["ends"] = {**given[0], "description": ends.get("description", "")}
    # one line (line and ends) or a system (lines between points)
    schema["oneOf"] = [{"required": ["line", "ends"]}, {"required": ["lines", "points"]}]


class Study(StrictModel):
    """A whole study file. ``sweep`` is kept raw here and expanded by
    :func:`cablestudy.study.cases.expand_cases`."""

    model_config = ConfigDict(**StrictModel.model_config, json_schema_extra=_line_or_reference)

    name: str = Field(description="study name; results go to <out>/<name>.nc")
    description: str = ""
    environment: Environment = Environment()
    line: Line | None = Field(
        None, description="the line of a one-line study (with ends); omit for a system (lines)"
    )
    ends: Ends | None = Field(None, description="end conditions of the one-line study's line")
    points: dict[str, SystemPoint] = Field(
        {}, description="system: points by name (fixed, free, or on a body)"
    )
    bodies: dict[str, SystemBody] = Field(
        {},
        description="system: bodies by name (prescribed: a 6-DOF position; free: found by "
        "equilibrium)",
    )
    lines: dict[str, SystemLine] = Field(
        {}, description="system: lines by name, each between two points (a, b)"
    )
    analysis: Analysis = Analysis()
    sweep: dict[str, Any] = Field(
        {},
        description="parameter sweeps: dotted path -> values; expanded by cablestudy.study.cases",
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
        if self.lines or self.points or self.bodies:
            return self._system()
        if self.line is None or self.ends is None:
            missing = "line" if self.line is None else "ends"
            raise FieldError(
                (missing,),
                f"the study has no '{missing}'; a study holds either one line (line and "
                "ends) or a system (lines between points)",
                None,
            )
        self._segment_masses(("line",), self.line)
        if self.analysis.dynamic is not None:
            check_one_line_excitation(self)  # body / point motions need a system
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
            for label, end in (("a", a), ("b", b)):
                if isinstance(end, FixedEnd):
                    x, y, z, key = *end.position, "position"
                elif isinstance(end, MooringEnd):
                    x, y, z, key = math.nan, math.nan, end.z, "z"
                else:
                    continue
                ground = env.seabed_z(x, y) if math.isfinite(x) else -env.depth
                if z < ground - 1e-9 * env.depth:
                    raise FieldError(
                        ("ends", label, key),
                        f"end {label} lies below the seabed (z = {z!r} m, seabed at "
                        f"z = {ground!r} m there); allowed z >= seabed height",
                        end.position if isinstance(end, FixedEnd) else end.z,
                    )
        return self

    def _segment_masses(self, where: tuple[str, ...], line: Line) -> None:
        """A non-negative mass for every segment given by its weight in the fluid."""
        rho, g = self.environment.density, self.environment.gravity
        for i, seg in enumerate(line.segments):
            if seg.mass_per_length is None and seg.mass_in(rho, g) < 0.0:
                assert seg.weight_in_fluid is not None
                raise FieldError(
                    (*where, "segments", i, "weight_in_fluid"),
                    f"implies a negative mass per length w/g + rho*A = "
                    f"{seg.mass_in(rho, g):.6g} kg/m (fluid density {rho:g} kg/m^3, "
                    f"diameter {seg.diameter:g} m); allowed weight_in_fluid >= "
                    f"-rho*g*A = {-rho * g * seg.area:.6g} N/m, or give mass_per_length",
                    seg.weight_in_fluid,
                )

    def _system(self) -> Study:
        """A system (lines between points): every reference resolved, every key used or
        refused naming what supports it, fixed points above the seabed. The checks of
        the physical system alone (:meth:`_layout`) pass once for the objects they read:
        a sweep's case shares them with its template (a sweep of frequency, 50 values:
        1.4 -> 0.5 ms)."""
        one_line = "a one-line study (line and ends)"
        parts = (self.line, self.ends, self.lines, self.points, self.bodies, self.environment)
        key = tuple(map(id, parts))
        if key not in _LAYOUTS:  # (the objects are kept alive there: their ids are theirs)
            self._layout(one_line)
            if len(_LAYOUTS) >= 64:
                _LAYOUTS.clear()
            _LAYOUTS[key] = parts
        for name, point in self.points.items():
            if (
                isinstance(point, FreePoint)
                and point.drag_area > 0.0
                and not self.environment.current
                and self.analysis.dynamic is None  # the dynamics drag a moving point
            ):
                raise FieldError(
                    ("points", name, "drag_area"),
                    f"C_D A = {point.drag_area:g} m^2: a point's drag acts in a current, or "
                    "on its motion in analysis.dynamic; allowed: 0, or give "
                    "environment.current or analysis.dynamic",
                    point.drag_area,
                )
        an = self.analysis
        refused_analyses = {
            "modal": an.modal is not None,
            "database": an.database is not None,
        }
        if an.dynamic is not None:  # the system time domain (dynamics/system_*.py)
            check_system_dynamics(self)
        else:
            for name, point in self.points.items():
                if isinstance(point, FreePoint) and point.added_mass != 0.0:
                    raise FieldError(
                        ("points", name, "added_mass"),
                        "added_mass acts in the dynamics only; allowed: add "
                        "analysis.dynamic, or remove the key",
                        point.added_mass,
                    )
        for key, given in refused_analyses.items():
            if given:
                raise FieldError(
                    ("analysis", key),
                    f"analysis.{key} is not available for a system yet; it is supported by "
                    f"{one_line}; a system runs analysis.static",
                    key,
                )
        self._system_method(one_line)
        if an.static.installation is not None:
            raise FieldError(
                ("analysis", "static", "installation"),
                f"cable laying is supported by {one_line}, not by a system",
                "installation",
            )
        return self

    def _layout(self, one_line: str) -> None:
        """The checks of :meth:`_system` that read the physical system alone (lines,
        points, bodies, environment), not the analysis."""
        for key in ("line", "ends"):
            if getattr(self, key) is not None:
                raise FieldError(
                    (key,),
                    f"a system study (lines, points, bodies) has no '{key}'; give each line "
                    "under lines with its end points a and b",
                    key,
                )
        if not self.lines:
            raise FieldError(("lines",), "a system needs at least one line between two points", {})
        for group in ("points", "bodies", "lines"):
            for name in getattr(self, group):
                if not _NAME.match(name):
                    raise FieldError(
                        (group, name),
                        "names are letters, digits, '_', '-', '.', starting with a letter or digit",
                        name,
                    )
        for name, point in self.points.items():
            if isinstance(point, BodyPoint) and point.body not in self.bodies:
                raise FieldError(
                    ("points", name, "body"),
                    f"no body of that name; allowed: {sorted(self.bodies) or 'none defined'}",
                    point.body,
                )
        used: set[str] = set()
        for name, line in self.lines.items():
            for end in ("a", "b"):
                ref = getattr(line, end)
                if ref not in self.points:
                    raise FieldError(
                        ("lines", name, end),
                        f"no point of that name; allowed: {sorted(self.points)}",
                        ref,
                    )
                used.add(ref)
            if line.a == line.b:
                raise FieldError(("lines", name, "b"), "a line joins two different points", line.b)
            refused = {
                "kind": (line.kind != "catenary", "kind: spring"),
                "pulleys": (bool(line.pulleys), "pulleys"),
                "winch": (line.winch is not None, "a winch"),
                "failure": (line.failure is not None, "a failure (break) condition"),
            }
            for key, (given, what) in refused.items():
                if given:
                    raise FieldError(
                        ("lines", name, key),
                        f"the system statics do not model {what}; it is supported by {one_line}",
                        key,
                    )
            for i, seg in enumerate(line.segments):
                if seg.failure is not None:
                    raise FieldError(
                        ("lines", name, "segments", i, "failure"),
                        "the system statics do not model a failure (break) condition; it "
                        f"is supported by {one_line}",
                        "failure",
                    )
            self._segment_masses(("lines", name), line)
        for name in self.points:
            if name not in used:
                raise FieldError(
                    ("points", name), "the point is on no line; allowed: points lines use", name
                )
        env = self.environment
        if env.depth is not None:
            for name, point in self.points.items():
                if not isinstance(point, FixedPoint):
                    continue
                x, y, z = point.position
                ground = env.seabed_z(x, y)
                if z < ground - 1e-9 * env.depth:
                    raise FieldError(
                        ("points", name, "position"),
                        f"the point lies below the seabed (z = {z!r} m, seabed at "
                        f"z = {ground!r} m there); allowed z >= seabed height",
                        list(point.position),
                    )

    def _system_method(self, one_line: str) -> None:
        """The static method of a system: one that gives each line's exact end stiffness
        (catenary, discrete), and what the cable method cannot carry refused by name."""
        static = self.analysis.static
        method = static.method
        if method not in ("catenary", "discrete"):
            raise FieldError(
                ("analysis", "static", "method"),
                "a system is solved with the end stiffness of methods 'catenary' and "
                f"'discrete' only; allowed: catenary, discrete ({method!r} is supported by "
                f"{one_line})",
                method,
            )
        current = self.environment.has_current and self.environment.density > 0.0
        if current and static.drag_diameter != "unstretched":
            raise FieldError(
                ("analysis", "static", "drag_diameter"),
                f"drag on the stretched diameter is modelled by method 'shooting', which "
                f"{one_line} supports, not by a system; allowed: unstretched",
                static.drag_diameter,
            )
        if method == "discrete":
            return
        for name, line in self.lines.items():
            for i, seg in enumerate(line.segments):
                if seg.bending_stiffness > 0.0:
                    raise FieldError(
                        ("lines", name, "segments", i, "bending_stiffness"),
                        f"EI = {seg.bending_stiffness:g} N m^2: method 'catenary' carries no "
                        "bending; allowed: 0, or analysis.static.method: discrete (which "
                        "models it)",
                        seg.bending_stiffness,
                    )
            for i, att in enumerate(line.attachments):
                if current and att.drag_area > 0.0:
                    raise FieldError(
                        ("lines", name, "attachments", i, "drag_area"),
                        f"C_D A = {att.drag_area:g} m^2 in a current: method 'catenary' has "
                        "no drag of lumped bodies; allowed: 0, or analysis.static.method: "
                        "discrete (which models it)",
                        att.drag_area,
                    )

    @property
    def is_system(self) -> bool:
        """True for a system study (lines between points), False for a one-line study."""
        return bool(self.lines)

    @property
    def system_names(self) -> dict[str, list[str]]:
        """A system study's names along its dataset's dimensions (line, free point, body)."""
        return {
            "line": list(self.lines),
            "point": [k for k, p in self.points.items() if p.kind == "free"],
            "body": list(self.bodies),
        }
