"""A motion that stretches a line implausibly far, or a non-linear axial law past the
strain range it was checked on.

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

from typing import Any

import numpy as np

from ..statics.limits import StaticLimits
from .common import segment_of
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


def dynamic_strain_warning(
    s: np.ndarray, tension_max: np.ndarray, segments: Any, limit: float
) -> str:
    """The warning of a dynamic response whose largest strain over the motion (of the
    tension envelope ``tension_max`` [N] at the arc lengths ``s`` [m], T / EA, or the
    segment's axial law's strain) is above ``limit`` [-]
    (``analysis.static.strain_warning``, the same plausibility limit as the statics');
    '' otherwise (and for NaN tensions: nothing to judge). A motion can stretch a line
    far beyond any material (an end moved faster than the line's axial waves: strains of
    1e12 at 1e9 Hz); the case keeps status 0 and its numbers, and says so."""
    s = np.asarray(s, dtype=float)
    T = np.asarray(tension_max, dtype=float)
    if T.shape != s.shape or not np.any(np.isfinite(T)):
        return ""
    k = segment_of(segments, s)
    strain = T / np.array([segments[i].elastic_stiffness for i in k])
    for i, seg in enumerate(segments):
        on = (k == i) & np.isfinite(T)
        if seg.is_nonlinear and np.any(on):
            strain[on] = seg.axial_law().strain(T[on])
    j = int(np.nanargmax(strain))
    if not strain[j] > limit:
        return ""
    return (
        f"{STRAIN}: largest dynamic strain {strain[j]:.4g} at s = {s[j]:.6g} m (tension "
        f"{T[j]:.6g} N, over the motion) above the plausibility limit {limit:g} "
        "(analysis.static.strain_warning): check the excitation's amplitude and frequency "
        "and the line's axial stiffness"
    )
