"""Reading MoorDyn input files (version 1 and version 2 layouts): text in, tables out.

The rules are MoorDyn's own (``MoorDyn::ReadInFile`` and ``findStartOfSection`` in
MoorDyn v2.7 ``source/MoorDyn2.cpp``, read, not copied):

- a section starts at a line holding ``---`` whose upper-cased text contains one of the
  section's key words (:data:`SECTIONS`), wherever they stand in the line: ``LINE
  DICTIONARY`` and ``LINE TYPES Chain studless 0.018m`` both open the line types; a
  section runs to the next line holding ``---``; a title with no key word (``MoorDyn
  Input File``, ``need this line``) opens nothing;
- a table section (all but options and outputs) has two rows after its title, the column
  names and the units, which are skipped; then one entry a row, read by position;
- options are ``value name [description]`` rows, names case-insensitive;
- ``#`` ends a row (MoorDyn); ``!`` and ``%`` do too here (descriptions in some files).

The layout of each table is told from its columns, not from the section's title (the
same title serves both versions, e.g. ``LINE DICTIONARY`` over a version 2 table):

- line types: 9 values (``Name Diam MassDen EA BA/-zeta Can Cat Cdn Cdt``, version 1) or
  10, 11 or 13 (``Name Diam Mass/m EA BA/-zeta EI Cd Ca CdAx CaAx [Cl [dF cF]]``,
  version 2, read by position as MoorDyn and MoorPy do, whatever the header names);
- points: 9 values (``ID Attachment X Y Z M V CdA Ca``) or 12 (``... M V FX FY FZ CdA Ca``);
- lines: ``ID LineType AttachA AttachB UnstrLen NumSegs Outputs`` (version 2), or
  ``Line LineType UnstrLen NumSegs NodeAnch NodeFair Flags`` (version 1) when the header
  names the length in the third column.

Every section is kept (line and rod types, bodies, rods, points, lines, failures, Syrope
initial tensions, options, outputs), so the result describes the whole system. Nothing
here reads other files or evaluates anything; each entry carries its file line number.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

#: section kind -> the key words that open it (MoorDyn2.cpp, ReadInFile)
SECTIONS: dict[str, tuple[str, ...]] = {
    "options": ("OPTIONS",),
    "line_types": ("LINE DICTIONARY", "LINE TYPES"),
    "rod_types": ("ROD DICTIONARY", "ROD TYPES"),
    "bodies": ("BODIES", "BODY LIST", "BODY PROPERTIES"),
    "rods": ("RODS", "ROD LIST", "ROD PROPERTIES"),
    "points": (
        "POINTS",
        "POINT LIST",
        "POINT PROPERTIES",
        "CONNECTION PROPERTIES",
        "NODE PROPERTIES",
    ),
    "lines": ("LINES", "LINE LIST", "LINE PROPERTIES"),
    "syrope_ic": ("SYROPE IC",),
    "failure": ("FAILURE",),
    "outputs": ("OUTPUT",),
}
#: sections without the two header rows of a table
_UNTABLED = ("options", "outputs")
_COMMENT = re.compile(r"[!#%]")

#: attachment words of points, bodies and rods (MoorDyn2.cpp; upper case)
FIXED_WORDS = ("ANCHOR", "FIXED", "FIX")
COUPLED_WORDS = ("FAIRLEAD", "VESSEL", "VES", "COUPLED", "CPLD")
PINNED_COUPLED_WORDS = ("VESSELPINNED", "VESPIN", "CPLDPIN", "COUPLEDPINNED")
FREE_WORDS = ("POINT", "CONNECT", "CON", "FREE")


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
    position: tuple[float, float, float]  # [m] (relative to the body for a Body# point)
    mass: float  # [kg]
    volume: float  # [m^3]
    force: tuple[float, float, float]  # [N] steady external force (12-column rows)
    drag_area: float  # CdA [m^2]
    added_mass: float  # Ca [-]
    source_line: int

    @property
    def kind(self) -> str:
        """'fixed', 'coupled', 'free' or 'body' (a Body# attachment), as MoorDyn reads the
        attachment word (letters before any number, case-insensitive)."""
        word = _letters(self.attachment)[0]
        if word in FIXED_WORDS:
            return "fixed"
        if word in COUPLED_WORDS:
            return "coupled"
        if word in FREE_WORDS:
            return "free"
        return "body"

    @property
    def body(self) -> int | None:
        """The body number of a ``Body#`` point, else None."""
        word, number = _letters(self.attachment)
        return int(number) if word == "BODY" and number else None


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


@dataclass(frozen=True)
class RodType:
    """A rod type: ``Name Diam Mass/m Cd Ca CdEnd CaEnd``."""

    name: str
    diameter: float  # [m]
    mass_per_length: float  # [kg/m]
    drag: float
    added_mass: float
    drag_end: float
    added_mass_end: float
    source_line: int


@dataclass(frozen=True)
class Body:
    """A rigid body: ``ID Attachment X0 Y0 Z0 r0 p0 y0 Mass CG* I* Volume CdA* Ca*``."""

    id: int
    attachment: str  # Fixed, Coupled/Vessel, CoupledPinned, Free
    position: tuple[float, float, float]  # reference point [m]
    rotation_deg: tuple[float, float, float]  # roll, pitch, yaw [deg] as written
    mass: float  # [kg]
    center_of_gravity: tuple[float, float, float]  # [m] from the reference point
    inertia: tuple[float, float, float]  # [kg m^2]
    volume: float  # [m^3]
    drag_area: tuple[float, ...]  # CdA [m^2], 1, 3 or 6 values as written
    added_mass: tuple[float, ...]  # Ca, 1 or 3 values
    source_line: int

    @property
    def kind(self) -> str:
        """'fixed', 'coupled', 'coupled_pinned' or 'free' (MoorDyn: any other word)."""
        word = _letters(self.attachment)[0]
        if word in FIXED_WORDS:
            return "fixed"
        if word in ("VESSEL", "VES", "COUPLED", "CPLD"):
            return "coupled"
        if word in PINNED_COUPLED_WORDS:
            return "coupled_pinned"
        return "free"


@dataclass(frozen=True)
class Rod:
    """A rod: ``ID RodType Attachment Xa Ya Za Xb Yb Zb NumSegs Outputs``."""

    id: int
    rod_type: str
    attachment: str
    end_a: tuple[float, float, float]  # [m]
    end_b: tuple[float, float, float]
    segments: int
    outputs: str
    source_line: int


@dataclass(frozen=True)
class Failure:
    """A failure condition: ``ID Point/RodEnd Lines FailTime FailTen``."""

    id: int
    attachment: str
    lines: tuple[int, ...]
    time: float  # [s]
    tension: float  # [N]
    source_line: int


@dataclass(frozen=True)
class SyropeInitial:
    """Syrope initial tensions: ``Line(s) Tmax0 Tmean0``."""

    lines: tuple[int, ...]
    max_tension: float  # [N]
    mean_tension: float  # [N]
    source_line: int


@dataclass
class MoorDynFile:
    """Everything one MoorDyn input file describes."""

    version: int
    line_types: dict[str, LineType] = field(default_factory=dict)
    points: dict[int, Point] = field(default_factory=dict)
    lines: dict[int, Line] = field(default_factory=dict)
    options: dict[str, Option] = field(default_factory=dict)  # key lower case
    outputs: list[str] = field(default_factory=list)
    rod_types: dict[str, RodType] = field(default_factory=dict)
    bodies: dict[int, Body] = field(default_factory=dict)
    rods: dict[int, Rod] = field(default_factory=dict)
    failures: list[Failure] = field(default_factory=list)
    syrope_initial: list[SyropeInitial] = field(default_factory=list)
    #: sections present, by kind: (title as written, file line)
    sections: dict[str, tuple[str, int]] = field(default_factory=dict)
    #: what the reader noticed and the user should know (mislabelled headers, ...)
    notes: list[str] = field(default_factory=list)
    source: str = "<moordyn>"
    #: the format it was read from, as a study's description names it
    kind: str = ""

    @property
    def format_name(self) -> str:
        """'MoorDyn v2', or the other format it was read from (a MoorPy design YAML)."""
        return self.kind or f"MoorDyn v{self.version}"

    def option(self, *names: str) -> Option | None:
        """The first option present under any of ``names`` (case-insensitive)."""
        for name in names:
            opt = self.options.get(name.lower())
            if opt is not None:
                return opt
        return None

    @property
    def other_sections(self) -> list[tuple[str, int, int]]:
        """Sections read but not mapped to a single line: (title, line, entry count)."""
        counts = {
            "rod_types": len(self.rod_types),
            "bodies": len(self.bodies),
            "rods": len(self.rods),
            "failure": len(self.failures),
            "syrope_ic": len(self.syrope_initial),
        }
        return [
            (title.strip(" -").upper(), line, counts[kind])
            for kind, (title, line) in self.sections.items()
            if kind in counts
        ]


def _letters(word: str) -> tuple[str, str]:
    """MoorDyn's ``decomposeString``, first part: (leading letters upper-cased, digits)."""
    m = re.match(r"([A-Za-z]*)(\d*)", word)
    assert m is not None
    return m.group(1).upper(), m.group(2)


def attachment_ref(text: str) -> tuple[str, int | None, str]:
    """('point' | 'rod' | 'unknown', number, end letter) of a line's AttachA/AttachB entry:
    ``3``, ``P3``, ``C3``, ``Point3``, ``Con3`` are point 3; ``R1A``, ``Rod1B`` rod ends."""
    m = re.fullmatch(r"([A-Za-z]*)(\d+)([A-Za-z]*)", text.strip())
    if m is None:
        return "unknown", None, ""
    word, number, end = m.group(1).upper(), int(m.group(2)), m.group(3).upper()
    if word in ("R", "ROD"):
        return "rod", number, end
    if word in ("", "C", "CON", "P", "POINT") and not end:
        return "point", number, ""
    return "unknown", number, end


def section_of(raw: str) -> str | None:
    """The section kind a line opens (MoorDyn's rule), 'unknown' for a ``---`` line with
    no key word, None for any other line."""
    if "---" not in raw:
        return None
    text = " ".join(raw.upper().split())
    kinds = [k for k, words in SECTIONS.items() if any(w in text for w in words)]
    if len(kinds) > 1:  # e.g. "LINE TYPES AND LINES": MoorDyn would open both here
        raise MoorDynFormatError(
            f"the section title {raw.strip()!r} names {' and '.join(kinds)}; a title names one "
            "section"
        )
    return kinds[0] if kinds else "unknown"


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


def _numbers(token: str, counts: tuple[int, ...], what: str, where: str) -> tuple[float, ...]:
    parts = token.split("|")
    if len(parts) not in counts:
        raise MoorDynFormatError(
            f"{where}: {what} takes {' or '.join(str(c) for c in counts)} values separated "
            f"by '|' (got {token!r})"
        )
    return tuple(_number(p, what, where) for p in parts)


V1_TYPE_COLUMNS = ("Name", "Diam", "MassDen", "EA", "BA/-zeta", "Can", "Cat", "Cdn", "Cdt")
V2_TYPE_COLUMNS = ("TypeName", "Diam", "Mass/m", "EA", "BA/-zeta", "EI", "Cd", "Ca", "CdAx", "CaAx")
V2_TYPE_OPTIONAL = ("Cl", "dF", "cF")
V1_POINT_COLUMNS = ("Node", "Type", "X", "Y", "Z", "M", "V", "FX", "FY", "FZ", "CdA", "CA")
V2_POINT_COLUMNS = ("ID", "Attachment", "X", "Y", "Z", "Mass", "Volume", "CdA", "Ca")
V1_LINE_COLUMNS = ("Line", "LineType", "UnstrLen", "NumSegs", "NodeAnch", "NodeFair", "Flags")
V2_LINE_COLUMNS = ("ID", "LineType", "AttachA", "AttachB", "UnstrLen", "NumSegs", "LineOutputs")
ROD_TYPE_COLUMNS = ("TypeName", "Diam", "Mass/m", "Cd", "Ca", "CdEnd", "CaEnd")
BODY_COLUMNS = (
    "ID", "Attachment", "X0", "Y0", "Z0", "r0", "p0", "y0", "Mass", "CG*", "I*", "Volume",
    "CdA*", "Ca*",
)  # fmt: skip
ROD_COLUMNS = ("ID", "RodType", "Attachment", "Xa", "Ya", "Za", "Xb", "Yb", "Zb", "NumSegs")
FAILURE_COLUMNS = ("ID", "Point", "Lines", "FailTime", "FailTen")
SYROPE_COLUMNS = ("Line(s)", "Tmax0", "Tmean0")


def _need(tokens: list[str], columns: tuple[str, ...], where: str, what: str) -> None:
    if len(tokens) < len(columns):
        raise MoorDynFormatError(
            f"{where}: a {what} row needs {len(columns)} values ({' '.join(columns)}), "
            f"got {len(tokens)}: {' '.join(tokens)!r}"
        )


def _line_type(tokens: list[str], where: str, n: int) -> LineType:
    num = _number
    if len(tokens) == 9:
        name, d, m, ea, ba, can, cat, cdn, cdt = tokens
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
            extra={},
            source_line=n,
        )
    if len(tokens) not in (10, 11, 13):
        raise MoorDynFormatError(
            f"{where}: a line type row has 9 values ({' '.join(V1_TYPE_COLUMNS)}: version 1) "
            f"or 10, 11 or 13 ({' '.join(V2_TYPE_COLUMNS)} [Cl [dF cF]]: version 2), got "
            f"{len(tokens)}: {' '.join(tokens)!r}"
        )
    name, d, m, ea, ba, ei, cd, ca, cdax, caax = tokens[:10]
    extra = dict(zip(V2_TYPE_OPTIONAL, tokens[10:13], strict=False))
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


def _point(tokens: list[str], where: str, n: int) -> Point:
    num = _number
    if len(tokens) == 9:
        pid, kind, x, y, z, m, v, cda, ca = tokens
        force = (0.0, 0.0, 0.0)
    elif len(tokens) == 12:
        pid, kind, x, y, z, m, v, fx, fy, fz, cda, ca = tokens
        force = (num(fx, "FX", where), num(fy, "FY", where), num(fz, "FZ", where))
    else:
        raise MoorDynFormatError(
            f"{where}: a point row has 9 values ({' '.join(V2_POINT_COLUMNS)}) or 12 "
            f"({' '.join(V1_POINT_COLUMNS)}), got {len(tokens)}: {' '.join(tokens)!r}"
        )
    word = _letters(kind)[0]
    if word not in (*FIXED_WORDS, *COUPLED_WORDS, *FREE_WORDS, "BODY") or (
        word == "BODY" and not _letters(kind)[1]
    ):
        raise MoorDynFormatError(
            f"{where}: point attachment {kind!r} is not one MoorDyn reads; allowed: "
            f"{', '.join(w.title() for w in (*FIXED_WORDS, *COUPLED_WORDS, *FREE_WORDS))} "
            "or Body<number>"
        )
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


def _line(tokens: list[str], v1_order: bool, where: str, n: int) -> Line:
    if v1_order:
        _need(tokens, V1_LINE_COLUMNS[:-1], where, "version 1 line")
        lid, ltype, length, nseg, a, b = tokens[:6]
    else:
        _need(tokens, V2_LINE_COLUMNS[:-1], where, "line")
        lid, ltype, a, b, length, nseg = tokens[:6]
    for end in (a, b):
        if attachment_ref(end)[0] == "unknown":
            raise MoorDynFormatError(
                f"{where}: line end {end!r} is neither a point (3, P3, C3, Point3) nor a rod "
                "end (R1A, Rod1B)"
            )
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


def _rod_type(tokens: list[str], where: str, n: int) -> RodType:
    _need(tokens, ROD_TYPE_COLUMNS, where, "rod type")
    name, *rest = tokens[:7]
    d, m, cd, ca, cde, cae = (
        _number(t, c, where) for t, c in zip(rest, ROD_TYPE_COLUMNS[1:], strict=False)
    )
    return RodType(name, d, m, cd, ca, cde, cae, n)


def _body(tokens: list[str], where: str, n: int) -> Body:
    _need(tokens, BODY_COLUMNS, where, "body")
    num = _number
    r6 = [num(t, c, where) for t, c in zip(tokens[2:8], BODY_COLUMNS[2:8], strict=True)]
    cg = _numbers(tokens[9], (1, 3), "CG", where)
    inertia = _numbers(tokens[10], (1, 3), "I", where)
    return Body(
        id=_integer(tokens[0], "body ID", where),
        attachment=tokens[1],
        position=(r6[0], r6[1], r6[2]),
        rotation_deg=(r6[3], r6[4], r6[5]),
        mass=num(tokens[8], "Mass", where),
        center_of_gravity=(0.0, 0.0, cg[0]) if len(cg) == 1 else (cg[0], cg[1], cg[2]),
        inertia=inertia * 3 if len(inertia) == 1 else (inertia[0], inertia[1], inertia[2]),
        volume=num(tokens[11], "Volume", where),
        drag_area=_numbers(tokens[12], (1, 2, 3, 6), "CdA", where),
        added_mass=_numbers(tokens[13], (1, 3), "Ca", where),
        source_line=n,
    )


def _rod(tokens: list[str], where: str, n: int) -> Rod:
    _need(tokens, ROD_COLUMNS, where, "rod")
    xyz = [_number(t, c, where) for t, c in zip(tokens[3:9], ROD_COLUMNS[3:9], strict=True)]
    return Rod(
        id=_integer(tokens[0], "rod ID", where),
        rod_type=tokens[1],
        attachment=tokens[2],
        end_a=(xyz[0], xyz[1], xyz[2]),
        end_b=(xyz[3], xyz[4], xyz[5]),
        segments=_integer(tokens[9], "NumSegs", where),
        outputs=tokens[10] if len(tokens) > 10 else "-",
        source_line=n,
    )


def _line_list(token: str, where: str) -> tuple[int, ...]:
    return tuple(_integer(t, "line number", where) for t in token.split(",") if t)


def _failure(tokens: list[str], where: str, n: int) -> Failure:
    _need(tokens, FAILURE_COLUMNS, where, "failure")
    return Failure(
        id=_integer(tokens[0], "failure ID", where),
        attachment=tokens[1],
        lines=_line_list(tokens[2], where),
        time=_number(tokens[3], "FailTime", where),
        tension=_number(tokens[4], "FailTen", where),
        source_line=n,
    )


def _syrope(tokens: list[str], where: str, n: int) -> SyropeInitial:
    _need(tokens, SYROPE_COLUMNS, where, "Syrope IC")
    return SyropeInitial(
        lines=_line_list(tokens[0], where),
        max_tension=_number(tokens[1], "Tmax0", where),
        mean_tension=_number(tokens[2], "Tmean0", where),
        source_line=n,
    )


def _add(table: dict, key: object, entry: object, what: str, where: str) -> None:
    if key in table:
        first = getattr(table[key], "source_line", "?")
        raise MoorDynFormatError(
            f"{where}: {what} {key!r} is defined twice (first on line {first})"
        )
    table[key] = entry


def parse_moordyn(text: str, source: str = "<moordyn>") -> MoorDynFile:
    """Read the text of a MoorDyn input file (either version; see the module docstring).

    Parameters
    ----------
    text : str
        The whole file.
    source : str
        Name used in messages (``source:line: ...``).

    Raises
    ------
    MoorDynFormatError
        Naming the file line, the value and what was expected.
    """
    out = MoorDynFile(version=2, source=source)
    kind: str | None = None  # None: front matter, or a title with no key word
    header: list[str] = []
    rows_to_skip = 0
    v1_lines = False
    v1_types = False

    for n, raw in enumerate(text.splitlines(), start=1):
        where = f"{source}:{n}"
        try:
            new_kind = section_of(raw)
        except MoorDynFormatError as exc:
            raise MoorDynFormatError(f"{where}: {exc}") from None
        if new_kind is not None:
            kind = None if new_kind == "unknown" else new_kind
            if kind is not None:
                if kind in out.sections:
                    raise MoorDynFormatError(
                        f"{where}: a second {raw.strip()!r} section (the first is on line "
                        f"{out.sections[kind][1]}); MoorDyn reads only the first, so the file "
                        "is ambiguous"
                    )
                out.sections[kind] = (raw.strip(), n)
            rows_to_skip = 0 if kind in _UNTABLED else 2
            header = []
            continue
        if kind is None:
            continue
        m = _COMMENT.search(raw)
        body = (raw[: m.start()] if m else raw).strip()
        if rows_to_skip:  # the column names, then the units (MoorDyn skips both)
            if not body:
                continue
            if rows_to_skip == 2:
                header = body.split()
            elif not body.startswith("("):
                out.notes.append(
                    f"{where}: {body!r} is taken as the units row of the table above, as "
                    "MoorDyn does (it skips the two rows after a section title)"
                )
            rows_to_skip -= 1
            if kind == "lines":
                # the unstretched length third: version 1's order ``Line LineType UnstrLen
                # NumSegs NodeAnch NodeFair``
                v1_lines = len(header) > 2 and header[2].lower().startswith(("unstr", "len"))
            continue
        if not body:
            continue
        tokens = body.split()
        if kind == "options":
            if len(tokens) < 2:
                out.notes.append(
                    f"{where}: option row {body!r} has no name; skipped as MoorDyn does"
                )
                continue
            key = tokens[1]
            _add(out.options, key.lower(), Option(key, tokens[0], n), "option", where)
        elif kind == "outputs":
            if tokens[0].upper() != "END":
                out.outputs.extend(tokens)
        elif kind == "line_types":
            lt = _line_type(tokens, where, n)
            v1_types = v1_types or len(tokens) == 9
            _add(out.line_types, lt.name, lt, "line type", where)
            if len(tokens) >= 10 and [h.lower() for h in header[6:10]] == [
                "can", "cat", "cdn", "cdt"
            ]:  # fmt: skip
                out.notes.append(
                    f"{where}: line type {lt.name!r}: the header names columns 7-10 Can Cat "
                    "Cdn Cdt, but a 10-column row is read by position as Cd Ca CdAx CaAx, as "
                    "MoorDyn and MoorPy read it"
                )
        elif kind == "points":
            pt = _point(tokens, where, n)
            _add(out.points, pt.id, pt, "point ID", where)
        elif kind == "lines":
            ln = _line(tokens, v1_lines, where, n)
            _add(out.lines, ln.id, ln, "line ID", where)
        elif kind == "rod_types":
            rt = _rod_type(tokens, where, n)
            _add(out.rod_types, rt.name, rt, "rod type", where)
        elif kind == "bodies":
            bd = _body(tokens, where, n)
            _add(out.bodies, bd.id, bd, "body ID", where)
        elif kind == "rods":
            rd = _rod(tokens, where, n)
            _add(out.rods, rd.id, rd, "rod ID", where)
        elif kind == "failure":
            out.failures.append(_failure(tokens, where, n))
        elif kind == "syrope_ic":
            out.syrope_initial.append(_syrope(tokens, where, n))
    out.version = 1 if v1_lines or v1_types else 2
    return out
