"""A motion that stretches a non-linear axial law past the strain range it was checked on.

``line.segments.N.axial.max_strain`` is the strain up to which the law was checked to
increase (study/line.py); a static solution beyond it fails
(:func:`cablestudy.statics.limits.apply_limits`). The dynamic analyses integrate the same
law wherever the motion takes it, so a response whose tension envelope passes the law's
tension at ``max_strain`` rests on the law's extrapolation: the case keeps its results
and status 0 and gets a ``strain`` warning naming the segment, the point, the tension and
the key (:mod:`cablestudy.analyses.plausibility`).

Pure: arrays in (SI units), a warning text out. The law is compared in tension, which it
gives everywhere, not in strain: past its checked range the law may not be invertible.
"""

from __future__ import annotations

import numpy as np

from ..statics.limits import StaticLimits
from .plausibility import STRAIN


def law_range_warning(s: np.ndarray, tension_max: np.ndarray, limits: StaticLimits) -> str:
    """The warning of a dynamic response whose largest tension ``tension_max`` [N] at the
    arc lengths ``s`` [m] (the static output points) passes, in some segment with a
    non-linear law, that law's tension at its ``max_strain``; '' when none does (and for
    NaN tensions: nothing to judge). The segment passed by the largest factor is named."""
    if not any(law is not None for law in limits.law):
        return ""
    s = np.asarray(s, dtype=float)
    T = np.asarray(tension_max, dtype=float)
    if T.shape != s.shape:
        return ""
    ends = limits.segment_ends
    seg = np.clip(np.searchsorted(ends, s, side="right") - 1, 0, len(ends) - 2)
    worst: tuple[float, int, int, float] | None = None
    for k, law in enumerate(limits.law):
        if law is None:
            continue
        on = (seg == k) & np.isfinite(T)
        if not np.any(on):
            continue
        j = int(np.argmax(np.where(on, T, -np.inf)))
        t_limit = float(law.tension(limits.max_strain[k]))
        if T[j] > t_limit > 0.0 and (worst is None or T[j] / t_limit > worst[0]):
            worst = (T[j] / t_limit, k, j, t_limit)
    if worst is None:
        return ""
    _, k, j, t_limit = worst
    return (
        f"{STRAIN}: the dynamic tension {T[j]:.6g} N at s = {s[j]:.6g} m in segment {k} "
        f"passes {t_limit:.6g} N, its axial law's tension at the end of the range 0 .. "
        f"{limits.max_strain[k]:g} over which it was checked to increase "
        f"(line.segments.{k}.axial.max_strain): the motion uses the law beyond it (raise "
        "max_strain if the law holds there)"
    )
