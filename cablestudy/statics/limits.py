"""Limits checked on a static solution: break conditions and the strain range an axial
law was checked on.

A case whose tension exceeds its break limit (``line.failure`` or a segment's own
``failure``) is recorded as broken: :data:`STATUS_BROKEN`, a message with where (the
arc length s [m]) and by how much, and its static results kept -- the solver did not
fail. A case whose strain passes the range over which its non-linear law was checked to
increase (``max_strain``) fails instead: the law is not trusted there.

The tension is checked at the output points and at the segment boundaries (interpolated
between output points). Along a piece between point loads the tension |T0 - q s| is
convex in s, so its maximum over a segment lies at the segment's ends or at an
attachment; attachments between output points are seen through the neighbouring points.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from .base import STATUS_BROKEN, STATUS_NO_SOLUTION, STATUS_OK, StaticResult


@dataclass(frozen=True, kw_only=True)
class StaticLimits:
    """Per segment (arrays of shape (n_segments,)): ``segment_ends`` [m] (n + 1,),
    ``break_tension`` [N] (inf: none), ``break_source`` text naming the key, and for a
    non-linear law ``law`` (or None) with its checked ``max_strain`` [-]."""

    segment_ends: np.ndarray
    break_tension: np.ndarray
    break_source: tuple[str, ...]
    law: tuple = ()
    max_strain: tuple[float, ...] = ()

    @property
    def active(self) -> bool:
        return bool(np.any(np.isfinite(self.break_tension))) or any(
            law is not None for law in self.law
        )


def _points(result: StaticResult, ends: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(s, tension) at the output points and at the segment boundaries inside."""
    s = np.asarray(result.s, dtype=float)
    T = np.asarray(result.tension, dtype=float)
    inner = ends[1:-1]
    inner = inner[(inner > s[0]) & (inner < s[-1])]
    if inner.size == 0:
        return s, T
    s_all = np.concatenate((s, inner))
    T_all = np.concatenate((T, np.interp(inner, s, T)))
    order = np.argsort(s_all, kind="stable")
    return s_all[order], T_all[order]


def apply_limits(result: StaticResult, limits: StaticLimits) -> StaticResult:
    """``result`` marked broken or failed when it passes a limit (module docstring);
    unchanged otherwise (and when it did not converge)."""
    if result.status != STATUS_OK or not limits.active:
        return result
    ends = limits.segment_ends
    s, T = _points(result, ends)
    seg = np.clip(np.searchsorted(ends, s, side="right") - 1, 0, len(ends) - 2)
    for k, law in enumerate(limits.law):
        if law is None:
            continue
        on = seg == k
        if not np.any(on):
            continue
        j = int(np.argmax(np.where(on, T, -np.inf)))
        strain = float(law.strain(T[j]))
        if strain > limits.max_strain[k]:
            return replace(
                StaticResult.failed(
                    result.s,
                    STATUS_NO_SOLUTION,
                    f"strain {strain:.6g} at s = {s[j]:.6g} m (tension {T[j]:.6g} N) in "
                    f"segment {k} passes the range 0 .. {limits.max_strain[k]:g} over which "
                    "its axial law was checked to increase (line.segments."
                    f"{k}.axial.max_strain); raise max_strain if the law holds there",
                    iterations=result.iterations,
                    residual=result.residual,
                )
            )
    limit = limits.break_tension[seg]
    over = T - limit
    if not np.any(over > 0.0):
        return result
    j = int(np.argmax(np.where(np.isfinite(limit), over / limit, -np.inf)))
    k = int(seg[j])
    pct = 100.0 * over[j] / limit[j]
    msg = (
        f"broken: tension {T[j]:.6g} N at s = {s[j]:.6g} m exceeds the break limit "
        f"{limit[j]:.6g} N ({limits.break_source[k]}) by {over[j]:.6g} N ({pct:.3g} %); "
        "static results kept"
    )
    first = float(s[np.flatnonzero(over > 0.0)[0]])
    last = float(s[np.flatnonzero(over > 0.0)[-1]])
    if not math.isclose(first, last):
        msg += f"; over the limit from s = {first:.6g} m to {last:.6g} m"
    return replace(result, status=STATUS_BROKEN, message=msg)
