"""A system study's sweep of its harmonic excitation in the frequency domain run as
arrays (issue 24): the frequency, amplitude, phase, degree of freedom or direction of a
body's or a point's harmonic motion swept under ``method: frequency``.

Such a sweep changes nothing but the motion: every case has the template's static
problem, element count and drag settings. The study is validated as the grid machinery
validates any sweep (:func:`cablestudy.study.grid.expand_grid`: the template once, each
swept value once at its path), and :func:`excitation_sweep` marks its cases
(:class:`ExcitationCase`). The runner keeps running them as cases (their content hashes
are the cache's keys, so a re-run, or a sweep with values added, finds every case it
has already solved, as before); only the evaluation of a chunk of them changes
(:func:`evaluate_excitation_chunk`): the statics and the linear model are the shared
ones (solved, and cached, once per sweep), the compiled drag iteration runs case after
case over the chunk's motions (:func:`cablestudy.analyses.system_frequency.
group_arrays`), and its output arrays are the chunk's arrays, the static outputs
broadcast beside them: no per-case evaluation or record. Each case's numbers, status,
message and warnings are those :func:`cablestudy.analyses.system.evaluate_system_case`
gives it (the slack and surface warnings by the same functions, called for the cases
whose arrays can raise them).

What the arrays do not take goes case by case through
:func:`cablestudy.analyses.system.evaluate_system_case`, counted in
``COUNTERS["fd_grid_fallback"]`` (the cases taken in ``COUNTERS["fd_grid_cases"]``): a
chunk whose statics fail or whose linear model cannot be built, a system of one line
(the one-line study's path, :mod:`cablestudy.analyses.system_one_line`), and each case
whose harmonic response fails or is not finite (its status and message are that
path's). ``method: auto`` sweeps are not marked: they judge each case (and may run the
time domain) case by case as before.
"""

from __future__ import annotations

import math
import re
import time
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from ..study.cases import Case
from ..study.grid import CaseGrid
from .counters import COUNTERS
from .grid_chunk import GridChunk, join_chunks, records_chunk
from .plausibility import SURFACE
from .variables import SYSTEM_OUTPUTS

#: the swept paths of a harmonic excitation (one entry, or entry ``i`` of a list)
_EXCITATION = re.compile(
    r"^analysis\.dynamic\.excitation(\.\d+)?\."
    r"(amplitude|frequency|period|phase_deg|dof|direction(\.[012])?)$"
)


@dataclass(frozen=True)
class ExcitationCase(Case):
    """A case of a sweep of the harmonic excitation (module docstring): evaluated with
    the other cases of its chunk as arrays."""


@dataclass(frozen=True)
class ExcitationGrid(CaseGrid):
    """A system study's sweep of its harmonic excitation: the grid it is
    (:func:`cablestudy.study.grid.expand_grid`'s), its cases marked
    (:class:`ExcitationCase`)."""

    def cases(self) -> list[Case]:
        found = self.memo.get("excitation_cases")
        if found is None:
            found = [
                ExcitationCase(c.index, c.coords, c.study, c.hash, c.static_hash)
                for c in CaseGrid.cases(self)
            ]
            self.memo["excitation_cases"] = self.memo["cases"] = found
        return found


def excitation_sweep(grid: CaseGrid) -> CaseGrid:
    """``grid`` as an :class:`ExcitationGrid` when it is a system study's sweep of only
    the harmonic excitation of a ``method: frequency`` analysis, else ``grid``."""
    template = grid.template
    dyn = template.analysis.dynamic
    if grid.chunked or not template.is_system or dyn is None or dyn.method != "frequency":
        return grid
    paths = [p for axis in grid.axes for p in axis.paths]
    if not paths or not all(_EXCITATION.match(p) for p in paths):
        return grid
    return ExcitationGrid(**{f.name: getattr(grid, f.name) for f in fields(grid)})


def evaluate_excitation_chunk(cases: list[Case]) -> GridChunk:
    """The chunk of ``cases`` (of one :class:`ExcitationGrid`) as arrays (module
    docstring); what the arrays do not take, case by case. Never raises for a case's
    fault: that is its status and message."""
    from .frequency import drag_settings
    from .system import case_statics
    from .system_frequency import group_arrays, system_frequency_model
    from .system_one_line import is_one_line

    t0 = time.perf_counter()
    first = cases[0]
    study = first.study
    deadline = time.monotonic() + study.analysis.time_limit
    system, res, status, message, static_data, static_warnings = case_statics(first, deadline)
    model = system_frequency_model(first, system, res) if status == 0 else None
    if status != 0 or isinstance(model, str) or is_one_line(system):
        return _case_by_case(cases)
    motions = _motions(cases)
    settings = drag_settings(study.analysis.dynamic)
    results, batch, finite = group_arrays(
        motions, model, system, res, settings, [False] * len(cases)
    )
    good = np.array([r.status == 0 for r in results], dtype=bool)
    for ok in finite.values():
        good &= ok
    rows = np.flatnonzero(good)
    chunks = []
    if rows.size:
        values = {k: v[rows] for k, v in batch.items()}
        taken = [cases[i] for i in rows]
        chunks.append(
            _arrays_chunk(taken, system, res, message, static_data, static_warnings, values, t0)
        )
        COUNTERS["fd_grid_cases"] += rows.size
    if rows.size < len(cases):
        chunks.append(_case_by_case([c for c, ok in zip(cases, good, strict=True) if not ok]))
    return join_chunks(chunks)


def _motions(cases: list[Case]) -> list[tuple[np.ndarray, np.ndarray, float]]:
    """Each case's :func:`cablestudy.analyses.system_frequency.harmonic_motion`: the
    bodies' rotations turned about their static orientation once per distinct motion
    (a sweep's cases share the bodies' static poses, and mostly their motion)."""
    from .system_frequency import body_axes_motion, turned_rotations

    turned: dict[bytes, np.ndarray] = {}
    out = []
    for c in cases:
        X, U, frequency = body_axes_motion(c.study)
        key = X.tobytes()  # bit for bit, signs of zeros too
        if key not in turned:
            turned[key] = turned_rotations(c.study, X)
        out.append((turned[key], U, frequency))
    return out


def _case_by_case(cases: list[Case]) -> GridChunk:
    """``cases`` by :func:`cablestudy.analyses.system.evaluate_system_case`, counted."""
    from .system import evaluate_system_case

    COUNTERS["fd_grid_fallback"] += len(cases)
    return records_chunk([evaluate_system_case(c) for c in cases], system=True)


def _arrays_chunk(
    cases: list[Case],
    system: Any,
    res: Any,
    message: str,
    static_data: dict[str, Any],
    static_warnings: list[str],
    values: dict[str, np.ndarray],
    t0: float,
) -> GridChunk:
    """The chunk of ``cases`` whose harmonic responses succeeded, their outputs
    ``values`` (one array per output, cases first): what :func:`records_chunk` makes of
    their records (:func:`cablestudy.analyses.system.evaluate_system_case`'s: the static
    outputs, the frequency domain's, ``dynamic_status`` 0; the statics' status 0 and
    message; the static warnings, each case's slack and surface warnings)."""
    n = len(cases)
    texts = {
        "dynamic_method": "frequency",
        "dynamic_method_reason": "method: frequency",
    }
    shared = {**static_data, "dynamic_status": np.asarray(0, dtype=np.int64)}
    data: dict[str, np.ndarray] = {}
    for name in sorted({*shared, *values, *texts}):
        dtype = SYSTEM_OUTPUTS[name].dtype
        if name in texts:
            text = texts[name]
            data[name] = np.full(n, text, dtype=f"<U{max(1, len(text))}")
        elif name in values:
            data[name] = values[name].astype(dtype, copy=False)
        else:
            v = np.asarray(shared[name])
            data[name] = np.broadcast_to(v, (n, *v.shape)).astype(dtype)
    warnings = _warnings(cases, system, static_data, static_warnings, values)
    fallback = str(getattr(res, "fallback", "") or "")
    wall = (time.perf_counter() - t0) / n
    return GridChunk(
        lo=0,
        hi=0,
        key="",
        status=np.zeros(n, dtype=np.int64),
        message=_text([message] * n),
        wall_time=np.full(n, wall),
        data=data,
        warning=_text(warnings),
        fallback_reason=_text([fallback] * n),
        hashes=_text([c.hash for c in cases]),
    )


def _warnings(
    cases: list[Case],
    system: Any,
    static_data: dict[str, Any],
    static_warnings: list[str],
    values: dict[str, np.ndarray],
) -> list[str]:
    """Each case's warning text, as :func:`cablestudy.analyses.system.
    evaluate_system_case` joins it: the static warnings, the slack warning
    (:func:`cablestudy.analyses.system._slack_warning`) and, without a static surface
    warning, the motion's surface warning (:func:`cablestudy.analyses.surface.
    system_motion_surface_warning`); each called only for the cases whose arrays can
    give one (an end or envelope tension at or below zero; an elevation above zero),
    the others' being empty."""
    from .plausibility import slack_warning
    from .surface import system_motion_surface_warning
    from .system import _slack_warning

    n = len(cases)
    names = list(cases[0].study.lines)

    def low(key: str) -> np.ndarray:
        if key not in values:
            return np.zeros(n, dtype=bool)
        return np.any(values[key].reshape(n, -1) <= 0.0, axis=1)

    slack = low("tension_min_a") | low("tension_min_b") | low("tension_envelope_min")
    surface = not any(w.startswith(SURFACE) for w in static_warnings)
    above = np.zeros(n, dtype=bool)
    if surface and "z_envelope_max" in values:
        above = np.any(values["z_envelope_max"].reshape(n, -1) > 0.0, axis=1)
    # a slack end (_slack_warning's first branch): the minima over each case's ends
    # (2, lines), in the same order, found for all the cases at once
    lowest = per_line = [math.nan] * n
    if "tension_min_a" in values and "tension_min_b" in values and len(names):
        ends = np.stack([values[f"tension_min_{e}"].reshape(n, -1) for e in "ab"], axis=1)
        lowest, per_line = ends.reshape(n, -1).min(axis=1).tolist(), ends.min(axis=1).tolist()
    out = []
    for i in range(n):
        found = list(static_warnings)
        end = slack[i] and lowest[i] <= 0.0
        if end:
            at = ", ".join(m for m, t in zip(names, per_line[i], strict=True) if t <= 0.0)
            found.append(slack_warning(lowest[i], f"at an end of line {at}"))
        if (slack[i] and not end) or above[i]:
            row = {**static_data, **{k: v[i] for k, v in values.items()}}
            if slack[i] and not end:
                found.append(_slack_warning(names, row))
            if above[i]:
                found.append(system_motion_surface_warning(cases[i].study, row))
        out.append("; ".join(w for w in found if w))
    return out


def _text(values: list[str]) -> np.ndarray:
    return np.array(values, dtype=str).reshape(len(values))
