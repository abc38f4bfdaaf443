"""Loading a study file: YAML with line numbers, errors that point at the line."""

from __future__ import annotations

import hashlib
import types
import typing
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import yaml
from pydantic import BaseModel, ValidationError

from .study import Study

Loc = tuple[str | int, ...]


class StudyError(ValueError):
    """A study file that cannot be run. ``problems`` lists one message per fault, each
    naming the YAML path, the bad value and what is allowed, with the line number."""

    def __init__(self, problems: list[str], source: str = "<study>") -> None:
        self.problems = list(problems)
        self.source = source
        super().__init__("\n".join(f"{source}:{p}" for p in self.problems))


@dataclass(frozen=True)
class StudySource:
    """The raw study: YAML text, parsed data and a map from YAML path to line number."""

    text: str
    data: dict[str, Any]
    lines: dict[Loc, int]
    source: str

    @property
    def sha256(self) -> str:
        return hashlib.sha256(self.text.encode()).hexdigest()

    def line_of(self, loc: Loc) -> int | None:
        """Line (1-based) of the deepest known YAML node on the path ``loc``."""
        for n in range(len(loc), -1, -1):
            if loc[:n] in self.lines:
                return self.lines[loc[:n]]
        return None


def _line_map(node: yaml.Node, loc: Loc, out: dict[Loc, int]) -> None:
    out.setdefault(loc, node.start_mark.line + 1)
    if isinstance(node, yaml.MappingNode):
        for key, value in node.value:
            sub = loc + (str(key.value),)
            out[sub] = key.start_mark.line + 1
            _line_map(value, sub, out)
    elif isinstance(node, yaml.SequenceNode):
        for i, item in enumerate(node.value):
            out[loc + (i,)] = item.start_mark.line + 1
            _line_map(item, loc + (i,), out)


def parse_study_text(text: str, source: str = "<study>") -> StudySource:
    """Parse YAML text, keeping line numbers. Raises :class:`StudyError`."""
    try:
        node = yaml.compose(text, Loader=yaml.SafeLoader)
        data = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        line = mark.line + 1 if mark is not None else "?"
        raise StudyError([f"{line}: not valid YAML: {exc}"], source) from None
    if not isinstance(data, dict):
        raise StudyError(
            [f"1: the study file must be a mapping of keys (name, line, ends, ...), "
             f"got {type(data).__name__}"],
            source,
        )
    lines: dict[Loc, int] = {}
    if node is not None:
        _line_map(node, (), lines)
    return StudySource(text=text, data=data, lines=lines, source=source)


def read_study_source(path: str | Path) -> StudySource:
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as exc:
        raise StudyError([f"0: cannot read the study file: {exc.strerror}"], str(path)) from None
    return parse_study_text(text, str(path))


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


def _models_at(loc: Loc) -> list[type[BaseModel]]:
    """Candidate model classes at a pydantic error location."""
    current: list[type[BaseModel]] = [Study]
    for part in loc:
        if isinstance(part, int):
            continue
        named = [m for m in current if part in m.model_fields]
        if named:
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
    for part in loc:
        if isinstance(part, int):
            out.append(part)
            continue
        if any(part in m.model_fields for m in models):
            out.append(part)
            models = [
                c
                for m in models
                if part in m.model_fields
                for c in _unwrap(m.model_fields[part].annotation)
            ] or models
            continue
        # union member names and tags ('fixed', 'CustomFluid', 'list[...]', ...)
        narrowed = [m for m in models if m.__name__ == part or (
            "kind" in m.model_fields and part in typing.get_args(m.model_fields["kind"].annotation)
        )]
        if narrowed:
            models = narrowed
            continue
        if "[" in part or part in ("str", "float", "int", "bool", "literal"):
            continue
        out.append(part)
    return tuple(out)


def dotted(loc: Loc) -> str:
    return ".".join(str(p) for p in loc) if loc else "<top>"


def format_validation_error(
    exc: ValidationError, src: StudySource, prefix: Loc = (), note: str = ""
) -> list[str]:
    """One message per pydantic error: ``line: path: what is wrong (got value)``."""
    problems: list[str] = []
    seen: set[str] = set()
    for err in exc.errors(include_url=False):
        loc = prefix + _clean_loc(tuple(err["loc"]))
        kind = err["type"]
        if kind == "extra_forbidden":
            allowed = sorted({f for m in _models_at(tuple(err["loc"])[:-1]) for f in m.model_fields})
            msg = f"unknown key {str(loc[-1])!r}; allowed keys here: {', '.join(allowed)}"
        elif kind == "missing":
            msg = "required key is missing"
        elif kind == "union_tag_invalid" or kind == "union_tag_not_found":
            ctx = err.get("ctx", {})
            msg = f"'kind' must be one of {ctx.get('expected_tags', '')}, got {err['input']!r}"
        else:
            text = err["msg"]
            if text.startswith("Value error, "):
                text = text[len("Value error, "):]
            shown = err.get("input")
            if isinstance(shown, dict | list) and len(repr(shown)) > 80:
                shown = f"{type(shown).__name__} of {len(shown)} items"
            msg = f"{text} (got {shown!r})"
        line = src.line_of(loc if kind != "missing" else loc[:-1])
        entry = f"{line if line is not None else '?'}: {dotted(loc)}: {msg}{note}"
        if entry not in seen:
            seen.add(entry)
            problems.append(entry)
    return problems


def validate_data(data: dict[str, Any], src: StudySource, prefix: Loc = (), note: str = "") -> Study:
    try:
        return Study.model_validate(data)
    except ValidationError as exc:
        raise StudyError(format_validation_error(exc, src, prefix, note), src.source) from None


def load_study(path: str | Path) -> tuple[Study, StudySource]:
    """Read and validate a study file (without expanding its sweep)."""
    src = read_study_source(path)
    return validate_data(src.data, src), src
