"""Sweep expansion: a study file becomes a list of cases, each a frozen object with its
coordinates and a content hash of everything that affects its result.

Sweep syntax (under ``sweep:``), each key a dotted path into the study file (list items
by index, e.g. ``line.segments.0.length``)::

    path: [v0, v1, ...]                        # explicit values
    path: {start: a, stop: b, num: n}          # n values, both ends included
    path: {start: a, stop: b, step: d}         # a, a + d, ... up to b (included)
    path: {values: [...], name: dim}           # any of the above with an explicit name
    path: {values: [...], labels: [a, b, ...]} # and text labels, one per value
    zip:                                       # keys that vary together along one dim
      - {name: dim, path1: [...], path2: [...]}

Each axis is a dataset dimension named after the last part of its path (an explicit
``name`` where two would clash); the cases are the cartesian product of the axes. An
axis with ``labels`` (a zip group too) has them as its coordinate, so a swept vector
reads ``motion = heave`` rather than an index.
"""

from __future__ import annotations

import copy
import difflib
import functools
import hashlib
import itertools
import json
import math
import re
import types
import typing
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .. import __version__
from .loader import Loc, StudyError, StudySource, _models_at, _unwrap, dotted, validate_data
from .study import Study

#: dimension names used by output variables; a sweep axis may not take them (a system's
#: ``line``, ``point``, ``body``, ``dof`` and ``dof_j`` included: a swept
#: ``analysis.dynamic.excitation.dof`` would otherwise collide with the outputs' ``dof``)
RESERVED_DIMS = frozenset(
    {"s", "component", "mode", "time", "complex", "point", "harmonic"}
    | {"line", "body", "dof", "dof_j", "pulley"}
)
#: study keys named as an output variable is (``ends.b.z``, ``environment.current.0.z``,
#: ``line.failure.tension``, ``analysis.dynamic.periods``): a dimension named after one
#: would clash with that variable in the dataset, so it is prefixed with its parent key
#: like :data:`RESERVED_DIMS` (``b_z``, ``current_z``, ``failure_tension``);
#: tests/unit/test_sweep_dim_names.py keeps this the schema's keys that are outputs' names
OUTPUT_NAMED_KEYS = frozenset({"z", "tension", "periods"})
_DIM = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")
MAX_CASES = 1_000_000


@dataclass(frozen=True)
class SweepAxis:
    """One dataset dimension: its name, length, and the values each path takes on it."""

    name: str
    paths: tuple[str, ...]
    values: tuple[tuple[Any, ...], ...]  # per path, the values along the axis
    units: str = ""
    long_name: str = ""
    labels: tuple[str, ...] | None = None  # text coordinate given in the study

    @property
    def size(self) -> int:
        return len(self.values[0])

    def coordinate(self) -> np.ndarray:
        """Coordinate values: the labels if given, else the (single, scalar) path's values,
        else 0..n-1."""
        if self.labels is not None:
            return np.array(self.labels)
        if len(self.paths) == 1 and all(_is_scalar(v) for v in self.values[0]):
            return np.asarray(self.values[0])
        return np.arange(self.size)


@dataclass(frozen=True)
class Case:
    """One case: index along each axis, coordinates, the resolved study, and hashes."""

    index: tuple[int, ...]
    coords: dict[str, Any] = field(hash=False)
    study: Study = field(hash=False)
    hash: str = ""
    static_hash: str = ""


def _is_scalar(v: Any) -> bool:
    return isinstance(v, int | float | str | bool) and not (isinstance(v, float) and math.isnan(v))


def _float_field(path: str) -> bool:
    """Whether the study field at dotted ``path`` (an item of a list field where its
    last part is an index) holds a float in every model that may be there."""
    parts = tuple(path.split("."))
    item = parts[-1].isdigit()
    names = [p for p in parts if not p.isdigit()]
    if not names:
        return False
    fields = [m.model_fields.get(names[-1]) for m in _models_at(tuple(names[:-1]))]
    found = [f for f in fields if f is not None]

    def is_float(annotation: Any, unwrap_list: bool) -> bool:
        origin = typing.get_origin(annotation)
        if origin is typing.Annotated:
            return is_float(typing.get_args(annotation)[0], unwrap_list)
        if origin in (typing.Union, types.UnionType):
            args = [a for a in typing.get_args(annotation) if a is not type(None)]
            return bool(args) and all(is_float(a, unwrap_list) for a in args)
        if unwrap_list and origin in (list, tuple):
            args = [a for a in typing.get_args(annotation) if a is not Ellipsis]
            return bool(args) and all(is_float(a, False) for a in args)
        return annotation is float

    return bool(found) and all(is_float(f.annotation, item) for f in found)


def _field_info(path: tuple[str, ...]) -> tuple[str, str]:
    """(units, long_name) of a study field from its description "... [unit]"."""
    parts = [p for p in path if not p.isdigit()]
    if not parts:
        return "", ".".join(path)
    if len(path) == 4 and path[0] == "bodies" and path[2] == "position" and path[3] in "012345":
        # one coordinate of a body's position: its own name and unit
        k = int(path[3])
        dof = ("surge", "sway", "heave", "roll", "pitch", "yaw")[k]
        return ("m" if k < 3 else "rad"), f"{dof} of body {path[1]} ({'.'.join(path)})"
    models = _models_at(tuple(parts[:-1]))
    for m in models:
        info = m.model_fields.get(parts[-1])
        if info is not None and info.description:
            desc = info.description
            match = re.search(r"\[([^\]]*)\]", desc)
            units = match.group(1) if match else ""
            units = "1" if units == "-" else units
            long_name = re.sub(r"\s*\[[^\]]*\]", "", desc).split(";")[0].strip()
            if long_name.count("(") > long_name.count(")"):
                # cut inside a parenthesis ("... (along the line; ..."): drop the open part
                long_name = long_name[: long_name.rfind("(")].strip()
            return units, f"{long_name} ({'.'.join(path)})"
    return "", ".".join(path)


def _tidy_range(values: list[float], start: float, stop: float | None) -> list[float]:
    """Range values rounded to 15 significant digits, so that steps of decimal numbers
    give the decimals written (0.45, not 0.44999999999999996: ``ds.sel(frequency=0.45)``
    works); the ends stay as given. Unrounded if rounding would merge values."""
    tidy = [float(f"{v:.15g}") for v in values]
    tidy[0] = start
    if stop is not None:
        tidy[-1] = stop
    return tidy if len(set(tidy)) == len(tidy) else values


#: marks a mapping without the key ``labels``
_ABSENT = object()


def _labels(labels: Any, n: int, at: str) -> tuple[str, ...] | None:
    """The ``labels`` of a sweep axis of ``n`` values checked (None if not given); raises
    ValueError naming the key."""
    if labels is _ABSENT:
        return None
    if (
        not isinstance(labels, list)
        or not labels
        or not all(isinstance(v, str) and v.strip() and "=" not in v for v in labels)
    ):
        raise ValueError(
            f"{at}.labels: must be a list of non-empty strings without '=', one per swept "
            f"value (got {labels!r})"
        )
    if len(labels) != n:
        raise ValueError(
            f"{at}.labels: {len(labels)} labels for {n} values; allowed: one label per "
            f"value (got {labels!r})"
        )
    twice = sorted({v for v in labels if labels.count(v) > 1})
    if twice:
        raise ValueError(
            f"{at}.labels: {', '.join(map(repr, twice))} listed twice; allowed: distinct "
            f"labels (each becomes one coordinate) (got {labels!r})"
        )
    return tuple(labels)


def _axis_values(
    spec: Any, where: str, line: int | None, *, distinct: bool = True
) -> tuple[list[Any], str | None, tuple[str, ...] | None]:
    """Values of one sweep axis, its explicit name and its labels, or a StudyError
    message. Values must be distinct where they become the dimension's coordinate
    (``distinct``); in a zip group the coordinate is the case index, so a path may repeat
    a value there."""
    at = f"{line if line is not None else '?'}: {where}"
    labels: Any = _ABSENT
    if isinstance(spec, dict) and "labels" in spec:
        spec = dict(spec)
        labels = spec.pop("labels")
    values, name = _axis_values_only(spec, at, distinct=distinct)
    return values, name, _labels(labels, len(values), at)


def _axis_values_only(spec: Any, at: str, *, distinct: bool) -> tuple[list[Any], str | None]:
    name = None
    if isinstance(spec, dict):
        spec = dict(spec)
        name = spec.pop("name", None)
        if name is not None and not isinstance(name, str):
            raise ValueError(f"{at}.name: must be a string, got {name!r}")
        keys = set(spec)
        if keys == {"values"}:
            spec = spec["values"]
        elif keys == {"start", "stop", "num"} or keys == {"start", "stop", "step"}:
            for k in keys:
                v = spec[k]
                if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
                    raise ValueError(f"{at}.{k}: must be a finite number (got {v!r})")
            start, stop = float(spec["start"]), float(spec["stop"])
            if "num" in keys:
                num = spec["num"]
                if not isinstance(num, int) or isinstance(num, bool) or num < 1:
                    raise ValueError(f"{at}.num: must be a whole number >= 1 (got {num!r})")
                if num > MAX_CASES:  # refused before numpy allocates them
                    raise ValueError(f"{at}.num: {num} values is more than the {MAX_CASES} allowed")
                values = [float(v) for v in np.linspace(start, stop, num)]
                return _tidy_range(values, start, stop if num > 1 else None), name
            step = float(spec["step"])
            if step == 0.0 or (stop - start) * step < 0.0:
                raise ValueError(
                    f"{at}.step: does not lead from start {start!r} to stop {stop!r}; "
                    f"allowed: a nonzero step with the sign of stop - start (got {step!r})"
                )
            ratio = (stop - start) / step  # may overflow to inf (a tiny step, a huge range)
            if not ratio < MAX_CASES:
                raise ValueError(
                    f"{at}.step: {step!r} from {start!r} to {stop!r} gives more than the "
                    f"{MAX_CASES} values allowed"
                )
            n = math.floor(ratio * (1.0 + 1e-12) + 1e-9) + 1
            if n > MAX_CASES:
                raise ValueError(f"{at}: {n} values is more than {MAX_CASES} allowed")
            values = [start + i * step for i in range(n)]
            return _tidy_range(values, start, None), name
        else:
            raise ValueError(
                f"{at}: a sweep axis is a list of values, {{start, stop, num}}, "
                f"{{start, stop, step}} or {{values}}, each with an optional name and "
                f"labels (got keys {sorted(keys)})"
            )
    if not isinstance(spec, list):
        raise ValueError(
            f"{at}: must be a list of values or a range mapping "
            f"{{start, stop, num}} / {{start, stop, step}} (got {spec!r})"
        )
    if len(spec) == 0:
        raise ValueError(
            f"{at}: an empty sweep axis gives no cases; allowed: a list of at "
            "least one value (got [])"
        )
    seen: list[Any] = []
    for v in spec:
        if distinct and v in seen:
            raise ValueError(
                f"{at}: the value {v!r} is listed twice; allowed: distinct values "
                f"(each becomes one coordinate) (got {spec!r})"
            )
        seen.append(v)
    return list(spec), name


def _default_dim(path: tuple[str, ...]) -> str:
    last = path[-1]
    if last.isdigit():
        named = [p for p in path if not p.isdigit()]
        return f"{named[-1]}_{last}" if named else f"index_{last}"
    if last in RESERVED_DIMS or last in OUTPUT_NAMED_KEYS:  # an output's name: prefix the parent
        named = [p for p in path[:-1] if not p.isdigit()]
        return f"{named[-1]}_{last}" if named else last
    return last


#: top-level keys that name or describe a study and cannot be swept
_NOT_SWEPT = ("name", "description", "sweep")


def check_path(data: dict[str, Any], path: str) -> str | None:
    """Why the dotted ``path`` cannot be swept in the study ``data`` (None: it can).

    Walks the study models and the data together: every key must be a field of the model
    at that point, every list index must exist in the file."""
    parts = str(path).split(".")
    if parts[0] in _NOT_SWEPT:
        return (
            f"{parts[0]!r} cannot be swept; allowed: paths into environment, line, ends or analysis"
        )
    models: list[Any] = [Study]
    node: Any = data
    done: list[str] = []
    keyed = False  # at a mapping of named entries (a system's points, bodies, lines)
    for part in parts:
        here = ".".join(done) or "<top>"
        if part == "":
            return f"{path!r} has an empty part; allowed: keys joined by single dots"
        if keyed:
            names = sorted(node) if isinstance(node, dict) else []
            if part not in names:
                return f"{here} has no entry {part!r}; allowed: {', '.join(names) or 'none'}"
            node, keyed = node[part], False
        elif isinstance(node, list):
            if not part.isdigit() or int(part) >= len(node):
                return (
                    f"{here} is a list of {len(node)} items; {part!r} is not an index "
                    f"into it (allowed 0..{len(node) - 1})"
                )
            node = node[int(part)]
        elif part.isdigit():
            return (
                f"{here} is not a list in the study file, so it has no item {part}; "
                "write the list out first"
            )
        else:
            fields = sorted({f for m in models for f in m.model_fields})
            if part not in fields:
                if not fields:
                    return f"{here} is a single value with no keys; {path} does not exist"
                close = difflib.get_close_matches(part, fields, n=1)
                hint = f" (did you mean {close[0]!r}?)" if close else ""
                return (
                    f"{'.'.join(done + [part])} does not exist{hint}; allowed keys under "
                    f"{here}: {', '.join(fields)}"
                )
            keyed = any(
                typing.get_origin(m.model_fields[part].annotation) is dict
                for m in models
                if part in m.model_fields
            )
            models = [
                c
                for m in models
                if part in m.model_fields
                for c in _unwrap(m.model_fields[part].annotation)
            ]
            node = node.get(part) if isinstance(node, dict) else None
        done.append(part)
    return None


def parse_sweep(src: StudySource) -> list[SweepAxis]:
    """The sweep axes of a study source, in file order (found once per source: a run
    asks three or four times). Raises :class:`StudyError`."""
    found = src.memo.get("axes")
    if found is None:
        found = src.memo["axes"] = tuple(_parse_sweep(src))
    return list(found)


def _parse_sweep(src: StudySource) -> list[SweepAxis]:
    raw = src.data.get("sweep") or {}
    if not isinstance(raw, dict):
        raise StudyError(
            [
                f"{src.line_of(('sweep',))}: sweep: must be a mapping of "
                f"dotted paths to values, got {raw!r}"
            ],
            src.source,
        )
    problems: list[str] = []
    axes: list[SweepAxis] = []
    key_locs: dict[str, Loc] = {}

    def add(
        name: str,
        paths: list[str],
        values: list[list[Any]],
        loc: Loc,
        labels: tuple[str, ...] | None = None,
    ) -> None:
        line = src.line_of(loc)
        if not _DIM.match(name) or name in RESERVED_DIMS:
            problems.append(
                f"{line}: {dotted(loc)}: dimension name {name!r} is not allowed (must be an "
                f"identifier and not one of {sorted(RESERVED_DIMS)}); give the axis a 'name'"
            )
            return
        clash = [a for a in axes if a.name == name]
        if clash:
            problems.append(
                f"{line}: {dotted(loc)}: dimension {name!r} is already used by "
                f"{clash[0].paths[0]!r}; give one of them an explicit name "
                f"({{values: [...], name: ...}})"
            )
            return
        units, long_name = _field_info(tuple(paths[0].split(".")))
        # a whole number swept into a float field is that float: the coordinate and the
        # case hash do not depend on how the number is written (1_000, 1000.0, 1e3)
        values = [
            [float(v) if type(v) is int else v for v in vals] if _float_field(p) else vals
            for p, vals in zip(paths, values, strict=True)
        ]
        if len(paths) > 1:
            long_name = "zipped: " + ", ".join(paths)
            units = ""
        axes.append(
            SweepAxis(name, tuple(paths), tuple(tuple(v) for v in values), units, long_name, labels)
        )

    for key, spec in raw.items():
        loc: Loc = ("sweep", str(key))
        if key == "zip":
            groups = spec if isinstance(spec, list) else None
            if not groups:
                problems.append(
                    f"{src.line_of(loc)}: sweep.zip: must be a non-empty list of "
                    "groups {name: dim, path: [values], ...}"
                )
                continue
            for gi, group in enumerate(groups):
                gloc: Loc = (*loc, gi)
                line = src.line_of(gloc)
                if not isinstance(group, dict) or not isinstance(group.get("name"), str):
                    problems.append(
                        f"{line}: sweep.zip.{gi}: each group needs a 'name' "
                        "(the dimension) and two or more paths with value lists "
                        f"(got {group!r})"
                    )
                    continue
                paths = [str(k) for k in group if k not in ("name", "labels")]
                whys = [(p, check_path(src.data, p)) for p in paths]
                whys = [(p, w) for p, w in whys if w is not None]
                if whys:
                    problems.extend(
                        f"{src.line_of((*gloc, p))}: sweep.zip.{gi}.{p}: the path does not lead "
                        f"to a setting of this study: {w} (got {p!r})"
                        for p, w in whys
                    )
                    continue
                vals = []
                try:
                    for p in paths:
                        where = f"sweep.zip.{gi}.{p}"
                        v, own_name, own = _axis_values(
                            group[p], where, src.line_of((*gloc, p)), distinct=False
                        )
                        if own_name is not None:
                            raise ValueError(
                                f"{src.line_of((*gloc, p))}: {where}.name: the dimension of a "
                                f"zip group is named beside its paths (sweep.zip.{gi}.name), "
                                "not on one of them"
                            )
                        if own is not None:
                            raise ValueError(
                                f"{src.line_of((*gloc, p))}: {where}.labels: the labels of a "
                                f"zip group go beside its name (sweep.zip.{gi}.labels), "
                                "not on one of its paths"
                            )
                        vals.append(v)
                except ValueError as exc:
                    problems.append(str(exc))
                    continue
                if not paths:
                    problems.append(f"{line}: sweep.zip.{gi}: a group needs at least one path")
                    continue
                sizes = {len(v) for v in vals}
                if len(sizes) != 1:
                    problems.append(
                        f"{line}: sweep.zip.{gi}: zipped paths must have equal lengths, got "
                        + ", ".join(f"{p}: {len(v)}" for p, v in zip(paths, vals, strict=True))
                    )
                    continue
                try:
                    labels = _labels(
                        group.get("labels", _ABSENT), len(vals[0]), f"{line}: sweep.zip.{gi}"
                    )
                except ValueError as exc:
                    problems.append(str(exc))
                    continue
                add(group["name"], paths, vals, gloc, labels)
                for p in paths:
                    key_locs[p] = (*gloc, p)
            continue
        why = check_path(src.data, str(key))
        if why is not None:
            problems.append(
                f"{src.line_of(loc)}: sweep.{key}: the path does not lead to a "
                f"setting of this study: {why} (got {key!r})"
            )
            continue
        try:
            values, name, labels = _axis_values(spec, f"sweep.{key}", src.line_of(loc))
        except ValueError as exc:
            problems.append(str(exc))
            continue
        add(name or _default_dim(tuple(str(key).split("."))), [str(key)], [values], loc, labels)
        key_locs[str(key)] = loc
    if problems:
        raise StudyError(problems, src.source)
    total = math.prod(a.size for a in axes) if axes else 1
    if total > MAX_CASES:
        raise StudyError(
            [
                f"{src.line_of(('sweep',))}: sweep: {total} cases is more than the "
                f"{MAX_CASES} allowed"
            ],
            src.source,
        )
    seen_paths: dict[str, str] = {}
    for axis in axes:
        for p in axis.paths:
            for q, dim in seen_paths.items():
                if p == q or p.startswith(q + ".") or q.startswith(p + "."):
                    what = "is swept twice" if p == q else f"overlaps the swept path {q!r}"
                    raise StudyError(
                        [
                            f"{src.line_of(key_locs.get(p, ('sweep',)))}: sweep.{p}: the path "
                            f"{what} (dimensions {dim!r} and {axis.name!r}); allowed: each "
                            f"setting on one axis (got {p!r})"
                        ],
                        src.source,
                    )
            seen_paths[p] = axis.name
    return axes


def sweep_key_loc(src: StudySource, path: str) -> Loc:
    """YAML location of the sweep key that sets ``path`` (for error lines)."""
    raw = src.data.get("sweep") or {}
    if path in raw:
        return ("sweep", path)
    for gi, group in enumerate(raw.get("zip") or []):
        if isinstance(group, dict) and path in group:
            return ("sweep", "zip", gi, path)
    return ("sweep",)


def _set_path(data: dict[str, Any], path: str, value: Any) -> None:
    """Set ``value`` at dotted ``path`` in ``data``, creating mappings the study model
    allows; raise KeyError with a reason when the path cannot exist."""
    parts = path.split(".")
    node: Any = data
    done: list[str] = []
    for i, part in enumerate(parts):
        last = i == len(parts) - 1
        if isinstance(node, list):
            if not part.isdigit() or int(part) >= len(node):
                raise KeyError(
                    f"{'.'.join(done) or '<top>'} is a list of {len(node)} items; "
                    f"{part!r} is not an index into it (allowed 0..{len(node) - 1})"
                )
            if last:
                node[int(part)] = value
            else:
                node = node[int(part)]
        elif isinstance(node, dict):
            if last:
                node[part] = value
            else:
                if part not in node or node[part] is None:
                    models = _models_at(tuple(done))
                    info = next(
                        (m.model_fields[part] for m in models if part in m.model_fields), None
                    )
                    if info is None:
                        allowed = sorted({f for m in models for f in m.model_fields})
                        raise KeyError(
                            f"{'.'.join(done + [part])} does not exist; allowed keys "
                            f"under {'.'.join(done) or '<top>'}: {', '.join(allowed)}"
                        )
                    kinds = _unwrap(info.annotation)
                    origin = typing.get_origin(info.annotation)
                    if not kinds or origin is list:
                        raise KeyError(
                            f"{'.'.join(done + [part])} is not in the study file, so "
                            f"{path} cannot be swept; write it out first"
                        )
                    node[part] = {}
                node = node[part]
        else:
            raise KeyError(
                f"{'.'.join(done) or '<top>'} is a value, not a mapping or a list; "
                f"{path} does not exist"
            )
        done.append(part)


def _hash(payload: Any) -> str:
    text = json.dumps(payload, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode()).hexdigest()


#: package files whose content does not affect any case's numbers
_NOT_PHYSICS = ("figures/", "run/", "cli.py", "bench.py", "__main__.py")


@functools.cache
def code_fingerprint() -> str:
    """Hash of the package source that computes results (solvers, physics, config
    defaults, case evaluation): a changed solver invalidates cached cases."""
    root = Path(__file__).resolve().parents[1]  # the package
    digest = hashlib.sha256(__version__.encode())
    for path in sorted(root.rglob("*.py")):
        rel = path.relative_to(root).as_posix()
        if rel.startswith(_NOT_PHYSICS):
            continue
        digest.update(rel.encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:20]


def case_hashes(study: Study) -> tuple[str, str]:
    """(case hash, static hash): content hashes of everything that affects the case's
    result (every validated setting with its defaults filled in, and the solver code), and
    of what affects its static solution only."""
    body = study.model_dump(mode="json", exclude={"name", "description", "sweep"})
    static_body = {k: v for k, v in body.items() if k != "analysis"}
    # the strain warning's limit judges the static solution, it does not change it
    static_body["static"] = {
        k: v for k, v in body["analysis"]["static"].items() if k != "strain_warning"
    }
    code = code_fingerprint()
    return _hash([code, body]), _hash([code, static_body])


def _copy_tree(node: Any) -> Any:
    """Copy of parsed YAML data (mappings, lists, scalars): five times faster than
    :func:`copy.deepcopy`, which matters for sweeps of thousands of cases."""
    if isinstance(node, dict):
        return {k: _copy_tree(v) for k, v in node.items()}
    if isinstance(node, list):
        return [_copy_tree(v) for v in node]
    if isinstance(node, str | int | float | bool | None):
        return node
    return copy.deepcopy(node)


def _value_loc(src: StudySource, key_loc: Loc, i: int) -> Loc:
    """YAML location of value ``i`` of the sweep axis at ``key_loc``: the list item where
    the values are listed (its own line in a block list), else the key itself."""
    node: Any = src.data
    for part in key_loc:
        node = (
            node.get(part)
            if isinstance(node, dict)
            else (node[part] if isinstance(node, list) and isinstance(part, int) else None)
        )
    if isinstance(node, list):
        return (*key_loc, i)
    if isinstance(node, dict) and isinstance(node.get("values"), list):
        return (*key_loc, "values", i)
    return key_loc


def _study_loc(path: str) -> Loc:
    return tuple(int(p) if p.isdigit() else p for p in path.split("."))


def report_sweep_faults(src: StudySource, axes: list[SweepAxis]) -> None:
    """Raise :class:`StudyError` naming every fault of the sweep's cases, each at its line:
    a fault in a swept value at the sweep key's line; a fault elsewhere that only some
    sweep cases have names the first such case and how many there are. Called by
    :func:`cablestudy.study.grid.expand_grid` when a swept value or a combination of
    them fails (the grid itself validates each value once); returns when every case is
    valid."""
    key_locs = {p: sweep_key_loc(src, p) for a in axes for p in a.paths}
    # per axis, path and index: (study location, (sweep key, location of the value))
    value_locs = [
        {
            p: [
                (_study_loc(p), (key_locs[p], _value_loc(src, key_locs[p], i)))
                for i in range(a.size)
            ]
            for p in a.paths
        }
        for a in axes
    ]
    faults: dict[str, list[dict[str, Any]]] = {}
    template = {k: v for k, v in src.data.items() if k != "sweep"}
    coordinates = [a.coordinate() for a in axes]
    n_cases = math.prod(a.size for a in axes)
    for index in itertools.product(*(range(a.size) for a in axes)):
        data = _copy_tree(template)
        coords: dict[str, Any] = {}
        swept = dict(locs[p][i] for locs, i in zip(value_locs, index, strict=True) for p in locs)
        bad = False
        for axis, coord, i in zip(axes, coordinates, index, strict=True):
            coords[axis.name] = coord[i].item()
            for path, values in zip(axis.paths, axis.values, strict=True):
                try:
                    _set_path(data, path, _copy_tree(values[i]))
                except KeyError as exc:
                    line = src.line_of(sweep_key_loc(src, path))
                    faults.setdefault(
                        f"{line}: sweep.{path}: {exc.args[0]} (got {path!r})", []
                    ).append(coords)
                    bad = True
        if bad:
            continue
        try:
            validate_data(data, src, swept=swept)
        except StudyError as exc:
            for p in exc.problems:
                faults.setdefault(p, []).append(dict(coords))
            if len(faults) > 20:
                break
    if not faults:
        return
    problems = []
    sweep_lines = sorted({src.line_of(loc) or 0 for loc in key_locs.values()})
    lines_note = f"; swept on line{'s' if len(sweep_lines) > 1 else ''} " + ", ".join(
        str(n) for n in sweep_lines
    )
    for p, where in faults.items():
        note = "" if "(value from sweep" in p else lines_note
        if len(where) == 1:
            problems.append(f"{p} [in sweep case {where[0]}{note}]")
        else:
            problems.append(
                f"{p} [in {len(where)} of {n_cases} sweep cases, first {where[0]}{note}]"
            )
    raise StudyError(problems, src.source)
