"""Writing imported study data as YAML text with comments pointing at the source lines."""

from __future__ import annotations

import json
import re
from typing import Any

import numpy as np

Path_ = tuple[str | int, ...]

_PLAIN = re.compile(r"^[A-Za-z_][A-Za-z0-9_.\-]*$")
_RESERVED = {"true", "false", "yes", "no", "on", "off", "null", "y", "n", "~"}


def scalar(value: Any) -> str:
    """One YAML scalar that our loader reads back as the same value."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if value != 0.0 and (abs(value) >= 1e6 or abs(value) < 1e-4):
            return np.format_float_scientific(value, unique=True, trim="-")
        return repr(value)
    if value is None:
        return "null"
    text = str(value)
    if _PLAIN.match(text) and text.lower() not in _RESERVED and not _numeric(text):
        return text
    return json.dumps(text)


def _numeric(text: str) -> bool:
    """True for text YAML reads as a number (a line named "1" is written "1", quoted)."""
    try:
        float(text)
    except ValueError:
        return False
    return True


def _flow(value: Any, path: Path_ = (), comments: dict | None = None) -> str | None:
    """Flow style for short lists and mappings of scalars (without comments), else None."""
    if comments and any(p[: len(path)] == path and len(p) > len(path) for p in comments):
        return None
    if isinstance(value, list) and all(not isinstance(v, dict | list) for v in value):
        return "[" + ", ".join(scalar(v) for v in value) + "]"
    if (
        isinstance(value, dict)
        and len(value) <= 3
        and all(not isinstance(v, dict | list) for v in value.values())
    ):
        return "{" + ", ".join(f"{scalar(k)}: {scalar(v)}" for k, v in value.items()) + "}"
    return None


def _tail(comments: dict[Path_, str], path: Path_) -> str:
    note = comments.get(path)
    return f"  # {note}" if note else ""


def _mapping(d: dict[str, Any], path: Path_, indent: int, comments: dict, out: list[str]) -> None:
    pad = " " * indent
    for name, value in d.items():
        sub = path + (name,)
        key = scalar(name)
        flow = (
            _flow(value, sub, comments) if not isinstance(value, str | int | float | bool) else None
        )
        if value is None or isinstance(value, str | int | float | bool):
            out.append(f"{pad}{key}: {scalar(value)}{_tail(comments, sub)}")
        elif flow is not None and not (isinstance(value, list) and not value):
            out.append(f"{pad}{key}: {flow}{_tail(comments, sub)}")
        elif isinstance(value, dict):
            out.append(f"{pad}{key}:{_tail(comments, sub)}")
            _mapping(value, sub, indent + 2, comments, out)
        else:
            out.append(f"{pad}{key}:{_tail(comments, sub)}")
            _sequence(value, sub, indent + 2, comments, out)


def _sequence(items: list[Any], path: Path_, indent: int, comments: dict, out: list[str]) -> None:
    pad = " " * indent
    for i, item in enumerate(items):
        sub = path + (i,)
        if isinstance(item, dict):
            flow = _flow(item, sub, comments)
            if flow is not None:
                out.append(f"{pad}- {flow}{_tail(comments, sub)}")
                continue
            if sub in comments:
                out.append(f"{pad}# {comments[sub]}")
            inner: list[str] = []
            _mapping(item, sub, indent + 2, comments, inner)
            inner[0] = pad + "- " + inner[0][indent + 2 :]
            out.extend(inner)
        else:
            out.append(f"{pad}- {_flow(item) or scalar(item)}{_tail(comments, sub)}")


def study_yaml(data: dict[str, Any], comments: dict[Path_, str], header: list[str]) -> str:
    """YAML text of ``data`` (mappings, lists and scalars), header lines first as comments.

    Parameters
    ----------
    data : the study as plain values
    comments : YAML path -> comment written at that key (or above that list item)
    header : lines written as comments at the top
    """
    out = [f"# {line}" if line else "#" for line in header]
    _mapping(data, (), 0, comments, out)
    return "\n".join(out) + "\n"
