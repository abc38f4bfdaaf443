"""Lines above the water's surface: the ``surface`` warning
(:func:`cablestudy.analyses.plausibility.surface_warning`) of each evaluation path's
static results, from its study's fluid.

The frame puts the surface of a liquid at z = 0 (docs/conventions.md). The statics give a
submerged line's buoyancy and the dynamics its added mass and drag everywhere, so a
buoyant stretch (a lazy wave's buoyancy section, a big buoy) can solve, with status 0,
arched above z = 0 where none of that exists. Such a case keeps its results and status 0
and says so in its ``warning``: the line (by name in a system), its highest node's height
and arc length. A line in a gas or vacuum (:func:`has_free_surface`) is never judged.

One function per path, each a few lines over the pure checks: a case alone
(:func:`case_surface_warning`, from :func:`cablestudy.analyses.evaluate.case_warnings`:
the statics, then the elevation envelope over the motion, both dynamic methods' output
``z_envelope_max``), a sweep run as arrays (:func:`template_surface_warnings`, from
:mod:`cablestudy.analyses.static_grid`), a system case (:func:`system_surface_warning`
and over its motion :func:`system_motion_surface_warning`,
:mod:`cablestudy.analyses.system`) and a system sweep run as arrays
(:func:`system_grid_surface_warnings`, :mod:`cablestudy.analyses.system_grid`).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np

from .plausibility import has_free_surface, surface_warning, surface_warnings


def _liquid(study: Any) -> bool:
    return has_free_surface(float(study.environment.density))


def static_surface_warning(study: Any, res: Any) -> str:
    """The warning of one line's static solution ``res`` (``s`` [m], ``position`` [m]
    (nodes, 3)) that rises above the surface; '' if none, or the fluid has no surface."""
    if not _liquid(study):
        return ""
    return surface_warning(np.asarray(res.s), np.asarray(res.position)[:, 2])


def case_surface_warning(study: Any, static: Any, data: dict[str, Any], ok: set[str]) -> str:
    """The ``surface`` warning of one line's case: of its static solution ``static``
    (None: it failed), else, where the dynamic analysis succeeded (in ``ok``), of the
    line's elevation envelope over the motion (``z_envelope_max`` (s,) [m] in ``data``,
    at the static output points: both dynamic methods give it; a fixed end, moved as
    given, left out), or where a model gives
    none (a line over sliding pulleys) of its kept whole-line time history
    (``history_line_position`` (time, s, 3) [m]; without it the motion is not judged)."""
    if static is None or not _liquid(study):
        return ""
    text = static_surface_warning(study, static)
    if text or "dynamic" not in ok:
        return text
    s = np.asarray(static.s, dtype=float)
    envelope = data.get("z_envelope_max")
    if envelope is not None:
        z = np.array(envelope, dtype=float)
        # a held end goes where its motion takes it: the input, not the model's answer
        held = [study.ends.a.kind == "fixed", study.ends.b.kind == "fixed"]
        z[[0, -1]] = np.where(held, np.nan, z[[0, -1]])
        return surface_warning(s, z, when="over the motion")
    history = data.get("history_line_position")
    if history is None:
        return ""
    z = np.asarray(history, dtype=float)[..., 2]  # (time, s)
    if z.ndim != 2 or z.shape[1] != s.size or not z.size:
        return ""
    return surface_warning(s, np.max(z, axis=0), when="in the kept time history")


def template_surface_warnings(
    template: Any, s: np.ndarray, position: np.ndarray, status: np.ndarray
) -> Iterable[tuple[int, str]]:
    """(case, warning) of the status-0 cases of a one-line sweep run as arrays whose line
    rises above the surface: ``s`` (cases, nodes) [m], ``position`` (cases, nodes, 3) [m];
    ``template``: the sweep's study (the fluid is never swept there)."""
    if not _liquid(template):
        return []
    return surface_warnings(s, np.asarray(position)[..., 2], np.asarray(status) == 0).items()


def system_surface_warning(study: Any, res: Any) -> str:
    """The warning of a solved system (``res.lines``: each line's static solution, in the
    order of ``study.lines``, all on the same number of nodes) where a line rises above
    the surface, naming it."""
    if not _liquid(study) or not res.lines:
        return ""
    s = np.array([np.asarray(r.s, dtype=float) for r in res.lines])
    z = np.array([np.asarray(r.position, dtype=float)[:, 2] for r in res.lines])
    return surface_warning(s, z, list(study.lines))


def system_motion_surface_warning(study: Any, data: dict[str, Any]) -> str:
    """The warning of a system case whose dynamics lift a line above the surface:
    ``data['z_envelope_max']`` (lines, s) [m], the lines' elevation envelope over the
    motion, at the static output points ``data['arc_length']`` (lines, s) [m], the
    lines named as in ``study.lines``, ends on fixed points and bodies (whose motion is
    given) left out; '' without a dynamic envelope."""
    envelope = data.get("z_envelope_max")
    if envelope is None or "arc_length" not in data or not _liquid(study):
        return ""
    z = np.array(envelope, dtype=float)
    if not np.any(z > 0.0):  # nothing above z = 0 (NaN counts as not): no warning
        return ""
    for i, line in enumerate(study.lines.values()):  # ends on fixed or body points are
        for k, point in ((0, line.a), (-1, line.b)):  # moved as given: not judged
            if study.points[point].kind != "free":
                z[i, k] = np.nan
    return surface_warning(
        np.asarray(data["arc_length"], dtype=float), z, list(study.lines), when="over the motion"
    )


def system_grid_surface_warnings(
    template: Any, out: dict[str, np.ndarray], status: np.ndarray
) -> Iterable[tuple[int, str]]:
    """(case, warning) of the status-0 cases of a system sweep run as arrays where a line
    rises above the surface: ``out['arc_length']`` and ``out['z']`` (cases, lines, nodes)
    [m], the lines named as in ``template.lines``."""
    if not _liquid(template):
        return []
    names = list(template.lines)
    return surface_warnings(out["arc_length"], out["z"], np.asarray(status) == 0, names).items()
