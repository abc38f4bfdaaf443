"""A swept key named as an output (``ends.b.z`` and the position ``z``) gives a dimension
prefixed with its parent, as one named as an output's dimension does
(docs/guide/sweeps.md): :data:`cablestudy.study.cases.OUTPUT_NAMED_KEYS` must hold every
key of the study schema that is also the name of an output variable or coordinate, or
the dataset gets a dimension and a variable of one name, which netCDF refuses after every
case has run."""

from __future__ import annotations

from typing import Any

from cablestudy.analyses.variables import CASE_VARIABLES, COORDINATES, OUTPUTS, SYSTEM_OUTPUTS
from cablestudy.study.cases import OUTPUT_NAMED_KEYS, RESERVED_DIMS, _default_dim
from cablestudy.study.study import Study


def _keys(schema: Any, found: set[str]) -> set[str]:
    if isinstance(schema, dict):
        found.update(schema.get("properties", {}))
        for value in schema.values():
            _keys(value, found)
    elif isinstance(schema, list):
        for value in schema:
            _keys(value, found)
    return found


def test_every_study_key_named_as_an_output_is_prefixed() -> None:
    outputs = set(OUTPUTS) | set(SYSTEM_OUTPUTS) | set(CASE_VARIABLES) | set(COORDINATES)
    clashing = _keys(Study.model_json_schema(), set()) & outputs
    assert clashing <= OUTPUT_NAMED_KEYS | RESERVED_DIMS, clashing - RESERVED_DIMS
    assert OUTPUT_NAMED_KEYS <= outputs  # no stale entry


def test_the_prefixed_names() -> None:
    assert _default_dim(("ends", "b", "z")) == "b_z"
    assert _default_dim(("environment", "current", "1", "z")) == "current_z"
    assert _default_dim(("line", "failure", "tension")) == "failure_tension"
    assert _default_dim(("line", "segments", "0", "length")) == "length"
