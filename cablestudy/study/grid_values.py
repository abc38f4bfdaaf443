"""Each swept value validated once at its own path, inside the smallest model that holds
it (:func:`validated_values`), rather than as a whole study.

A model's validation reads only its own sub-tree of the study data, so the value a whole
validation gives at a swept path is what the deepest model on that path gives when it is
validated alone from the user's sub-tree with the swept value put in -- provided nothing
above it can change that sub-tree or choose another model for it. That holds when every
model above it, on the way down the path, has

- no ``mode="before"`` or ``"wrap"`` model validator (which could rewrite the sub-tree
  from its siblings: a segment given by ``line_type``), no field validator on the field
  the path takes and no post-init hook;
- on that field, no validator in the annotation (a plain model, an optional one, a list
  of them, or a union whose discriminator, asked about the new sub-tree, picks the
  template's model again) and no alias.

The ``mode="after"`` validators above the model (the checks that combine fields:
:meth:`Study._physical`) then run on the template with the value put in
(:func:`cablestudy.study.grid_studies.case_study`), so a value fails where the whole
study would. Anything else -- a path these rules do not cover, a value that fails
anywhere -- returns None: the caller validates the whole study as before, so that a
fault is named in exactly today's words.
"""

from __future__ import annotations

import functools
import types
import typing
from typing import Any

from pydantic import (
    AfterValidator,
    BaseModel,
    BeforeValidator,
    Discriminator,
    PlainValidator,
    Tag,
    WrapValidator,
)
from pydantic.fields import FieldInfo

from .cases import _copy_tree, _set_path
from .grid_studies import case_study
from .study import Study

_VALIDATORS = (AfterValidator, BeforeValidator, PlainValidator, WrapValidator)


class _Opaque(Exception):
    """The path is not one whose value a model alone validates exactly as the study."""


@functools.cache
def _transparent(cls: type[BaseModel], part: str) -> bool:
    """Whether model ``cls`` validates its field ``part`` as the field's own model would
    alone: no validator of ``cls`` can rewrite or replace it before or after (the
    ``mode="after"`` model validators, which read the built model, are run again by
    :func:`cablestudy.study.grid_studies.case_study`)."""
    decs = cls.__pydantic_decorators__  # type: ignore[attr-defined]
    if any(d.info.mode != "after" for d in decs.model_validators.values()):
        return False
    if any(part in d.info.fields or "*" in d.info.fields for d in decs.field_validators.values()):
        return False
    if decs.root_validators or decs.validators:
        return False
    if getattr(cls, "__pydantic_post_init__", None) is not None:
        return False
    info = cls.model_fields.get(part)
    return info is not None and info.alias is None and info.validation_alias is None


#: what a resolver gives: the model class (or the list type) pydantic validates the data as
Resolver = typing.Callable[[Any], Any]


def _resolver(tp: Any, meta: list[Any], disc: Any = None) -> Resolver:
    """A function of the data giving the model class (or list type) pydantic validates
    it as, for annotation ``tp`` with ``meta`` (its metadata) and discriminator
    ``disc``; raises :class:`_Opaque` where a validator sits on the way or a union is not
    decided by a discriminator."""
    for m in meta:
        if isinstance(m, _VALIDATORS):
            raise _Opaque
        if isinstance(m, Discriminator):
            disc = m.discriminator
        elif isinstance(m, FieldInfo):
            if m.discriminator is not None:
                disc = m.discriminator
            _resolver(type(None), list(m.metadata))  # validators only
    if isinstance(disc, Discriminator):
        disc = disc.discriminator
    origin = typing.get_origin(tp)
    if origin is typing.Annotated:
        base, *extra = typing.get_args(tp)
        return _resolver(base, extra, disc)
    if origin in (typing.Union, types.UnionType):
        # the data on a swept path is never None (_set_path makes a mapping of it)
        args = [a for a in typing.get_args(tp) if a is not type(None)]
        if disc is None:
            if len(args) != 1:
                raise _Opaque
            return _resolver(args[0], [])
        table: dict[Any, Resolver] = {}
        for a in args:
            member = _resolver(a, [])
            if callable(disc):
                tags = [m.tag for m in typing.get_args(a)[1:] if isinstance(m, Tag)]
            else:
                cls = member(None)  # a model class: its tag field's literal values
                if not (isinstance(cls, type) and issubclass(cls, BaseModel)):
                    raise _Opaque
                info = cls.model_fields.get(disc)
                if info is None:
                    raise _Opaque
                tags = list(typing.get_args(info.annotation))
            for tag in tags:
                if tag in table:
                    raise _Opaque
                table[tag] = member
        if callable(disc):
            return lambda data: table[disc(data)](data)
        return lambda data: table[data[disc]](data)
    return lambda data: tp


@functools.cache
def _field_resolver(cls: type[BaseModel], part: str) -> Resolver | None:
    """The resolver of field ``part`` of model ``cls`` (None: the model is not
    transparent for it, or its annotation is not resolved by the data alone)."""
    if not _transparent(cls, part):
        return None
    info = cls.model_fields[part]
    try:
        return _resolver(info.annotation, list(info.metadata), info.discriminator)
    except _Opaque:
        return None


@functools.cache
def _item_resolver(seq: Any) -> Resolver | None:
    """The resolver of an item of the list type ``seq`` (None: not a plain list)."""
    origin = typing.get_origin(seq)
    args = typing.get_args(seq)
    if not (origin is list and len(args) == 1) and not (
        origin is tuple and len(args) == 2 and args[1] is Ellipsis
    ):
        return None
    try:
        return _resolver(args[0], [])
    except _Opaque:
        return None


def _spine_set(data: dict[str, Any], path: str, value: Any) -> None:
    """Put ``value`` at ``path`` of ``data`` as :func:`_set_path` does, with the mappings
    and lists on the way copied first (the rest of the data is shared, not copied)."""
    node: Any = data
    for part in path.split(".")[:-1]:
        if isinstance(node, list):
            if not part.isdigit() or int(part) >= len(node):
                break
            key: Any = int(part)
            child = node[key]
        elif isinstance(node, dict):
            key, child = part, node.get(part)
        else:
            break
        if isinstance(child, dict):
            child = dict(child)
        elif isinstance(child, list):
            child = list(child)
        else:
            break
        node[key] = child
        node = child
    _set_path(data, path, value)


def _enclosing(
    template: Study, data: dict[str, Any], parts: list[str]
) -> tuple[int, BaseModel, Any]:
    """(depth, model, sub-tree of ``data``) of the deepest model of ``template`` on the path
    ``parts`` (its leaf excluded), after checking that every model above it lets it be
    validated alone (module docstring)."""
    nodes: list[Any] = [template]
    for part in parts[:-1]:
        node = nodes[-1]
        nodes.append(node[int(part)] if isinstance(node, list | tuple) else getattr(node, part))
    depth = max(j for j, n in enumerate(nodes) if isinstance(n, BaseModel))
    sub: Any = data
    resolve: Resolver | None = None
    for j in range(depth):
        node, part, child = nodes[j], parts[j], nodes[j + 1]
        if isinstance(node, BaseModel):
            resolve = _field_resolver(type(node), part)
            if not isinstance(sub, dict) or part not in sub:
                raise _Opaque
            sub = sub[part]
        else:
            sub = sub[int(part)]
        if resolve is None:
            raise _Opaque
        kind = resolve(sub)
        if isinstance(child, BaseModel):
            if kind is not type(child):
                raise _Opaque
        elif isinstance(child, list | tuple) and isinstance(sub, list):
            resolve = _item_resolver(kind)
        else:
            raise _Opaque
    return depth, nodes[depth], sub


def validated_values(
    template: Study, base: dict[str, Any], paths: tuple[str, ...], values: tuple[Any, ...]
) -> tuple[dict[str, Any], Study] | None:
    """The validated value at each of ``paths`` (swept together to ``values``) and the
    template with them put in (:func:`cablestudy.study.grid_studies.case_study`), each
    value validated inside its smallest enclosing model from the user's data ``base``
    (the study file without its sweep); None where that would not be exactly what a
    validation of the whole study gives, or where anything fails (the caller then
    validates the whole study)."""
    try:
        data = dict(base)
        for path, value in zip(paths, values, strict=True):
            _spine_set(data, path, _copy_tree(value))
        out: dict[str, Any] = {}
        models: dict[tuple[str, ...], BaseModel] = {}
        for path in paths:
            parts = path.split(".")
            depth, owner, sub = _enclosing(template, data, parts)
            where = tuple(parts[:depth])
            model = models.get(where)
            if model is None:
                model = models[where] = type(owner).model_validate(sub)
            node: Any = model
            for part in parts[depth:]:
                node = node[int(part)] if isinstance(node, list | tuple) else getattr(node, part)
            out[path] = node
        return out, case_study(template, out)
    except Exception:  # noqa: BLE001 -- any fault: the whole study says it in today's words
        return None
