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
SURFACE = "surface"
SLACK = "slack"
UNSETTLED = "unsettled"
FALLBACK = "fallback"
UNCHECKED = "unchecked"
#: the time domain's step check (:mod:`cablestudy.dynamics.step_check`, which writes the
#: same word: a statics run loads no dynamics)
STEP = "step"
#: the kinds of warning, in the order a case lists them
KINDS = (STRAIN, SURFACE, SLACK, UNSETTLED, STEP, FALLBACK, UNCHECKED)
#: the key under which a time-domain run hands its step check's warning to the case's
#: warnings (popped from the outputs before they become data variables)
STEP_WARNING_KEY = "_step_warning"


def take_step_warning(data: dict) -> str:
    """The step check's warning of a case's outputs ``data`` ('' if none), removed from
    them (it is a warning, not a data variable)."""
    return str(data.pop(STEP_WARNING_KEY, "") or "")


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


#: fluids denser than this [kg/m^3] are liquids, with their free surface at z = 0 (the
#: sea's, cablestudy's frame); gases (air, 1.2 kg/m^3; even at 100 bar about 120) and
#: vacuum have none, and a line in them may be anywhere
LIQUID_DENSITY = 200.0
#: how far above z = 0 a node must be, relative to its line's length, to count as out of
#: the water: a held end at z = 0 is met to the static tolerance (1e-9 of the length and
#: below), a millimetre per kilometre is far above that and far below a physical rise
SURFACE_TOLERANCE = 1e-6


def has_free_surface(density: float) -> bool:
    """Whether a fluid of ``density`` [kg/m^3] has a free surface at z = 0 (a liquid:
    :data:`LIQUID_DENSITY`)."""
    return density > LIQUID_DENSITY


def highest_points(s: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The highest node of each line: its height z [m] and arc length s [m]. ``z`` (...,
    nodes), ``s`` broadcastable to it; (...) out, NaN where every node is NaN."""
    z = np.asarray(z, dtype=float)
    s = np.broadcast_to(np.asarray(s, dtype=float), z.shape)
    blank = np.all(np.isnan(z), axis=-1)
    k = np.argmax(np.where(np.isnan(z), -np.inf, z), axis=-1)[..., None]
    top = np.take_along_axis(z, k, axis=-1)[..., 0]
    at = np.take_along_axis(s, k, axis=-1)[..., 0]
    return np.where(blank, np.nan, top), np.where(blank, np.nan, at)


def surface_warning(
    s: np.ndarray, z: np.ndarray, names: list[str] | None = None, *, when: str = "static"
) -> str:
    """The warning of a line (``z`` (nodes,), names None) or of lines (``z`` (lines,
    nodes), their ``names``) in a liquid that rise above its surface z = 0 by more than
    :data:`SURFACE_TOLERANCE` of their length (``s`` [m]: arc lengths, broadcastable to
    ``z`` [m]). It names the line that rises highest, its highest node (z, s) and, when
    more than one is above, all of them; '' when none is. ``when``: 'static' (the
    static shape), or the dynamic envelope it judges (worded into the text)."""
    z = np.atleast_2d(np.asarray(z, dtype=float))
    s = np.broadcast_to(np.asarray(s, dtype=float), z.shape)
    top, at = highest_points(s, z)
    length = np.nanmax(s, axis=-1) - np.nanmin(s, axis=-1)
    above = top > SURFACE_TOLERANCE * np.maximum(length, 1.0)  # NaN: False
    if not np.any(above):
        return ""
    worst = int(np.argmax(np.where(above, top, -np.inf)))
    who = "the line" if names is None else f"line {names[worst]}"
    text = (
        f"{SURFACE}: {who} rises above the water's surface (z = 0) to z = {top[worst]:.4g} m "
        f"at s = {at[worst]:.4g} m (its highest node{'' if when == 'static' else ', ' + when}), "
        "where the model still gives it buoyancy and added mass, which out of the water do "
        "not exist: check the buoyancy (diameters, attachments) and the end positions"
    )
    if names is not None and np.count_nonzero(above) > 1:
        listed = ", ".join(n for n, a in zip(names, above, strict=True) if a)
        text += f" (lines above the surface: {listed})"
    return text


def surface_warnings(
    s: np.ndarray, z: np.ndarray, ok: np.ndarray, names: list[str] | None = None
) -> dict[int, str]:
    """:func:`surface_warning` of each case of a batch whose ``ok`` (cases,) is true:
    ``z`` (cases, nodes) of one line or (cases, lines, nodes) with their ``names``, ``s``
    broadcastable to it; {case: text} of the cases that have one."""
    z = np.asarray(z, dtype=float)
    s = np.broadcast_to(np.asarray(s, dtype=float), z.shape)
    top = np.fmax.reduce(z.reshape(len(z), -1), axis=-1) if z.size else np.zeros(len(z))
    found: dict[int, str] = {}
    for i in np.flatnonzero(np.asarray(ok, dtype=bool) & (top > 0.0)):
        text = surface_warning(s[i], z[i], names)
        if text:
            found[int(i)] = text
    return found


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
