"""What every analysis kind shares: the status of an analysis that did not run, the
segment of a point of the line, the text of a solver's exception, and the check of
outputs for NaN and infinity (one case's or a column of cases' at once).
"""

from __future__ import annotations

import math
import traceback
from typing import Any

import numpy as np

from .variables import OUTPUTS

#: status of an analysis that did not run because the static analysis it starts from
#: failed (the code of :data:`cablestudy.dynamics.modal.STATUS_STATIC_FAILED`)
STATUS_NOT_RUN = 5


def segment_of(segments: Any, s: np.ndarray) -> np.ndarray:
    """The index of the segment (of ``segments``, in order along the line) each arc
    length ``s`` [m] lies on; a point at a joint belongs to the segment after it."""
    ends = np.cumsum([seg.length for seg in segments])
    return np.minimum(np.searchsorted(ends, s, side="right"), len(segments) - 1)


def exception_message(exc: Exception) -> str:
    tb = traceback.extract_tb(exc.__traceback__)
    where = f" at {tb[-1].name}:{tb[-1].lineno}" if tb else ""
    return f"{type(exc).__name__}: {exc}{where}"


#: the outputs last checked by :func:`non_finite_outputs` per analysis, with the answer (holding
#: the arrays, so that a later call with the very same objects can reuse it)
_LAST_CHECKED: dict[str, tuple[dict[str, Any], list[str]]] = {}


def non_finite_outputs(data: dict[str, Any], analysis: str) -> list[str]:
    """Float variables of ``analysis`` in ``data`` holding NaN or infinity where the
    registry does not give NaN a meaning (e.g. 'no seabed contact')."""
    known = getattr(data, "non_finite", None)
    if known is not None:  # found on the arrays of a batch (CheckedOutputs)
        return list(known)
    last = _LAST_CHECKED.get(analysis)
    if (
        last is not None
        and len(last[0]) == len(data)
        and all(k in data and data[k] is v for k, v in last[0].items())
    ):
        return list(last[1])  # the very same arrays (outputs shared between cases)
    bad = []
    for k, v in data.items():
        spec = OUTPUTS.get(k)
        if spec is None or spec.analysis != analysis:
            continue
        v = v if isinstance(v, np.ndarray) else np.asarray(v)
        if v.dtype.kind != "f":
            continue
        if v.ndim == 0:  # a number: no array reductions needed
            x = float(v)
            if not (math.isfinite(x) or (spec.nan_means and math.isnan(x))):
                bad.append(k)
            continue
        if spec.nan_means:
            v = v[~np.isnan(v)]
        if not np.isfinite(v).all():
            bad.append(k)
    _LAST_CHECKED[analysis] = (dict(data), sorted(bad))
    return sorted(bad)


def non_finite_cases(columns: dict[str, np.ndarray], analysis: str) -> list[list[str]]:
    """:func:`non_finite_outputs` of K cases at once: ``columns`` maps output names to arrays
    (K, ...) whose row k is case k's value; per case the sorted names found."""
    n_cases = len(next(iter(columns.values()))) if columns else 0
    bad: list[list[str]] = [[] for _ in range(n_cases)]
    for name in sorted(columns):
        spec = OUTPUTS.get(name)
        v = columns[name]
        if spec is None or spec.analysis != analysis or v.dtype.kind != "f":
            continue
        good = np.isfinite(v)
        if spec.nan_means:
            good |= np.isnan(v)
        for k in np.flatnonzero(~good.reshape(n_cases, -1).all(axis=1)):
            bad[k].append(name)
    return bad


class CheckedOutputs(dict):
    """Outputs whose float variables holding NaN or infinity are known already
    (``non_finite``, sorted names): :func:`non_finite_outputs` takes them instead of scanning
    the arrays."""

    non_finite: list[str]
