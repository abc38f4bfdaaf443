"""Warnings on results that are valid but implausible or risky: a case that gets one keeps
status 0, and its ``warning`` (empty when none) says why, as ``message`` says why a case
failed.

Pure functions: numbers in, warning texts out (SI units). Each text starts with its
kind and a colon (:data:`KINDS`), so that the end-of-run report can group them; a case's
warnings are joined by :data:`SEPARATOR`.
"""

from __future__ import annotations

import math

import numpy as np

STRAIN = "strain"
SLACK = "slack"
UNSETTLED = "unsettled"
FALLBACK = "fallback"
UNCHECKED = "unchecked"
#: the kinds of warning, in the order a case lists them
KINDS = (STRAIN, SLACK, UNSETTLED, FALLBACK, UNCHECKED)
#: between the warnings of one case
SEPARATOR = "; "


def largest_strain(
    tension: np.ndarray, axial_stiffness: np.ndarray, strain: np.ndarray | None = None
) -> np.ndarray:
    """The largest strain along each line [-]: of the law's ``strain`` where given (same
    shape as ``tension``), else T / EA. Arrays (..., nodes) in, (...) out; NaN only where
    every node is NaN."""
    e = np.asarray(tension, dtype=float) / axial_stiffness if strain is None else strain
    return np.fmax.reduce(np.asarray(e, dtype=float), axis=-1)  # NaN nodes skipped


def strain_warning(max_strain: float, limit: float) -> str:
    """The warning of a static solution whose largest strain ``max_strain`` [-] is above
    ``limit`` [-] (``analysis.static.strain_warning``); '' otherwise."""
    if not max_strain > limit:  # NaN: nothing to judge
        return ""
    return (
        f"{STRAIN}: largest strain {max_strain:.4g} above the plausibility limit "
        f"{limit:g} (analysis.static.strain_warning): check the line's length and end "
        "positions, or its axial law"
    )


def slack_warning(tension_min: float, where: str) -> str:
    """The warning of a dynamic response whose smallest tension ``tension_min`` [N]
    (``where``: at the excited end, or along the line) is at or below zero: the line goes
    slack, and snap loads follow when it tightens again; '' otherwise."""
    if not tension_min <= 0.0:
        return ""
    return (
        f"{SLACK}: the dynamic tension {where} falls to {tension_min:.4g} N (at or below "
        "zero: the line goes slack and snaps taut again)"
    )


def unsettled_warning(periods: float, max_periods: int) -> str:
    """The warning of a time-domain run that stopped at ``max_periods`` without its
    per-period tension extremes settling; ``periods``: excitation periods simulated."""
    shown = f"{periods:.4g}"
    return (
        f"{UNSETTLED}: no steady state after {shown} periods (analysis.dynamic.max_periods "
        f"{max_periods}): the tensions are the envelope of the last periods"
    )


def fallback_warning(reason: str) -> str:
    """The warning of a case the batched kernel handed to the general solver."""
    return f"{FALLBACK}: solved one by one by the general solver, not the batched kernel ({reason})"


def dynamic_warnings(
    data: dict[str, np.ndarray],
    *,
    max_periods: int,
    fixed_duration: bool = False,
    static_tension: np.ndarray | None = None,
) -> list[str]:
    """The warnings of one case's successful dynamic outputs ``data`` (as
    :func:`cablestudy.analyses.dynamic.run_dynamic` gives them): slack at the excited end or
    along the line (where the static tension ``static_tension`` [N], on the same points,
    is positive), and a time-domain run that stopped at ``max_periods`` without
    settling (not one of a ``fixed_duration``, which does not look for a steady state).
    None for a line that parted (``break_time``): the break is the news."""
    out: list[str] = []
    if math.isfinite(_number(data.get("break_time"))):
        return out  # the line parted: break_time and break_s say so, its tensions fall to 0
    t_end = _number(data.get("tension_min"))
    envelope = data.get("tension_envelope_min")
    if envelope is not None and static_tension is not None:
        # only where the static line is taut: a stretch already untensioned in statics (a
        # laid stretch that seabed friction has emptied) does not go slack, it is slack
        env = np.asarray(envelope, dtype=float)
        st = np.asarray(static_tension, dtype=float)
        if env.shape == st.shape:
            envelope = np.where(st > 0.0, env, np.nan)
    t_line = float(np.nanmin(envelope)) if _any_finite(envelope) else math.nan
    if t_end <= 0.0:
        out.append(slack_warning(t_end, "at the excited end"))
    elif t_line <= 0.0:
        out.append(slack_warning(t_line, "along the line"))
    settled = _number(data.get("steady_converged"))
    periods = _number(data.get("periods"))
    if settled == 0.0 and not fixed_duration and periods >= max_periods - 1e-9:
        out.append(unsettled_warning(periods, max_periods))
    return out


def joined(warnings: list[str]) -> str:
    """One case's warnings as its ``warning`` text (in :data:`KINDS` order)."""
    order = {k: i for i, k in enumerate(KINDS)}
    kept = sorted((w for w in warnings if w), key=lambda w: order.get(w.split(":")[0], 99))
    return SEPARATOR.join(kept)


def _number(value: object) -> float:
    if value is None:
        return math.nan
    arr = np.asarray(value)
    if arr.size != 1 or arr.dtype.kind not in "biuf":
        return math.nan
    return float(arr.reshape(()))


def _any_finite(value: object) -> bool:
    if value is None:
        return False
    arr = np.asarray(value)
    return arr.dtype.kind == "f" and bool(np.isfinite(arr).any())
