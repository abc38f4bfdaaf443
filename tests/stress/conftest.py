"""Helpers for the stress suite: build a study from a dict, evaluate it in-process."""

from __future__ import annotations

from typing import Any

import numpy as np
import yaml

from cablestudy.analyses.evaluate import check_supported, evaluate_case
from cablestudy.analyses.variables import OUTPUTS, CaseRecord
from cablestudy.study.grid import expand_cases
from cablestudy.study.loader import parse_study_text


def study_dict(
    *,
    length: float = 100.0,
    b: tuple[float, float, float] = (80.0, 0.0, -20.0),
    weight: float | None = None,
    mass: float | None = 2.0,
    ea: float = 1e8,
    fluid: Any = "water",
    method: str = "catenary",
    current: list | None = None,
    depth: float | None = None,
    time_limit: float = 60.0,
    diameter: float = 0.05,
) -> dict[str, Any]:
    seg: dict[str, Any] = {"length": length, "diameter": diameter, "axial_stiffness": ea}
    if weight is not None:
        seg["weight_in_fluid"] = weight
    if mass is not None:
        seg["mass_per_length"] = mass
    env: dict[str, Any] = {"fluid": fluid}
    if current:
        env["current"] = current
    if depth is not None:
        env["depth"] = depth
    return {
        "name": "stress",
        "environment": env,
        "line": {"segments": [seg]},
        "ends": {
            "a": {"kind": "fixed", "position": [0.0, 0.0, 0.0]},
            "b": {"kind": "fixed", "position": list(b)},
        },
        "analysis": {"static": {"method": method, "nodes": 41}, "time_limit": time_limit},
    }


def evaluate(data: dict[str, Any]) -> CaseRecord:
    src = parse_study_text(yaml.safe_dump(data, sort_keys=False), "<stress>")
    _, cases = expand_cases(src)
    assert len(cases) == 1
    check_supported(cases, src)  # as the runner does before any work
    return evaluate_case(cases[0])


def assert_honest(rec: CaseRecord) -> None:
    """A status-0 case holds no NaN or infinity (but NaN where the output registry
    gives it a meaning, e.g. no seabed contact); a failed case says why."""
    if rec.status == 0:
        for name, value in rec.data.items():
            arr = np.asarray(value)
            if OUTPUTS[name].nan_means:
                arr = arr[~np.isnan(arr)]
            if arr.dtype.kind == "f":
                assert np.all(np.isfinite(arr)), f"status 0 but non-finite {name}"
        assert rec.message == ""
    else:
        assert rec.message.strip(), "failed case without a message"
