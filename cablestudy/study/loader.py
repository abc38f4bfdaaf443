"""Loading a study file: YAML with line numbers, errors that point at the line."""

from __future__ import annotations

import difflib
import hashlib
import types
import typing
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ValidationError

from .base import FieldError
from .safe_yaml import (
    YamlRefused,
    compose_and_load,
    dotted,
    line_map,
    max_study_bytes,
    printable,
    too_large,
)
from .study import Study

Loc = tuple[str | int, ...]


class StudyError(ValueError):
    """A study file that cannot be run. ``problems`` lists one message per fault, each
    naming the YAML path, the bad value and what is allowed, with the line number."""

    def __init__(self, problems: list[str], source: str = "<study>") -> None:
        self.problems = [printable(p) for p in problems]
        self.source = printable(source)
        super().__init__("\n".join(f"{source}:{p}" for p in self.problems))


@dataclass(frozen=True)
class StudySource:
    """The raw study: YAML text, parsed data and a map from YAML path to line number."""

    text: str
    data: dict[str, Any]
    lines: dict[Loc, int]
    source: str
    #: what files the study refers to hold and cablestudy does not model (by name)
    notes: tuple[str, ...] = ()
    #: what is found once from the source (its sweep axes, :func:`.cases.parse_sweep`)
    memo: dict[str, Any] = field(default_factory=dict, compare=False, repr=False)

    @property
    def sha256(self) -> str:
        return hashlib.sha256(self.text.encode()).hexdigest()

    def line_of(self, loc: Loc) -> int | None:
        """Line (1-based) of the deepest known YAML node on the path ``loc``."""
        for n in range(len(loc), -1, -1):
            if loc[:n] in self.lines:
                return self.lines[loc[:n]]
        return None


def _byte_size(text: str) -> int:
    return len(text.encode("utf-8", "surrogatepass"))


def parse_study_text(
    text: str, source: str = "<study>", *, max_bytes: int | None = None
) -> StudySource:
    """Parse YAML text within the limits of :mod:`cablestudy.study.safe_yaml`, keeping
    line numbers. ``max_bytes`` [bytes] defaults to the configured study size limit.
    Raises :class:`StudyError`."""
    try:
        limit = max_study_bytes() if max_bytes is None else max_bytes
        if len(text) > limit or _byte_size(text) > limit:
            raise YamlRefused([too_large(_byte_size(text), limit, exact=True)])
        node, data = compose_and_load(text)
    except YamlRefused as exc:
        raise StudyError(exc.problems, source) from None
    if data is None:
        raise StudyError(
            [
                "1: <top>: the study file is empty; allowed: a mapping with at "
                "least name, line and ends"
            ],
            source,
        )
    if not isinstance(data, dict):
        raise StudyError(
            [
                f"1: <top>: the study file must be a mapping of keys (name, line, ends, ...) "
                f"(got {type(data).__name__})"
            ],
            source,
        )
    lines: dict[Loc, int] = {}
    if node is not None:
        line_map(node, (), lines)
    bad_keys = [k for k in data if not isinstance(k, str)]
    if bad_keys:
        raise StudyError([f"1: <top>: keys must be text, got {bad_keys!r}"], source)
    return StudySource(text=text, data=data, lines=lines, source=source)


#: seconds a named pipe (FIFO) given as the study file may take to get its first data
PIPE_WAIT = 10.0


def _open_without_waiting(path: Path) -> Any:
    """``path`` open for reading in binary mode. A named pipe (FIFO) is opened without
    blocking (a plain ``open`` waits forever for a writer that may never come) and given
    :data:`PIPE_WAIT` seconds to get data or be closed by its writer (``<(...)``, a
    writer started beside the run), else refused; regular files read as usual."""
    import os
    import select
    import stat

    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    try:
        if stat.S_ISFIFO(os.fstat(fd).st_mode):
            poller = select.poll()
            poller.register(fd, select.POLLIN)
            if not poller.poll(int(PIPE_WAIT * 1000)):
                raise OSError(0, f"it is a named pipe that nobody wrote to within {PIPE_WAIT:g} s")
        os.set_blocking(fd, True)  # reads wait for a writer's data, as usual
        return os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise


def _unreadable(path: Path, exc: OSError) -> str:
    """Why the study file ``path`` cannot be read, for :class:`StudyError` (which puts the
    path first): no line number, as no line of it was read."""
    if isinstance(exc, FileNotFoundError):
        where = path.resolve(strict=False)
        return f" cannot read the study file: it does not exist (no file at {where})"
    return f" cannot read the study file: {exc.strerror}"


def read_study_source(path: str | Path, *, max_bytes: int | None = None) -> StudySource:
    """Read a study file (UTF-8 YAML) keeping line numbers; a file over ``max_bytes``
    [bytes] (default: the configured study size limit) is refused before it is read in
    full. Raises :class:`StudyError`."""
    path = Path(path)
    try:
        limit = max_study_bytes() if max_bytes is None else max_bytes
    except YamlRefused as exc:
        raise StudyError(exc.problems, str(path)) from None
    try:
        with _open_without_waiting(path) as stream:
            raw = stream.read(limit + 1)
            if len(raw) > limit:
                size = path.stat().st_size
                raise StudyError([too_large(size, limit, exact=size > limit)], str(path))
    except OSError as exc:
        raise StudyError([_unreadable(path, exc)], str(path)) from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        raise StudyError(
            [
                f"{line}: the study file is not UTF-8 text ({exc.reason} at byte "
                f"{exc.start}); allowed: UTF-8 text"
            ],
            str(path),
        ) from None
    return resolve_references(parse_study_text(text, str(path), max_bytes=limit), path.parent)


def resolve_references(src: StudySource, folder: Path) -> StudySource:
    """Replace ``line: {moordyn: path, line: N}`` by the segments and attachments it
    names (see :class:`~cablestudy.study.line.MoorDynLineRef`); other studies pass
    through unchanged. Raises :class:`StudyError` at the ``line:`` key's line."""
    from .line import MoorDynLineRef

    line = src.data.get("line")
    if not (isinstance(line, dict) and "moordyn" in line):
        return src
    where = src.line_of(("line", "moordyn"))
    try:
        ref = MoorDynLineRef.model_validate(line)
    except ValidationError as exc:
        problems = []
        for err in exc.errors(include_url=False):
            sub = ("line",) + tuple(err["loc"])[:2]
            msg = err["msg"].replace("Input should be", "must be")
            if err["type"] == "extra_forbidden":
                msg = f"unknown key; allowed keys here: {', '.join(MoorDynLineRef.model_fields)}"
            problems.append(
                f"{src.line_of(sub) or where}: {dotted(sub)}: {msg} (got {_shown(err['input'])})"
            )
        raise StudyError(problems, src.source) from None
    from ..interchange import InterchangeError, line_from_reference, read_in_scope

    try:
        resolved, notes = line_from_reference(ref.moordyn, ref.line, folder)
    except InterchangeError as exc:
        raise StudyError(
            [f"{where}: line.moordyn: {exc} (got {ref.moordyn!r})"], src.source
        ) from None
    data = dict(src.data)
    data["line"] = resolved
    # the referenced file travels with the study text (as YAML comments), so its hash
    # and the result files' study_yaml change when the file does
    raw, _ = read_in_scope(ref.moordyn, folder)
    digest = hashlib.sha256(raw.encode()).hexdigest()
    appendix = "".join(f"\n#| {line}" for line in raw.splitlines())
    text = (
        src.text.rstrip("\n")
        + f"\n\n# ---- line.moordyn {ref.moordyn} (sha256 {digest}), as read:"
        + appendix
        + "\n"
    )
    return StudySource(
        text=text,
        data=data,
        lines=src.lines,
        source=src.source,
        notes=tuple(f"line.moordyn {ref.moordyn}: {n}" for n in notes),
    )


# ----------------------------------------------------------------- error wording


def _unwrap(tp: Any) -> list[Any]:
    """The model classes an annotation may hold (through Optional, Annotated, list, Union)."""
    origin = typing.get_origin(tp)
    if origin is typing.Annotated:
        return _unwrap(typing.get_args(tp)[0])
    if origin in (typing.Union, types.UnionType, list, dict):
        out: list[Any] = []
        for arg in typing.get_args(tp):
            out.extend(_unwrap(arg))
        return out
    if isinstance(tp, type) and issubclass(tp, BaseModel):
        return [tp]
    return []


def _kind_tagged(models: list[type[BaseModel]], part: str | int) -> list[type[BaseModel]]:
    """The members of a 'kind'-discriminated union that ``part`` names as their tag ([] if
    ``models`` is not such a union). pydantic puts the tag in error paths, and a tag may
    also be a field name ('force' is both a kind of end and a key of that end)."""
    if len(models) < 2:
        return []
    return [
        m
        for m in models
        if "kind" in m.model_fields and part in typing.get_args(m.model_fields["kind"].annotation)
    ]


def _is_mapping(models: list[type[BaseModel]], part: str) -> bool:
    """Whether field ``part`` of ``models`` is a mapping of named entries (dict[str, X])."""
    return any(
        typing.get_origin(m.model_fields[part].annotation) is dict
        for m in models
        if part in m.model_fields
    )


def _models_at(loc: Loc) -> list[type[BaseModel]]:
    """Candidate model classes at a pydantic error location."""
    current: list[type[BaseModel]] = [Study]
    keyed = False  # at a mapping of named entries (a system's points, bodies, lines)
    for part in loc:
        if isinstance(part, int):
            continue
        if keyed:
            keyed = False
            continue
        tagged = _kind_tagged(current, part)
        if tagged:
            current = tagged
            continue
        named = [m for m in current if part in m.model_fields]
        if named:
            keyed = _is_mapping(named, part)
            current = [c for m in named for c in _unwrap(m.model_fields[part].annotation)]
            continue
        # a discriminator tag or a union member's class name
        tagged = []
        for m in current:
            kind = m.model_fields.get("kind")
            if kind is not None and part in typing.get_args(kind.annotation):
                tagged.append(m)
            elif m.__name__ == part:
                tagged.append(m)
        current = tagged or current
    return current


def _clean_loc(loc: Loc) -> Loc:
    """Drop union-member and discriminator parts pydantic adds to error paths."""
    out: list[str | int] = []
    models: list[type[BaseModel]] = [Study]
    keyed = False  # at a mapping of named entries (a system's points, bodies, lines)
    for i, part in enumerate(loc):
        if isinstance(part, int) or keyed:
            out.append(part)
            keyed = False
            continue
        tagged = _kind_tagged(models, part)
        if tagged:
            models = tagged
            continue
        if any(part in m.model_fields for m in models):
            out.append(part)
            keyed = _is_mapping([m for m in models if part in m.model_fields], part)
            models = [
                c
                for m in models
                if part in m.model_fields
                for c in _unwrap(m.model_fields[part].annotation)
            ]
            continue
        # union member names and tags ('fixed', 'CustomFluid', 'list[...]', ...)
        narrowed = [
            m
            for m in models
            if m.__name__ == part
            or any(
                tag in m.model_fields and part in typing.get_args(m.model_fields[tag].annotation)
                for tag in ("kind", "law")  # discriminators: ends' kind, axial law
            )
        ]
        if narrowed:
            models = narrowed
            continue
        if "[" in part or part in ("str", "float", "int", "bool", "literal"):
            continue
        if models and i < len(loc) - 1:
            continue  # the tag of a union with a callable discriminator
        out.append(part)
    return tuple(out)


_TYPE_WORDS = {
    "float_type": "must be a number",
    "int_type": "must be a whole number",
    "string_type": "must be text",
    "bool_type": "must be true or false",
    "list_type": "must be a list",
    "dict_type": "must be a mapping of keys",
    "model_type": "must be a mapping of keys",
    "model_attributes_type": "must be a mapping of keys",
}


def _field_description(loc: Loc) -> str:
    """The description of the field at raw pydantic location ``loc`` (or '')."""
    if not loc:
        return ""
    for model in _models_at(loc[:-1]):
        info = model.model_fields.get(str(loc[-1]))
        if info is not None and info.description:
            return info.description
    return ""


def _describe(err: dict[str, Any]) -> tuple[Loc, str, Any, bool]:
    """(extra location, message, offending value, value known) of one pydantic error."""
    kind = err["type"]
    raw = tuple(err["loc"])
    ctx = err.get("ctx") or {}
    cause = ctx.get("error")
    if isinstance(cause, FieldError):
        return cause.loc, cause.message, cause.value, True
    if kind == "extra_forbidden":
        key = str(raw[-1])
        allowed = sorted(
            {
                f
                for m in _models_at(raw[:-1])
                for f, info in m.model_fields.items()
                if info.annotation is not type(None)  # a key kept only to be refused
            }
        )
        alias = alias_hint(key, allowed)
        close = difflib.get_close_matches(key, allowed, n=1)
        hint = f" ({alias})" if alias else f" (did you mean {close[0]!r}?)" if close else ""
        return (
            (),
            (f"unknown key {key!r}{hint}; allowed keys here: {', '.join(allowed)}"),
            err["input"],
            True,
        )
    if kind == "missing":
        desc = _field_description(raw)
        what = f" ({desc})" if desc else ""
        return (), f"required key {str(raw[-1])!r} is missing{what}", None, False
    if kind in ("union_tag_invalid", "union_tag_not_found"):
        tags = ctx.get("expected_tags", "")
        key = str(ctx.get("discriminator", "'kind'")).strip("'")  # 'kind', or 'law' of axial
        if kind == "union_tag_not_found":
            if not tags:  # pydantic names the tags only when the given one is wrong
                kinds = [
                    a
                    for m in _models_at(raw)
                    if key in m.model_fields
                    for a in typing.get_args(m.model_fields[key].annotation)
                ]
                tags = ", ".join(repr(k) for k in kinds)
            return (), f"needs a '{key}': one of {tags}", err["input"], True
        return (key,), f"'{key}' must be one of {tags}", ctx.get("tag", err["input"]), True
    text = _TYPE_WORDS.get(kind, err["msg"])
    if text.startswith("Value error, "):
        text = text[len("Value error, ") :]
    text = text.replace("Input should be", "must be")
    if kind in ("too_short", "too_long"):
        bound = ctx.get("min_length", ctx.get("max_length"))
        word = "at least" if kind == "too_short" else "at most"
        text = f"must be a list of {word} {bound} items, not {ctx.get('actual_length', '?')}"
    return (), text, err.get("input"), True


#: usual symbols and other tools' names -> (the study key, what it is); a key is
#: suggested where the model at the faulty place has it
ALIASES: dict[str, tuple[str, str]] = {
    "ea": ("axial_stiffness", "the axial stiffness EA [N]"),
    "ei": ("bending_stiffness", "the bending stiffness EI [N m^2]"),
    "mbl": ("minimum_breaking_load", "the minimum breaking load [N]"),
    "cd": ("drag_normal", "the normal drag coefficient"),
    "cdn": ("drag_normal", "the normal drag coefficient"),
    "cdt": ("drag_tangential", "the tangential drag coefficient"),
    "cd_ax": ("drag_tangential", "the tangential (axial) drag coefficient"),
    "ca": ("added_mass_normal", "the normal added-mass coefficient"),
    "can": ("added_mass_normal", "the normal added-mass coefficient"),
    "cat": ("added_mass_tangential", "the tangential added-mass coefficient"),
    "ca_ax": ("added_mass_tangential", "the tangential (axial) added-mass coefficient"),
    "w": ("weight_in_fluid", "the submerged weight per length [N/m]"),
    "wet_weight": ("weight_in_fluid", "the submerged weight per length [N/m]"),
    "massden": ("mass_per_length", "the mass per length [kg/m]"),
    "mass": ("mass_per_length", "the mass per length [kg/m]"),
    "d": ("diameter", "the hydrodynamic diameter [m]"),
    "diam": ("diameter", "the hydrodynamic diameter [m]"),
    "l": ("length", "the unstretched length [m]"),
    "unstrlen": ("length", "the unstretched length [m]"),
    "t": ("period", "the excitation period [s]"),
    "f": ("frequency", "the excitation frequency [Hz]"),
    "freq": ("frequency", "the excitation frequency [Hz]"),
}


def alias_hint(key: str, allowed: list[str]) -> str:
    """'did you mean ...' for a usual symbol (``EA``, ``Cd``, ``MBL``, ...) whose study key
    is allowed where ``key`` was given ('' otherwise). MBL in a segment or line, where
    the key lives under ``failure``, points there."""
    hit = ALIASES.get(key.lower())
    if hit is None:
        return ""
    target, what = hit
    if target in allowed:
        return f"did you mean {target!r}? {key} is {what}"
    if target == "minimum_breaking_load" and "failure" in allowed:
        return f"did you mean 'failure: {{minimum_breaking_load: ...}}'? {key} is {what}"
    return ""


def _shown(value: Any) -> str:
    if isinstance(value, dict | list) and len(repr(value)) > 80:
        return f"a {type(value).__name__} of {len(value)} items"
    if isinstance(value, str) and len(value) > 80:
        return f"{value[:40]!r}... (text of {len(value)} characters)"
    text = repr(value)
    return text if len(text) <= 200 else text[:200] + "..."


def format_validation_error(
    exc: ValidationError,
    src: StudySource,
    swept: dict[Loc, tuple[Loc, Loc]] | None = None,
) -> list[str]:
    """One message per faulty field: ``line: path: what is wrong and what is allowed
    (got value)``. Alternatives of a union that fail at the same field are joined.

    ``swept`` maps a study path set by a sweep to (the sweep key that set it, the YAML
    location of the value used): a fault in a swept value points at that value's line."""
    grouped: dict[tuple[Loc, str, str], list[str]] = {}
    for err in exc.errors(include_url=False):
        extra, msg, value, known = _describe(err)
        loc = _clean_loc(tuple(err["loc"])) + extra
        line_loc = loc if err["type"] != "missing" else loc[:-1]
        line = src.line_of(line_loc)
        where = dotted(loc)
        if swept:
            origin = next((sk for sl, sk in swept.items() if loc[: len(sl)] == sl), None)
            if origin is not None:
                line = src.line_of(origin[1])
                where = f"{where} (value from {dotted(origin[0])})"
        head = f"{line if line is not None else '?'}: {where}"
        tail = f" (got {_shown(value)})" if known else ""
        msgs = grouped.setdefault((loc, head, tail), [])
        if msg not in msgs:
            msgs.append(msg)
    problems = []
    for (_, head, tail), msgs in grouped.items():
        problems.append(f"{head}: {'; or '.join(msgs)}{tail}")
    return problems


def validate_data(
    data: dict[str, Any],
    src: StudySource,
    swept: dict[Loc, tuple[Loc, Loc]] | None = None,
) -> Study:
    """Validate parsed study data; raise :class:`StudyError` naming each fault's line."""
    try:
        return Study.model_validate(data)
    except ValidationError as exc:
        raise StudyError(format_validation_error(exc, src, swept), src.source) from None


def load_study(path: str | Path) -> tuple[Study, StudySource]:
    """Read and validate a study file (without expanding its sweep)."""
    src = read_study_source(path)
    return validate_data(src.data, src), src
