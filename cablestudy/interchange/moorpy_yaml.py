"""The design-level mooring YAML of the open floating-wind tools (RAFT / MoorPy): a
``mooring:`` mapping with ``water_depth``, ``points``, ``lines`` and ``line_types``,
read into the same tables as a MoorDyn file, so that one mapping serves both.

Keys (from the RAFT/WISDEM mooring schema): a line type has ``name``, ``diameter`` [m],
``mass_density`` [kg/m], ``stiffness`` (EA) [N], and optionally ``damping`` (BA) [N s],
``bending_stiffness`` [N m^2], ``transverse_drag``, ``tangential_drag`` (on pi d l),
``transverse_added_mass``, ``tangential_added_mass``; a point has ``name``, ``type``
(fixed, vessel, free / connection), ``location`` [m], and optionally ``mass`` [kg],
``volume`` [m^3], ``CdA`` [m^2], ``Ca``; a line has ``name``, ``endA``, ``endB``,
``type`` and ``length`` [m]. Keys cablestudy does not model (cost, breaking load,
anchor types, ...) are reported by name.
"""

from __future__ import annotations

import re
from typing import Any

import yaml

from ..study.safe_yaml import line_map
from .moordyn_format import InterchangeError, Line, LineType, MoorDynFile, Option, Point

Loc = tuple[str | int, ...]


class _Loader(yaml.SafeLoader):
    """Safe YAML loader that also reads ``1e-9`` as a number (YAML 1.2), as design files
    written by Python tools do."""


_Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^[-+]?(?:[0-9][0-9_]*)(?:\.[0-9_]*)?[eE][-+]?[0-9]+$"),
    list("-+0123456789"),
)


def _load(text: str) -> Any:
    return yaml.load(text, Loader=_Loader)  # noqa: S506 - a SafeLoader subclass


_TYPE_KEYS = {
    "name", "diameter", "mass_density", "stiffness", "damping", "bending_stiffness",
    "transverse_drag", "tangential_drag", "transverse_added_mass", "tangential_added_mass",
}  # fmt: skip
_POINT_KEYS = {"name", "type", "location", "mass", "volume", "CdA", "Ca"}
_LINE_KEYS = {"name", "endA", "endB", "type", "length", "NumSegs", "n_segments"}
_POINT_KINDS = {"fixed": "Fixed", "vessel": "Coupled", "free": "Free", "connection": "Free"}


def is_mooring_yaml(text: str) -> bool:
    """True if ``text`` looks like a RAFT/MoorPy design YAML (a ``mooring:`` mapping or
    the mapping itself with ``lines`` and ``line_types``)."""
    try:
        data = _load(text)
    except yaml.YAMLError:
        return False
    if not isinstance(data, dict):
        return False
    body = data.get("mooring", data)
    return isinstance(body, dict) and "lines" in body and "line_types" in body


def parse_mooring_yaml(text: str, source: str) -> tuple[MoorDynFile, list[str]]:
    """Tables of a RAFT/MoorPy ``mooring:`` YAML, and warnings for keys not modelled.

    Points and lines are numbered 1, 2, ... in file order; their names are kept in
    the comments through :attr:`Point.attachment` (points) and the line outputs field."""
    try:
        node = yaml.compose(text, Loader=_Loader)
        data = _load(text)
    except yaml.YAMLError as exc:
        raise InterchangeError(f"{source}: not valid YAML: {exc}") from None
    lines_at: dict[Loc, int] = {}
    if node is not None:
        line_map(node, (), lines_at)
    prefix: tuple[str | int, ...] = (
        ("mooring",) if isinstance(data, dict) and "mooring" in data else ()
    )
    body = data.get("mooring") if prefix else data
    if not isinstance(body, dict):
        raise InterchangeError(f"{source}: expected a 'mooring:' mapping with lines and line_types")
    warnings: list[str] = []

    def at(*loc: str | int) -> int:
        return lines_at.get(prefix + loc, 0)

    def num(
        entry: dict[str, Any], key: str, loc: tuple[str | int, ...], default: float | None = None
    ) -> float:
        value = entry.get(key, default)
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise InterchangeError(
                f"{source}:{at(*loc)}: {'.'.join(str(p) for p in prefix + loc)}.{key}: "
                f"must be a number (got {value!r})"
            )
        return float(value)

    def extra_keys(entry: dict[str, Any], allowed: set[str], loc: tuple[str | int, ...]) -> None:
        for key in entry:
            if key not in allowed:
                dotted = ".".join(str(p) for p in prefix + loc)
                warnings.append(
                    f"{source}:{at(*loc, key) or at(*loc)}: {dotted}.{key} = {entry[key]!r} "
                    "is not modelled by cablestudy"
                )

    md = MoorDynFile(version=2, source=source, kind="MoorPy design YAML")
    for i, lt in enumerate(body.get("line_types") or []):
        loc = ("line_types", i)
        extra_keys(lt, _TYPE_KEYS, loc)
        name = str(lt.get("name", f"type{i + 1}"))
        md.line_types[name] = LineType(
            name=name,
            diameter=num(lt, "diameter", loc),
            mass_per_length=num(lt, "mass_density", loc),
            axial_stiffness=repr(num(lt, "stiffness", loc)),
            damping=repr(num(lt, "damping", loc, 0.0)),
            bending_stiffness=num(lt, "bending_stiffness", loc, 0.0),
            drag_normal=num(lt, "transverse_drag", loc, 0.0),
            added_mass_normal=num(lt, "transverse_added_mass", loc, 0.0),
            drag_tangential=num(lt, "tangential_drag", loc, 0.0),
            added_mass_tangential=num(lt, "tangential_added_mass", loc, 0.0),
            extra={},
            source_line=at(*loc),
        )
    ids: dict[str, int] = {}
    for i, pt in enumerate(body.get("points") or []):
        loc = ("points", i)
        extra_keys(pt, _POINT_KEYS, loc)
        name = str(pt.get("name", f"point{i + 1}"))
        kind = str(pt.get("type", "free")).lower()
        if kind not in _POINT_KINDS:
            raise InterchangeError(
                f"{source}:{at(*loc, 'type')}: point {name!r}: type {kind!r}; allowed: "
                f"{', '.join(_POINT_KINDS)}"
            )
        where = pt.get("location")
        if not (isinstance(where, list) and len(where) == 3):
            raise InterchangeError(
                f"{source}:{at(*loc)}: point {name!r}: location must be [x, y, z] (got {where!r})"
            )
        ids[name] = i + 1
        md.points[i + 1] = Point(
            id=i + 1,
            attachment=_POINT_KINDS[kind],
            position=(
                num({"x": where[0]}, "x", loc),
                num({"y": where[1]}, "y", loc),
                num({"z": where[2]}, "z", loc),
            ),
            mass=num(pt, "mass", loc, 0.0),
            volume=num(pt, "volume", loc, 0.0),
            force=(0.0, 0.0, 0.0),
            drag_area=num(pt, "CdA", loc, 0.0),
            added_mass=num(pt, "Ca", loc, 0.0),
            source_line=at(*loc),
        )
    for i, ln in enumerate(body.get("lines") or []):
        loc = ("lines", i)
        extra_keys(ln, _LINE_KEYS, loc)
        ends = []
        for key in ("endA", "endB"):
            name = str(ln.get(key))
            if name not in ids:
                raise InterchangeError(
                    f"{source}:{at(*loc, key)}: line {ln.get('name', i + 1)!r}: {key} {name!r} "
                    f"is not a point; points: {', '.join(ids)}"
                )
            ends.append(str(ids[name]))
        segs = ln.get("NumSegs", ln.get("n_segments", 0))
        md.lines[i + 1] = Line(
            id=i + 1,
            line_type=str(ln.get("type")),
            attach_a=ends[0],
            attach_b=ends[1],
            length=num(ln, "length", loc),
            segments=int(segs) if isinstance(segs, int) else 0,
            outputs="-",
            source_line=at(*loc),
        )
    if "water_depth" in body:
        md.options["wtrdpth"] = Option(
            "WtrDpth", repr(num(body, "water_depth", ())), at("water_depth")
        )
    for key in body:
        if key not in ("water_depth", "points", "lines", "line_types"):
            warnings.append(f"{source}:{at(key)}: mooring.{key} is not modelled by cablestudy")
    if not md.lines:
        raise InterchangeError(f"{source}: the mooring YAML lists no lines")
    return md, warnings


def line_names(text: str) -> dict[str, int]:
    """Line name -> number (1, 2, ... in file order) of a RAFT/MoorPy mooring YAML."""
    data = _load(text)
    body = data.get("mooring", data) if isinstance(data, dict) else {}
    return {str(ln.get("name", i + 1)): i + 1 for i, ln in enumerate(body.get("lines") or [])}
