"""Reading MoorDyn input files (version 1 and version 2 layouts): text in, tables out.

Written from the format's documentation (moordyn.readthedocs.io, "Input Files"): a
file is free-form front matter, then sections, each opened by a header line of dashes
around a key phrase (``---- LINE TYPES ----``). Table sections (line types, points,
lines) have a row of column names and a row of units in parentheses, then one entry a
row; values are read by position, not by header name. The options section holds
``value key [description]`` rows in any order. Version 2 treats ``!``, ``#`` and ``%``
as comment characters; blank lines are skipped everywhere.

Version 1 differs in the section names (``LINE DICTIONARY``, ``NODE PROPERTIES`` or
``CONNECTION PROPERTIES``, ``LINE PROPERTIES``, ``SOLVER OPTIONS``), the order of the
hydrodynamic columns of a line type (``Can Cat Cdn Cdt`` instead of v2's
``EI Cd Ca CdAx CaAx``), steady point forces ``FX FY FZ`` in the point table, and the
order of the line table (``Line LineType UnstrLen NumSegs NodeAnch NodeFair``).

Nothing here reads other files or evaluates anything: the result is plain data, each
entry carrying the line number it came from.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

#: section key phrases (upper case, single spaces) -> (section kind, version hint)
SECTIONS: dict[str, tuple[str, int | None]] = {
    "LINE TYPES": ("line_types", None),
    "LINE DICTIONARY": ("line_types", 1),
    "ROD TYPES": ("rod_types", 2),
    "BODIES": ("bodies", 2),
    "BODY LIST": ("bodies", 2),
    "BODY PROPERTIES": ("bodies", 2),
    "RODS": ("rods", 2),
    "ROD LIST": ("rods", 2),
    "ROD PROPERTIES": ("rods", 2),
    "POINTS": ("points", 2),
    "POINT LIST": ("points", 2),
    "CONNECTION PROPERTIES": ("points", 1),
    "NODE PROPERTIES": ("points", 1),
    "POINT PROPERTIES": ("points", 1),
    "LINES": ("lines", 2),
    "LINE LIST": ("lines", 2),
    "LINE PROPERTIES": ("lines", 1),
    "FAILURE": ("failure", 2),
    "CONTROL": ("control", 2),
    "EXTERNAL LOADS": ("external_loads", 2),
    "OPTIONS": ("options", 2),
    "SOLVER OPTIONS": ("options", 1),
    "OUTPUTS": ("outputs", None),
    "OUTPUT": ("outputs", None),
    "OUTPUT LIST": ("outputs", None),
}

_HEADER = re.compile(r"^\s*-{3,}\s*(?P<title>[^-].*?)?\s*-*\s*$")
_COMMENT = re.compile(r"[!#%]")


class InterchangeError(ValueError):
    """A file of another tool that cannot become a study (the message says where and why)."""


class MoorDynFormatError(InterchangeError):
    """A MoorDyn file that cannot be read; the message names the file line."""


@dataclass(frozen=True)
class LineType:
    """One line type, in SI units, with the raw text of fields we may not model."""

    name: str
    diameter: float  # [m] volume-equivalent
    mass_per_length: float  # [kg/m] in air
    axial_stiffness: str  # EA [N] as written (nonlinear forms are text)
    damping: str  # BA [N s] or -zeta [-], as written
    bending_stiffness: float  # EI [N m^2] (0 in v1)
    drag_normal: float
    added_mass_normal: float
    drag_tangential: float  # on the wetted surface pi d l
    added_mass_tangential: float
    extra: dict[str, str]  # further columns by their documented names (Cl, dF, cF)
    source_line: int


@dataclass(frozen=True)
class Point:
    """A point (v1: connection or node): where line ends meet."""

    id: int
    attachment: str  # as written: Fixed, Coupled, Free, Vessel, Connect, Body1, ...
    position: tuple[float, float, float]  # [m]
    mass: float  # [kg]
    volume: float  # [m^3]
    force: tuple[float, float, float]  # [N] v1 steady external force (0 in v2)
    drag_area: float  # CdA [m^2]
    added_mass: float  # Ca [-]
    source_line: int

    @property
    def kind(self) -> str:
        """'fixed', 'coupled', 'free' or 'body' (a Body#/Rod# attachment)."""
        word = self.attachment.lower()
        if word in ("fixed", "fix", "anchor"):
            return "fixed"
        if word in ("coupled", "vessel", "vec", "cpld", "ves"):
            return "coupled"
        if word in ("free", "connect", "con", "point"):
            return "free"
        return "body"


@dataclass(frozen=True)
class Line:
    """A line: a uniform length of one line type between two attachments."""

    id: int
    line_type: str
    attach_a: str  # point ID as text (or R#A / R#B for a rod end)
    attach_b: str
    length: float  # unstretched [m]
    segments: int  # NumSegs
    outputs: str
    source_line: int


@dataclass(frozen=True)
class Option:
    key: str
    value: str
    source_line: int


@dataclass
class MoorDynFile:
    """The tables of one MoorDyn input file."""

    version: int
    line_types: dict[str, LineType] = field(default_factory=dict)
    points: dict[int, Point] = field(default_factory=dict)
    lines: dict[int, Line] = field(default_factory=dict)
    options: dict[str, Option] = field(default_factory=dict)  # key lower case
    outputs: list[str] = field(default_factory=list)
    #: sections we read but do not model: kind -> (title, first line, entry count)
    other_sections: list[tuple[str, int, int]] = field(default_factory=list)
    source: str = "<moordyn>"

    def option(self, *names: str) -> Option | None:
        """The first option present under any of ``names`` (case-insensitive)."""
        for name in names:
            opt = self.options.get(name.lower())
            if opt is not None:
                return opt
        return None


def _strip(raw: str, version: int) -> str:
    text = raw.rstrip("\n")
    if version != 1:
        m = _COMMENT.search(text)
        if m is not None:
            text = text[: m.start()]
    return text.strip()


def _section_of(raw: str) -> tuple[str, str] | None:
    """(kind, title) if ``raw`` is a section header line, else None."""
    m = _HEADER.match(raw)
    if m is None:
        return None
    title = " ".join((m.group("title") or "").replace("-", " ").split()).upper()
    kind = SECTIONS.get(title)
    if kind is not None:
        return kind[0], title
    return "unknown", title


def _number(token: str, what: str, where: str) -> float:
    try:
        value = float(token)
    except ValueError:
        raise MoorDynFormatError(f"{where}: {what} must be a number (got {token!r})") from None
    if value != value or value in (float("inf"), float("-inf")):
        raise MoorDynFormatError(f"{where}: {what} must be finite (got {token!r})")
    return value


def _integer(token: str, what: str, where: str) -> int:
    value = _number(token, what, where)
    if value != int(value):
        raise MoorDynFormatError(f"{where}: {what} must be a whole number (got {token!r})")
    return int(value)


def _guess_version(lines: list[str]) -> int:
    """1 if any section title or line-type header is of the version 1 layout."""
    for raw in lines:
        sec = _section_of(raw)
        if sec is not None and SECTIONS.get(sec[1], ("", None))[1] == 1:
            return 1
    return 2


V1_TYPE_COLUMNS = ("Name", "Diam", "MassDen", "EA", "BA/-zeta", "Can", "Cat", "Cdn", "Cdt")
V2_TYPE_COLUMNS = ("TypeName", "Diam", "Mass/m", "EA", "BA/-zeta", "EI", "Cd", "Ca", "CdAx", "CaAx")
V2_TYPE_OPTIONAL = ("Cl", "dF", "cF")
V1_POINT_COLUMNS = ("Node", "Type", "X", "Y", "Z", "M", "V", "FX", "FY", "FZ", "CdA", "CA")
V2_POINT_COLUMNS = ("ID", "Attachment", "X", "Y", "Z", "Mass", "Volume", "CdA", "Ca")
V1_LINE_COLUMNS = ("Line", "LineType", "UnstrLen", "NumSegs", "NodeAnch", "NodeFair", "Flags")
V2_LINE_COLUMNS = ("ID", "LineType", "AttachA", "AttachB", "UnstrLen", "NumSegs", "LineOutputs")


def _need(tokens: list[str], columns: tuple[str, ...], where: str, what: str) -> None:
    if len(tokens) < len(columns):
        raise MoorDynFormatError(
            f"{where}: a {what} row needs {len(columns)} values ({' '.join(columns)}), "
            f"got {len(tokens)}: {' '.join(tokens)!r}"
        )


def _line_type(tokens: list[str], layout: int, where: str, n: int) -> LineType:
    num = _number
    if layout == 1:
        _need(tokens, V1_TYPE_COLUMNS, where, "version 1 line type")
        name, d, m, ea, ba, can, cat, cdn, cdt = tokens[:9]
        return LineType(
            name=name,
            diameter=num(d, "Diam", where),
            mass_per_length=num(m, "MassDen", where),
            axial_stiffness=ea,
            damping=ba,
            bending_stiffness=0.0,
            drag_normal=num(cdn, "Cdn", where),
            added_mass_normal=num(can, "Can", where),
            drag_tangential=num(cdt, "Cdt", where),
            added_mass_tangential=num(cat, "Cat", where),
            extra={f"column {i + 1}": t for i, t in enumerate(tokens[9:], start=9)},
            source_line=n,
        )
    _need(tokens, V2_TYPE_COLUMNS, where, "line type")
    name, d, m, ea, ba, ei, cd, ca, cdax, caax = tokens[:10]
    extra = dict(zip(V2_TYPE_OPTIONAL, tokens[10:13], strict=False))
    extra.update({f"column {i + 1}": t for i, t in enumerate(tokens[13:], start=13)})
    return LineType(
        name=name,
        diameter=num(d, "Diam", where),
        mass_per_length=num(m, "Mass/m", where),
        axial_stiffness=ea,
        damping=ba,
        bending_stiffness=num(ei, "EI", where),
        drag_normal=num(cd, "Cd", where),
        added_mass_normal=num(ca, "Ca", where),
        drag_tangential=num(cdax, "CdAx", where),
        added_mass_tangential=num(caax, "CaAx", where),
        extra=extra,
        source_line=n,
    )


def _point(tokens: list[str], layout: int, where: str, n: int) -> Point:
    num = _number
    if layout == 1:
        _need(tokens, V1_POINT_COLUMNS, where, "version 1 point")
        pid, kind, x, y, z, m, v, fx, fy, fz, cda, ca = tokens[:12]
        force = (num(fx, "FX", where), num(fy, "FY", where), num(fz, "FZ", where))
    else:
        _need(tokens, V2_POINT_COLUMNS, where, "point")
        pid, kind, x, y, z, m, v, cda, ca = tokens[:9]
        force = (0.0, 0.0, 0.0)
    return Point(
        id=_integer(pid, "point ID", where),
        attachment=kind,
        position=(num(x, "X", where), num(y, "Y", where), num(z, "Z", where)),
        mass=num(m, "Mass", where),
        volume=num(v, "Volume", where),
        force=force,
        drag_area=num(cda, "CdA", where),
        added_mass=num(ca, "Ca", where),
        source_line=n,
    )


def _line(tokens: list[str], layout: int, where: str, n: int) -> Line:
    if layout == 1:
        _need(tokens, V1_LINE_COLUMNS[:-1], where, "version 1 line")
        lid, ltype, length, nseg, a, b = tokens[:6]
    else:
        _need(tokens, V2_LINE_COLUMNS[:-1], where, "line")
        lid, ltype, a, b, length, nseg = tokens[:6]
    return Line(
        id=_integer(lid, "line ID", where),
        line_type=ltype,
        attach_a=a,
        attach_b=b,
        length=_number(length, "UnstrLen", where),
        segments=_integer(nseg, "NumSegs", where),
        outputs=tokens[6] if len(tokens) > 6 else "-",
        source_line=n,
    )


def parse_moordyn(text: str, source: str = "<moordyn>") -> MoorDynFile:
    """Read the text of a MoorDyn input file (either version).

    Parameters
    ----------
    text : str
        The whole file.
    source : str
        Name used in error messages (``source:line: ...``).

    Raises
    ------
    MoorDynFormatError
        Naming the file line, the value and what was expected.
    """
    raw_lines = text.splitlines()
    version = _guess_version(raw_lines)
    out = MoorDynFile(version=version, source=source)
    kind: str | None = None  # None: front matter
    title = ""
    header_rows = 0
    entries = 0
    start = 0
    type_layout = version

    def close() -> None:
        if kind not in (None, "line_types", "points", "lines", "options", "outputs", "end"):
            out.other_sections.append((title, start, entries))

    for n, raw in enumerate(raw_lines, start=1):
        sec = _section_of(raw)
        if sec is not None:
            new_kind, new_title = sec
            if new_kind == "unknown" and kind is None:
                continue  # a dashed title inside the front matter
            close()
            if new_kind == "unknown" and "NEED THIS LINE" in new_title:
                kind = "end"
            else:
                kind, title = new_kind, new_title
            header_rows, entries, start = 0, 0, n
            continue
        if kind in (None, "end"):
            continue
        body = _strip(raw, version)
        if not body:
            continue
        where = f"{source}:{n}"
        tokens = body.split()
        if kind == "options":
            if len(tokens) < 2:
                raise MoorDynFormatError(
                    f"{where}: an option row is 'value key [description]' (got {body!r})"
                )
            key = tokens[1]
            out.options[key.lower()] = Option(key=key, value=tokens[0], source_line=n)
            continue
        if kind == "outputs":
            if tokens[0].upper() != "END":
                out.outputs.extend(tokens)
            continue
        if header_rows < 2:  # a table: a row of names, then (optionally) one of units
            if header_rows == 0:
                header_rows = 1
                if kind == "line_types" and any(
                    t.lower() in ("can", "cdn", "cat", "cdt") for t in tokens
                ):
                    type_layout = 1
                continue
            header_rows = 2
            if tokens[0].startswith("("):
                continue
        entries += 1
        if kind == "line_types":
            lt = _line_type(tokens, type_layout, where, n)
            if lt.name in out.line_types:
                raise MoorDynFormatError(
                    f"{where}: line type {lt.name!r} is defined twice (first on line "
                    f"{out.line_types[lt.name].source_line})"
                )
            out.line_types[lt.name] = lt
        elif kind == "points":
            pt = _point(tokens, version, where, n)
            if pt.id in out.points:
                raise MoorDynFormatError(f"{where}: point ID {pt.id} is defined twice")
            out.points[pt.id] = pt
        elif kind == "lines":
            ln = _line(tokens, version, where, n)
            if ln.id in out.lines:
                raise MoorDynFormatError(f"{where}: line ID {ln.id} is defined twice")
            out.lines[ln.id] = ln
    close()
    if not out.lines:
        raise MoorDynFormatError(
            f"{source}: no lines found; a MoorDyn file needs a LINES section (version 2) or "
            "LINE PROPERTIES section (version 1) with at least one line"
        )
    return out
