"""The Study of a case of a grid (:mod:`cablestudy.study.grid`), without a
pydantic validation per case.

The template is validated once and each swept value once at its own path
(:func:`cablestudy.study.grid.expand_grid`). A case's :class:`~cablestudy.study.study.Study`
is then the template with the validated swept values put in by copying the models along
each swept path (:func:`case_study`), and the checks that combine fields -- the models'
``mode="after"`` validators (a segment's mass or weight, attachments inside the line,
:meth:`Study._physical`: ends above the seabed, a weightless line longer than its chord)
-- run on every copied model, so that a combination fails exactly where the full
validation would; a study whose combinations fail has its faults named at their lines
(:func:`cablestudy.study.cases.report_sweep_faults`).
"""

from __future__ import annotations

import inspect
import itertools
from typing import Any

from pydantic import AfterValidator, BaseModel, BeforeValidator, PlainValidator, WrapValidator
from pydantic_core import PydanticUndefined

from .analysis import HarmonicExcitation
from .line import Segment
from .study import Study
from .system_dynamics import BodyHarmonic, PointHarmonic

#: swept paths through a model with a ``mode="before"`` validator that derives other
#: fields from the swept one are not put in by copying: a segment given by ``line_type``
#: (its diameter, mass and stiffness come from the material), a harmonic motion given by
#: its ``period`` (its frequency is 1 / period)
_DERIVING: dict[type, str] = {
    Segment: "line_type",
    HarmonicExcitation: "period",
    BodyHarmonic: "period",
    PointHarmonic: "period",
}


def copyable(template: Study, path: str) -> bool:
    """Whether the swept ``path`` can be put into copies of ``template`` (every model on
    the way has its value set as its own field, none derives other fields from it, and
    the validators of a field the path goes through can run again on its built value:
    :func:`_field_checks`)."""
    node: Any = template
    parts = path.split(".")
    for k, part in enumerate(parts):
        if isinstance(node, BaseModel):
            field = _DERIVING.get(type(node))
            if field is not None and (getattr(node, field, None) is not None or part == field):
                return False
            if part not in type(node).model_fields:
                return False
            if k < len(parts) - 1 and _field_checks(type(node), part) is None:
                return False
            node = getattr(node, part)
        elif isinstance(node, list | tuple):
            if not part.isdigit() or int(part) >= len(node):
                return False
            node = node[int(part)]
        else:
            return False
    return not isinstance(node, BaseModel | list | tuple | dict)


def value_at(study: Study, path: str) -> Any:
    """The validated value at dotted ``path`` of ``study``."""
    node: Any = study
    for part in path.split("."):
        node = node[int(part)] if isinstance(node, list | tuple) else getattr(node, part)
    return node


def _field_checks(cls: type, name: str) -> list[Any] | None:
    """The validators of field ``name`` of model ``cls`` that check its built value (a
    field validator ``mode="after"`` of the value alone, an ``AfterValidator`` of its
    annotation: Environment's distinct current heights, a nonzero direction), run again
    where a swept value changes the field inside (an item of its list); None where one
    cannot be run again on the built value (a validator before, around or instead of
    pydantic's, or one that reads the other fields)."""
    key = (cls, name)
    if key in _FIELD_CHECKS:
        return _FIELD_CHECKS[key]
    found: list[Any] | None = []
    decs = cls.__pydantic_decorators__.field_validators.values()  # type: ignore[attr-defined]
    funcs = [(d.info.mode, d.func) for d in decs if name in d.info.fields or "*" in d.info.fields]
    for meta in cls.model_fields[name].metadata:  # type: ignore[attr-defined]
        if isinstance(meta, AfterValidator):
            funcs.append(("after", meta.func))
        elif isinstance(meta, BeforeValidator | PlainValidator | WrapValidator):
            funcs.append(("before", meta.func))
    for mode, func in funcs:
        try:
            alone = len(inspect.signature(func).parameters) == 1
        except (TypeError, ValueError):
            alone = False
        if mode != "after" or not alone:
            found = None
            break
        found.append(func)
    _FIELD_CHECKS[key] = found
    return found


_FIELD_CHECKS: dict[tuple[type, str], list[Any] | None] = {}


def _after_validators(cls: type) -> list[Any]:
    found = _AFTER.get(cls)
    if found is None:
        decs = cls.__pydantic_decorators__.model_validators.values()  # type: ignore[attr-defined]
        found = [d.func for d in decs if d.info.mode == "after"]
        _AFTER[cls] = found
    return found


_AFTER: dict[type, list[Any]] = {}


def _defaults(cls: type) -> list[tuple[str, Any]]:
    """The fields of model ``cls`` with a plain default (what a field the user left out
    holds before any validator derives it)."""
    found = _DEFAULTS.get(cls)
    if found is None:
        found = [
            (name, info.default)
            for name, info in cls.model_fields.items()  # type: ignore[attr-defined]
            if info.default is not PydanticUndefined and info.default_factory is None
        ]
        _DEFAULTS[cls] = found
    return found


_DEFAULTS: dict[type, list[tuple[str, Any]]] = {}


def _rebuilt(node: Any, updates: dict[tuple[str, ...], Any]) -> Any:
    """``node`` with the values ``updates`` (relative path -> value) put in: models on
    the way are shallow copies, with fields their validators derived reset to what the
    user gave and every ``mode="after"`` validator run again (raising as in a full
    validation)."""
    if () in updates:
        return updates[()]
    groups: dict[str, dict[tuple[str, ...], Any]] = {}
    for rel, value in updates.items():
        groups.setdefault(rel[0], {})[rel[1:]] = value
    if isinstance(node, list | tuple):
        items = list(node)
        for key, sub in groups.items():
            items[int(key)] = _rebuilt(items[int(key)], sub)
        return type(node)(items)
    new = node.model_copy(update={k: _rebuilt(getattr(node, k), sub) for k, sub in groups.items()})
    for name, sub in groups.items():
        if () in sub:
            continue  # the swept value itself, validated at its own path
        # a field changed inside (an item of its list): its own checks again (copyable)
        for check in _field_checks(type(new), name) or ():
            value = check(getattr(new, name))
            if value is not getattr(new, name):
                object.__setattr__(new, name, value)
    unset = new.model_fields_set
    for name, default in _defaults(type(new)):
        # a field left out that a validator filled in (e.g. a line's total length)
        if name not in unset and name not in groups and getattr(new, name) is not default:
            object.__setattr__(new, name, default)
    for check in _after_validators(type(new)):
        result = check(new)
        if result is not None:
            new = result
    return new


def case_study(template: Study, values: dict[str, Any]) -> Study:
    """The study of one case: ``template`` with the validated ``values`` (dotted path ->
    value) put in, its combined checks run (raises as :meth:`Study.model_validate`
    would on the whole study)."""
    return _rebuilt(template, {tuple(p.split(".")): v for p, v in values.items()})


def combinations_ok(grid: Any) -> bool:
    """Whether every case of ``grid`` passes the checks that combine fields (the models'
    ``mode="after"`` validators on the case's study)."""
    try:
        for index in itertools.product(*(range(n) for n in grid.shape)):
            grid.study_at(index)
    except (ValueError, AssertionError, TypeError):
        return False
    return True


def axis_studies(grid: Any) -> list[Study]:
    """The template and, per swept value, the template with that value alone put in: what
    :func:`cablestudy.analyses.evaluate.check_supported` is asked about before any work (whether
    the static method supports every setting a case may have)."""
    studies = [grid.template]
    for path, (_, vals) in grid.validated.items():
        studies.extend(case_study(grid.template, {path: v}) for v in vals)
    return studies
